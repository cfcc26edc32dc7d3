//! The renderer on whatever adapter exists (Mesa lavapipe in CI): every shader validates, a
//! broken one is reported at its line and the old pipeline keeps drawing, and golden images of
//! the default scene and each debug view match committed PNGs within a tolerance that a
//! visible change (shadows off) exceeds.
//!
//! Record new goldens with `UPDATE_SNAPSHOTS=1 cargo test --test suite render_scene::`.

use std::path::Path;

use lectern::render::frame::ShadowFilter;
use lectern::render::{DebugView, Headless, shaders};
use lectern::scene;

use crate::common;

const SIZE: (u32, u32) = (320, 180);
/// The golden images: large enough that a fish is several pixels long.
const GOLDEN_SIZE: (u32, u32) = (640, 360);

/// The default scene with caustics off: the goldens of every other technique were recorded
/// without them (one golden and the toggle tests below have them on).
fn headless(shader_dir: &Path) -> Headless {
    let s = scene::load_scene(Path::new(scene::DEFAULT_SCENE)).unwrap();
    let mut h = Headless::new(s, shader_dir).unwrap();
    h.settings.caustics = false;
    h
}

/// Differences between two images: the fraction of pixels with any channel off by more than
/// `PIXEL_TOL`, and the mean absolute channel difference (0–255).
fn diff(a: &image::RgbaImage, b: &image::RgbaImage) -> (f64, f64) {
    assert_eq!(a.dimensions(), b.dimensions());
    let mut off = 0usize;
    let mut sum = 0u64;
    for (p, q) in a.pixels().zip(b.pixels()) {
        let d = (0..3).map(|c| p[c].abs_diff(q[c])).max().unwrap();
        sum += (0..3).map(|c| p[c].abs_diff(q[c]) as u64).sum::<u64>();
        if d > PIXEL_TOL {
            off += 1;
        }
    }
    let n = (a.width() * a.height()) as f64;
    (off as f64 / n, sum as f64 / (3.0 * n))
}

/// For the measurements below: a channel off by more than this counts a pixel as changed.
const PIXEL_TOL: u8 = 2;

/// Whether a golden recorded as `a` would accept `b` (egui_kittest's comparison; see
/// `common::scene_within_tolerance`).
fn within_tolerance(a: &image::RgbaImage, b: &image::RgbaImage) -> bool {
    common::scene_within_tolerance(a, b)
}

/// Compares with (or, under `UPDATE_SNAPSHOTS=1`, records) `tests/snapshots/scene-{name}.png`
/// through egui_kittest; a failure leaves `.new.png` and `.diff.png` beside it.
fn golden(name: &str, img: &image::RgbaImage) {
    let options = common::scene_snapshot_options(img);
    egui_kittest::image_snapshot_options(img, format!("scene-{name}"), &options);
}

#[test]
fn every_shader_validates_with_naga() {
    let files = shaders::list(Path::new("shaders"));
    assert!(files.len() >= 9, "{files:?}");
    for f in &files {
        assert_eq!(shaders::check_file(f), vec![], "{}", f.display());
        // include-only files are checked through their users; entry files fully
        let src = shaders::load(f).unwrap();
        assert!(
            src.text.lines().next().unwrap().starts_with("// "),
            "{}: header comment",
            f.display()
        );
    }
}

fn copy_shaders(dir: &Path) {
    for f in shaders::list(Path::new("shaders")) {
        std::fs::copy(&f, dir.join(f.file_name().unwrap())).unwrap();
    }
}

fn break_line(path: &Path, line: usize) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    lines[line - 1] = "    let broken = ;".into();
    std::fs::write(path, lines.join("\n")).unwrap();
}

