//! Rigid bodies through the public API: exact inertia (Mirtich), the point lattice, the free
//! body (Dzhanibekov flip, energy, |L|), the quaternion update, and floating (Archimedes).

use glam::{DMat3, DQuat, DVec3};
use lectern::rigid::{
    BuoyancySamples, Integrator, NoForces, RigidBody, RigidState, TriMesh, WaterForces, mass,
    quat_euler_update,
};
use lectern::waves::WaveSum;

fn assert_mat_close(a: DMat3, b: DMat3, tol: f64) {
    for c in 0..3 {
        for r in 0..3 {
            let (x, y) = (a.col(c)[r], b.col(c)[r]);
            assert!(
                (x - y).abs() <= tol,
                "entry ({r},{c}): {x} vs {y}\n{a}\nvs\n{b}"
            );
        }
    }
}

#[test]
fn mirtich_unit_cube() {
    let p = mass::mirtich(&TriMesh::cuboid(DVec3::ZERO, DVec3::ONE));
    assert!((p.mass - 1.0).abs() < 1e-14);
    assert!((p.center - DVec3::splat(0.5)).length() < 1e-14);
    assert_mat_close(p.inertia, DMat3::IDENTITY / 6.0, 1e-14);
}

#[test]
fn mirtich_centred_box_2x3x4() {
    let p = mass::mirtich(&TriMesh::centred_box(DVec3::new(2.0, 3.0, 4.0)));
    assert!((p.mass - 24.0).abs() < 1e-12);
    assert!(p.center.length() < 1e-14);
    assert_mat_close(
        p.inertia,
        DMat3::from_diagonal(DVec3::new(50.0, 40.0, 26.0)),
        1e-12,
    );
    // ERRATA 7: m/12 · diag(b²+c², a²+c², a²+b²), with density 3
    let q = p.with_density(3.0);
    assert_mat_close(
        q.inertia,
        DMat3::from_diagonal(DVec3::new(150.0, 120.0, 78.0)),
        1e-11,
    );
}

/// Sign convention: I = ∫(|r|²𝟙 − r rᵀ) dm, so I_xy = −∫x'y' dm = −(1/120 − 1/96) = +1/480.
#[test]
fn mirtich_corner_tetrahedron() {
    let p = mass::mirtich(&TriMesh::corner_tetrahedron());
    assert!((p.mass - 1.0 / 6.0).abs() < 1e-15);
    assert!((p.center - DVec3::splat(0.25)).length() < 1e-15);
    let (d, o) = (1.0 / 80.0, 1.0 / 480.0);
    let expected = DMat3::from_cols(
        DVec3::new(d, o, o),
        DVec3::new(o, d, o),
        DVec3::new(o, o, d),
    );
    assert_mat_close(p.inertia, expected, 1e-15);
}

#[test]
fn mirtich_is_translation_independent_and_rotates_as_r_i_rt() {
    for mesh in [
        TriMesh::corner_tetrahedron(),
        TriMesh::buoy(),
        TriMesh::bottle(),
    ] {
        let p = mass::mirtich(&mesh);
        let offset = DVec3::new(3.5, -7.25, 11.0);
        let t = mass::mirtich(&mesh.translated(offset));
        assert!((t.mass - p.mass).abs() < 1e-12 * p.mass.max(1.0));
        assert!((t.center - (p.center + offset)).length() < 1e-10);
        assert_mat_close(
            t.inertia,
            p.inertia,
            1e-10 * p.inertia.col(0).length().max(1e-3),
        );
        let r = DMat3::from_quat(DQuat::from_euler(glam::EulerRot::XYZ, 0.3, -1.1, 2.0));
        let rot = mass::mirtich(&mesh.transformed(r));
        assert!((rot.mass - p.mass).abs() < 1e-12 * p.mass.max(1.0));
        assert!((rot.center - r * p.center).length() < 1e-12);
        let scale = p.inertia.col(0).length().max(1e-6);
        assert_mat_close(rot.inertia, r * p.inertia * r.transpose(), 1e-12 * scale);
    }
}

/// Cell centres of an n³ lattice over a cube: Σ x² = m a²/12 (1 − 1/n²) exactly.
#[test]
fn point_lattice_cube_is_exact_times_one_minus_inv_n_squared() {
    let mesh = TriMesh::centred_box(DVec3::splat(2.0));
    let exact = mass::mirtich(&mesh);
    for n in [1usize, 2, 3, 7, 20] {
        let p = mass::point_lattice(&mesh, n);
        assert!(
            (p.mass - exact.mass).abs() < 1e-12,
            "n = {n}: mass {}",
            p.mass
        );
        assert!(p.center.length() < 1e-12);
        let factor = 1.0 - 1.0 / (n * n) as f64;
        assert_mat_close(p.inertia, exact.inertia * factor, 1e-11);
    }
}

