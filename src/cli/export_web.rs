//! `lectern export DECK --web DIR`: the deck as a static web page that pages through the same
//! slides with every plot live (docs/web.md). DIR gets `index.html` and three classic scripts
//! (a page opened from `file://` may neither `fetch` nor import modules): `lectern.js`
//! (wasm-bindgen's `no-modules` glue), `player.js` (the player's wasm, gzipped, as Z85 text: `z85.rs`) and
//! `bundle.js` (the [`WebBundle`], gzipped, as Z85: the deck and every file its loading and
//! drawing read, collected with [`project_files::Recording`], every formula the slides asked
//! for typeset by the app's own Typst at twice its layout size, and the fonts the slides use),
//! and `scene-still.jpg`, the water scene as `render-scene` draws it, which the page shows with
//! a one-line note where the browser has no WebGL2.
//!
//! The player is `target/web-player/`, made by `scripts/build-player`; export runs that script
//! (with a progress line) when the player is missing or older than the sources.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use anyhow::Context as _;

use crate::app::{LecternApp, OffscreenRenderer, SlideOptions};
use crate::deck::DeckSession;
use crate::math::{MathStyle, MathSyntax, Request};
use crate::project_files::{self, Recording};
use crate::web_bundle::{WebBundle, bundle_path};

/// The slide size the formulas are laid out at for the page, in pixels (they are typeset at
/// twice that, so they stay sharp on a high-DPI screen; smaller windows downsample).
const LAYOUT_WIDTH_PX: u32 = 1280;

/// What `export --web` wrote.
pub struct WebExport {
    pub files: Vec<PathBuf>,
    /// Slides' problems (a formula that failed, a widget that could not load).
    pub failures: Vec<String>,
}

/// Writes the page for the deck at `deck_path` into `out`, with the player in `player_dir`.
pub fn export_web(deck_path: &Path, out: &Path, player_dir: &Path) -> anyhow::Result<WebExport> {
    let recording = Arc::new(Recording::default());
    project_files::install(recording.clone()).map_err(anyhow::Error::msg)?;
    crate::math::pool::record_requests();
    let deck_real = deck_path
        .canonicalize()
        .with_context(|| format!("cannot read {}", deck_path.display()))?;
    let root = crate::paths::project_root(&deck_real);
    // What the app reads at start (deck, ink, tweaks), then every slide drawn once: what the
    // widgets read, and every formula they ask for.
    let session = DeckSession::open(&deck_real).map_err(|d| anyhow::anyhow!("{d}"))?;
    let deck = session.deck().clone();
    let _app = LecternApp::new(session);
    crate::widgets::work_precision::DETERMINISTIC.store(true, std::sync::atomic::Ordering::Relaxed);
    let mut renderer = OffscreenRenderer::new()?;
    let size = [
        LAYOUT_WIDTH_PX,
        ((LAYOUT_WIDTH_PX as f32 / deck.aspect.ratio()).round() as u32).clamp(16, 8192),
    ];
    let mut failures: Vec<String> = (deck.broken_slides.iter())
        .map(|b| format!("{} (shown as an error slide)", b.diagnostic))
        .collect();
    for (index, slide) in deck.slides.iter().enumerate() {
        let mut state = crate::app::SlideState::default();
        renderer.render_slide_with(&deck, index, &mut state, size, SlideOptions::default())?;
        for problem in state.problems() {
            failures.push(format!(
                "{}: slide {} ({:?}): {problem}",
                deck_path.display(),
                index + 1,
                slide.key()
            ));
        }
        let _ = crate::app::plot_data::slide_data(slide, &mut state);
    }
    read_scene_mode_files(&root, &_app.scene_path);
    let deck_in_bundle = bundle_path(&root, &deck_real)
        .ok_or_else(|| anyhow::anyhow!("{} is outside its project folder", deck_real.display()))?;
    let mut bundle = WebBundle::new(deck_in_bundle);
    typeset_formulas(&mut bundle, crate::math::pool::take_recorded())?;
    bundle_files(&mut bundle, &root, &recording.files_read())?;
    // a face that is both a slide face and a fallback is stored once (`add_blob`)
    for (name, bytes) in crate::math::web_fonts() {
        bundle.add_font(name, bytes);
    }
    // (after the bundle's files were read: the still is no file of the page's bundle)
    let still = match scene_still(&_app.scene_path) {
        Ok(jpeg) => Some(jpeg),
        Err(e) => {
            eprintln!("lectern: warning: no still of the scene for browsers without WebGL2: {e:#}");
            None
        }
    };
    let written = write_page(out, &deck.title, &bundle, player_dir, still)?;
    Ok(WebExport {
        files: written,
        failures,
    })
}