#[test]
fn a_broken_shader_copy_reports_its_file_and_line() {
    let dir = tempfile::tempdir().unwrap();
    copy_shaders(dir.path());
    // a line inside a function body of each entry shader
    for name in ["water.wgsl", "pbr.wgsl", "sky.wgsl", "tonemap.wgsl"] {
        let path = dir.path().join(name);
        let original = std::fs::read_to_string(&path).unwrap();
        let line = original
            .lines()
            .position(|l| l.trim_start().starts_with("let "))
            .unwrap()
            + 1;
        break_line(&path, line);
        let d = shaders::check_file(&path);
        assert_eq!(d.len(), 1, "{name}");
        assert_eq!(
            (d[0].file.as_path(), d[0].line),
            (path.as_path(), line),
            "{}",
            d[0]
        );
        assert!(d[0].col > 0);
        // naga's excerpt shows the file's own line numbers, not those of the expanded text
        let here = format!("{}:{line}:", path.display());
        assert!(d[0].message.contains(&here), "{}", d[0].message);
        assert!(
            d[0].message.contains(&format!("{line} │")),
            "{}",
            d[0].message
        );
        std::fs::write(&path, original).unwrap();
    }
    // an error in an included file is reported in that file, at its own line
    let common = dir.path().join("common.wgsl");
    let line = std::fs::read_to_string(&common)
        .unwrap()
        .lines()
        .position(|l| l.contains("let d = w.direction;"))
        .unwrap()
        + 1;
    break_line(&common, line);
    let d = shaders::check_file(&dir.path().join("water.wgsl"));
    assert_eq!(
        (d[0].file.as_path(), d[0].line),
        (common.as_path(), line),
        "{}",
        d[0]
    );
}

#[test]
fn hot_reload_keeps_the_old_pipeline_on_error_and_swaps_in_the_fix() {
    let dir = tempfile::tempdir().unwrap();
    copy_shaders(dir.path());
    let mut h = headless(dir.path());
    h.sim.set_time(1.0);
    let before = h.render(SIZE).unwrap();

    // 1. a syntax error: naga rejects it, the old pipeline keeps drawing
    let water = dir.path().join("water.wgsl");
    let good = std::fs::read_to_string(&water).unwrap();
    let bad_line = good
        .lines()
        .position(|l| l.contains("let fresnel = mix("))
        .unwrap()
        + 1;
    break_line(&water, bad_line);
    assert!(h.renderer.reload_shaders(std::slice::from_ref(&water)));
    let errors: Vec<String> = h
        .renderer
        .shader_errors()
        .iter()
        .map(|d| d.to_string())
        .collect();
    assert_eq!(errors.len(), 1);
    assert!(
        errors[0].starts_with(&format!("{}:{bad_line}:", water.display())),
        "{}",
        errors[0]
    );
    let during = h.render(SIZE).unwrap();
    assert!(
        within_tolerance(&before, &during),
        "the old water pipeline must stay in use"
    );

    // 2. valid WGSL that does not fit the renderer (entry point renamed): reported at the
    //    renamed function, not by a panic
    let tonemap = dir.path().join("tonemap.wgsl");
    let tm = std::fs::read_to_string(&tonemap).unwrap();
    std::fs::write(&tonemap, tm.replace("fn fs_main(", "fn fs_renamed(")).unwrap();
    h.renderer.reload_shaders(std::slice::from_ref(&tonemap));
    assert_eq!(h.renderer.shader_errors().len(), 2);
    let renamed_line = tm.lines().position(|l| l.contains("fn fs_main(")).unwrap() + 1;
    assert!(
        h.renderer.shader_errors().iter().any(|d| d.file == tonemap
            && d.line == renamed_line
            && d.message.contains("entry point named `fs_main`")),
        "{:?}",
        h.renderer.shader_errors()
    );
    let still = h.render(SIZE).unwrap();
    assert!(within_tolerance(&before, &still));
    std::fs::write(&tonemap, tm).unwrap();
    h.renderer.reload_shaders(std::slice::from_ref(&tonemap));

    // 3. the fix (a visible one: red water) swaps in
    std::fs::write(
        &water,
        good.replace(
            "return with_normals_view(color, n, straight.rgb);",
            "return vec4f(1.0, 0.0, 0.0, 1.0);",
        ),
    )
    .unwrap();
    h.renderer.reload_shaders(std::slice::from_ref(&water));
    assert!(h.renderer.shader_errors().is_empty());
    let after = h.render(SIZE).unwrap();
    assert!(
        !within_tolerance(&before, &after),
        "the new pipeline must be in use"
    );
    let red = after
        .pixels()
        .filter(|p| p[0] > 200 && p[1] < 30 && p[2] < 30)
        .count();
    assert!(
        red > (SIZE.0 * SIZE.1 / 4) as usize,
        "water covers much of the frame: {red}"
    );
}

