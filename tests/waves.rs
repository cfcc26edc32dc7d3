//! The Gerstner sum on the CPU: heights at world points invert the horizontal displacement,
//! the analytic normal matches finite differences, a calm sea is flat.

use glam::{DVec2, DVec3};
use lectern::waves::{GRAVITY, GerstnerWave, WaveSpectrum, WaveSum};

fn sea() -> WaveSum {
    WaveSum::new(
        vec![
            GerstnerWave {
                direction: [1.0, 0.0],
                wavelength: 9.0,
                amplitude: 0.35,
                steepness: 0.8,
                speed: 3.7,
            },
            GerstnerWave {
                direction: [0.6, 0.8],
                wavelength: 4.0,
                amplitude: 0.12,
                steepness: 0.7,
                speed: 2.5,
            },
            GerstnerWave {
                direction: [-0.3, 1.0],
                wavelength: 2.3,
                amplitude: 0.05,
                steepness: 0.5,
                speed: 1.9,
            },
        ],
        0.5,
    )
}

#[test]
fn height_at_a_world_point_is_on_the_displaced_surface() {
    let w = sea();
    assert!(w.horizontal_steepness() < 1.0);
    for k in 0..200 {
        let rest = DVec2::new(
            (k as f64 * 0.731).sin() * 20.0,
            (k as f64 * 1.37).cos() * 20.0,
        );
        let t = k as f64 * 0.1;
        let p = w.surface_point(rest, t);
        let h = w.height(DVec2::new(p.x, p.z), t);
        assert!(
            (h - p.y).abs() < 1e-4,
            "at {rest}: height {h} vs surface {}",
            p.y
        );
        assert!(h >= w.lowest_level() && h <= w.highest_level());
    }
}

#[test]
fn analytic_normal_matches_finite_differences() {
    let w = sea();
    let e = 1e-5;
    for k in 0..50 {
        let rest = DVec2::new(k as f64 * 0.37, -(k as f64) * 0.21);
        let t = 1.3 + k as f64 * 0.05;
        let dx = (w.surface_point(rest + DVec2::X * e, t)
            - w.surface_point(rest - DVec2::X * e, t))
            / (2.0 * e);
        let dz = (w.surface_point(rest + DVec2::Y * e, t)
            - w.surface_point(rest - DVec2::Y * e, t))
            / (2.0 * e);
        let numeric = dz.cross(dx).normalize();
        let n = w.normal(rest, t);
        assert!((n - numeric).length() < 1e-6, "{n} vs {numeric}");
        assert!(n.y > 0.0);
    }
}

#[test]
fn a_single_wave_normal_is_gpu_gems_eq_12() {
    let w = WaveSum::new(vec![sea().waves[0].clone()], 0.0);
    let (k, a, q_a) = (
        std::f64::consts::TAU / 9.0,
        0.35f64,
        0.8 / (std::f64::consts::TAU / 9.0),
    );
    for i in 0..20 {
        let rest = DVec2::new(i as f64 * 0.4, 0.0);
        let theta = k * rest.x - k * 3.7 * 0.7;
        let gems = DVec3::new(-k * a * theta.cos(), 1.0 - q_a * k * theta.sin(), 0.0).normalize();
        assert!((w.normal(rest, 0.7) - gems).length() < 1e-6);
    }
}

#[test]
fn crests_move_along_the_wave_direction() {
    let w = WaveSum::new(
        vec![GerstnerWave {
            direction: [0.0, 1.0],
            wavelength: 10.0,
            amplitude: 0.2,
            steepness: 0.0,
            speed: 2.0,
        }],
        0.0,
    );
    // the crest at z = 2.5 (θ = π/2) at t = 0 is at z = 4.5 one second later
    assert!((w.height(DVec2::new(0.0, 2.5), 0.0) - 0.2).abs() < 1e-6);
    assert!((w.height(DVec2::new(0.0, 4.5), 1.0) - 0.2).abs() < 1e-6);
}

#[test]
fn calm_water_is_flat() {
    let w = WaveSum::calm(-1.0);
    assert_eq!(w.height(DVec2::new(3.0, 4.0), 10.0), -1.0);
    assert_eq!(w.normal_at(DVec2::new(3.0, 4.0), 10.0), DVec3::Y);
    let junk = WaveSum::new(
        vec![GerstnerWave {
            direction: [0.0, 0.0],
            wavelength: 0.0,
            amplitude: f32::NAN,
            steepness: 5.0,
            speed: f32::INFINITY,
        }],
        0.0,
    );
    assert!(junk.height(DVec2::new(1.0, 1.0), 1.0).is_finite());
}

