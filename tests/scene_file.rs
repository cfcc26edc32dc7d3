//! Scene files: the default parses; malformed RON and out-of-range values give clear errors
//! with file:line:col, never a panic or an out-of-memory; a reload keeps camera and time.
//! Scene simulation (no GPU): fixed-step determinism, the real school and rigid bodies wired
//! in (fish count live, flee point, Archimedes, integrator switch at large h).

use std::path::Path;

use glam::Vec3;
use lectern::rigid::Integrator;
use lectern::scene::{self, Object, Scene, SceneSim};

const DEFAULT: &str = "scenes/water.ron";

fn default_text() -> String {
    std::fs::read_to_string(DEFAULT).unwrap()
}

#[test]
fn default_scene_parses_with_four_distinct_materials() {
    let s = scene::load_scene(Path::new(DEFAULT)).unwrap();
    assert!(s.materials.len() >= 4);
    let mut names: Vec<&str> = s.materials.iter().map(|m| m.name.as_str()).collect();
    names.dedup();
    assert_eq!(names.len(), s.materials.len());
    assert!(s.objects.iter().any(|o| matches!(o, Object::Seabed { .. })));
    assert!(
        s.objects
            .iter()
            .any(|o| matches!(o, Object::Floating { .. }))
    );
    assert!(s.school.count > 0 && !s.water.waves.is_empty());
}

#[test]
fn every_shipped_scene_checks_clean() {
    for e in std::fs::read_dir("scenes").unwrap().flatten() {
        let p = e.path();
        if p.extension().is_some_and(|x| x == "ron") {
            assert_eq!(scene::check_file(&p), vec![], "{}", p.display());
        }
    }
}

#[test]
fn malformed_ron_reports_file_line_and_column() {
    // drop the comma after `distance: 9.0` (in the camera block)
    let text = default_text().replacen("distance: 9.0,", "distance: 9.0", 1);
    let line = text
        .lines()
        .position(|l| l.contains("distance: 9.0"))
        .unwrap()
        + 2;
    let d = scene::parse_scene(&text, Path::new("scenes/bad.ron")).unwrap_err();
    assert_eq!(d.file, Path::new("scenes/bad.ron"));
    assert_eq!(d.line, line, "{d}");
    assert!(d.col > 0);
    assert!(
        d.to_string()
            .starts_with(&format!("scenes/bad.ron:{line}:")),
        "{d}"
    );
}

#[test]
fn negative_fish_count_is_a_clear_error() {
    let text = default_text().replacen("count: 450", "count: -5", 1);
    let line = text.lines().position(|l| l.contains("count: -5")).unwrap() + 1;
    let d = scene::parse_scene(&text, Path::new("w.ron")).unwrap_err();
    assert_eq!(d.line, line, "{d}");
}

#[test]
fn a_billion_fish_is_rejected_before_any_allocation() {
    let text = default_text().replacen("count: 450", "count: 1000000000", 1);
    let line = text
        .lines()
        .position(|l| l.contains("count: 1000000000"))
        .unwrap()
        + 1;
    let d = scene::parse_scene(&text, Path::new("w.ron")).unwrap_err();
    assert!(
        d.message.contains("1000000000") && d.message.contains("too many fish"),
        "{d}"
    );
    assert_eq!(d.line, line, "{d}");
}

#[test]
fn out_of_range_values_name_the_field() {
    let cases = [
        ("roughness: 0.9", "roughness: 1.5", "roughness"),
        ("wavelength: 9.0", "wavelength: -1.0", "wavelength"),
        ("wavelength: 9.0", "wavelength: NaN", "wavelength"),
        ("cube_size: 128", "cube_size: 100", "cube_size"),
        ("resolution: 192", "resolution: 100000", "resolution"),
        (
            "material: \"rock\"",
            "material: \"granite\"",
            "unknown material",
        ),
        ("turbidity: 2.2", "turbidity: 40.0", "turbidity"),
        (
            "significant_height: 0.12",
            "significant_height: -1.0",
            "significant_height",
        ),
        ("count: 24", "count: 40", "count"),
    ];
    for (from, to, needle) in cases {
        let text = default_text().replacen(from, to, 1);
        assert_ne!(text, default_text(), "{from}");
        let d = scene::parse_scene(&text, Path::new("w.ron")).unwrap_err();
        assert!(d.message.contains(needle), "{to}: {d}");
        assert!(d.line > 0, "{to}: {d}");
    }
}

