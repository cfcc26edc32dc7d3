//! The water scene in the exported page (issue #25), in the same headless Chromium as
//! [`super::web_player`]: a slide's live Scene widget against `render-scene`, a toggle, an orbit,
//! `Tab` for scene mode, and a browser without WebGL2, which gets a note and the exported still.

use std::path::Path;
use std::process::Command;

use lectern::deck::load_deck;

use crate::web_player::{SIZE, browser_missing, exported_lecture, python, slide_number};

/// The page's Scene widget against render-scene's frame (SwiftShader's WebGL2 against
/// lavapipe's Vulkan, the widget's picture also resampled once more by egui): mean absolute
/// difference per channel (0–255) and the fraction of pixels off by more than 48 in a channel.
/// Measured (SwiftShader's float targets: the page offers EXT_color_buffer_float): mean 2.83,
/// 0.33 % of pixels far off (sub-pixel placement of the widget, the upscale's filtering, the
/// rasterisers' edges). The bounds leave room for that (×1.6, ×4.5) and stay below what
/// switching the shadows off does to the same frame (mean 5.48, 5.09 % far off): a picture
/// without shadows, without the school or with a wrong camera fails.
const MAX_SCENE_MEAN_DIFF: f64 = 4.5;
const MAX_SCENE_FAR_FRACTION: f64 = 0.015;
/// Shadows off against on, and scene mode against the slide: the least mean difference that
/// counts as "the picture changed" (shadows off measured 5.48).
const MIN_TOGGLE_MEAN_DIFF: f64 = 2.0;

/// The slide with live Scene widgets the scene check opens (the shadows on the left).
const SCENE_SLIDE: &str = "project-shadow-map";

/// What `lectern render-scene` draws for the Scene widget `spec` at `size` (its time, toggles,
/// camera and render scale), on the default adapter (lavapipe in CI), with 8-bit targets when
/// the page's WebGL2 had no float ones (`eight_bit`).
fn render_scene_frame(
    spec: &lectern::deck::widgets::scene::SceneSpec,
    size: (u32, u32),
    render_scale: f32,
    eight_bit: bool,
) -> image::RgbaImage {
    use lectern::render::caps::RenderCaps;
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let scene = lectern::scene::load_scene(&root.join("scenes/water.ron")).unwrap();
    let gpu = lectern::render::gpu::Gpu::headless().unwrap();
    let caps = if eight_bit {
        RenderCaps::webgl2_like()
    } else {
        RenderCaps::decide(&gpu.caps)
    };
    let mut h =
        lectern::render::Headless::with_gpu(gpu, caps, scene, &root.join("shaders")).unwrap();
    h.settings = lectern::widgets::scene::render_settings(spec, render_scale);
    let cam = &spec.camera;
    h.sim.camera.yaw_deg = cam.yaw_deg.unwrap() as f32;
    h.sim.camera.pitch_deg = cam.pitch_deg.unwrap() as f32;
    h.sim.camera.distance = cam.distance.unwrap() as f32;
    if let Some(t) = cam.target {
        h.sim.camera.target = glam::Vec3::new(t[0] as f32, t[1] as f32, t[2] as f32);
    }
    h.sim.set_time(spec.time_s);
    h.render(size).unwrap()
}

/// Mean absolute difference per channel (0–255) of two same-sized RGB pictures, and the
/// fraction of pixels whose largest channel difference passes `far`.
fn difference(a: &image::RgbaImage, b: &image::RgbaImage, far: u8) -> (f64, f64) {
    assert_eq!(a.dimensions(), b.dimensions());
    let (mut sum, mut far_n) = (0u64, 0u64);
    for (p, q) in a.pixels().zip(b.pixels()) {
        let d = (0..3).map(|c| p[c].abs_diff(q[c])).collect::<Vec<_>>();
        sum += d.iter().map(|&v| u64::from(v)).sum::<u64>();
        far_n += u64::from(d.iter().any(|&v| v > far));
    }
    let n = f64::from(a.width() * a.height());
    (sum as f64 / (3.0 * n), far_n as f64 / n)
}