#[test]
fn a_saved_common_wgsl_rebuilds_only_the_techniques_of_its_own_folder() {
    // two shader folders, each with its own common.wgsl; the renderer is built from `mine`
    let (mine, other) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
    copy_shaders(mine.path());
    copy_shaders(other.path());
    let mut h = headless(mine.path());
    let line_of = |path: &Path| {
        std::fs::read_to_string(path)
            .unwrap()
            .lines()
            .position(|l| l.contains("let d = w.direction;"))
            .unwrap()
            + 1
    };
    // the other folder's namesake, broken: nothing here is rebuilt, nothing reported
    let theirs = other.path().join("common.wgsl");
    break_line(&theirs, line_of(&theirs));
    assert!(
        !h.renderer.reload_shaders(std::slice::from_ref(&theirs)),
        "a common.wgsl in another folder must not rebuild this renderer's techniques"
    );
    assert!(
        h.renderer.shader_errors().is_empty(),
        "{:?}",
        h.renderer.shader_errors()
    );
    // this folder's own, written the long way round: the same file, so its users rebuild, fail,
    // and keep their last good pipelines with the error at common.wgsl's own line
    let ours = mine.path().join("common.wgsl");
    let line = line_of(&ours);
    break_line(&ours, line);
    let written = mine.path().join("sub/../common.wgsl");
    assert!(h.renderer.reload_shaders(std::slice::from_ref(&written)));
    let errors = h.renderer.shader_errors();
    assert!(!errors.is_empty());
    for d in &errors {
        assert_eq!((d.file.as_path(), d.line), (ours.as_path(), line), "{d}");
        assert!(d.col > 0, "{d}");
    }
    assert!(h.render(SIZE).is_ok(), "the last good pipelines still draw");
}

/// The golden frames (name, image) of `h` (caustics off): two times, each debug view, and
/// one with caustics on.
fn golden_frames(h: &mut Headless) -> Vec<(String, image::RgbaImage)> {
    let mut out = Vec::new();
    for t in [0.0, 2.5] {
        h.sim.set_time(t);
        out.push((format!("t{t}"), h.render(GOLDEN_SIZE).unwrap()));
    }
    h.sim.set_time(2.5);
    for (view, name) in [
        (DebugView::ShadowMap, "shadow-map"),
        (DebugView::Normals, "normals"),
        (DebugView::EnvCube, "env-cube"),
        (DebugView::CausticsMap, "caustics-map"),
    ] {
        h.settings.debug_view = view;
        out.push((name.to_owned(), h.render(GOLDEN_SIZE).unwrap()));
    }
    h.settings.debug_view = DebugView::None;
    h.settings.caustics = true;
    out.push(("caustics-t2.5".to_owned(), h.render(GOLDEN_SIZE).unwrap()));
    out
}

#[test]
fn golden_images_of_the_default_scene_and_debug_views() {
    let mut h = headless(Path::new("shaders"));
    for (name, img) in golden_frames(&mut h) {
        golden(&name, &img);
    }
}

/// The same frames on the GL backend (`WGPU_BACKEND=gl`, llvmpipe's GL in CI: the stand-in
/// for WebGL2's GLSL) within the goldens' tolerance of the committed (Vulkan) ones.
#[test]
fn the_gl_backend_draws_the_goldens_within_their_tolerance() {
    let s = scene::load_scene(Path::new(scene::DEFAULT_SCENE)).unwrap();
    let Some(mut h) = common::gl_headless("render_scene", s, Path::new("shaders")) else {
        return;
    };
    h.settings.caustics = false;
    let mut failed = Vec::new();
    for (name, img) in golden_frames(&mut h) {
        let path = format!("tests/snapshots/scene-{name}.png");
        let want = image::open(&path).unwrap().to_rgba8();
        let failing = common::scene_failing_pixels(&want, &img);
        eprintln!(
            "GL {name}: {failing} pixels fail (at most {})",
            common::scene_max_failed_pixels(&want)
        );
        if failing > common::scene_max_failed_pixels(&want) {
            img.save(format!("target/gl-scene-{name}.png")).unwrap();
            failed.push(format!("{name}: {failing} pixels"));
        }
    }
    assert!(
        failed.is_empty(),
        "GL differs from the goldens (target/gl-scene-*.png): {failed:?}"
    );
}

/// The lower half of a frame from the default camera: seabed seen through the water (with
/// the rocks' and fish's share of it).
fn seabed(img: &image::RgbaImage) -> image::RgbaImage {
    let (w, h) = img.dimensions();
    image::imageops::crop_imm(img, 0, h / 2, w, h - h / 2).to_image()
}