/// Reads (so the recording bundles them) what scene mode (`Tab`) loads in the player though no
/// slide drew it: the scene file and every technique's shader with its includes. A file that
/// does not load is left to the player, which shows the scene's error as the desktop does; a
/// scene found outside the project (the current folder's, for a deck elsewhere) is not the
/// page's to carry.
fn read_scene_mode_files(root: &Path, scene_path: &Path) {
    let real = scene_path
        .canonicalize()
        .unwrap_or_else(|_| scene_path.to_path_buf());
    if bundle_path(root, &real).is_none() && crate::bundled::in_bundled_folder(&real).is_none() {
        return;
    }
    let _ = crate::scene::load_scene(scene_path);
    let Ok(folder) = crate::bundled::shader_folder_for_scene(scene_path) else {
        return;
    };
    for name in crate::render::pipeline::TECHNIQUE_SHADERS {
        let _ = crate::render::shaders::load(&folder.dir.join(name));
    }
}

/// The picture `index.html` shows, with a one-line note, where the browser has no WebGL2 (without
/// which neither the slides nor the scene can draw): scene mode's scene as `render-scene`
/// draws it at full quality, JPEG (~1 % of the page: 800×450 at quality 80 is 71 KB, where
/// 960×540 at 85 was 114 KB and took the folder past 8 MB).
pub const STILL_FILE: &str = "scene-still.jpg";
pub const STILL_SIZE_PX: (u32, u32) = (800, 450);
/// Seconds into the scene: the schools have spread from where they spawned.
pub const STILL_TIME_S: f64 = 6.0;
const JPEG_QUALITY: u8 = 80;

fn scene_still(scene_path: &Path) -> anyhow::Result<Vec<u8>> {
    let scene = crate::scene::load_scene(scene_path).map_err(|d| anyhow::anyhow!("{d}"))?;
    let folder = crate::bundled::shader_folder_for_scene(scene_path).map_err(anyhow::Error::msg)?;
    let mut h = crate::render::Headless::new(scene, &folder.dir)?;
    h.sim.set_time(STILL_TIME_S);
    let rgb = image::DynamicImage::ImageRgba8(h.render(STILL_SIZE_PX)?).into_rgb8();
    let mut jpeg = Vec::new();
    image::codecs::jpeg::JpegEncoder::new_with_quality(&mut jpeg, JPEG_QUALITY)
        .encode_image(&rgb)?;
    Ok(jpeg)
}

/// Each formula asked for, once (at the largest size asked), typeset at twice that size.
fn typeset_formulas(bundle: &mut WebBundle, asked: Vec<Request>) -> anyhow::Result<()> {
    type Key = (String, MathSyntax, MathStyle, [u8; 4]);
    let mut largest: HashMap<Key, f32> = HashMap::new();
    for r in asked {
        let size = largest
            .entry((r.src, r.syntax, r.style, r.rgba))
            .or_insert(0.0);
        *size = size.max(r.size_px);
    }
    let mut keys: Vec<(Key, f32)> = largest.into_iter().collect();
    keys.sort_by(|a, b| a.0.0.cmp(&b.0.0).then(a.0.3.cmp(&b.0.3)));
    for ((src, syntax, style, rgba), size_px) in keys {
        let em_px = 2.0 * size_px;
        let result = crate::math::pool().typeset(Request {
            src: src.clone(),
            syntax,
            style,
            size_px: em_px,
            rgba,
        });
        bundle
            .add_formula(&src, syntax, style, rgba, em_px, &result)
            .map_err(anyhow::Error::msg)?;
    }
    Ok(())
}

/// The files read, by their path under `root`.
fn bundle_files(bundle: &mut WebBundle, root: &Path, read: &[PathBuf]) -> anyhow::Result<()> {
    for path in read {
        // the shaders and scene built into lectern (a project without its own) go where the
        // player looks for a project's
        let built_in = crate::bundled::in_bundled_folder(path)
            .and_then(|rel| rel.to_str().map(|r| r.replace('\\', "/")));
        let Some(rel) = bundle_path(root, path).or(built_in) else {
            eprintln!(
                "lectern: warning: {} is outside the project folder {}: left out of the page",
                path.display(),
                root.display()
            );
            continue;
        };
        let bytes =
            std::fs::read(path).with_context(|| format!("cannot read {}", path.display()))?;
        bundle.add_file(rel, &bytes);
    }
    Ok(())
}

