//! On/off tests of the scene techniques that render_scene.rs does not cover: FXAA on the
//! geometric edges, the fish's countershading and shadows, and the cheaper water normals of the
//! lower quality rungs. Each fails if its technique stops changing the picture visibly (or, for
//! the cheaper rung, starts changing it more than a little).
//!
//! Record the golden with `UPDATE_SNAPSHOTS=1 cargo test --test suite scene_techniques::`.

use std::path::Path;

use lectern::render::Headless;
use lectern::render::frame::WaterNormals;
use lectern::scene;

use crate::common;

const SIZE: (u32, u32) = (640, 360);

fn headless(shader_dir: &Path) -> Headless {
    let s = scene::load_scene(Path::new(scene::DEFAULT_SCENE)).unwrap();
    let mut h = Headless::new(s, shader_dir).unwrap();
    h.settings.caustics = false;
    h.sim.set_time(2.5);
    h
}

fn luma(p: &image::Rgba<u8>) -> i32 {
    (299 * p[0] as i32 + 587 * p[1] as i32 + 114 * p[2] as i32) / 1000
}

/// Pixels whose luma steps by more than `step` to the right or down neighbour: hard edges.
fn hard_steps(img: &image::RgbaImage, step: i32) -> Vec<(u32, u32)> {
    let (w, h) = img.dimensions();
    let mut out = Vec::new();
    for y in 0..h - 1 {
        for x in 0..w - 1 {
            let l = luma(img.get_pixel(x, y));
            let r = luma(img.get_pixel(x + 1, y));
            let d = luma(img.get_pixel(x, y + 1));
            if (l - r).abs() > step || (l - d).abs() > step {
                out.push((x, y));
            }
        }
    }
    out
}

/// Of the hard steps of `aliased` (each pixel against its right or lower neighbour, whichever
/// steps more), the fraction whose pixel in `smoothed` lies strictly between the two sides'
/// lumas by a margin: intermediate values along the edges.
fn intermediate_fraction(
    aliased: &image::RgbaImage,
    smoothed: &image::RgbaImage,
    step: i32,
) -> f64 {
    let edges = hard_steps(aliased, step);
    let between = edges
        .iter()
        .filter(|&&(x, y)| {
            let l = luma(aliased.get_pixel(x, y));
            let r = luma(aliased.get_pixel(x + 1, y));
            let d = luma(aliased.get_pixel(x, y + 1));
            let other = if (l - r).abs() >= (l - d).abs() { r } else { d };
            let (lo, hi) = (l.min(other), l.max(other));
            let s = luma(smoothed.get_pixel(x, y));
            s > lo + 4 && s < hi - 4
        })
        .count();
    between as f64 / edges.len().max(1) as f64
}

/// A silhouette against the sky: the camera low over the water, looking past the floating
/// bodies at the horizon; FXAA (on by default) blends along every edge: fewer hard steps,
/// and intermediate values where the aliased picture steps from one side to the other.
#[test]
fn fxaa_softens_the_silhouettes_against_the_sky() {
    let mut h = headless(Path::new("shaders"));
    let c = &mut h.sim.camera;
    (c.pitch_deg, c.distance, c.target) = (4.0, 6.0, glam::Vec3::new(0.0, 0.3, 0.0));
    let on = h.render(SIZE).unwrap();
    h.settings.fxaa = false;
    let off = h.render(SIZE).unwrap();
    let (steps_on, steps_off) = (hard_steps(&on, 40).len(), hard_steps(&off, 40).len());
    let between = intermediate_fraction(&off, &on, 40);
    eprintln!(
        "hard steps (luma > 40): {steps_off} without FXAA, {steps_on} with; {:.1} % of the \
         aliased edge pixels take an intermediate value with FXAA",
        100.0 * between
    );
    assert!(steps_off > 200, "the view has edges to smooth: {steps_off}");
    assert!(
        (steps_on as f64) < 0.75 * steps_off as f64,
        "FXAA left {steps_on} of {steps_off} hard steps"
    );
    assert!(between > 0.25, "{:.1} % intermediate", 100.0 * between);
    assert_eq!(intermediate_fraction(&off, &off, 40), 0.0);
    assert!(!common::scene_within_tolerance(&on, &off));
    let options = common::scene_snapshot_options(&on);
    egui_kittest::image_snapshot_options(&on, "scene-fxaa-silhouettes", &options);
}

