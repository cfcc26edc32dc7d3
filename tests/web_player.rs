//! The web player in a real browser (issue #24): `lectern export --web` of the bundled lecture,
//! opened in Debian's headless Chromium (software WebGL2) from `file://` and from a static
//! server on 127.0.0.1, driven by `tests/browser/player.py` (selenium, chromium-driver). Skipped,
//! loudly, only where Chromium is not installed; CI installs it (`.ci/run`).

use crate::common;

use std::path::{Path, PathBuf};
use std::process::Command;

use lectern::deck::load_deck;

const CHROMIUM: &str = "/usr/bin/chromium";
const DRIVER: &str = "/usr/bin/chromedriver";
const SIZE: [u32; 2] = [1280, 720];
/// What the students type into the slope field's editor.
const EQUATION: &str = "-2*x + cos(3*t)";

/// Slide 1 in the page against `export`'s PNG of it, with the snapshot goldens' tolerance (a
/// pixel fails beyond common::SCENE_SNAPSHOT_THRESHOLD, at most 0.1 % may fail). Measured:
/// 0.064 % (WebGL2 through SwiftShader and the offscreen renderer differ at a few text edges);
/// a missing title, formula or line of text fails by far more.
const MAX_FAILED_FRACTION: f64 = common::SCENE_MAX_FAILED_FRACTION;

fn python() -> PathBuf {
    if let Some(p) = std::env::var_os("LECTERN_BROWSER_PYTHON") {
        return p.into();
    }
    Path::new(env!("CARGO_MANIFEST_DIR")).join("target/browser-venv/bin/python")
}

fn browser_missing() -> bool {
    if Path::new(CHROMIUM).exists() && Path::new(DRIVER).exists() {
        return false;
    }
    eprintln!(
        "\n\n*** SKIPPED: the web player's browser test needs Debian's chromium and \
         chromium-driver ({CHROMIUM}, {DRIVER}): apt-get install chromium chromium-driver, \
         then scripts/setup-browser-test ***\n"
    );
    true
}

fn lectern() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_lectern"));
    c.current_dir(env!("CARGO_MANIFEST_DIR"));
    c
}

fn free_port() -> u16 {
    std::net::TcpListener::bind("127.0.0.1:0")
        .and_then(|l| l.local_addr())
        .map(|a| a.port())
        .unwrap()
}

/// Kills the static server when the test ends, however it ends.
struct Server(std::process::Child);
impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