#[test]
fn missing_file_is_an_error_not_a_panic() {
    let d = scene::load_scene(Path::new("scenes/does-not-exist.ron")).unwrap_err();
    assert_eq!(d.line, 0);
    assert!(d.message.contains("cannot read"));
}

#[test]
fn reloading_a_scene_keeps_camera_and_time() {
    let s = scene::load_scene(Path::new(DEFAULT)).unwrap();
    let mut sim = SceneSim::new(s.clone());
    sim.set_time(3.25);
    sim.camera.orbit(40.0, 10.0);
    let cam = sim.camera;
    let t = sim.time_secs();
    assert!((t - 3.25).abs() < 1e-5, "{t}");
    let mut edited = s;
    edited.camera.distance = 99.0;
    edited.school.count = 10;
    sim.replace_scene(edited);
    assert_eq!(sim.time_secs(), t);
    assert_eq!(sim.camera, cam);
    assert_eq!(sim.snapshot().fish.len(), 10);
}

fn small_scene() -> Scene {
    let mut s = scene::load_scene(Path::new(DEFAULT)).unwrap();
    s.school.count = 300;
    s
}

/// The lowest quality rungs step the school once every few fixed steps, by that much time: the
/// fish swim as far and stay as reproducible, the school costs a third, and the floating bodies
/// take every step as before.
#[test]
fn a_school_stepped_every_third_step_swims_alike_and_leaves_the_bodies_alone() {
    let s = small_scene();
    let run = |every: u32, t: f64| {
        let mut sim = SceneSim::new(s.clone());
        sim.set_school_every(every);
        sim.set_time(t);
        sim.snapshot()
    };
    let (every_step, every_third) = (run(1, 1.5), run(3, 1.5));
    assert_eq!(every_third, run(3, 1.5), "reproducible");
    assert_eq!(every_step.bodies, every_third.bodies, "bodies untouched");
    assert_ne!(
        every_step.fish, every_third.fish,
        "the school did step differently"
    );
    let start = run(1, 0.0);
    let centroid = |f: &[lectern::school::FishInstance]| {
        f.iter().map(|f| f.position).sum::<Vec3>() / f.len() as f32
    };
    let travelled = |f: &[lectern::school::FishInstance]| {
        f.iter()
            .zip(&start.fish)
            .map(|(a, b)| (a.position - b.position).length())
            .sum::<f32>()
            / f.len() as f32
    };
    let (d1, d3) = (travelled(&every_step.fish), travelled(&every_third.fish));
    assert!(d1 > 0.5, "the fish swam: {d1} m");
    assert!((d3 - d1).abs() < 0.1 * d1, "{d3} m vs {d1} m in 1.5 s");
    let shift = (centroid(&every_third.fish) - centroid(&every_step.fish)).length();
    assert!(shift < 0.2, "the school's centre moved {shift} m apart");
    // 90 fixed steps: 30 school steps of three steps' time; halfway through a group of three
    // the school has not moved yet
    let (a, b) = (run(3, 90.0 / 60.0), run(3, 91.0 / 60.0));
    assert_eq!(a.fish, b.fish);
    assert_ne!(a.bodies, b.bodies);
}

#[test]
fn the_state_at_time_t_does_not_depend_on_how_it_was_reached() {
    let s = small_scene();
    let mut direct = SceneSim::new(s.clone());
    direct.set_time(1.5);
    let mut in_two = SceneSim::new(s.clone());
    in_two.set_time(0.7);
    in_two.set_time(1.5);
    let mut back = SceneSim::new(s);
    back.set_time(2.5);
    back.set_time(1.5); // earlier: starts again from t = 0
    let a = direct.snapshot();
    assert_eq!(a, in_two.snapshot());
    assert_eq!(a, back.snapshot());
    // and the world really moved: fish swam, bodies moved
    let mut zero = SceneSim::new(small_scene());
    zero.set_time(0.0);
    let z = zero.snapshot();
    assert!(
        a.fish
            .iter()
            .zip(&z.fish)
            .any(|(p, q)| (p.position - q.position).length() > 0.3)
    );
    assert!(
        a.bodies
            .iter()
            .zip(&z.bodies)
            .any(|(p, q)| (p.position - q.position).length() > 0.01)
    );
}