fn write_page(
    out: &Path,
    title: &str,
    bundle: &WebBundle,
    player_dir: &Path,
    still: Option<Vec<u8>>,
) -> anyhow::Result<Vec<PathBuf>> {
    std::fs::create_dir_all(out).with_context(|| format!("cannot create {}", out.display()))?;
    let read = |name: &str| {
        let p = player_dir.join(name);
        std::fs::read(&p).with_context(|| format!("cannot read the web player's {}", p.display()))
    };
    let glue = read("lectern.js")?;
    let wasm = read("lectern_bg.wasm")?;
    // gzipped (a third of the size, opened by the browser's own DecompressionStream), as Z85
    // text (a file:// page reads no binary file; Z85 costs 25 % where base64 costs 33 %)
    let gzip_script = |name: &str, bytes: &[u8]| -> anyhow::Result<Vec<u8>> {
        let mut gz = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::best());
        std::io::Write::write_all(&mut gz, bytes)?;
        let gz = gz.finish()?;
        let text = crate::z85::encode(&gz);
        Ok(format!(
            "window.{name} = {{ bytes: {}, z85: \"{text}\" }};\n",
            gz.len()
        )
        .into_bytes())
    };
    let wasm_js = gzip_script("LECTERN_WASM_GZ", &wasm)?;
    let bundle_js = gzip_script("LECTERN_BUNDLE_GZ", &bundle.to_bytes())?;
    let mut files = vec![
        ("index.html", index_html(title).into_bytes()),
        ("lectern.js", glue),
        ("player.js", wasm_js),
        ("bundle.js", bundle_js),
    ];
    match still {
        Some(jpeg) => files.push((STILL_FILE, jpeg)),
        // (an old one would show a scene this deck may not have)
        None => {
            let _ = std::fs::remove_file(out.join(STILL_FILE));
        }
    }
    let mut written = Vec::new();
    for (name, bytes) in files {
        let file = out.join(name);
        write_atomic(&file, &bytes)?;
        written.push(file);
    }
    Ok(written)
}

/// Writes through a temporary file and a rename, so a page is never half-written.
fn write_atomic(file: &Path, bytes: &[u8]) -> anyhow::Result<()> {
    let tmp = file.with_extension("lectern-tmp");
    std::fs::write(&tmp, bytes).with_context(|| format!("cannot write {}", tmp.display()))?;
    std::fs::rename(&tmp, file).with_context(|| format!("cannot write {}", file.display()))
}

fn index_html(title: &str) -> String {
    let title = title
        .replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;");
    INDEX_HTML
        .replace("{title}", &title)
        .replace("{still}", STILL_FILE)
}

/// Classic scripts only (see the module's doc); the wasm is decoded and started here, and any
/// failure to start shows as text in `#lectern-error`.
const INDEX_HTML: &str = r#"<!doctype html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>{title}</title>
<link rel="icon" href="data:,">
<style>
  html, body { margin: 0; height: 100%; overflow: hidden; background: #101014; }
  #lectern-canvas { display: block; width: 100%; height: 100%; touch-action: none; }
  #lectern-loading, #lectern-error { position: absolute; left: 2em; top: 2em; right: 2em;
    font: 18px/1.5 system-ui, sans-serif; color: #e8e8e8; }
  #lectern-error { display: none; color: #ffb4a8; white-space: pre-wrap; }
  #lectern-still { display: none; margin-top: 1em; max-width: 100%;
    max-height: calc(100vh - 10em); }