fn serve(dir: &Path) -> (Server, u16) {
    let port = free_port();
    let child = Command::new("python3")
        .args(["-m", "http.server", "--bind", "127.0.0.1"])
        .arg(port.to_string())
        .arg("--directory")
        .arg(dir)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    for _ in 0..100 {
        if std::net::TcpStream::connect(("127.0.0.1", port)).is_ok() {
            break;
        }
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
    (Server(child), port)
}

fn slide_number(deck: &lectern::deck::Deck, key: &str) -> usize {
    1 + deck.slides.iter().position(|s| s.key() == key).unwrap()
}

/// What `export --data` writes for the slope field once its equation is `EQUATION` (the
/// problem file changed so in a copy of the lecture; no closed form then, as in the browser).
fn expected_csv(dir: &Path) -> PathBuf {
    let (_copy, deck_path) = common::lecture_copy();
    let problem = deck_path.with_file_name("problems/forced.ron");
    let text = std::fs::read_to_string(&problem).unwrap();
    let text = text.replace("\"cos(t) - x\"", &format!("{EQUATION:?}"));
    let text = text
        .lines()
        .filter(|l| !l.trim_start().starts_with("exact:"))
        .collect::<Vec<_>>()
        .join("\n");
    std::fs::write(&problem, text).unwrap();
    let deck = load_deck(&deck_path).unwrap();
    let index = slide_number(&deck, "slope-field") - 1;
    let slide = &deck.slides[index];
    let mut state = lectern::app::SlideState::default();
    state.set_deck_path(deck.file.as_deref());
    let csv = lectern::app::plot_data::slide_data(slide, &mut state)
        .into_iter()
        .find_map(|w| w.csv)
        .unwrap();
    let file = dir.join("expected.csv");
    std::fs::write(&file, csv).unwrap();
    file
}

fn failed_fraction(page: &image::RgbaImage, export: &image::RgbaImage) -> f64 {
    common::scene_failing_pixels(export, page) as f64 / f64::from(SIZE[0] * SIZE[1])
}

#[test]
fn the_exported_page_pages_plots_and_types_in_chromium() {
    if browser_missing() {
        return;
    }
    let py = python();
    assert!(
        py.exists(),
        "{} is missing: run scripts/setup-browser-test (a venv with selenium under target/)",
        py.display()
    );
    let tmp = tempfile::tempdir().unwrap();
    let page = tmp.path().join("page");
    let deck_path = Path::new(env!("CARGO_MANIFEST_DIR")).join("slides/lecture.ron");
    let started = std::time::Instant::now();
    let out = lectern()
        .args(["export", "slides/lecture.ron", "--web"])
        .arg(&page)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "export --web failed:\n{stderr}");
    eprintln!(
        "{stderr}export --web took {:.1} s",
        started.elapsed().as_secs_f64()
    );
    for f in ["index.html", "lectern.js", "player.js", "bundle.js"] {
        assert!(page.join(f).is_file(), "{f} missing");
    }

    let deck = load_deck(&deck_path).unwrap();
    let export_png = lectern::app::render_slide_png(&deck, 0, SIZE).unwrap();
    let expect = expected_csv(tmp.path());
    let (_server, port) = serve(&page);
    let skipped: Vec<String> = (deck.slides.iter().enumerate())
        .filter(|(_, s)| s.skip)
        .map(|(i, _)| (i + 1).to_string())
        .collect();
    let shots = tmp.path().join("shots");
    std::fs::create_dir_all(&shots).unwrap();
    let run = Command::new(&py)
        .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/browser/player.py"))
        .arg("--url")
        .arg(format!("file://{}/index.html", page.display()))
        .arg("--url")
        .arg(format!("http://127.0.0.1:{port}/index.html"))
        .arg("--shots")
        .arg(&shots)
        .args(["--size", &format!("{}x{}", SIZE[0], SIZE[1])])
        .args(["--euler", &slide_number(&deck, "euler").to_string()])
        .args(["--slope", &slide_number(&deck, "slope-field").to_string()])
        .args(["--spiral", &slide_number(&deck, "inaccuracy").to_string()])
        .args([
            "--work-precision",
            &slide_number(&deck, "work-precision").to_string(),
        ])
        .args(["--equation", EQUATION])
        .arg("--skipped")
        .arg(skipped.join(","))
        .arg("--expect")
        .arg(&expect)
        .output()
        .unwrap();
    let said = String::from_utf8_lossy(&run.stderr);
    let figures = String::from_utf8_lossy(&run.stdout);
    eprintln!("{said}\nfigures: {figures}");
    assert!(run.status.success(), "the browser checks failed:\n{said}");
    for tag in ["file", "http"] {
        let shot = image::open(shots.join(format!("slide1-{tag}.png")))
            .unwrap()
            .into_rgba8();
        assert_eq!(shot.dimensions(), export_png.dimensions(), "{tag}");
        let failed = failed_fraction(&shot, &export_png);
        if failed > MAX_FAILED_FRACTION {
            let keep = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/web-player-test");
            let _ = std::fs::create_dir_all(&keep);
            let _ = shot.save(keep.join(format!("slide1-{tag}.png")));
            let _ = export_png.save(keep.join("slide1-export.png"));
        }
        eprintln!("slide 1 from {tag}: {:.3} % of pixels off", 100.0 * failed);
        assert!(
            failed <= MAX_FAILED_FRACTION,
            "slide 1 from {tag} differs from export's PNG in {:.2} % of its pixels \
             (target/web-player-test/ has both)",
            100.0 * failed
        );
    }

    // A damaged bundle, cut short or edited inside its compressed bytes: a readable error on
    // the page, not a blank canvas.
    let bundle = std::fs::read(page.join("bundle.js")).unwrap();
    let mut edited = bundle.clone();
    let middle = edited.len() / 2;
    for b in &mut edited[middle..middle + 8] {
        *b = if *b == b'A' { b'B' } else { b'A' };
    }
    for (name, damaged) in [
        ("cut", bundle[..bundle.len() / 2].to_vec()),
        ("edited", edited),
    ] {
        let broken = tmp.path().join(format!("broken-{name}"));
        std::fs::create_dir_all(&broken).unwrap();
        for f in ["index.html", "lectern.js", "player.js"] {
            std::fs::copy(page.join(f), broken.join(f)).unwrap();
        }
        std::fs::write(broken.join("bundle.js"), damaged).unwrap();
        let run = Command::new(&py)
            .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/browser/player.py"))
            .arg("--broken")
            .arg(&broken)
            .output()
            .unwrap();
        let said = String::from_utf8_lossy(&run.stderr);
        eprintln!("{said}\n{}", String::from_utf8_lossy(&run.stdout));
        assert!(
            run.status.success(),
            "the {name} bundle's page check failed:\n{said}"
        );
    }
}

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
    assert!(
        py.exists(),
        "{} is missing: run scripts/setup-browser-test",
        py.display()
    );
    let tmp = tempfile::tempdir().unwrap();
    let page = tmp.path().join("page");
    let out = lectern()
        .args(["export", "slides/lecture.ron", "--web"])
        .arg(&page)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "export --web failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
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