/// Mean of the three channels over an image, 0–255.
fn mean_level(img: &image::RgbaImage) -> f64 {
    let sum: u64 = img
        .pixels()
        .map(|p| (0..3).map(|c| p[c] as u64).sum::<u64>())
        .sum();
    sum as f64 / (3.0 * (img.width() * img.height()) as f64)
}

/// Caustics change the seabed beyond the golden tolerance, move with the waves, and only
/// redistribute the sunlight (the area ratio keeps flat water's mean), so the seabed gets
/// brighter lines, not a brighter floor.
#[test]
fn toggling_caustics_changes_the_seabed_and_they_move_with_the_waves() {
    let mut h = headless(Path::new("shaders"));
    h.sim.set_time(2.5);
    let off = seabed(&h.render(GOLDEN_SIZE).unwrap());
    h.settings.caustics = true;
    let on = seabed(&h.render(GOLDEN_SIZE).unwrap());
    let (frac, mean) = diff(&on, &off);
    eprintln!(
        "caustics on vs off, seabed: {:.1} % of pixels off, mean diff {mean:.2}; mean level \
         {:.2} on, {:.2} off",
        frac * 100.0,
        mean_level(&on),
        mean_level(&off)
    );
    assert!(
        !within_tolerance(&on, &off),
        "caustics made no visible difference on the seabed"
    );
    assert!(
        frac > 0.2,
        "caustics lit only {:.1} % of the seabed",
        frac * 100.0
    );
    assert!(
        (mean_level(&on) - mean_level(&off)).abs() < 0.02 * mean_level(&off),
        "caustics should redistribute the light, not add it"
    );
    h.sim.set_time(2.7);
    let later = seabed(&h.render(GOLDEN_SIZE).unwrap());
    h.settings.caustics = false;
    let later_off = seabed(&h.render(GOLDEN_SIZE).unwrap());
    // the pattern moves: 0.2 s changes the lit seabed more than the unlit one
    let (moved_on, moved_off) = (diff(&later, &on).1, diff(&later_off, &off).1);
    eprintln!("0.2 s later, mean diff: {moved_on:.2} with caustics, {moved_off:.2} without");
    assert!(moved_on > 1.2 * moved_off);
}

/// The cheaper shadow filter of the lowest quality rungs keeps every shadow: drawn at those
/// rungs' render scale, against the 3×3 PCF frame it differs along shadow edges (here mostly
/// the fish's thin shadows on the sand), far less than the shadows themselves make, and it
/// does differ (the variant is built and chosen).
#[test]
fn the_bilinear_shadow_filter_keeps_the_shadows_and_changes_only_their_edges() {
    let mut h = headless(Path::new("shaders"));
    h.sim.set_time(2.5);
    let first_hard = scene::quality::LADDER
        .iter()
        .find(|r| !r.soft_shadows)
        .unwrap();
    h.settings.render_scale = first_hard.render_scale;
    let pcf = seabed(&h.render(GOLDEN_SIZE).unwrap());
    h.settings.shadow_filter = ShadowFilter::Bilinear;
    let bilinear = seabed(&h.render(GOLDEN_SIZE).unwrap());
    h.settings.shadows = false;
    let none = seabed(&h.render(GOLDEN_SIZE).unwrap());
    let (edge_frac, edge_mean) = diff(&bilinear, &pcf);
    let (shadow_frac, shadow_mean) = diff(&none, &pcf);
    eprintln!(
        "bilinear vs 3×3 PCF: {:.2} % of pixels, mean {edge_mean:.3}; no shadows vs PCF: \
         {:.2} %, mean {shadow_mean:.3}",
        edge_frac * 100.0,
        shadow_frac * 100.0
    );
    let levels = [&pcf, &bilinear, &none].map(mean_level);
    eprintln!(
        "mean level: PCF {:.2}, bilinear {:.2}, no shadows {:.2}",
        levels[0], levels[1], levels[2]
    );
    assert!(edge_mean > 0.0, "the filter made no difference at all");
    assert!(
        edge_mean < 0.5 * shadow_mean,
        "{edge_mean} vs {shadow_mean}"
    );
    // as much shadow on the sand, with crisper edges: the mean light stays where PCF has it
    let darkening = levels[2] - levels[0];
    assert!(
        (levels[1] - levels[0]).abs() < 0.1 * darkening,
        "the shadows darken by {darkening:.2} with PCF, {:.2} with one tap",
        levels[2] - levels[1]
    );
}

