//! `BodyBatch` against `RigidBody::step`, body by body.

use super::*;
use crate::rigid::{BodyConstants, NoForces, RigidBody, Wrench};
use glam::{DMat3, DQuat, DVec3};

/// A state- and time-dependent wrench, so every stage's argument matters.
fn push(mass: f64, s: &RigidState, t: f64) -> Wrench {
    Wrench {
        force: DVec3::new(0.0, -9.81, 0.0) * mass - 0.4 * s.p + DVec3::new(t.cos(), 0.0, 0.0),
        torque: DVec3::new(s.q.x, -s.q.z, 0.5 * s.q.y) * 3.0 - 0.2 * s.l,
    }
}

struct Pushy;

impl BatchForces for Pushy {
    fn wrench(&self, _first: usize, t: f64, mass: F4, s: &State4) -> [F4; 6] {
        let mut out = [F4::ZERO; 6];
        for j in 0..4 {
            let w = push(mass.0[j], &lane_state(s, j), t);
            let a = [w.force.to_array(), w.torque.to_array()].concat();
            for (o, v) in out.iter_mut().zip(a) {
                o.0[j] = v;
            }
        }
        out
    }
}

/// Seven bodies (not a multiple of four): different masses, tilted (non-diagonal) inertia.
fn bodies(method: Integrator) -> Vec<RigidBody> {
    (0..7)
        .map(|i| {
            let f = i as f64;
            let r = DMat3::from_quat(DQuat::from_euler(glam::EulerRot::XYZ, 0.3 * f, -0.2 * f, f));
            let inertia =
                r * DMat3::from_diagonal(DVec3::new(1.0 + 0.1 * f, 2.0, 3.0 + f)) * r.transpose();
            let state = RigidState {
                x: DVec3::new(f, -0.5 * f, 0.25),
                q: DQuat::from_euler(glam::EulerRot::ZYX, 0.7 - f, 0.1 * f, 0.4),
                p: DVec3::new(0.3, f, -1.0),
                l: DVec3::new(0.01 + 0.1 * f, 2.0 - 0.3 * f, 0.5),
            };
            RigidBody::new(1.0 + 0.3 * f, inertia, state).with_integrator(method)
        })
        .collect()
}

fn batch_of(bodies: &[RigidBody], method: Integrator) -> BodyBatch {
    let mut b = BodyBatch::new(method);
    for body in bodies {
        b.push(&body.constants, body.state);
    }
    b
}

fn close(a: DVec3, b: DVec3) -> bool {
    (a - b).length() <= 1e-12 * b.length().max(1e-12)
}

fn assert_same(batch: &BodyBatch, bodies: &[RigidBody], what: &str) {
    assert_eq!(batch.len(), bodies.len());
    for (i, body) in bodies.iter().enumerate() {
        let (a, b) = (batch.state(i), body.state);
        let q_ok = (a.q - b.q).length() <= 1e-12;
        assert!(
            close(a.x, b.x) && q_ok && close(a.p, b.p) && close(a.l, b.l),
            "{what}, body {i}:\\n{a:?}\\nvs\\n{b:?}"
        );
    }
}

#[test]
fn batch_matches_rigid_body_step_for_every_integrator() {
    for method in Integrator::ALL {
        for h in [1.0 / 60.0, 0.1] {
            let mut free = bodies(method);
            let mut batch = batch_of(&free, method);
            let mut pushed = bodies(method);
            let mut batch_pushed = batch_of(&pushed, method);
            for _ in 0..30 {
                free.iter_mut().for_each(|b| b.step(h, &NoForces));
                batch.step(h, &FreeBodies);
                let f = |c: &BodyConstants, s: &RigidState, t: f64| push(c.mass, s, t);
                pushed.iter_mut().for_each(|b| b.step(h, &f));
                batch_pushed.step(h, &Pushy);
            }
            assert_same(&batch, &free, &format!("{method:?} free, h = {h}"));
            assert_same(
                &batch_pushed,
                &pushed,
                &format!("{method:?} pushed, h = {h}"),
            );
            assert!((batch.time - free[0].time).abs() < 1e-12);
            if method == Integrator::SymplecticEuler {
                // the same free-rotation code, the same operations: the same bits
                for (i, b) in free.iter().enumerate() {
                    assert_eq!(batch.state(i), b.state, "body {i}");
                }
            }
        }
    }
}

#[test]
fn portable_and_avx2_kernels_agree_bit_for_bit() {
    for method in Integrator::ALL {
        let mut a = batch_of(&bodies(method), method);
        let mut b = a.clone();
        for _ in 0..20 {
            a.step(0.05, &Pushy);
            b.step_portable(0.05, &Pushy);
        }
        for i in 0..a.len() {
            assert_eq!(a.state(i), b.state(i), "{method:?} body {i}");
        }
    }
}

#[test]
fn a_blown_up_body_is_reset_and_leaves_its_neighbours_alone() {
    for method in Integrator::ALL {
        let mut list = bodies(method);
        list[2].state.l.y = f64::NAN;
        list[5].state.x.x = f64::INFINITY;
        let mut batch = batch_of(&list, method);
        for k in 0..3 {
            list.iter_mut().for_each(|b| b.step(0.02, &NoForces));
            batch.step(0.02, &FreeBodies);
            if k == 0 {
                let reset = batch.state(2);
                assert_eq!(
                    (reset.q, reset.p, reset.l),
                    (DQuat::IDENTITY, DVec3::ZERO, DVec3::ZERO)
                );
                assert_eq!(batch.state(5).x, DVec3::ZERO);
            }
        }
        assert_same(&batch, &list, &format!("{method:?}"));
        for i in [0, 1, 3, 4, 6] {
            let s = batch.state(i);
            assert!(s.l.length() > 0.1 && s.q.is_finite(), "{method:?} body {i}");
        }
    }
}

#[test]
fn bad_steps_are_ignored_and_states_round_trip() {
    let list = bodies(Integrator::Rk4);
    let mut batch = batch_of(&list, Integrator::Rk4);
    for h in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        batch.step(h, &FreeBodies);
    }
    assert_eq!(batch.time, 0.0);
    assert_same(&batch, &list, "unstepped");
    assert!(BodyBatch::new(Integrator::Euler).is_empty());
}