</style>
</head>
<body>
<canvas id="lectern-canvas"></canvas>
<div id="lectern-loading">Loading the slides…</div>
<div id="lectern-error" role="alert"></div>
<img id="lectern-still" alt="The water scene, as exported" onerror="this.remove()">
<script src="lectern.js"></script>
<script src="player.js"></script>
<script src="bundle.js"></script>
<script>
(function () {
  function isPacked(v) {
    return v && typeof v.z85 === "string" && typeof v.bytes === "number";
  }
  function fail(message) {
    var box = document.getElementById("lectern-error");
    box.textContent = "lectern could not show the slides: " + message;
    box.style.display = "block";
    document.getElementById("lectern-canvas").style.display = "none";
    var loading = document.getElementById("lectern-loading");
    if (loading) loading.remove();
  }
  // no WebGL2, nothing draws: say why, and show the scene as exported
  function hasWebGL2() {
    try {
      var gl = window.WebGL2RenderingContext && document.createElement("canvas").getContext("webgl2");
      var lose = gl && gl.getExtension("WEBGL_lose_context");
      if (lose) lose.loseContext();  // (the player makes its own)
      return !!gl;
    } catch (e) {
      return false;
    }
  }
  if (!hasWebGL2()) {
    fail("this browser has no WebGL2, which the slides draw with: turn on hardware " +
      "acceleration or open the page in a current Firefox, Chrome or Safari. Below, the water " +
      "scene as exported.");
    var still = document.getElementById("lectern-still");
    if (still) {
      // under the note, in its flow
      document.getElementById("lectern-error").appendChild(still);
      still.src = "{still}";
      still.style.display = "block";
    }
    return;
  }
  if (typeof wasm_bindgen === "undefined" || !isPacked(window.LECTERN_WASM_GZ)) {
    fail("the player (lectern.js, player.js) is missing or damaged: export the page again " +
      "with `lectern export DECK --web DIR`");
    return;
  }
  if (!isPacked(window.LECTERN_BUNDLE_GZ)) {
    fail("the slides' bundle (bundle.js) is missing or damaged: export the page again " +
      "with `lectern export DECK --web DIR`");
    return;
  }
  if (typeof DecompressionStream === "undefined") {
    fail("this browser is too old for the page (it lacks DecompressionStream)");
    return;
  }
  // Z85 (ZeroMQ RFC 32, src/z85.rs) -> the gzip's bytes; throws on a character outside it
  var Z85 = "0123456789abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ.-:+=^!/*?&<>()[]{}@%$#";
  var digit = new Int16Array(128).fill(-1);
  for (var d = 0; d < 85; d++) digit[Z85.charCodeAt(d)] = d;
  function z85(packed) {
    var text = packed.z85, groups = text.length / 5;
    if (groups !== Math.floor(groups) || packed.bytes > groups * 4) throw new Error("bad length");
    var out = new Uint8Array(groups * 4);
    for (var g = 0, i = 0, o = 0; g < groups; g++) {
      var value = 0;
      for (var k = 0; k < 5; k++, i++) {
        var c = text.charCodeAt(i), v = c < 128 ? digit[c] : -1;
        if (v < 0) throw new Error("not Z85");
        value = value * 85 + v;
      }
      if (value > 0xffffffff) throw new Error("not Z85");
      out[o++] = value >>> 24; out[o++] = (value >>> 16) & 255;
      out[o++] = (value >>> 8) & 255; out[o++] = value & 255;
    }
    return out.subarray(0, packed.bytes);
  }
  // -> the bytes, with the browser's own DecompressionStream
  function gunzip(packed) {
    return Promise.resolve(packed).then(function (p) {
      var stream = new Blob([z85(p)]).stream().pipeThrough(new DecompressionStream("gzip"));
      return new Response(stream).arrayBuffer();
    });
  }
  // (the browser's own words for a broken gzip stream, e.g. "Failed to fetch", mislead)
  var bundle = gunzip(window.LECTERN_BUNDLE_GZ).catch(function () {
    throw new Error("the slides' bundle (bundle.js) is damaged (it does not unpack): export " +
      "the page again with `lectern export DECK --web DIR`");
  });
  Promise.all([gunzip(window.LECTERN_WASM_GZ), bundle])
    .then(function (opened) {
      window.LECTERN_BUNDLE = new Uint8Array(opened[1]);
      return wasm_bindgen({ module_or_path: opened[0] });
    })
    .catch(function (e) { fail(e && e.message ? e.message : String(e)); });
})();
</script>
</body>
</html>
"#;

/// The web player to copy: `$LECTERN_WEB_PLAYER`, else `target/web-player/` of the source tree
/// this binary was built from, built first by `scripts/build-player` when it is missing or
/// older than the sources.
pub fn find_player() -> anyhow::Result<PathBuf> {
    if let Some(dir) = std::env::var_os("LECTERN_WEB_PLAYER") {
        return Ok(PathBuf::from(dir));
    }
    let tree = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = tree.join("target/web-player");
    let built = modified(&dir.join("lectern_bg.wasm"));
    let script = tree.join("scripts/build-player");
    if !script.is_file() {
        return match built {
            Some(_) => Ok(dir),
            None => anyhow::bail!(
                "no web player at {} and no source tree to build it from (set LECTERN_WEB_PLAYER)",
                dir.display()
            ),
        };
    }
    let sources = newest(&[
        tree.join("src"),
        tree.join("Cargo.toml"),
        tree.join("Cargo.lock"),
    ]);
    let fresh = matches!((built, sources), (Some(b), Some(s)) if b >= s);
    if !fresh {
        eprintln!(
            "lectern: building the web player ({}; several minutes the first time)…",
            if built.is_some() {
                "older than the sources"
            } else {
                "not built yet"
            }
        );
        let status = std::process::Command::new(&script)
            .current_dir(tree)
            .status()
            .with_context(|| format!("cannot run {}", script.display()))?;
        if !status.success() {
            anyhow::bail!("{} failed ({status})", script.display());
        }
    }
    Ok(dir)
}

fn modified(p: &Path) -> Option<std::time::SystemTime> {
    std::fs::metadata(p).and_then(|m| m.modified()).ok()
}

/// The newest modification time of the files under `paths`.
fn newest(paths: &[PathBuf]) -> Option<std::time::SystemTime> {
    let mut best = None;
    let mut stack: Vec<PathBuf> = paths.to_vec();
    while let Some(p) = stack.pop() {
        if p.is_dir() {
            if let Ok(entries) = std::fs::read_dir(&p) {
                stack.extend(entries.flatten().map(|e| e.path()));
            }
        } else if let Some(t) = modified(&p) {
            best = best.max(Some(t));
        }
    }
    best
}