#[test]
fn point_lattice_converges_on_a_buoy() {
    let mesh = TriMesh::buoy();
    let exact = mass::mirtich(&mesh);
    let coarse = mass::point_lattice(&mesh, 10);
    let fine = mass::point_lattice(&mesh, 60);
    let err = |p: &mass::MassProperties| (p.inertia.col(1).y / exact.inertia.col(1).y - 1.0).abs();
    assert!(err(&fine) < 0.02, "fine lattice error {}", err(&fine));
    assert!(
        err(&fine) < err(&coarse),
        "{} vs {}",
        err(&fine),
        err(&coarse)
    );
    assert!((fine.mass / exact.mass - 1.0).abs() < 0.02);
}

#[test]
fn shipped_meshes_are_closed_with_positive_volume() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/meshes");
    for name in ["box.obj", "buoy.obj", "bottle.obj"] {
        let mesh = TriMesh::load_obj(&dir.join(name)).unwrap();
        mesh.check_closed().unwrap();
        assert!(mass::mirtich(&mesh).mass > 0.0, "{name}");
    }
}

fn tumbling(method: Integrator) -> RigidBody {
    RigidBody::free_spinning(
        DVec3::new(1.0, 2.0, 3.0),
        DVec3::new(0.01, 1.0, 0.0),
        method,
    )
}

/// Times at which the body's ω_y crosses zero going downwards (linear interpolation).
fn downward_crossings(method: Integrator, h: f64, t_end: f64) -> Vec<f64> {
    let mut b = tumbling(method);
    let mut prev = b.omega_body().y;
    let mut out = Vec::new();
    while b.time < t_end {
        b.step(h, &NoForces);
        let w = b.omega_body().y;
        if prev > 0.0 && w <= 0.0 {
            out.push(b.time - h * w / (w - prev));
        }
        prev = w;
    }
    out
}

/// The intermediate axis flips: ω_y goes from +1 to −1 and back with period 41.509 s.
#[test]
fn dzhanibekov_flip_period() {
    let crossings = downward_crossings(Integrator::Rk4, 1.0 / 240.0, 130.0);
    assert!(crossings.len() >= 3, "{crossings:?}");
    let periods: Vec<f64> = crossings.windows(2).map(|w| w[1] - w[0]).collect();
    eprintln!("RK4 flip periods at h = 1/240: {periods:.5?}");
    for w in crossings.windows(2) {
        let period = w[1] - w[0];
        assert!((period - 41.509).abs() <= 0.01, "period {period}");
    }
    // and it really flips: ω_y reaches −1 between crossings
    let mut b = tumbling(Integrator::Rk4);
    let mut min_wy = f64::INFINITY;
    for _ in 0..(41.5 * 60.0) as usize {
        b.step(1.0 / 60.0, &NoForces);
        min_wy = min_wy.min(b.omega_body().y);
    }
    assert!(min_wy < -0.99, "min ω_y {min_wy}");
}

fn energy_drift(method: Integrator, h: f64, t_end: f64) -> (f64, RigidBody) {
    let mut b = tumbling(method);
    let e0 = b.energy();
    let mut worst: f64 = 0.0;
    let steps = (t_end / h).round() as usize;
    for _ in 0..steps {
        b.step(h, &NoForces);
        worst = worst.max((b.energy() / e0 - 1.0).abs());
    }
    (worst, b)
}

#[test]
fn rk4_keeps_energy_and_angular_momentum() {
    let l0 = tumbling(Integrator::Rk4).angular_momentum();
    let (drift, b) = energy_drift(Integrator::Rk4, 1.0 / 60.0, 30.0);
    eprintln!("RK4 max |E/E0 - 1| over 30 s at h = 1/60: {drift:e}");
    assert!(drift <= 1e-9, "RK4 energy drift {drift:e}");
    // no torque: dL/dt = 0 in every stage, so L (and |L|) is exact
    assert_eq!(b.angular_momentum(), l0);
    let (euler, _) = energy_drift(Integrator::Euler, 1.0 / 60.0, 30.0);
    eprintln!("Euler max |E/E0 - 1| over 30 s at h = 1/60: {euler:e}");
    assert!(
        euler > 1e4 * drift.max(1e-13) && euler > 1e-4,
        "Euler drift {euler:e}"
    );
    let (mid, _) = energy_drift(Integrator::Midpoint, 1.0 / 60.0, 30.0);
    let (sym, _) = energy_drift(Integrator::SymplecticEuler, 1.0 / 60.0, 30.0);
    eprintln!("Midpoint {mid:e}, symplectic Euler {sym:e}");
    assert!(mid < euler && drift < mid);
}

