//! The rigid body's data, shared by the stepping code (`step`, `batch`) and the body itself
//! (`body`): the 13-number state `X = (x, q, P, L)`, the constants its derivative needs, the
//! forces acting on it and the integrator choice. It imports neither, so `body` → `step` →
//! `state` has no cycle.

use super::principal::principal_axes;
use crate::ode::Tableau;
use glam::{DMat3, DQuat, DVec3};
use serde::{Deserialize, Serialize};

/// Position of the centre of mass, orientation (body → world), linear and angular momentum.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidState {
    /// metres, world
    pub x: DVec3,
    /// world_from_body rotation (unit after every step)
    pub q: DQuat,
    /// linear momentum, kg m/s, world
    pub p: DVec3,
    /// angular momentum about the centre of mass, kg m²/s, world
    pub l: DVec3,
}

impl RigidState {
    pub const DIM: usize = 13;

    pub fn at_rest(x: DVec3, q: DQuat) -> Self {
        Self {
            x,
            q,
            p: DVec3::ZERO,
            l: DVec3::ZERO,
        }
    }

    pub fn to_array(&self) -> [f64; 13] {
        let (x, q, p, l) = (self.x, self.q, self.p, self.l);
        [
            x.x, x.y, x.z, q.x, q.y, q.z, q.w, p.x, p.y, p.z, l.x, l.y, l.z,
        ]
    }

    pub fn from_slice(s: &[f64]) -> Self {
        Self {
            x: DVec3::new(s[0], s[1], s[2]),
            q: DQuat::from_xyzw(s[3], s[4], s[5], s[6]),
            p: DVec3::new(s[7], s[8], s[9]),
            l: DVec3::new(s[10], s[11], s[12]),
        }
    }
}

/// Force and torque (about the centre of mass), world frame.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Wrench {
    pub force: DVec3,
    pub torque: DVec3,
}

impl std::ops::Add for Wrench {
    type Output = Wrench;
    fn add(self, o: Wrench) -> Wrench {
        Wrench {
            force: self.force + o.force,
            torque: self.torque + o.torque,
        }
    }
}

/// The body's constants the right-hand side needs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyConstants {
    pub mass: f64,
    pub inv_mass: f64,
    /// about the centre of mass, body axes
    pub inertia_body: DMat3,
    pub inv_inertia_body: DMat3,
    /// body_from_principal: the principal axes of `inertia_body` (moments ascending)
    pub principal: DQuat,
    /// 1 / I_k for the principal moments I₁ ≤ I₂ ≤ I₃
    pub inv_principal_moments: DVec3,
}

impl BodyConstants {
    /// Constants for mass `mass` and body inertia `inertia_body` (about the centre of mass).
    /// A non-positive or non-finite mass becomes 1; a singular inertia (a point or a rod) is
    /// regularised so ω stays finite. The principal axes are found once, here.
    pub fn new(mass: f64, inertia_body: DMat3) -> Self {
        let mass = if mass.is_finite() && mass > 0.0 {
            mass
        } else {
            1.0
        };
        let det = inertia_body.determinant();
        let inertia_body = if det.is_finite() && det.abs() > 1e-300 {
            inertia_body
        } else {
            DMat3::IDENTITY * mass.max(1e-12) * 1e-6
        };
        let axes = principal_axes(inertia_body);
        Self {
            mass,
            inv_mass: 1.0 / mass,
            inertia_body,
            inv_inertia_body: inertia_body.inverse(),
            principal: axes.rotation(),
            inv_principal_moments: 1.0 / axes.moments,
        }
    }

    /// Angular velocity ω = R I_body⁻¹ Rᵀ L (rad/s, world). `q` need not be exactly unit.
    pub fn omega(&self, q: DQuat, l: DVec3) -> DVec3 {
        let r = DMat3::from_quat(q.normalize());
        r * (self.inv_inertia_body * (r.transpose() * l))
    }

    /// Linear velocity P/M.
    pub fn velocity(&self, p: DVec3) -> DVec3 {
        p * self.inv_mass
    }
}

/// What pushes a body: the wrench on it in a given state at time `t` (seconds).
pub trait Forces {
    fn wrench(&self, body: &BodyConstants, state: &RigidState, t: f64) -> Wrench;
}

/// No forces: a free body (the tumbling-box slide).
#[derive(Debug, Clone, Copy, Default)]
pub struct NoForces;

impl Forces for NoForces {
    fn wrench(&self, _: &BodyConstants, _: &RigidState, _: f64) -> Wrench {
        Wrench::default()
    }
}

impl<F: Fn(&BodyConstants, &RigidState, f64) -> Wrench> Forces for F {
    fn wrench(&self, body: &BodyConstants, state: &RigidState, t: f64) -> Wrench {
        self(body, state, t)
    }
}

/// The integrators a body can be stepped with; switchable between steps.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
pub enum Integrator {
    /// Forward Euler on the 13 numbers (first order; a free body's energy grows).
    Euler,
    /// The midpoint method (ERRATA 3), second order.
    Midpoint,
    /// Classical RK4 (ERRATA 1), fourth order.
    #[default]
    Rk4,
    /// Kick P, L with the old state's wrench, drift x with the new P, then rotate by the
    /// symplectic splitting of the free rigid body ([`super::free_rotation`]: exact
    /// sub-rotations about the principal axes, composed symmetrically). L and |L| are kept
    /// exactly in free flight, the energy error stays bounded (no drift) and the free rotation
    /// is second order; with forces the kick–drift makes the whole step first order.
    SymplecticEuler,
}

impl Integrator {
    pub const ALL: [Integrator; 4] = [
        Integrator::Euler,
        Integrator::Midpoint,
        Integrator::Rk4,
        Integrator::SymplecticEuler,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Integrator::Euler => "Euler",
            Integrator::Midpoint => "Midpoint",
            Integrator::Rk4 => "RK4",
            Integrator::SymplecticEuler => "Symplectic Euler",
        }
    }

    /// The same method as the ODE layer names it (its CLI key, its colour).
    pub fn method(self) -> crate::ode::Method {
        match self {
            Integrator::Euler => crate::ode::Method::Euler,
            Integrator::Midpoint => crate::ode::Method::Midpoint,
            Integrator::Rk4 => crate::ode::Method::Rk4,
            Integrator::SymplecticEuler => crate::ode::Method::SymplecticEuler,
        }
    }

    /// The Butcher tableau of an explicit Runge–Kutta method (`RigidBody::step` runs the same
    /// arithmetic over fixed-size arrays; this is its reference).
    pub fn tableau(self) -> Option<Tableau> {
        match self {
            Integrator::Euler => Some(Tableau::euler()),
            Integrator::Midpoint => Some(Tableau::midpoint()),
            Integrator::Rk4 => Some(Tableau::rk4()),
            Integrator::SymplecticEuler => None,
        }
    }
}
