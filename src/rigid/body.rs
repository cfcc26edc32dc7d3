//! One rigid body: the 13-number state `X = (x, q, P, L)` and its derivative
//! `Ẋ = (P/M, ½ ω q, F, τ)` with `ω = R I_body⁻¹ Rᵀ L` (ERRATA 2 and 4), integrated by an
//! explicit Runge–Kutta method over a fixed-size `[f64; 13]` ([`super::step`]) or by symplectic
//! Euler with the symplectic free-rotation splitting ([`super::free_rotation`]).

use super::mass::MassProperties;
use super::principal::principal_axes;
use super::step;
use crate::ode::{System, Tableau};
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

/// The body as an ODE system over its 13 numbers, for [`ExplicitRk`].
pub struct BodySystem<'a, F: ?Sized> {
    pub body: &'a BodyConstants,
    pub forces: &'a F,
}

impl<F: Forces + ?Sized> System for BodySystem<'_, F> {
    fn dim(&self) -> usize {
        RigidState::DIM
    }

    fn rhs(&self, t: f64, x: &[f64], dxdt: &mut [f64]) {
        let x: &[f64; 13] = x.try_into().expect("13 numbers");
        dxdt.copy_from_slice(&step::derivative(self.body, self.forces, t, x));
    }
}

/// `q + ½ h ω q` with or without renormalisation: the explicit-Euler quaternion update.
/// Without renormalising, ‖q‖ grows by exactly √(1 + (h|ω|/2)²) per step, since (0, ω) q is
/// orthogonal to q in ℝ⁴.
pub fn quat_euler_update(q: DQuat, omega: DVec3, h: f64, renormalise: bool) -> DQuat {
    let q_new = q + DQuat::from_xyzw(omega.x, omega.y, omega.z, 0.0) * q * (0.5 * h);
    if renormalise {
        q_new.normalize()
    } else {
        q_new
    }
}

/// A rigid body: constants, state, clock and the chosen integrator.
pub struct RigidBody {
    pub constants: BodyConstants,
    pub state: RigidState,
    /// seconds
    pub time: f64,
    pub integrator: Integrator,
}

impl RigidBody {
    /// A body with the given mass and body-space inertia about its centre of mass, at rest.
    /// A singular inertia (a point or a rod) is regularised so ω stays finite.
    pub fn new(mass: f64, inertia_body: DMat3, state: RigidState) -> Self {
        Self {
            constants: BodyConstants::new(mass, inertia_body),
            state,
            time: 0.0,
            integrator: Integrator::default(),
        }
    }

    /// A body from mass properties (inertia in the mesh's axes), its centre of mass at `x`.
    pub fn from_mass_properties(props: &MassProperties, x: DVec3, q: DQuat) -> Self {
        Self::new(props.mass, props.inertia, RigidState::at_rest(x, q))
    }

    /// A free body with mass 1, body inertia `diag(inertia_diag)`, at the origin, identity
    /// orientation, spinning with `omega_body` (rad/s): the tumbling-box slide.
    pub fn free_spinning(inertia_diag: DVec3, omega_body: DVec3, integrator: Integrator) -> Self {
        let inertia = DMat3::from_diagonal(inertia_diag);
        let mut b = Self::new(
            1.0,
            inertia,
            RigidState::at_rest(DVec3::ZERO, DQuat::IDENTITY),
        );
        b.state.l = inertia * omega_body;
        b.integrator = integrator;
        b
    }

    pub fn with_integrator(mut self, integrator: Integrator) -> Self {
        self.integrator = integrator;
        self
    }

    /// Advances by `dt_secs` under `forces` with the current integrator, then renormalises q.
    /// A non-finite or non-positive step is ignored.
    pub fn step<F: Forces + ?Sized>(&mut self, dt_secs: f64, forces: &F) {
        if !(dt_secs.is_finite() && dt_secs > 0.0) {
            return;
        }
        let h = dt_secs;
        match self.integrator {
            Integrator::SymplecticEuler => {
                step::symplectic_euler(&self.constants, forces, self.time, &mut self.state, h)
            }
            method => {
                let mut x = self.state.to_array();
                step::explicit_rk(method, &self.constants, forces, self.time, &mut x, h);
                self.state = RigidState::from_slice(&x);
            }
        }
        let q = self.state.q.normalize();
        // a blown-up state (NaN) is reset to rest rather than poisoning everything after it
        if !(q.is_finite() && self.state.x.is_finite() && self.state.p.is_finite()) {
            self.state.q = DQuat::IDENTITY;
            self.state.p = DVec3::ZERO;
            self.state.l = DVec3::ZERO;
            if !self.state.x.is_finite() {
                self.state.x = DVec3::ZERO;
            }
        } else {
            self.state.q = q;
        }
        self.time += h;
    }

    /// Centre of mass and orientation, f32 for the renderer.
    pub fn pose(&self) -> (glam::Vec3, glam::Quat) {
        (self.state.x.as_vec3(), self.state.q.as_quat())
    }

    /// Angular velocity, world (rad/s).
    pub fn omega(&self) -> DVec3 {
        self.constants.omega(self.state.q, self.state.l)
    }

    /// Angular velocity in body axes (rad/s).
    pub fn omega_body(&self) -> DVec3 {
        self.state.q.normalize().inverse() * self.omega()
    }

    /// Linear velocity (m/s).
    pub fn velocity(&self) -> DVec3 {
        self.constants.velocity(self.state.p)
    }

    /// Kinetic energy, translational + rotational: |P|²/2M + ½ L·ω (J).
    pub fn energy(&self) -> f64 {
        0.5 * self.state.p.length_squared() * self.constants.inv_mass
            + 0.5 * self.state.l.dot(self.omega())
    }

    /// Potential energy in uniform gravity `g` (m/s², e.g. (0, −9.81, 0)): −M g·x.
    pub fn potential_energy(&self, gravity: DVec3) -> f64 {
        -self.constants.mass * gravity.dot(self.state.x)
    }

    /// Angular momentum, world (kg m²/s).
    pub fn angular_momentum(&self) -> DVec3 {
        self.state.l
    }
}
