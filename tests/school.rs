//! The school through the public API: exact neighbour search, parallel-transport frames,
//! determinism, live count changes, staying in the water.

use glam::{Quat, Vec3};
use lectern::school::grid::{NeighbourGrid, brute_force_neighbours};
use lectern::school::rng::SplitMix64;
use lectern::school::{
    Aabb, Environment, FISH_FORWARD, FISH_UP, School, SchoolParams, transport, upright_frame,
};
use lectern::waves::{GerstnerWave, WaveSum};

#[test]
fn grid_neighbours_equal_brute_force_on_random_inputs() {
    let mut g = SplitMix64::new(42);
    let mut grid = NeighbourGrid::default();
    for trial in 0..12 {
        let n = 200 + 150 * trial;
        let bounds = Aabb::new(Vec3::new(-4.0, -2.0, -3.0), Vec3::new(4.0, 2.0, 3.0));
        // some points outside the bounds, some duplicated, some on cell boundaries
        let mut xs: Vec<f32> = (0..n).map(|_| g.range(-5.0, 5.0)).collect();
        let mut ys: Vec<f32> = (0..n).map(|_| g.range(-2.5, 2.5)).collect();
        let zs: Vec<f32> = (0..n).map(|_| g.range(-3.5, 3.5)).collect();
        xs[1] = xs[0];
        ys[1] = ys[0];
        xs[2] = 0.0;
        let radius = g.range(0.2, 1.5);
        let query = radius * g.range(0.5, 1.0);
        grid.build(&xs, &ys, &zs, &bounds, radius);
        let (mut a, mut b) = (Vec::new(), Vec::new());
        for i in 0..n {
            a.clear();
            b.clear();
            grid.neighbours(&xs, &ys, &zs, i, query, &mut a);
            brute_force_neighbours(&xs, &ys, &zs, i, query, &mut b);
            a.sort_unstable();
            assert_eq!(a, b, "trial {trial}, point {i}");
        }
    }
}

#[test]
fn grid_caps_its_cell_count_and_stays_exact() {
    let mut g = SplitMix64::new(3);
    let n = 500;
    let xs: Vec<f32> = (0..n).map(|_| g.range(-1000.0, 1000.0)).collect();
    let ys: Vec<f32> = (0..n).map(|_| g.range(-1000.0, 1000.0)).collect();
    let zs: Vec<f32> = (0..n).map(|_| g.range(-1000.0, 1000.0)).collect();
    let bounds = Aabb::new(Vec3::splat(-1000.0), Vec3::splat(1000.0));
    let mut grid = NeighbourGrid::default();
    grid.build(&xs, &ys, &zs, &bounds, 0.01);
    let [a, b, c] = grid.dims();
    assert!(a * b * c <= lectern::school::grid::MAX_CELLS);
    let (mut x, mut y) = (Vec::new(), Vec::new());
    for i in 0..n {
        x.clear();
        y.clear();
        grid.neighbours(&xs, &ys, &zs, i, 150.0_f32.min(grid.cell_size()), &mut x);
        brute_force_neighbours(&xs, &ys, &zs, i, 150.0_f32.min(grid.cell_size()), &mut y);
        x.sort_unstable();
        assert_eq!(x, y);
    }
}

/// Follows the unit tangents `headings` with the shipped transport step; returns the ups.
fn transported_ups(headings: &[Vec3]) -> Vec<Vec3> {
    let mut q = upright_frame(headings[0]);
    let mut ups = vec![q * FISH_UP];
    for &t in &headings[1..] {
        q = transport(q, t);
        assert!(
            (q * FISH_FORWARD).dot(t) > 1.0 - 1e-5,
            "the fish must face its heading"
        );
        ups.push(q * FISH_UP);
    }
    ups
}

fn tangents(path: &[Vec3]) -> Vec<Vec3> {
    path.windows(2).map(|w| (w[1] - w[0]).normalize()).collect()
}