/// The coarse grids of the lowest rungs draw the same surfaces with a quarter of the
/// triangles: at those rungs' render scale the picture changes only slightly, and it does
/// change (the coarse lists are drawn).
#[test]
fn coarse_grids_draw_the_same_water_and_seabed_with_a_quarter_of_the_triangles() {
    let mut h = headless(Path::new("shaders"));
    h.sim.set_time(2.5);
    let rung = scene::quality::LADDER
        .iter()
        .find(|r| r.coarse_grids)
        .unwrap();
    h.settings.render_scale = rung.render_scale;
    let full = h.render(GOLDEN_SIZE).unwrap();
    h.settings.coarse_grids = true;
    let coarse = h.render(GOLDEN_SIZE).unwrap();
    h.settings.shadows = false;
    let unshadowed = h.render(GOLDEN_SIZE).unwrap();
    let (frac, mean) = diff(&coarse, &full);
    let (_, shadow_mean) = diff(&unshadowed, &coarse);
    eprintln!(
        "coarse vs full grids: {:.2} % of pixels, mean {mean:.3} (shadows off: mean \
         {shadow_mean:.3})",
        frac * 100.0
    );
    assert!(mean > 0.0, "the coarse lists made no difference at all");
    assert!(mean < 0.5 * shadow_mean, "{mean} vs {shadow_mean}");
    let r = &h.renderer;
    assert_eq!(r.water_index_count_coarse() * 4, r.water_index_count());
}

/// The tolerance is tight enough that the golden catches a missing school or a moved sun.
#[test]
fn the_golden_fails_without_the_fish_or_with_the_sun_moved() {
    let want = image::open("tests/snapshots/scene-t2.5.png")
        .unwrap()
        .to_rgba8();
    let render = |edit: &dyn Fn(&mut scene::Scene)| {
        let mut s = scene::load_scene(Path::new(scene::DEFAULT_SCENE)).unwrap();
        edit(&mut s);
        let mut h = Headless::new(s, Path::new("shaders")).unwrap();
        h.settings.caustics = false;
        h.sim.set_time(2.5);
        h.render(GOLDEN_SIZE).unwrap()
    };
    let same = render(&|_| {});
    assert!(within_tolerance(&same, &want), "the unedited scene matches");
    let no_fish = render(&|s| s.school.count = 0);
    let (n, max) = (
        common::scene_failing_pixels(&no_fish, &want),
        common::scene_max_failed_pixels(&want),
    );
    eprintln!("no fish: {n} pixels fail the golden's comparison (it allows {max})");
    assert!(
        !within_tolerance(&no_fish, &want),
        "no fish: {n} pixels fail"
    );
    // the sun 3 degrees further round: every shadow moves a little
    let moved = render(&|s| {
        let d = glam::Vec3::from(s.sun.direction);
        s.sun.direction = (glam::Quat::from_rotation_y(3f32.to_radians()) * d).to_array();
    });
    let n = common::scene_failing_pixels(&moved, &want);
    eprintln!("sun moved 3 degrees: {n} pixels fail the golden's comparison (it allows {max})");
    assert!(
        !within_tolerance(&moved, &want),
        "sun moved: {n} pixels fail"
    );
}

#[test]
fn rendering_is_deterministic_and_toggling_shadows_exceeds_the_tolerance() {
    let mut h = headless(Path::new("shaders"));
    h.sim.set_time(2.5);
    let a = h.render(SIZE).unwrap();
    let b = h.render(SIZE).unwrap();
    assert_eq!(diff(&a, &b), (0.0, 0.0), "same frame, same bytes");
    h.settings.shadows = false;
    let c = h.render(SIZE).unwrap();
    let (off, mean) = diff(&a, &c);
    assert!(
        !within_tolerance(&a, &c),
        "shadows off must change the image: {off} {mean}"
    );
    // and each other technique toggle is visible too
    h.settings.shadows = true;
    for toggle in 0..5 {
        let mut s = h.settings;
        match toggle {
            0 => s.env_map = false,
            1 => s.normal_maps = false,
            2 => s.brdf = false,
            3 => s.fresnel = false,
            _ => s.caustics = true,
        }
        let saved = std::mem::replace(&mut h.settings, s);
        let img = h.render(SIZE).unwrap();
        h.settings = saved;
        assert!(
            !within_tolerance(&a, &img),
            "toggle {toggle} made no visible difference"
        );
    }
}