#[test]
fn floating_bodies_ride_the_waves() {
    let mut sim = SceneSim::new(small_scene());
    // every body's height ranges over more than a centimetre within two seconds of waves
    let mut lo = [f32::INFINITY; 3];
    let mut hi = [f32::NEG_INFINITY; 3];
    for k in 0..=10 {
        sim.set_time(4.0 + 0.2 * k as f64);
        let snap = sim.snapshot();
        assert_eq!(snap.bodies.len(), 3);
        for (i, p) in snap.bodies.iter().enumerate() {
            lo[i] = lo[i].min(p.position.y);
            hi[i] = hi[i].max(p.position.y);
        }
    }
    assert!(
        (0..3).all(|i| hi[i] - lo[i] > 0.01),
        "every body bobs: heights from {lo:?} to {hi:?}"
    );
    let b = sim.snapshot();
    for p in &b.bodies {
        assert!(
            p.position.y.abs() < 0.5,
            "a floating body stays near the surface: {p:?}"
        );
        assert!(p.orientation.is_normalized());
    }
    assert!(
        sim.readouts()
            .iter()
            .all(|r| r.resets == 0 && r.angular_momentum.is_finite())
    );
}

#[test]
fn a_half_dense_box_floats_half_submerged_in_calm_water() {
    let mut s = small_scene();
    s.water.waves.clear();
    s.water.spectrum = None;
    s.school.count = 0;
    s.objects.retain(|o| !matches!(o, Object::Floating { .. }));
    s.objects.push(Object::Floating {
        material: "painted_wood".into(),
        shape: scene::Shape::Box {
            size: [1.0, 0.4, 0.8],
        },
        position: [0.0, 0.0],
        density: 500.0,
        tilt_deg: 0.0,
    });
    let mut sim = SceneSim::new(s);
    sim.set_time(12.0);
    let y = sim.snapshot().bodies[0].position.y;
    // Archimedes: half of its 0.4 m height under water, so its centre sits at the level
    assert!(y.abs() < 0.02 * 0.4 + 0.005, "centre at {y} m, level 0");
    assert!(sim.readouts()[0].kinetic_j < 1e-2);
}

#[test]
fn switching_the_integrator_at_a_large_step_changes_the_motion() {
    let run = |method: Integrator| {
        let mut s = small_scene();
        s.school.count = 0;
        s.simulation.body_h_secs = 0.15;
        s.simulation.integrator = method;
        let mut sim = SceneSim::new(s);
        sim.set_time(6.0);
        (sim.snapshot().bodies, sim.readouts())
    };
    let (rk4, rk4_r) = run(Integrator::Rk4);
    let (euler, euler_r) = run(Integrator::Euler);
    let (symp, _) = run(Integrator::SymplecticEuler);
    assert!(
        rk4_r.iter().all(|r| r.resets == 0),
        "RK4 is stable at h = 0.15: {rk4_r:?}"
    );
    let differ = |a: &[scene::BodyPose], b: &[scene::BodyPose]| {
        a.iter()
            .zip(b)
            .map(|(p, q)| (p.position - q.position).length())
            .fold(0.0, f32::max)
    };
    let e_rk4: f64 = rk4_r.iter().map(|r| r.kinetic_j).sum();
    let e_euler: f64 = euler_r.iter().map(|r| r.kinetic_j).sum();
    let euler_blew_up = euler_r.iter().any(|r| r.resets > 0);
    assert!(
        euler_blew_up || differ(&rk4, &euler) > 0.05,
        "Euler at h = 0.15 must visibly differ: {e_euler} J vs {e_rk4} J"
    );
    assert!(differ(&rk4, &symp) > 1e-3);
    // the switch is live: changing it mid-run takes effect at the next step
    let mut s = small_scene();
    s.school.count = 0;
    let mut sim = SceneSim::new(s);
    sim.set_time(1.0);
    sim.scene.simulation.integrator = Integrator::Midpoint;
    sim.step_once();
    assert_eq!(sim.integrator(), Integrator::Midpoint);
}

