//! Scene files: the default parses; malformed RON and out-of-range values give clear errors
//! with file:line:col, never a panic or an out-of-memory; a reload keeps camera and time.

use std::path::Path;

use lectern::scene::{self, Object, SceneSim};

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
    // drop the comma after `distance: 12.0` (line 6 of the camera block)
    let text = default_text().replacen("distance: 12.0,", "distance: 12.0", 1);
    let line = text
        .lines()
        .position(|l| l.contains("distance: 12.0"))
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
    let text = default_text().replacen("count: 250", "count: -5", 1);
    let line = text.lines().position(|l| l.contains("count: -5")).unwrap() + 1;
    let d = scene::parse_scene(&text, Path::new("w.ron")).unwrap_err();
    assert_eq!(d.line, line, "{d}");
}

#[test]
fn a_billion_fish_is_rejected_before_any_allocation() {
    let text = default_text().replacen("count: 250", "count: 1000000000", 1);
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
            "material: \"wet_rock\"",
            "material: \"granite\"",
            "unknown material",
        ),
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
    let mut edited = s;
    edited.camera.distance = 99.0;
    edited.school.count = 10;
    sim.replace_scene(edited);
    assert_eq!(sim.time_secs(), 3.25);
    assert_eq!(sim.camera, cam);
    assert_eq!(sim.snapshot().fish.len(), 10);
}

#[test]
fn floating_bodies_ride_the_waves() {
    let s = scene::load_scene(Path::new(DEFAULT)).unwrap();
    let a = scene::sim::body_poses(&s, 0.0);
    let b = scene::sim::body_poses(&s, 1.3);
    assert_eq!(a.len(), 3);
    assert!(
        a.iter()
            .zip(&b)
            .any(|(p, q)| (p.position.y - q.position.y).abs() > 0.01)
    );
    for p in &a {
        assert!(
            p.position.y.abs() < 0.5,
            "a floating body sits near the surface: {p:?}"
        );
    }
}