/// Straight along +x, then an S-curve (a left turn into a right turn) in a tilted plane.
fn straight_then_s_curve() -> Vec<Vec3> {
    let mut path: Vec<Vec3> = (0..100)
        .map(|i| Vec3::new(i as f32 * 0.05, 0.0, 0.0))
        .collect();
    let plane_up = Vec3::new(0.0, 1.0, 0.4).normalize();
    let side = plane_up.cross(Vec3::X).normalize();
    let start = *path.last().unwrap();
    for i in 1..400 {
        let s = i as f32 * 0.05;
        // x(s) = s, lateral = sin: curvature changes sign at s = π (an inflection)
        let lateral = (s * 0.5).sin() * 1.5 - 0.75 * s;
        path.push(start + Vec3::X * s + side * lateral + plane_up * 0.02 * s);
    }
    path
}

#[test]
fn parallel_transport_never_flips_on_a_straight_run_and_s_curve() {
    let path = straight_then_s_curve();
    let t = tangents(&path);
    let ups = transported_ups(&t);
    for (k, w) in ups.windows(2).enumerate() {
        assert!(
            w[0].dot(w[1]) > 0.99,
            "up flipped at step {k}: {} -> {}",
            w[0],
            w[1]
        );
        assert!(
            ups[k].dot(t[k]).abs() < 1e-3,
            "up must stay normal to the heading"
        );
    }
    // the test bites: a Frenet frame's normal flips through the inflection
    let mut flips = 0;
    let mut prev_n: Option<Vec3> = None;
    for w in t.windows(2).skip(100) {
        let n = (w[1] - w[0]).try_normalize();
        if let (Some(a), Some(b)) = (prev_n, n) {
            if a.dot(b) < 0.0 {
                flips += 1;
            }
        }
        prev_n = n.or(prev_n);
    }
    assert!(
        flips >= 1,
        "the Frenet normal should flip at the inflection"
    );
}

/// Along a helix (radius a, pitch 2πb) a twist-free frame turns against the Frenet frame at
/// the torsion rate: after one turn the angle between them is 2π b/√(a² + b²).
#[test]
fn parallel_transport_along_a_helix_has_no_twist() {
    let (a, b) = (1.0f64, 0.4f64);
    let steps = 20_000;
    let pt = |u: f64| Vec3::new((a * u.cos()) as f32, (b * u) as f32, (a * u.sin()) as f32);
    let tangent = |u: f64| {
        let c = (a * a + b * b).sqrt();
        Vec3::new(
            (-a * u.sin() / c) as f32,
            (b / c) as f32,
            (a * u.cos() / c) as f32,
        )
    };
    let normal = |u: f64| Vec3::new(-(u.cos() as f32), 0.0, -(u.sin() as f32));
    let headings: Vec<Vec3> = (0..=steps)
        .map(|k| tangent(std::f64::consts::TAU * k as f64 / steps as f64))
        .collect();
    let _ = pt;
    let mut q = upright_frame(headings[0]);
    // start with up along the Frenet normal, so the angle starts at 0
    let rot = Quat::from_rotation_arc(q * FISH_UP, normal(0.0));
    q = (rot * q).normalize();
    let mut prev_up = q * FISH_UP;
    let mut max_twist: f32 = 0.0;
    for h in &headings[1..] {
        q = transport(q, *h);
        let up = q * FISH_UP;
        // no rotation about the heading: the up vector's change has no component along
        // heading × up beyond what the turn of the heading forces
        let side = h.cross(up);
        max_twist = max_twist.max((up - prev_up).dot(side).abs());
        prev_up = up;
    }
    let end_up = q * FISH_UP;
    let n = normal(std::f64::consts::TAU);
    let t = headings[steps];
    let bn = t.cross(n);
    let angle = (end_up.dot(bn) as f64).atan2(end_up.dot(n) as f64).abs();
    let expected = std::f64::consts::TAU * b / (a * a + b * b).sqrt();
    assert!(
        (angle - expected).abs() < 2e-3,
        "PT vs Frenet after one turn: {angle} vs {expected}"
    );
    assert!(max_twist < 1e-5, "per-step twist {max_twist}");
}