#[test]
fn fish_count_changes_live_up_to_ten_thousand() {
    let mut sim = SceneSim::new(small_scene());
    sim.set_time(0.5);
    sim.scene.school.count = 10_000;
    sim.step_once();
    let snap = sim.snapshot();
    assert_eq!(snap.fish.len(), 10_000);
    assert!(
        snap.fish
            .iter()
            .all(|f| f.position.is_finite() && f.orientation.is_normalized())
    );
    // fish stay in the water: below the surface, above the seabed
    assert!(
        snap.fish
            .iter()
            .all(|f| f.position.y < 0.0 && f.position.y > -3.0)
    );
    sim.scene.school.count = 50;
    sim.step_once();
    assert_eq!(sim.snapshot().fish.len(), 50);
}

#[test]
fn fish_flee_the_point_the_lecturer_sets() {
    let near = |sim: &SceneSim, p: Vec3| {
        sim.snapshot()
            .fish
            .iter()
            .filter(|f| (f.position - p).length() < 1.5)
            .count()
    };
    let p = Vec3::new(0.0, -1.2, 0.0);
    let mut calm = SceneSim::new(small_scene());
    calm.set_time(1.0);
    let mut fleeing = SceneSim::new(small_scene());
    fleeing.set_time(1.0);
    fleeing.flee_point = Some(p);
    for _ in 0..120 {
        calm.step_once();
        fleeing.step_once();
    }
    let (a, b) = (near(&calm, p), near(&fleeing, p));
    assert!(
        b * 2 < a.max(1) || (b == 0 && a > 0),
        "{b} fish near the flee point vs {a} without"
    );
}

#[test]
fn a_body_denser_than_water_is_rejected_with_its_field() {
    let text = default_text().replace("density: 300.0", "density: 7800.0");
    let d = scene::parse_scene(&text, Path::new("w.ron")).unwrap_err();
    assert!(
        d.message.contains("density") && d.message.contains("sink"),
        "{d}"
    );
    assert!(
        text.lines()
            .nth(d.line - 1)
            .unwrap()
            .contains("density: 7800.0"),
        "{d}"
    );
}

#[test]
fn range_errors_point_at_the_offending_occurrence_not_the_first() {
    let cases = [
        ("roughness: 0.45", "roughness: 1.7"), // third material
        ("material: \"rock\"", "material: \"granite\""), // first rock, not the seabed
        ("peak_wavelength: 6.0", "peak_wavelength: -2.0"), // inside the spectrum
    ];
    for (from, to) in cases {
        let text = default_text().replacen(from, to, 1);
        assert_ne!(text, default_text(), "{from}");
        let line = text.lines().position(|l| l.contains(to)).unwrap() + 1;
        let d = scene::parse_scene(&text, Path::new("w.ron")).unwrap_err();
        assert_eq!(d.line, line, "{to}: {d}");
        // at the value itself, after `name: `
        let value_at = to.find(": ").unwrap() + 2;
        let col = text.lines().nth(line - 1).unwrap().find(to).unwrap() + value_at + 1;
        assert_eq!(d.col, col, "{to}: {d}");
    }
}

/// A scene file that leaves a section out gets what the shipped scene has.
#[test]
fn the_code_defaults_are_the_shipped_scene() {
    let s = scene::load_scene(std::path::Path::new(scene::DEFAULT_SCENE)).unwrap();
    assert_eq!(s.sky, scene::model::Sky::default());
    assert_eq!(s.simulation, scene::Simulation::default());
    assert_eq!(s.school, scene::model::default_school());
    assert_eq!(s.quality, scene::Quality::default());
}
