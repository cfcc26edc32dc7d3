//! Helpers shared by the integration tests.
#![allow(dead_code)]

use std::path::{Path, PathBuf};

/// A copy of the bundled lecture with the problem and tableau files it names, in a temporary
/// project (`DIR/slides/lecture.ron`), so tests may break or write into it.
pub fn lecture_copy() -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("slides");
    let slides = dir.path().join("slides");
    for sub in ["problems", "tableaux"] {
        std::fs::create_dir_all(slides.join(sub)).unwrap();
        for entry in std::fs::read_dir(src.join(sub)).unwrap() {
            let entry = entry.unwrap().path();
            std::fs::copy(&entry, slides.join(sub).join(entry.file_name().unwrap())).unwrap();
        }
    }
    let path = slides.join("lecture.ron");
    std::fs::copy(src.join("lecture.ron"), &path).unwrap();
    (dir, path)
}

/// The circle x' = −y, y' = x written inline, for small test decks.
pub const CIRCLE: &str = r#"ode: Inline((vars: ["x", "y"], rhs: ["-y", "x"], initial: [1.0, 0.0], exact: Some(["x*cos(t - t0) - y*sin(t - t0)", "x*sin(t - t0) + y*cos(t - t0)"])))"#;

/// The scene goldens' comparison (egui_kittest's image snapshot, the same dify call): a pixel
/// fails above this weighted squared YIQ distance (a uniform 2/255 step is ≈ 2.0; lavapipe and
/// llvmpipe's GL differ by 1/255 here and there, renders on one adapter are byte-identical) …
pub const SCENE_SNAPSHOT_THRESHOLD: f32 = 2.0;
/// … and at most this fraction of the pixels may fail (0.1 %: 230 pixels at 640×360).
pub const SCENE_MAX_FAILED_FRACTION: f64 = 0.001;

pub fn scene_max_failed_pixels(img: &image::RgbaImage) -> usize {
    (SCENE_MAX_FAILED_FRACTION * f64::from(img.width() * img.height())) as usize
}

/// Pixels the scene goldens' comparison fails between `a` and `b`.
pub fn scene_failing_pixels(a: &image::RgbaImage, b: &image::RgbaImage) -> usize {
    assert_eq!(a.dimensions(), b.dimensions());
    dify::diff::get_results(
        a.clone(),
        b.clone(),
        SCENE_SNAPSHOT_THRESHOLD,
        true,
        None,
        &None,
        &None,
    )
    .map_or(0, |(n, _)| n.max(0) as usize)
}

/// Whether a scene golden recorded as `a` would accept `b`.
pub fn scene_within_tolerance(a: &image::RgbaImage, b: &image::RgbaImage) -> bool {
    scene_failing_pixels(a, b) <= scene_max_failed_pixels(a)
}

/// egui_kittest's snapshot options for the scene goldens of `img`'s size.
pub fn scene_snapshot_options(img: &image::RgbaImage) -> egui_kittest::SnapshotOptions {
    egui_kittest::SnapshotOptions::new()
        .threshold(SCENE_SNAPSHOT_THRESHOLD)
        .max_failed_pixels(scene_max_failed_pixels(img))
}

/// A headless device on the GL backend (Mesa's llvmpipe in CI), or None after saying loudly why
/// not: the caller skips only its GL case.
pub fn gl_gpu(test: &str) -> Option<lectern::render::gpu::Gpu> {
    let request = lectern::render::gpu::GpuRequest {
        backends: Some(wgpu::Backends::GL),
        ..Default::default()
    };
    match lectern::render::gpu::Gpu::new(&request) {
        Ok(gpu) => Some(gpu),
        Err(e) => {
            eprintln!(
                "\n!!!!! {test}: SKIPPING THE GL CASE: no GL adapter ({e:#}); \
                 install libegl1 libgl1-mesa-dri !!!!!\n"
            );
            None
        }
    }
}

/// The scene renderer on the GL backend with the formats its adapter allows.
pub fn gl_headless(
    test: &str,
    scene: lectern::scene::Scene,
    shaders: &Path,
) -> Option<lectern::render::Headless> {
    let gpu = gl_gpu(test)?;
    assert_eq!(gpu.adapter_info.backend, wgpu::Backend::Gl);
    let caps = lectern::render::caps::RenderCaps::decide(&gpu.caps);
    Some(lectern::render::Headless::with_gpu(gpu, caps, scene, shaders).unwrap())
}

/// Every text a slide draws, as (text, screen rect, clip rect).
pub fn text_boxes(output: &egui::FullOutput) -> Vec<(String, egui::Rect, egui::Rect)> {
    use egui::epaint::Shape;
    fn walk(shape: &Shape, clip: egui::Rect, out: &mut Vec<(String, egui::Rect, egui::Rect)>) {
        match shape {
            Shape::Vec(v) => v.iter().for_each(|s| walk(s, clip, out)),
            // row by row: a label in a wrapping row is laid out from the row's left edge
            // (its galley's rect covers that leading space), so the rows' own rects are where
            // the glyphs are
            Shape::Text(t) if t.angle == 0.0 => {
                for row in &t.galley.rows {
                    let text: String = row.row.glyphs.iter().map(|g| g.chr).collect();
                    if !text.trim().is_empty() {
                        let rect = row.rect_without_leading_space().translate(t.pos.to_vec2());
                        out.push((text, rect, clip));
                    }
                }
            }
            _ => {}
        }
    }
    let mut out = Vec::new();
    for c in &output.shapes {
        walk(&c.shape, c.clip_rect, &mut out);
    }
    out
}

/// Runs `lectern export` with `args`; its stderr.
pub fn export(args: &[&std::ffi::OsStr]) -> String {
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_lectern"))
        .arg("export")
        .args(args)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(o.status.success(), "{err}");
    err
}

/// A poppler tool (CI installs poppler-utils: `.ci/run`, `scripts/setup-debian`).
pub fn poppler(tool: &str, args: &[&std::ffi::OsStr]) -> std::process::Output {
    let o = std::process::Command::new(tool)
        .args(args)
        .output()
        .unwrap_or_else(|e| panic!("{tool} (poppler-utils) is needed to read the PDF back: {e}"));
    assert!(
        o.status.success(),
        "{tool}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    o
}
