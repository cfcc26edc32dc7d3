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

/// The boids rule written plainly over all pairs: the reference for the vectorised pass.
fn brute_force_steering(s: &School, env: &Environment, i: usize) -> Vec3 {
    let p = s.params();
    let (pos, vel) = (s.position(i), s.velocity(i));
    let (mut count, mut v_sum, mut d_sum, mut sep) = (0.0f32, Vec3::ZERO, Vec3::ZERO, Vec3::ZERO);
    let school = p.school_of(s.id(i));
    for j in (0..s.len()).filter(|&j| j != i && p.school_of(s.id(j)) == school) {
        let d = s.position(j) - pos;
        let d2 = d.length_squared();
        if d2 > 0.0 && d2 < p.neighbour_radius * p.neighbour_radius {
            count += 1.0;
            v_sum += s.velocity(j);
            d_sum += d;
        }
        if d2 > 0.0 && d2 < p.separation_radius * p.separation_radius {
            sep -= d / d2;
        }
    }
    let mut a = sep * p.separation_weight;
    if count > 0.0 {
        a += (v_sum / count - vel) * p.alignment_weight + d_sum / count * p.cohesion_weight;
    }
    let (lo, hi) = env.swim_box();
    let (centre, _) = p.school_centre(school, s.time_secs(), (lo, hi));
    a += ((centre - pos) * p.goal_weight).clamp_length_max(0.5 * p.max_accel);
    let m = p.bounds_margin;
    let into_lo = ((lo + Vec3::splat(m) - pos) / m).max(Vec3::ZERO);
    let into_hi = ((pos - (hi - Vec3::splat(m))) / m).max(Vec3::ZERO);
    a += (into_lo - into_hi) * p.bounds_weight * p.max_speed;
    if let Some(f) = env.flee_point {
        let d = pos - f;
        if d.length() < p.flee_radius {
            a += d.normalize() * p.flee_weight * p.max_speed * (1.0 - d.length() / p.flee_radius);
        }
    }
    a.clamp_length_max(p.max_accel)
}

#[test]
fn vectorised_steering_equals_the_brute_force_boids_rule() {
    let mut env = Environment::new(tank());
    env.flee_point = Some(Vec3::new(1.0, -2.0, 0.5));
    // dense enough that runs are longer than one SIMD chunk, with a few close pairs; three
    // schools that must not see each other, each pulled to its centre
    let params = SchoolParams {
        count: 1500,
        separation_radius: 0.5,
        max_accel: 1e3,
        schools: 3,
        goal_weight: 0.7,
        ..Default::default()
    };
    let mut s = School::new(&params, &env);
    s.step(1.0 / 60.0, &env);
    s.rebuild_grid(&env);
    s.compute_steering(&env);
    let mut worst = 0.0f32;
    for i in 0..s.len() {
        let want = brute_force_steering(&s, &env, i);
        let got = s.acceleration(i);
        let err = (got - want).length() / want.length().max(1.0);
        worst = worst.max(err);
    }
    // f32 sums in another order: agreement to rounding, not bit for bit
    assert!(worst < 1e-4, "worst relative difference {worst:e}");
}

#[test]
fn integration_keeps_the_heading_on_the_velocity_and_the_frame_unit() {
    let env = Environment::new(tank());
    let mut s = School::new(
        &SchoolParams {
            count: 777, // not a multiple of any SIMD width
            ..Default::default()
        },
        &env,
    );
    for _ in 0..60 {
        s.step(1.0 / 60.0, &env);
    }
    let p = s.params().clone();
    for f in s.instances().zip(0..s.len()) {
        let (inst, i) = f;
        let v = s.velocity(i);
        let heading = inst.orientation * FISH_FORWARD;
        assert!(
            heading.dot(v.normalize()) > 1.0 - 1e-5,
            "fish {i}: {heading} vs {v}"
        );
        assert!((inst.orientation.length() - 1.0).abs() < 1e-6);
        assert!(v.length() >= p.min_speed * 0.9999 && v.length() <= p.max_speed * 1.0001);
    }
}

#[test]
fn a_reversed_heading_turns_half_way_round_the_fish_own_up_axis() {
    let q = upright_frame(Vec3::new(1.0, 0.2, -0.3));
    let (f, up) = (q * FISH_FORWARD, q * FISH_UP);
    let r = transport(q, -f);
    assert!(
        (r * FISH_FORWARD + f).length() < 1e-5,
        "{}",
        r * FISH_FORWARD
    );
    assert!(
        (r * FISH_UP - up).length() < 1e-5,
        "the back flipped: {}",
        r * FISH_UP
    );
    // a NaN heading does not poison the frame
    let bad = transport(q, Vec3::NAN);
    assert!(bad.is_finite() && (bad.length() - 1.0).abs() < 1e-6);
}