/// The fish's shadows on the sand: switching only them off changes the seabed visibly.
#[test]
fn fish_shadows_change_the_picture() {
    let mut h = headless(Path::new("shaders"));
    let with = h.render(SIZE).unwrap();
    h.settings.fish_shadows = false;
    let without = h.render(SIZE).unwrap();
    let n = common::scene_failing_pixels(&with, &without);
    eprintln!("fish shadows off: {n} pixels differ visibly");
    assert!(!common::scene_within_tolerance(&with, &without));
    // and they are shadows: the picture gets lighter without them
    let mean = |img: &image::RgbaImage| img.pixels().map(luma).sum::<i32>() as f64;
    assert!(mean(&without) > mean(&with));
}

/// Countershading (a dark back, a light belly; fish.wgsl) seen from above: the school is
/// darker with it than with the belly's colour all round, visibly.
#[test]
fn countershading_darkens_the_fish_seen_from_above() {
    let dir = tempfile::tempdir().unwrap();
    for f in lectern::render::shaders::list(Path::new("shaders")) {
        std::fs::copy(&f, dir.path().join(f.file_name().unwrap())).unwrap();
    }
    let fish = dir.path().join("fish.wgsl");
    let text = std::fs::read_to_string(&fish).unwrap();
    let line = "let back = smoothstep(0.45, 0.8, in.uv.y);";
    assert!(text.contains(line), "fish.wgsl countershades by uv.y");
    std::fs::write(&fish, text.replace(line, "let back = 0.0;")).unwrap();
    let look_down = |h: &mut Headless| {
        let c = &mut h.sim.camera;
        (c.pitch_deg, c.distance) = (70.0, 9.0);
    };
    let mut h = headless(Path::new("shaders"));
    look_down(&mut h);
    let shaded = h.render(SIZE).unwrap();
    let mut flat = headless(dir.path());
    look_down(&mut flat);
    let plain = flat.render(SIZE).unwrap();
    let n = common::scene_failing_pixels(&shaded, &plain);
    let darker = shaded
        .pixels()
        .zip(plain.pixels())
        .filter(|(a, b)| luma(a) + 8 < luma(b))
        .count();
    let lighter = shaded
        .pixels()
        .zip(plain.pixels())
        .filter(|(a, b)| luma(a) > luma(b) + 8)
        .count();
    eprintln!(
        "countershading off: {n} pixels differ visibly; {darker} darker with it, {lighter} \
         lighter"
    );
    assert!(!common::scene_within_tolerance(&shaded, &plain));
    assert!(darker > 4 * lighter.max(1), "{darker} vs {lighter}");
}

/// The lower rungs' water normals (short waves per pixel, long ones per vertex) draw nearly
/// the same sea, and differ from it (the variants are built and chosen).
#[test]
fn fewer_waves_per_pixel_keep_the_sea_nearly_the_same() {
    let mut h = headless(Path::new("shaders"));
    let rung = scene::quality::LADDER
        .iter()
        .find(|r| r.water_normals == WaterNormals::Short6)
        .unwrap();
    h.settings.render_scale = rung.render_scale;
    let full = h.render(SIZE).unwrap();
    h.settings.water_normals = WaterNormals::Short6;
    let short6 = h.render(SIZE).unwrap();
    h.settings.water_normals = WaterNormals::Short12;
    let short12 = h.render(SIZE).unwrap();
    h.settings.water_normals = WaterNormals::PerPixel;
    h.settings.shadows = false;
    let unshadowed = h.render(SIZE).unwrap();
    let mean_diff = |a: &image::RgbaImage, b: &image::RgbaImage| {
        let sum: u64 = a
            .pixels()
            .zip(b.pixels())
            .map(|(p, q)| (0..3).map(|c| p[c].abs_diff(q[c]) as u64).sum::<u64>())
            .sum();
        sum as f64 / (3.0 * f64::from(a.width() * a.height()))
    };
    let (d6, d12, ds) = (
        mean_diff(&short6, &full),
        mean_diff(&short12, &full),
        mean_diff(&unshadowed, &full),
    );
    eprintln!(
        "mean channel difference from all waves per pixel: 6 per pixel {d6:.3}, 12 {d12:.3}; shadows off {ds:.3}"
    );
    assert!(d6 > 0.0 && d12 > 0.0, "the variants made no difference");
    assert!(
        d12 <= d6 * 1.05,
        "more waves per pixel should be closer: {d12} vs {d6}"
    );
    assert!(d6 < 0.5 * ds, "{d6} vs shadows' {ds}");
}