#[test]
fn unnormalised_quaternion_update_grows_by_the_predicted_factor() {
    let omega = DVec3::new(0.3, -1.2, 0.7);
    let h = 0.05;
    let factor = (1.0 + (h * omega.length() / 2.0).powi(2)).sqrt();
    let mut q = DQuat::from_euler(glam::EulerRot::XYZ, 0.2, 0.4, -0.1);
    for _ in 0..100 {
        let next = quat_euler_update(q, omega, h, false);
        let ratio = next.length() / q.length();
        assert!((ratio - factor).abs() < 1e-14, "ratio {ratio} vs {factor}");
        q = next;
    }
    assert!(
        q.length() > 1.01,
        "the norm must visibly drift: {}",
        q.length()
    );
    let renormalised = quat_euler_update(q.normalize(), omega, h, true);
    assert!((renormalised.length() - 1.0).abs() < 1e-15);
}

#[test]
fn shipped_update_keeps_the_quaternion_unit_for_1e5_steps() {
    for method in Integrator::ALL {
        let mut b = tumbling(method);
        let mut worst: f64 = 0.0;
        for _ in 0..100_000 {
            b.step(1.0 / 60.0, &NoForces);
            worst = worst.max((b.state.q.length() - 1.0).abs());
        }
        assert!(worst < 1e-6, "{method:?}: |q| - 1 reached {worst:e}");
    }
}

/// A box of density ρ floats with a fraction ρ/ρ_water of its height submerged.
#[test]
fn floating_box_settles_at_the_archimedes_waterline() {
    for (density, fraction) in [(500.0, 0.5), (250.0, 0.25), (750.0, 0.75)] {
        let size = DVec3::new(1.0, 0.8, 1.2);
        let mesh = TriMesh::centred_box(size);
        let unit = mass::mirtich(&mesh);
        let props = unit.with_density(density);
        let samples = BuoyancySamples::from_mesh(&mesh, &unit, unit.volume(), 8);
        let waves = WaveSum::calm(0.0);
        let forces = WaterForces {
            gravity: DVec3::new(0.0, -9.81, 0.0),
            water_density: 1000.0,
            waves: &waves,
            samples: &samples,
            linear_drag: 2.0 * props.mass,
            angular_drag: 2.0 * props.inertia.col(0).x,
            wave_time_offset: 0.0,
        };
        let mut b =
            RigidBody::from_mass_properties(&props, DVec3::new(0.0, 0.5, 0.0), DQuat::IDENTITY);
        for _ in 0..(40.0 * 60.0) as usize {
            b.step(1.0 / 60.0, &forces);
        }
        let depth = 0.0 - (b.state.x.y - size.y / 2.0);
        let measured = depth / size.y;
        eprintln!("density {density}: submerged fraction {measured:.5} (Archimedes {fraction})");
        assert!(
            (measured / fraction - 1.0).abs() < 0.03,
            "fraction {measured} vs {fraction}"
        );
        assert!(
            b.velocity().length() < 1e-3,
            "still moving: {}",
            b.velocity()
        );
    }
}

#[test]
fn a_huge_or_nan_step_does_not_panic() {
    let mut b = tumbling(Integrator::Rk4);
    b.step(1e9, &NoForces);
    b.step(f64::NAN, &NoForces);
    b.step(-1.0, &NoForces);
    assert!(b.state.q.is_finite());
}

/// Symplectic Euler's free rotation is the symplectic splitting: its energy error oscillates
/// but does not grow. A first-order Lie–Euler rotation (exp(h ω(q_n))) fails this: its error
/// grows like Euler's, ~40× from the first 30 s to the tenth.
#[test]
fn symplectic_euler_energy_error_stays_bounded_for_300_s() {
    let h = 1.0 / 60.0;
    let mut b = tumbling(Integrator::SymplecticEuler);
    let (e0, l0) = (b.energy(), b.angular_momentum());
    let (mut early, mut late, mut l_err): (f64, f64, f64) = (0.0, 0.0, 0.0);
    for i in 1..=18_000 {
        b.step(h, &NoForces);
        let err = (b.energy() / e0 - 1.0).abs();
        let t = i as f64 * h;
        if t <= 30.0 + 1e-9 {
            early = early.max(err);
        }
        if t >= 270.0 - 1e-9 {
            late = late.max(err);
        }
        l_err = l_err.max((b.angular_momentum().length() / l0.length() - 1.0).abs());
    }
    let (euler, _) = energy_drift(Integrator::Euler, h, 30.0);
    eprintln!(
        "symplectic Euler max |E/E0 - 1|: {early:.3e} over [0, 30] s, {late:.3e} over [270, 300] s; \
         Euler {euler:.3e} over 30 s; max ||L|/|L0| - 1| {l_err:.1e}"
    );
    assert!(
        late <= 2.0 * early,
        "energy error grows: {early:e} -> {late:e}"
    );
    assert!(early * 1e3 < euler, "{early:e} vs Euler {euler:e}");
    assert!(l_err <= 1e-12, "|L| drifts by {l_err:e}");
    // no torque: the world L is not touched by the rotation drift at all
    assert_eq!(b.angular_momentum(), l0);
}