fn tank() -> Aabb {
    Aabb::new(Vec3::new(-10.0, -6.0, -10.0), Vec3::new(10.0, 2.0, 10.0))
}

fn waves() -> WaveSum {
    WaveSum::new(
        vec![GerstnerWave {
            direction: [1.0, 0.3],
            wavelength: 8.0,
            amplitude: 0.4,
            steepness: 0.6,
            speed: 3.0,
        }],
        0.0,
    )
}

#[test]
fn the_school_is_deterministic_and_stays_in_the_water() {
    let w = waves();
    let mut env = Environment::new(tank());
    env.surface = Some(&w);
    env.seabed_height = -5.0;
    env.flee_point = Some(Vec3::new(0.0, -2.0, 0.0));
    let params = SchoolParams {
        count: 3000,
        ..Default::default()
    };
    let mut a = School::new(&params, &env);
    let mut b = School::new(&params, &env);
    for _ in 0..120 {
        a.step(1.0 / 60.0, &env);
        b.step(1.0 / 60.0, &env);
    }
    let (ia, ib): (Vec<_>, Vec<_>) = (a.instances().collect(), b.instances().collect());
    assert_eq!(ia, ib);
    let top = w.lowest_level() as f32;
    for f in &ia {
        assert!(
            f.position.y <= top && f.position.y >= -5.0,
            "{}",
            f.position
        );
        assert!(f.position.x.abs() <= 10.0 && f.position.z.abs() <= 10.0);
        assert!((f.orientation.length() - 1.0).abs() < 1e-5);
        assert!(f.tail_phase >= 0.0 && f.tail_phase < std::f32::consts::TAU);
    }
    let other = School::new(
        &SchoolParams {
            seed: 8,
            ..params.clone()
        },
        &env,
    );
    assert_ne!(other.position(0), School::new(&params, &env).position(0));
}

#[test]
fn fish_flee_the_pointer() {
    let params = SchoolParams {
        count: 2000,
        ..Default::default()
    };
    let flee = Vec3::new(0.0, -2.0, 0.0);
    let mut env = Environment::new(tank());
    let near = |s: &School| {
        (0..s.len())
            .filter(|&i| s.position(i).distance(flee) < 1.5)
            .count()
    };
    let mut scared = School::new(&params, &env);
    let before = near(&scared);
    env.flee_point = Some(flee);
    for _ in 0..180 {
        scared.step(1.0 / 60.0, &env);
    }
    assert!(
        before >= 3 && near(&scared) <= 1,
        "{before} fish near the pointer before, {} after",
        near(&scared)
    );
}

#[test]
fn count_changes_add_and_remove_fish_deterministically() {
    let env = Environment::new(tank());
    let params = SchoolParams {
        count: 500,
        ..Default::default()
    };
    let mut s = School::new(&params, &env);
    s.step(1.0 / 60.0, &env);
    s.set_params(
        &SchoolParams {
            count: 300,
            ..params.clone()
        },
        &env,
    );
    assert_eq!(s.len(), 300);
    assert!((0..300).all(|i| s.id(i) < 300));
    s.set_params(
        &SchoolParams {
            count: 800,
            ..params.clone()
        },
        &env,
    );
    assert_eq!(s.len(), 800);
    // a new fish starts exactly as it would have in a school created that big
    let fresh = School::new(
        &SchoolParams {
            count: 800,
            ..params.clone()
        },
        &env,
    );
    let k = (0..800).find(|&i| s.id(i) == 650).unwrap();
    assert_eq!(s.position(k), fresh.position(650));
    // bad input: huge steps and NaN do not panic or poison the state
    s.step(1e9, &env);
    s.step(f32::NAN, &env);
    assert!((0..s.len()).all(|i| s.position(i).is_finite()));
}

#[test]
fn school_params_read_from_ron_with_defaults() {
    let p: SchoolParams = ron::from_str("(count: 10000, max_accel: 3.0)").unwrap();
    assert_eq!(p.count, 10000);
    assert_eq!(p.max_accel, 3.0);
    assert_eq!(p.seed, SchoolParams::default().seed);
}
