//! `lectern export --web` without a browser (issue #24): what goes into the page's bundle, and
//! the export's failure rules. The player is a stand-in (`LECTERN_WEB_PLAYER`), so these run
//! without the wasm build; `tests/web_player.rs` opens a real page in Chromium.

use std::path::{Path, PathBuf};
use std::process::Command;

use lectern::web_bundle::WebBundle;

/// A stand-in player: export copies these files, nothing here runs them.
fn fake_player(dir: &Path) -> PathBuf {
    let p = dir.join("player");
    std::fs::create_dir_all(&p).unwrap();
    std::fs::write(p.join("lectern.js"), "var wasm_bindgen = function () {};\n").unwrap();
    std::fs::write(p.join("lectern_bg.wasm"), b"\0asm\x01\0\0\0").unwrap();
    p
}

fn export_web(dir: &Path, deck: &Path, extra: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_lectern"))
        .env("LECTERN_WEB_PLAYER", fake_player(dir))
        .arg("export")
        .arg(deck)
        .arg("--web")
        .arg(dir.join("page"))
        .args(extra)
        .output()
        .unwrap()
}

/// `window.NAME = { bytes: N, z85: "<Z85 of gzip>" };` opened as the page opens it.
fn gunzip_script(file: &Path, name: &str) -> Vec<u8> {
    let js = std::fs::read_to_string(file).unwrap();
    let (bytes, text) = js
        .trim()
        .strip_prefix(&format!("window.{name} = {{ bytes: "))
        .and_then(|s| s.strip_suffix("\" };"))
        .and_then(|s| s.split_once(", z85: \""))
        .unwrap();
    let gz = lectern::z85::decode(text, bytes.parse().unwrap()).unwrap();
    let mut out = Vec::new();
    std::io::Read::read_to_end(&mut flate2::read::GzDecoder::new(&gz[..]), &mut out).unwrap();
    out
}

/// The bundle as the player reads it from bundle.js's `window.LECTERN_BUNDLE_GZ`.
fn read_bundle(page: &Path) -> WebBundle {
    WebBundle::from_bytes(&gunzip_script(&page.join("bundle.js"), "LECTERN_BUNDLE_GZ")).unwrap()
}

#[test]
fn the_bundle_holds_the_deck_its_files_formulas_and_fonts() {
    let dir = tempfile::tempdir().unwrap();
    let slides = dir.path().join("talk/slides");
    std::fs::create_dir_all(slides.join("problems")).unwrap();
    std::fs::write(
        slides.join("problems/decay.ron"),
        r#"(name: "Decay", vars: ["x"], rhs: ["-x"], initial: [1.0])"#,
    )
    .unwrap();
    std::fs::write(slides.join("unused.ron"), "(not: \"named by the deck\")").unwrap();
    let deck = slides.join("talk.ron");
    std::fs::write(
        &deck,
        r#"(title: "Talk <1>", slides: [
            (title: "One", body: [Math(src: "dot(x) = -x"), Text("with $h$ inline")]),
            (title: "Two", body: [Widget(Spiral((ode: File("problems/decay.ron"), h: 0.1)))]),
        ])"#,
    )
    .unwrap();
    let o = export_web(dir.path(), &deck, &[]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    let page = dir.path().join("page");
    let html = std::fs::read_to_string(page.join("index.html")).unwrap();
    // classic scripts only (file:// allows no modules), the title escaped
    for script in ["lectern.js", "player.js", "bundle.js"] {
        assert!(
            html.contains(&format!("<script src=\"{script}\"></script>")),
            "{html}"
        );
    }
    assert!(!html.contains("type=\"module\"") && html.contains("Talk &lt;1&gt;"));
    // the player's wasm, gzipped, as Z85
    let wasm = gunzip_script(&page.join("player.js"), "LECTERN_WASM_GZ");
    assert_eq!(wasm, b"\0asm\x01\0\0\0");

    let b = read_bundle(&page);
    assert_eq!(b.deck, "slides/talk.ron");
    let mut paths: Vec<&str> = b.files.iter().map(|f| f.path.as_str()).collect();
    paths.sort();
    assert_eq!(paths, ["slides/problems/decay.ron", "slides/talk.ron"]);
    let deck_bytes = b
        .files
        .iter()
        .find(|f| f.path == "slides/talk.ron")
        .unwrap();
    assert_eq!(
        b.bytes_of(deck_bytes).unwrap(),
        std::fs::read(&deck).unwrap()
    );
    // both formulas, typeset (not errors), at twice a 1280-pixel slide's size
    let srcs: Vec<&str> = b.formulas.iter().map(|f| f.src.as_str()).collect();
    assert!(
        srcs.contains(&"dot(x) = -x") && srcs.contains(&"h"),
        "{srcs:?}"
    );
    for f in &b.formulas {
        let img = b.rendered(f).unwrap().unwrap();
        assert!(img.width > 8 && img.height > 8, "{}: {img:?}", f.src);
        assert!(f.em_px > 40.0, "{}: {} px per em", f.src, f.em_px);
    }
    let fonts: Vec<&str> = b.fonts.iter().map(|f| f.path.as_str()).collect();
    assert!(fonts.contains(&"LibertinusSerif-Regular"), "{fonts:?}");
    assert!(fonts.iter().any(|f| f.starts_with("lectern-")), "{fonts:?}");
    // each face once: Libertinus Serif Regular is a slide face and a fallback, one byte string
    let blob_of = |name: &str| b.fonts.iter().find(|f| f.path == name).unwrap().blob;
    assert_eq!(
        blob_of("LibertinusSerif-Regular"),
        blob_of("lectern-Libertinus Serif")
    );
    // the maths fallback's family is a slide face's (NewCMMath-Book covers it): left out
    assert!(
        !fonts.contains(&"lectern-New Computer Modern Math") && fonts.contains(&"NewCMMath-Book"),
        "{fonts:?}"
    );
    let mut blobs: Vec<usize> = b.fonts.iter().map(|f| f.blob).collect();
    blobs.sort();
    blobs.dedup();
    let sizes: Vec<usize> = blobs.iter().map(|&i| b.blob(i).unwrap().len()).collect();
    let mut contents: Vec<&[u8]> = blobs.iter().map(|&i| b.blob(i).unwrap()).collect();
    contents.sort();
    contents.dedup();
    assert_eq!(
        contents.len(),
        blobs.len(),
        "a face stored twice: {sizes:?}"
    );
}