#[test]
fn time_moves_the_waves_and_fish() {
    let mut h = headless(Path::new("shaders"));
    h.sim.set_time(0.0);
    let a = h.render(SIZE).unwrap();
    h.sim.set_time(0.5);
    let b = h.render(SIZE).unwrap();
    assert!(!within_tolerance(&a, &b));
}

#[test]
fn ten_thousand_fish_grow_the_instance_buffer_and_the_water_grid_follows_live_edits() {
    let mut h = headless(Path::new("shaders"));
    h.sim.scene.school.count = 3000;
    h.sim.step_once();
    h.sim.set_time(0.2);
    let a = h.render(SIZE).unwrap();
    let before = h.renderer.fish_capacity();
    assert!(before >= h.sim.fish_count() && before < 12_000, "{before}");
    h.sim.scene.school.count = 12_000;
    h.sim.step_once();
    let b = h.render(SIZE).unwrap();
    assert_eq!(h.sim.fish_count(), 12_000);
    assert!(h.renderer.fish_capacity() >= 12_000, "the buffer grew");
    assert!(!within_tolerance(&a, &b), "four times the fish must show");
    // a coarser water grid (live slider) is rebuilt, and drawn without a wgpu error
    let n = h.renderer.water_index_count();
    h.sim.scene.water.resolution = 16;
    h.render(SIZE).unwrap();
    assert!(h.renderer.water_index_count() < n / 10);
}

/// Below render scale 0.7 the caustics map is drawn at half size (the automatic quality's
/// lower rungs): the caustics still show, and going back up draws the same frame as before.
#[test]
fn caustics_follow_the_render_scale_down_and_back() {
    let mut h = headless(Path::new("shaders"));
    h.sim.set_time(2.5);
    h.settings.caustics = true;
    let full = h.render(SIZE).unwrap();
    h.settings.render_scale = 0.55;
    let low_on = seabed(&h.render(SIZE).unwrap());
    h.settings.caustics = false;
    let low_off = seabed(&h.render(SIZE).unwrap());
    let (frac, mean) = diff(&low_on, &low_off);
    assert!(
        !within_tolerance(&low_on, &low_off),
        "at scale 0.55 the caustics must still show: {frac} {mean}"
    );
    // back up, later: the lit passes must read the map drawn this frame (a bind group left on
    // an old map would show the waves of an earlier frame)
    h.settings.caustics = true;
    h.settings.render_scale = 1.0;
    h.sim.set_time(2.7);
    let again = h.render(SIZE).unwrap();
    let mut fresh = headless(Path::new("shaders"));
    fresh.settings.caustics = true;
    fresh.sim.set_time(2.7);
    let want = fresh.render(SIZE).unwrap();
    assert_eq!(
        diff(&again, &want),
        (0.0, 0.0),
        "back at full size, as drawn fresh"
    );
    assert!(!within_tolerance(&full, &want), "2.7 s differs from 2.5 s");
}

/// Blue share of a pixel: b / (r + g + b).
fn blueness(p: &image::Rgba<u8>) -> f64 {
    p[2] as f64 / (p[0] as f64 + p[1] as f64 + p[2] as f64).max(1.0)
}

fn luma(p: &image::Rgba<u8>) -> f64 {
    0.2126 * p[0] as f64 + 0.7152 * p[1] as f64 + 0.0722 * p[2] as f64
}

/// Points the camera from 60 m up towards (sin yaw, ·, cos yaw), `pitch_deg` up.
fn look_from_high(h: &mut Headless, yaw_deg: f32, pitch_deg: f32) {
    let c = &mut h.sim.camera;
    // the orbit camera's yaw and pitch place the eye; it looks back at the target, so the
    // eye goes the opposite way
    c.target = glam::Vec3::new(0.0, 60.0, 0.0);
    c.distance = 5.0;
    c.yaw_deg = yaw_deg + 180.0;
    c.pitch_deg = -pitch_deg;
}