/// The JONSWAP wind sea: seeded (same file, same sea), its significant height the one asked
/// for, deep-water speeds, the biggest waves near the peak wavelength, directions spread about
/// the wind, and never looping crests (Σ Q k A < 1, which the height iteration relies on).
#[test]
fn the_spectrum_is_seeded_scaled_to_its_height_and_spread_about_the_wind() {
    let spec = WaveSpectrum::default();
    let waves = spec.waves();
    assert_eq!(waves.len(), spec.count as usize);
    assert_eq!(waves, spec.waves(), "the same seed gives the same sea");
    let other = WaveSpectrum {
        seed: spec.seed + 1,
        ..spec.clone()
    };
    assert_ne!(waves, other.waves(), "another seed, another sea");
    let m0: f64 = waves
        .iter()
        .map(|w| (w.amplitude as f64).powi(2) / 2.0)
        .sum();
    let hs = 4.0 * m0.sqrt();
    assert!(
        (hs - spec.significant_height as f64).abs() < 1e-4,
        "H_s {hs} for {}",
        spec.significant_height
    );
    for w in &waves {
        let k = std::f64::consts::TAU / w.wavelength as f64;
        let c = (GRAVITY / k).sqrt();
        assert!(
            (w.speed as f64 - c).abs() < 1e-3 * c,
            "{w:?}: deep water c = {c}"
        );
    }
    let biggest = waves
        .iter()
        .max_by(|a, b| a.amplitude.total_cmp(&b.amplitude))
        .unwrap();
    let ratio = biggest.wavelength / spec.peak_wavelength;
    assert!(
        (0.6..=1.6).contains(&ratio),
        "the biggest wave is {ratio}× the peak"
    );
    // shorter than the peak: a broad range of lengths (an irregular sea, not a lattice)
    let shortest = waves
        .iter()
        .map(|w| w.wavelength)
        .fold(f32::INFINITY, f32::min);
    assert!(
        shortest < 0.15 * spec.peak_wavelength,
        "shortest {shortest}"
    );
    let wind = glam::Vec2::from(spec.wind_direction).normalize();
    let mean_cos: f32 = waves
        .iter()
        .map(|w| glam::Vec2::from(w.direction).normalize().dot(wind))
        .sum::<f32>()
        / waves.len() as f32;
    assert!(
        mean_cos > 0.7 && mean_cos < 0.99,
        "spread about the wind: mean cos {mean_cos}"
    );
    let sum = WaveSum::new(waves, 0.0);
    assert!(sum.horizontal_steepness() < 1.0);
    // and the sum is the same Gerstner function: heights at world points sit on the surface
    let p = DVec2::new(1.3, -0.4);
    let h = sum.height(p, 2.0);
    let rest = sum.rest_point_under(p, 2.0);
    let on = sum.surface_point(rest, 2.0);
    assert!((DVec2::new(on.x, on.z) - p).length() < 1e-6 && (on.y - h).abs() < 1e-9);
}

/// `height` and `rest_point_under` sum only the terms they need (cosines in the iteration, the
/// sine once after): bit for bit what the definition through `displacement` gives, on the
/// shipped scene's 24-wave sea and on the three-wave one, at points and times all over.
#[test]
fn the_height_query_is_exactly_the_displacement_definition() {
    use lectern::waves::HEIGHT_ITERATIONS;
    let by_definition = |s: &WaveSum, q: DVec2, t: f64| {
        let mut p0 = q;
        for _ in 0..HEIGHT_ITERATIONS {
            let d = s.displacement(p0, t);
            p0 = q - DVec2::new(d.x, d.z);
        }
        (p0, s.mean_level as f64 + s.displacement(p0, t).y)
    };
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let shipped = lectern::scene::load_scene(&root.join("scenes/water.ron"))
        .unwrap()
        .water
        .wave_sum();
    assert!(shipped.waves.len() >= 20, "{}", shipped.waves.len());
    for s in [shipped, sea()] {
        for i in 0..400 {
            let q = DVec2::new(-20.0 + 0.1 * i as f64, 7.0 * (0.37 * i as f64).sin());
            let t = 0.013 * i as f64;
            let (p0, y) = by_definition(&s, q, t);
            assert_eq!(s.rest_point_under(q, t), p0, "at {q}, t = {t}");
            assert_eq!(s.height(q, t), y, "at {q}, t = {t}");
        }
    }
}