#[test]
fn a_broken_formula_fails_export_web_naming_it_unless_keep_going() {
    let dir = tempfile::tempdir().unwrap();
    let deck = dir.path().join("bad.ron");
    std::fs::write(
        &deck,
        r#"(title: "Bad", slides: [(title: "One", body: [Math(src: "dot(x) = #nosuchfn(x)")])])"#,
    )
    .unwrap();
    let o = export_web(dir.path(), &deck, &[]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "{err}");
    assert!(err.contains("slide 1") && err.contains("nosuchfn"), "{err}");
    // the page is written all the same, its formula's error inside
    let b = read_bundle(&dir.path().join("page"));
    assert!(b.formulas.iter().any(|f| b.rendered(f).unwrap().is_err()));
    let o = export_web(dir.path(), &deck, &["--keep-going"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// Scene mode (`Tab`) runs in the page too (issue #25): a project with no `scenes/` or
/// `shaders/` of its own gets lectern's built-in water scene and every shader the renderer
/// builds, with their includes, at the paths the player looks for a project's own.
#[test]
fn the_bundle_carries_the_built_in_scene_and_shaders_for_scene_mode() {
    let dir = tempfile::tempdir().unwrap();
    let slides = dir.path().join("talk/slides");
    std::fs::create_dir_all(&slides).unwrap();
    let deck = slides.join("talk.ron");
    std::fs::write(
        &deck,
        r#"(title: "T", slides: [(title: "One", body: [Text("x")])])"#,
    )
    .unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_lectern"))
        // (no scenes/ in the current folder either)
        .current_dir(dir.path())
        .env("LECTERN_WEB_PLAYER", fake_player(dir.path()))
        .env("XDG_CACHE_HOME", dir.path().join("cache"))
        .arg("export")
        .arg(&deck)
        .arg("--web")
        .arg(dir.path().join("page"))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(!err.contains("outside the project"), "{err}");
    let b = read_bundle(&dir.path().join("page"));
    let has = |p: &str| b.files.iter().any(|f| f.path == p);
    assert!(has("scenes/water.ron"), "no scene in the page");
    let scene = (b.files.iter().find(|f| f.path == "scenes/water.ron")).unwrap();
    assert_eq!(
        b.bytes_of(scene).unwrap(),
        lectern::bundled::WATER_SCENE.as_bytes()
    );
    for name in lectern::render::pipeline::TECHNIQUE_SHADERS {
        assert!(has(&format!("shaders/{name}")), "{name} missing");
    }
    for include in [
        "common.wgsl",
        "encoding.wgsl",
        "fullscreen.wgsl",
        "brdf.wgsl",
    ] {
        assert!(
            has(&format!("shaders/{include}")),
            "include {include} missing"
        );
    }
}