/// Preetham's sky through the whole pipeline: looking at the sun, the sun disc (drawn by the
/// background, per pixel) is the brightest thing in the frame and at its centre; looking away
/// from it, the sky is bluer high up than at the horizon; the environment cube holds the sky
/// without the disc (its brightest texel is far below the disc's white, so reflections take
/// the sun from the specular lobe alone), and its roughest mip keeps the sharp sky's mean
/// (prefiltering only blurs it).
#[test]
fn the_sky_is_bluer_above_the_horizon_the_disc_is_at_the_sun_and_the_env_mean_is_the_sky_mean() {
    let mut h = headless(Path::new("shaders"));
    let sun = glam::Vec3::from(h.sim.scene.sun.direction).normalize();
    let sun_yaw = sun.x.atan2(sun.z).to_degrees();
    let sun_pitch = sun.y.asin().to_degrees();
    look_from_high(&mut h, sun_yaw, sun_pitch);
    let img = h.render(SIZE).unwrap();
    let (w, hgt) = img.dimensions();
    let (mut best, mut at) = (0.0, (0, 0));
    for (x, y, p) in img.enumerate_pixels() {
        if luma(p) > best {
            (best, at) = (luma(p), (x, y));
        }
    }
    let off = ((at.0 as f64 - w as f64 / 2.0).hypot(at.1 as f64 - hgt as f64 / 2.0)) as u32;
    assert!(
        off <= 4,
        "the brightest pixel {at:?} is {off} px from the sun at the centre"
    );
    assert!(best > 250.0, "the sun disc is white-hot: {best}");

    // away from the sun, looking at the horizon
    look_from_high(&mut h, sun_yaw + 180.0, 0.0);
    let img = h.render(SIZE).unwrap();
    let top = blueness(img.get_pixel(w / 2, 2));
    let horizon = blueness(img.get_pixel(w / 2, hgt / 2 - 3));
    eprintln!("blue share: {top:.3} high up, {horizon:.3} at the horizon");
    assert!(top > horizon + 0.03, "{top} vs {horizon}");

    // the env cube view: the sharp equator band against the roughest one (mip strip)
    h.settings.debug_view = DebugView::EnvCube;
    let img = h.render(GOLDEN_SIZE).unwrap();
    let (w, hgt) = img.dimensions();
    let cell = (w as f32 / 4.0).min(hgt as f32 / 3.6);
    let strip_top = (3.0 * cell) as u32 + 1;
    let band_mean = |y: u32| {
        let x0 = ((w as f32 - 4.0 * cell) / 2.0) as u32;
        let xs = x0 + 1..x0 + (4.0 * cell) as u32 - 1;
        let n = xs.len() as f64;
        xs.map(|x| luma(img.get_pixel(x, y))).sum::<f64>() / n
    };
    // the cross (faces, above the mip strip): sky only, no disc
    let brightest_in_cube = img
        .enumerate_pixels()
        .filter(|(_, y, _)| *y < strip_top)
        .map(|(_, _, p)| luma(p))
        .fold(0.0, f64::max);
    eprintln!("brightest texel of the cube view: {brightest_in_cube:.1}, the disc {best:.1}");
    assert!(
        brightest_in_cube < best - 20.0,
        "the cube holds the sun disc: {brightest_in_cube} vs the disc's {best}"
    );
    // The roughest lobe about a near-horizontal direction averages the sky and the ground
    // around the horizon: compare it with the sharp side faces' mean (elevations −45°..45°),
    // not with the sharp band at the same elevation (with a low sun the band sits on the
    // horizon's bright gradient, which a wide lobe rightly spreads out).
    let x0 = ((w as f32 - 4.0 * cell) / 2.0) as u32;
    let (y0, y1) = (cell as u32 + 1, (2.0 * cell) as u32 - 1);
    let (x0, x1) = (x0 + 1, x0 + (4.0 * cell) as u32 - 1);
    let side_faces = (y0..y1)
        .flat_map(|y| (x0..x1).map(move |x| (x, y)))
        .map(|(x, y)| luma(img.get_pixel(x, y)))
        .sum::<f64>()
        / ((y1 - y0) * (x1 - x0)) as f64;
    let sharp_band = band_mean(strip_top + 1);
    let roughest = band_mean(hgt - 2);
    eprintln!(
        "env means: {side_faces:.1} sharp side faces, {sharp_band:.1} sharp band, {roughest:.1} roughest mip"
    );
    assert!(
        (roughest - side_faces).abs() < 0.15 * side_faces,
        "prefiltering changed the sky's mean: {side_faces} → {roughest}"
    );
}