/// Mean distance from each point to its nearest other point (brute force).
fn mean_nearest_neighbour(points: &[Vec3]) -> f32 {
    let total: f32 = points
        .iter()
        .enumerate()
        .map(|(i, p)| {
            points
                .iter()
                .enumerate()
                .filter(|&(j, _)| j != i)
                .map(|(_, q)| p.distance(*q))
                .fold(f32::INFINITY, f32::min)
        })
        .sum();
    total / points.len() as f32
}

/// The shipped scene's schools after 20 s: each a tight, aligned school, not a carpet.
/// Clark–Evans ratio: the school's mean nearest-neighbour distance over that of the same number
/// of fish spread uniformly through the swim box (measured, not the Poisson formula, so the
/// box's edges count alike). Polarisation: |mean unit heading|.
#[test]
fn the_scene_schools_are_clustered_and_polarised_and_miss_the_seabed_and_rocks() {
    use lectern::scene::{self, sim};
    let scene = scene::load_scene(std::path::Path::new(scene::DEFAULT_SCENE)).unwrap();
    let waves = scene.water.wave_sum();
    let obstacles = sim::rock_obstacles(&scene);
    let env = sim::environment(&scene, &waves, None, &obstacles);
    let p = scene.school.clone();
    assert!(
        p.school_count() >= 3,
        "several schools: {}",
        p.school_count()
    );
    let mut s = School::new(&p, &env);
    // the rocks' real meshes: the farthest vertex of each from its centre
    let rocks: Vec<(Vec3, f32)> = scene
        .objects
        .iter()
        .filter_map(|o| match o {
            scene::model::Object::Rock {
                position,
                radius,
                seed,
                ..
            } => {
                let m = lectern::render::mesh::rock(*radius, *seed);
                let reach = m.positions.iter().map(|v| v.length()).fold(0.0, f32::max);
                Some((Vec3::from(*position), reach))
            }
            _ => None,
        })
        .collect();
    assert!(!rocks.is_empty());
    let seabed_top = env.swim_box().0.y;
    let dt = scene.simulation.dt_secs;
    for step in 0..1200 {
        s.step(dt, &env);
        if step % 20 == 0 {
            for i in 0..s.len() {
                let x = s.position(i);
                assert!(
                    x.y >= seabed_top - 1e-4,
                    "step {step}: fish {i} in the seabed at {x}"
                );
                for &(c, reach) in &rocks {
                    assert!(
                        x.distance(c) > reach,
                        "step {step}: fish {i} at {x} inside the rock at {c} (reach {reach})"
                    );
                }
            }
        }
    }
    let (lo, hi) = env.swim_box();
    for k in 0..p.school_count() {
        let members: Vec<usize> = (0..s.len())
            .filter(|&i| p.school_of(s.id(i)) == k)
            .collect();
        let points: Vec<Vec3> = members.iter().map(|&i| s.position(i)).collect();
        let mut g = SplitMix64::new(99 + k as u64);
        let uniform: Vec<Vec3> = (0..points.len())
            .map(|_| {
                Vec3::new(
                    g.range(lo.x, hi.x),
                    g.range(lo.y, hi.y),
                    g.range(lo.z, hi.z),
                )
            })
            .collect();
        let ratio = mean_nearest_neighbour(&points) / mean_nearest_neighbour(&uniform);
        let heading: Vec3 = members
            .iter()
            .map(|&i| s.velocity(i).normalize())
            .sum::<Vec3>()
            / members.len() as f32;
        let polarisation = heading.length();
        eprintln!(
            "school {k}: {} fish, Clark–Evans ratio {ratio:.3}, polarisation {polarisation:.3}",
            members.len()
        );
        assert!(ratio < 0.5, "school {k}: Clark–Evans ratio {ratio}");
        assert!(
            polarisation > 0.8,
            "school {k}: polarisation {polarisation}"
        );
    }
}

/// The same count scattered uniformly with random headings (the classic boids' start) is
/// neither: the measure above can fail.
#[test]
fn a_scattered_school_fails_the_school_measures() {
    let env = Environment::new(tank());
    let p = SchoolParams {
        count: 300,
        ..Default::default()
    };
    let s = School::new(&p, &env);
    let heading: Vec3 = (0..s.len())
        .map(|i| s.velocity(i).normalize())
        .sum::<Vec3>()
        / s.len() as f32;
    assert!(
        heading.length() < 0.3,
        "random headings: {}",
        heading.length()
    );
}
