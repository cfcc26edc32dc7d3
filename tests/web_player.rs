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
pub(crate) const SIZE: [u32; 2] = [1280, 720];
/// What the students type into the slope field's editor.
const EQUATION: &str = "-2*x + cos(3*t)";

/// Slide 1 in the page against `export`'s PNG of it, with the snapshot goldens' tolerance (a
/// pixel fails beyond common::SCENE_SNAPSHOT_THRESHOLD, at most 0.1 % may fail). Measured:
/// 0.064 % (WebGL2 through SwiftShader and the offscreen renderer differ at a few text edges);
/// a missing title, formula or line of text fails by far more.
const MAX_FAILED_FRACTION: f64 = common::SCENE_MAX_FAILED_FRACTION;

/// The Python with selenium that drives the browser (it must exist once the browser does).
pub(crate) fn python() -> PathBuf {
    let py = match std::env::var_os("LECTERN_BROWSER_PYTHON") {
        Some(p) => PathBuf::from(p),
        None => Path::new(env!("CARGO_MANIFEST_DIR")).join("target/browser-venv/bin/python"),
    };
    assert!(
        py.exists(),
        "{} is missing: run scripts/setup-browser-test (a venv with selenium under target/)",
        py.display()
    );
    py
}

pub(crate) fn browser_missing() -> bool {
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

pub(crate) fn lectern() -> Command {
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

/// The bundled lecture's page, exported once for the browser tests of this file and of
/// [`super::web_scene`] (into `target/`, where it stays for a look after a failure); the pages
/// are only read.
pub(crate) fn exported_lecture() -> &'static Path {
    static PAGE: std::sync::OnceLock<PathBuf> = std::sync::OnceLock::new();
    PAGE.get_or_init(|| {
        let page = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/web-test/page");
        let _ = std::fs::remove_dir_all(&page);
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
        page
    })
}

pub(crate) fn slide_number(deck: &lectern::deck::Deck, key: &str) -> usize {
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
    let tmp = tempfile::tempdir().unwrap();
    let page = exported_lecture();
    let deck_path = Path::new(env!("CARGO_MANIFEST_DIR")).join("slides/lecture.ron");
    for f in ["index.html", "lectern.js", "player.js", "bundle.js"] {
        assert!(page.join(f).is_file(), "{f} missing");
    }

    let deck = load_deck(&deck_path).unwrap();
    let export_png = lectern::app::render_slide_png(&deck, 0, SIZE).unwrap();
    let expect = expected_csv(tmp.path());
    let (_server, port) = serve(page);
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