/// The water reaches the horizon: in the normals view (the sky black, the water its normal's
/// colour) every pixel below the horizon line is water, for a camera a few metres up looking
/// level, and for one looking down at the default angle. (The old 80 m slab left a black band
/// of several degrees under the horizon.)
#[test]
fn along_a_line_of_sight_through_the_horizon_every_pixel_below_it_is_water() {
    let mut h = headless(Path::new("shaders"));
    h.settings.debug_view = DebugView::Normals;
    for (eye_height, pitch) in [(3.0f32, 0.0f32), (6.0, 12.0)] {
        let c = &mut h.sim.camera;
        c.target = glam::Vec3::new(0.0, eye_height, 0.0);
        c.distance = 0.5;
        c.yaw_deg = 30.0;
        c.pitch_deg = 0.0;
        // look down by `pitch`: the eye stays at about `eye_height`
        c.pitch_deg = pitch;
        let img = h.render(SIZE).unwrap();
        let (w, hgt) = img.dimensions();
        let fov = h.sim.camera.fov_deg.to_radians();
        // the true horizon's row: `pitch` degrees above the centre
        let horizon_row =
            hgt as f32 / 2.0 - (pitch.to_radians().tan() / (fov / 2.0).tan()) * hgt as f32 / 2.0;
        let first = (horizon_row + 2.0).max(0.0) as u32;
        let mut sky_below = 0;
        for y in first..hgt {
            for x in 0..w {
                let p = img.get_pixel(x, y);
                if p[0] < 8 && p[1] < 8 && p[2] < 8 {
                    sky_below += 1;
                }
            }
        }
        assert_eq!(
            sky_below, 0,
            "eye {eye_height} m, pitch {pitch}°: {sky_below} sky pixels below the horizon row {horizon_row}"
        );
        // and the sky is there above it (the test can see the difference)
        let above = img.get_pixel(w / 2, (horizon_row - 4.0).max(0.0) as u32);
        assert!(
            above[0] < 8 && above[1] < 8 && above[2] < 8,
            "sky above: {above:?}"
        );
    }
}

/// The share of an image's pixels that differ from `background` (any channel by more than 3),
/// and the spread of their luma (p95 − p5, 0–255).
fn coverage_and_contrast(img: &image::RgbaImage, background: [u8; 3]) -> (f64, f64) {
    let mut lumas: Vec<f64> = img
        .pixels()
        .filter(|p| (0..3).any(|c| p[c].abs_diff(background[c]) > 3))
        .map(luma)
        .collect();
    let covered = lumas.len() as f64 / (img.width() * img.height()) as f64;
    if lumas.is_empty() {
        return (0.0, 0.0);
    }
    lumas.sort_by(f64::total_cmp);
    let at = |q: f64| lumas[((lumas.len() - 1) as f64 * q) as usize];
    (covered, at(0.95) - at(0.05))
}

/// The debug views fill their panel (a wide one, as on the project slides and in scene mode)
/// with what they show, and spread it over the grey levels: the shadow map zoomed to its
/// casters and stretched to their depths, the caustics map cropped to the panel, the normals
/// coloured on the geometry (the sky, black, is the only background there). The shadow view
/// of the branch before this (a centred square, mostly the pale "nothing casts" colour)
/// covered 56 % of its panel with a luma spread of 58 (now ~138); the caustics map 55 %.
#[test]
fn debug_views_fill_their_panel_with_contrast() {
    let mut h = headless(Path::new("shaders"));
    h.sim.set_time(2.5);
    // the panel colour of the map views (0.05 linear, sRGB-encoded)
    let map_background = [63, 63, 63];
    for (view, background, min_contrast) in [
        (DebugView::ShadowMap, map_background, 80.0),
        (DebugView::CausticsMap, map_background, 80.0),
        // normals are hues at one luma, mostly the water's and the sand's up: coverage only
        (DebugView::Normals, [0, 0, 0], 0.0),
    ] {
        h.settings.debug_view = view;
        if view == DebugView::Normals {
            // the draw-call slide's camera: looking down on the scene, a strip of sky on top
            let c = &mut h.sim.camera;
            c.target = glam::Vec3::new(0.0, -1.0, 0.0);
            (c.yaw_deg, c.pitch_deg, c.distance) = (30.0, 40.0, 12.0);
        }
        let img = h.render(GOLDEN_SIZE).unwrap();
        let (covered, contrast) = coverage_and_contrast(&img, background);
        eprintln!("{view:?}: {covered:.3} of the panel, contrast {contrast:.1}");
        assert!(covered >= 0.9, "{view:?} covers {covered:.3} of its panel");
        assert!(
            contrast > min_contrast,
            "{view:?}: contrast {contrast:.1} ≤ {min_contrast}"
        );
    }
}