/// The Scene widget's picture inside a screenshot of the canvas (one CSS pixel per pixel).
fn crop(shot: &image::RgbaImage, rect: &serde_json::Value) -> image::RgbaImage {
    let at = |k: &str| rect[k].as_f64().unwrap();
    let (x, y) = (at("x").round() as u32, at("y").round() as u32);
    let (w, h) = (at("w").round() as u32, at("h").round() as u32);
    image::imageops::crop_imm(shot, x, y, w, h).to_image()
}

/// Issue #25 in the browser: the shadow-mapping slide's live Scene draws what `render-scene`
/// draws, switching shadows off changes it, a drag orbits it, `Tab` shows scene mode (its backend line, frame
/// rate and rung in the figures), and the console stays clean.
#[test]
fn the_water_scene_runs_live_in_chromium() {
    if browser_missing() {
        return;
    }
    let py = python();
    let tmp = tempfile::tempdir().unwrap();
    let page = exported_lecture();
    let deck_path = Path::new(env!("CARGO_MANIFEST_DIR")).join("slides/lecture.ron");
    let deck = load_deck(&deck_path).unwrap();
    let number = slide_number(&deck, SCENE_SLIDE);
    let slide = &deck.slides[number - 1];
    let spec = slide
        .widgets()
        .into_iter()
        .find_map(|(_, w)| match w {
            lectern::widgets::WidgetSpec::Scene(s) => Some(s.clone()),
            _ => None,
        })
        .unwrap();
    let shots = tmp.path().join("shots");
    std::fs::create_dir_all(&shots).unwrap();
    let run = Command::new(&py)
        .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/browser/scene.py"))
        .arg("--url")
        .arg(format!("file://{}/index.html", page.display()))
        .args(["--slide", &number.to_string()])
        .arg("--shots")
        .arg(&shots)
        .args(["--size", &format!("{}x{}", SIZE[0], SIZE[1])])
        .output()
        .unwrap();
    let said = String::from_utf8_lossy(&run.stderr);
    let figures = String::from_utf8_lossy(&run.stdout);
    eprintln!("{said}\nfigures: {figures}");
    assert!(
        run.status.success(),
        "the browser's scene checks failed:\n{said}"
    );
    let figures: serde_json::Value =
        serde_json::from_str(figures.lines().last().unwrap_or("{}")).unwrap();
    let backend = figures["backend"].as_str().unwrap_or_default().to_owned();
    assert!(
        backend.starts_with("GL"),
        "the panel's first line: {backend:?}"
    );
    let open = |name: &str| image::open(shots.join(name)).unwrap().into_rgba8();
    let shown = crop(&open("scene-widget.png"), &figures["widget"]);
    let no_shadows = crop(&open("scene-widget-no-shadows.png"), &figures["widget"]);
    let scale =
        lectern::scene::quality::LADDER[lectern::scene::quality::BROWSER_START_RUNG].render_scale;
    let eight_bit = backend.contains("8-bit");
    let want = render_scene_frame(&spec, shown.dimensions(), scale, eight_bit);
    let (mean, far) = difference(&shown, &want, 48);
    let (toggle_mean, toggle_far) = difference(&shown, &no_shadows, 48);
    eprintln!(
        "scene widget {:?} vs render-scene ({}): mean |diff| {mean:.2}, {:.2} % of pixels off by \
         more than 48; shadows off vs on: mean {toggle_mean:.2}, {:.2} %",
        shown.dimensions(),
        if eight_bit {
            "8-bit targets"
        } else {
            "float targets"
        },
        100.0 * far,
        100.0 * toggle_far
    );
    if mean > MAX_SCENE_MEAN_DIFF || far > MAX_SCENE_FAR_FRACTION {
        let keep = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/web-player-test");
        let _ = std::fs::create_dir_all(&keep);
        let _ = shown.save(keep.join("scene-widget-page.png"));
        let _ = want.save(keep.join("scene-widget-render-scene.png"));
    }
    assert!(
        mean <= MAX_SCENE_MEAN_DIFF && far <= MAX_SCENE_FAR_FRACTION,
        "the page's Scene differs from render-scene's frame (target/web-player-test/)"
    );
    assert!(
        toggle_mean > MIN_TOGGLE_MEAN_DIFF,
        "switching shadows off did not change the picture (mean {toggle_mean:.2})"
    );
    let orbited = crop(&open("scene-widget-orbited.png"), &figures["widget"]);
    let (orbit_mean, _) = difference(&no_shadows, &orbited, 48);
    eprintln!("a drag across the widget: mean |diff| {orbit_mean:.2}");
    assert!(
        orbit_mean > MIN_TOGGLE_MEAN_DIFF,
        "dragging across the Scene did not orbit its camera (mean {orbit_mean:.2})"
    );
    let mode = open("scene-mode.png");
    let (mode_mean, _) = difference(&mode, &open("scene-widget.png"), 48);
    assert!(
        mode_mean > MIN_TOGGLE_MEAN_DIFF,
        "Tab did not change the page"
    );
}