/// Angle (rad) of the rotation between two orientations.
fn angle_between(a: DQuat, b: DQuat) -> f64 {
    let d = a.inverse() * b;
    2.0 * DVec3::new(d.x, d.y, d.z).length().asin()
}

fn orientation_at(method: Integrator, h: f64, t_end: f64) -> DQuat {
    let mut b = tumbling(method);
    for _ in 0..(t_end / h).round() as usize {
        b.step(h, &NoForces);
    }
    b.state.q
}

/// The free rotation is second order: halving h quarters the orientation error (against RK4
/// at h = 1/4000). The old Lie–Euler rotation measured order 1 here.
#[test]
fn symplectic_euler_free_rotation_is_second_order() {
    let t_end = 10.0;
    let reference = orientation_at(Integrator::Rk4, 1.0 / 4000.0, t_end);
    let errs: Vec<f64> = [0.1, 0.05, 0.025]
        .iter()
        .map(|&h| {
            angle_between(
                reference,
                orientation_at(Integrator::SymplecticEuler, h, t_end),
            )
        })
        .collect();
    let orders: Vec<f64> = errs.windows(2).map(|w| (w[0] / w[1]).log2()).collect();
    eprintln!("symplectic Euler rotation error at t = 10 s: {errs:?}, orders {orders:.3?}");
    for p in &orders {
        assert!((p - 2.0).abs() < 0.15, "order {p} ({errs:?})");
    }
}

/// The flip survives the symplectic map: period within 0.01 s of 41.509 s at h = 1/60
/// (measured 41.50991; RK4 at h = 1/240 gives 41.50922).
#[test]
fn symplectic_euler_shows_the_dzhanibekov_flip() {
    let crossings = downward_crossings(Integrator::SymplecticEuler, 1.0 / 60.0, 130.0);
    assert!(crossings.len() >= 3, "{crossings:?}");
    let periods: Vec<f64> = crossings.windows(2).map(|w| w[1] - w[0]).collect();
    eprintln!("symplectic Euler flip periods at h = 1/60: {periods:.5?} (exact 41.509)");
    for p in &periods {
        assert!((p - 41.509).abs() <= 0.01, "period {p}");
    }
    let mut b = tumbling(Integrator::SymplecticEuler);
    let mut min_wy = f64::INFINITY;
    for _ in 0..(41.5 * 60.0) as usize {
        b.step(1.0 / 60.0, &NoForces);
        min_wy = min_wy.min(b.omega_body().y);
    }
    assert!(min_wy < -0.99, "min ω_y {min_wy}");
}

/// A box meshed in tilted axes has a non-diagonal inertia tensor; every integrator (the
/// splitting through its principal frame) moves it exactly as the axis-aligned box, up to the
/// fixed rotation between the two body frames.
#[test]
fn tilted_inertia_moves_like_the_diagonal_one() {
    let dims = DVec3::new(2.0, 1.2, 0.5);
    let r0 = DQuat::from_euler(glam::EulerRot::XYZ, 0.7, -1.3, 0.4);
    let aligned = mass::mirtich(&TriMesh::centred_box(dims));
    let tilted = mass::mirtich(&TriMesh::centred_box(dims).transformed(DMat3::from_quat(r0)));
    assert!(
        tilted.inertia.col(0).z.abs() > 0.05,
        "not tilted: {}",
        tilted.inertia
    );
    let q1 = DQuat::from_euler(glam::EulerRot::ZYX, 0.2, 0.9, -0.3);
    let l = DVec3::new(0.05, 2.0, 0.3);
    for method in Integrator::ALL {
        // body-2 coordinates are R0 times body-1 coordinates: world_from_body2 = q1 R0⁻¹
        let state = |q| RigidState {
            x: DVec3::ZERO,
            q,
            p: DVec3::new(0.5, 0.0, 0.0),
            l,
        };
        let mut a =
            RigidBody::new(aligned.mass, aligned.inertia, state(q1)).with_integrator(method);
        let mut b = RigidBody::new(tilted.mass, tilted.inertia, state(q1 * r0.inverse()))
            .with_integrator(method);
        for _ in 0..1800 {
            a.step(1.0 / 60.0, &NoForces);
            b.step(1.0 / 60.0, &NoForces);
        }
        let angle = angle_between(a.state.q, b.state.q * r0);
        eprintln!("{method:?}: tilted vs aligned after 30 s: {angle:.2e} rad");
        assert!(angle < 1e-10, "{method:?}: {angle:e} rad");
        assert!((a.omega() - b.omega()).length() < 1e-10 * a.omega().length());
        assert!((a.state.x - b.state.x).length() < 1e-12);
    }
}
