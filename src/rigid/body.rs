//! One rigid body: the 13-number state `X = (x, q, P, L)` and its derivative
//! `Ẋ = (P/M, ½ ω q, F, τ)` with `ω = R I_body⁻¹ Rᵀ L` (ERRATA 2 and 4), integrated by an
//! explicit Runge–Kutta method over a fixed-size `[f64; 13]` ([`super::step`]) or by symplectic
//! Euler with the symplectic free-rotation splitting ([`super::free_rotation`]).

use super::mass::MassProperties;
use super::state::{BodyConstants, Forces, Integrator, RigidState};
use super::step;
use crate::ode::System;
use glam::{DMat3, DQuat, DVec3};

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