/// A browser without WebGL2 (the page's check finds none; nothing could draw the slides): the
/// page says so in one line and shows the scene as exported, whose pixels on the page are the
/// still's (scaled to fit), and starts no player. The still is the scene's frame at its time.
#[test]
fn without_webgl2_the_page_says_why_and_shows_the_scene_as_exported() {
    use lectern::cli::export_web::{STILL_FILE, STILL_SIZE_PX, STILL_TIME_S};
    if browser_missing() {
        return;
    }
    let page = exported_lecture();
    let still = image::open(page.join(STILL_FILE)).unwrap().into_rgba8();
    assert_eq!(still.dimensions(), STILL_SIZE_PX);
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let scene = lectern::scene::load_scene(&root.join("scenes/water.ron")).unwrap();
    let mut h = lectern::render::Headless::new(scene, &root.join("shaders")).unwrap();
    h.sim.set_time(STILL_TIME_S);
    let frame = h.render(STILL_SIZE_PX).unwrap();
    let (mean, _) = difference(&still, &frame, 48);
    // the same check against the scene two seconds on must fail: waves and fish have moved
    h.sim.set_time(STILL_TIME_S + 2.0);
    let (later, _) = difference(&still, &h.render(STILL_SIZE_PX).unwrap(), 48);
    eprintln!(
        "the still against render-scene at {STILL_TIME_S} s: mean |diff| {mean:.2}; \
         2 s later: {later:.2}"
    );
    // (the JPEG against the PNG: its loss is ~2)
    assert!(
        mean < 3.0,
        "the still is not the scene's frame (mean {mean:.2})"
    );
    assert!(later > 3.0, "the check cannot tell the scene's times apart");

    let tmp = tempfile::tempdir().unwrap();
    let run = Command::new(python())
        .arg(root.join("tests/browser/scene.py"))
        .arg("--no-webgl2")
        .arg("--url")
        .arg(format!("file://{}/index.html", page.display()))
        .arg("--shots")
        .arg(tmp.path())
        .args(["--size", "1280x720"])
        .output()
        .unwrap();
    let said = String::from_utf8_lossy(&run.stderr);
    let figures = String::from_utf8_lossy(&run.stdout);
    eprintln!("{said}\nfigures: {figures}");
    assert!(run.status.success(), "the page without WebGL2:\n{said}");
    let figures: serde_json::Value =
        serde_json::from_str(figures.lines().last().unwrap_or("{}")).unwrap();
    let rect = &figures["still"];
    assert_eq!(
        rect["naturalWidth"].as_u64(),
        Some(u64::from(STILL_SIZE_PX.0))
    );
    let shot = image::open(tmp.path().join("no-webgl2.png"))
        .unwrap()
        .into_rgba8();
    let shown = crop(&shot, rect);
    let want = image::imageops::resize(
        &still,
        shown.width(),
        shown.height(),
        image::imageops::FilterType::Triangle,
    );
    let (mean, far) = difference(&shown, &want, 48);
    eprintln!(
        "the still on the page {:?}: mean |diff| {mean:.2}, {:.2} % far off",
        shown.dimensions(),
        100.0 * far
    );
    assert!(
        shown.width() > 600 && mean < 4.0 && far < 0.01,
        "the page does not show the still (mean {mean:.2}, {:.2} % far off)",
        100.0 * far
    );
}
