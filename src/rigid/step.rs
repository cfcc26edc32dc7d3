//! One body's step over a fixed-size `[f64; 13]` state: the right-hand side, Euler, midpoint
//! and RK4 with their stages in registers (no heap, no run-time tableau), and symplectic Euler
//! with the free-rotation splitting.
//!
//! The RK arithmetic is [`crate::ode::ExplicitRk`]'s with the same tableau, expression for
//! expression (`x + (h a) k` per stage, `x += (h b) k` per weight, zero entries skipped), so
//! results are bit-identical to it (tested).

use super::free_rotation;
use super::state::{BodyConstants, Forces, Integrator, RigidState};
use glam::DQuat;

/// `Ẋ = (P/M, ½ ω q, F, τ)` with `ω = R I_body⁻¹ Rᵀ L` (ERRATA 2, 4).
#[inline(always)]
pub fn derivative<F: Forces + ?Sized>(
    c: &BodyConstants,
    forces: &F,
    t: f64,
    x: &[f64; 13],
) -> [f64; 13] {
    let s = RigidState::from_slice(x);
    let v = c.velocity(s.p);
    let w = c.omega(s.q, s.l);
    // ½ ω q: the quaternion product of the pure quaternion (0, ω) with q
    let q_dot = DQuat::from_xyzw(w.x, w.y, w.z, 0.0) * s.q * 0.5;
    let wrench = forces.wrench(c, &s, t);
    let (f, tau) = (wrench.force, wrench.torque);
    [
        v.x, v.y, v.z, q_dot.x, q_dot.y, q_dot.z, q_dot.w, f.x, f.y, f.z, tau.x, tau.y, tau.z,
    ]
}

/// `x + ha · k` (one stage's argument).
#[inline(always)]
fn stage(x: &[f64; 13], ha: f64, k: &[f64; 13]) -> [f64; 13] {
    std::array::from_fn(|i| x[i] + ha * k[i])
}

/// `x += hb · k` (one weight of the update).
#[inline(always)]
fn accumulate(x: &mut [f64; 13], hb: f64, k: &[f64; 13]) {
    for i in 0..13 {
        x[i] += hb * k[i];
    }
}

/// One step of Euler, midpoint or RK4 from `t` to `t + h`, in place (q not renormalised).
/// `SymplecticEuler` is not an RK method: it leaves `x` untouched (use [`symplectic_euler`]).
#[inline]
pub fn explicit_rk<F: Forces + ?Sized>(
    method: Integrator,
    c: &BodyConstants,
    forces: &F,
    t: f64,
    x: &mut [f64; 13],
    h: f64,
) {
    let f = |t: f64, x: &[f64; 13]| derivative(c, forces, t, x);
    match method {
        Integrator::Euler => {
            let k1 = f(t + 0.0 * h, x);
            accumulate(x, h * 1.0, &k1);
        }
        Integrator::Midpoint => {
            let k1 = f(t + 0.0 * h, x);
            let k2 = f(t + 0.5 * h, &stage(x, h * 0.5, &k1));
            accumulate(x, h * 1.0, &k2);
        }
        Integrator::Rk4 => {
            let k1 = f(t + 0.0 * h, x);
            let k2 = f(t + 0.5 * h, &stage(x, h * 0.5, &k1));
            let k3 = f(t + 0.5 * h, &stage(x, h * 0.5, &k2));
            let k4 = f(t + 1.0 * h, &stage(x, h * 1.0, &k3));
            accumulate(x, h * (1.0 / 6.0), &k1);
            accumulate(x, h * (1.0 / 3.0), &k2);
            accumulate(x, h * (1.0 / 3.0), &k3);
            accumulate(x, h * (1.0 / 6.0), &k4);
        }
        Integrator::SymplecticEuler => {}
    }
}

/// Symplectic Euler for a rigid body: P += h F, L += h τ (the old state's wrench), x += h P/M
/// with the new P, then the free-rotation splitting with the new L (q left unnormalised).
#[inline]
pub fn symplectic_euler<F: Forces + ?Sized>(
    c: &BodyConstants,
    forces: &F,
    t: f64,
    s: &mut RigidState,
    h: f64,
) {
    let wr = forces.wrench(c, s, t);
    s.p += h * wr.force;
    s.l += h * wr.torque;
    s.x += h * c.velocity(s.p);
    // the map assumes a unit q; after a step it is one, but a caller may set any state
    let q = if (s.q.length_squared() - 1.0).abs() > 1e-14 {
        s.q.normalize()
    } else {
        s.q
    };
    let q_new = free_rotation::drift(
        q.to_array(),
        s.l.to_array(),
        c.principal.to_array(),
        c.inv_principal_moments.to_array(),
        h,
    );
    s.q = DQuat::from_array(q_new);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ode::ExplicitRk;
    use crate::rigid::{BodySystem, NoForces, Wrench};
    use glam::{DMat3, DVec3};

    /// A state-, time-dependent wrench so every stage's argument matters.
    fn pushy(c: &BodyConstants, s: &RigidState, t: f64) -> Wrench {
        Wrench {
            force: DVec3::new(0.0, -9.81, 0.0) * c.mass - 0.3 * c.velocity(s.p)
                + DVec3::new(t.sin(), 0.0, 0.0),
            torque: DVec3::new(s.q.x, -s.q.z, s.q.y) * 2.0 - 0.1 * c.omega(s.q, s.l),
        }
    }

    #[test]
    fn fixed_size_rk_is_bit_identical_to_explicit_rk() {
        let inertia = DMat3::from_cols(
            DVec3::new(2.0, 0.3, -0.1),
            DVec3::new(0.3, 1.5, 0.2),
            DVec3::new(-0.1, 0.2, 3.0),
        );
        let c = BodyConstants::new(2.5, inertia);
        let x0 = RigidState {
            x: DVec3::new(0.1, 2.0, -0.3),
            q: DQuat::from_euler(glam::EulerRot::XYZ, 0.4, -1.0, 2.2),
            p: DVec3::new(1.0, -0.5, 0.25),
            l: DVec3::new(0.2, 3.0, -1.0),
        }
        .to_array();
        for method in [Integrator::Euler, Integrator::Midpoint, Integrator::Rk4] {
            let mut rk = ExplicitRk::new(method.tableau().unwrap(), 13);
            for (h, t) in [(1.0 / 60.0, 0.0), (0.37, 3.1), (1e-5, -2.0)] {
                let (mut a, mut b) = (x0, x0);
                for i in 0..5 {
                    let ti = t + i as f64 * h;
                    let sys = BodySystem {
                        body: &c,
                        forces: &pushy,
                    };
                    rk.step(&sys, ti, &mut a, h);
                    explicit_rk(method, &c, &pushy, ti, &mut b, h);
                }
                assert_eq!(a, b, "{method:?}, h = {h}");
                let sys = BodySystem {
                    body: &c,
                    forces: &NoForces,
                };
                let (mut a, mut b) = (x0, x0);
                rk.step(&sys, t, &mut a, h);
                explicit_rk(method, &c, &NoForces, t, &mut b, h);
                assert_eq!(a, b, "{method:?} free, h = {h}");
            }
        }
    }
}
