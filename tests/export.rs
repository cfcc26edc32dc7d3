//! Headless export: the bundled deck through the window's slide renderer into PNGs, on whatever
//! adapter exists (Mesa's software one in CI).

use std::path::Path;
use std::process::Command;

use lectern::app::{OffscreenRenderer, SlideState};
use lectern::deck::load_deck;

fn lecture() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("slides/lecture.ron")
}

/// Not blank: many distinct colours, and a good share of pixels away from the background.
fn assert_not_blank(img: &image::RgbaImage, what: &str) {
    let mut colours = std::collections::HashSet::new();
    for p in img.pixels() {
        colours.insert(p.0);
    }
    let bg = img.get_pixel(img.width() / 2, 2).0;
    let differing = img
        .pixels()
        .filter(|p| {
            p.0.iter()
                .zip(bg)
                .map(|(a, b)| (*a as i32 - b as i32).abs())
                .sum::<i32>()
                > 60
        })
        .count();
    let share = differing as f64 / (img.width() * img.height()) as f64;
    assert!(colours.len() > 50, "{what}: only {} colours", colours.len());
    assert!(
        share > 0.003,
        "{what}: only {:.4} of the pixels carry content",
        share
    );
}

#[test]
fn every_bundled_slide_renders_headless_at_the_requested_size() {
    let deck = load_deck(&lecture()).unwrap();
    let mut r = OffscreenRenderer::software_first().expect("an adapter (lavapipe or llvmpipe)");
    for size in [[640, 360], [1024, 768]] {
        for i in 0..deck.slides.len() {
            let img = r
                .render_slide(&deck, i, &mut SlideState::default(), size)
                .unwrap();
            assert_eq!([img.width(), img.height()], size);
            assert_not_blank(&img, &format!("slide {} at {size:?}", i + 1));
        }
    }
}

/// The canvas scales with the output: a 4K render is the 720p render, four... nine times the
/// pixels. Downscaled, they must agree (same layout, same line breaks).
#[test]
fn the_same_slide_at_720p_and_4k() {
    let deck = load_deck(&lecture()).unwrap();
    let mut r = OffscreenRenderer::software_first().unwrap();
    let small = r
        .render_slide(&deck, 1, &mut SlideState::default(), [1280, 720])
        .unwrap();
    let big = r
        .render_slide(&deck, 1, &mut SlideState::default(), [3840, 2160])
        .unwrap();
    let down = image::imageops::resize(&big, 1280, 720, image::imageops::FilterType::Triangle);
    let (mut diff, mut n) = (0u64, 0u64);
    for (a, b) in small.pixels().zip(down.pixels()) {
        for c in 0..3 {
            diff += (a.0[c] as i64 - b.0[c] as i64).unsigned_abs();
            n += 1;
        }
    }
    let mean = diff as f64 / n as f64;
    assert!(
        mean < 4.0,
        "720p and downscaled 4K differ by {mean:.2} per channel"
    );
}

#[test]
fn export_cli_writes_one_png_per_slide() {
    let out = tempfile::tempdir().unwrap();
    let status = Command::new(env!("CARGO_BIN_EXE_lectern"))
        .args(["export"])
        .arg(lecture())
        .arg("--out")
        .arg(out.path())
        .args(["--size", "800x450"])
        .status()
        .unwrap();
    assert!(status.success());
    let deck = load_deck(&lecture()).unwrap();
    for i in 1..=deck.slides.len() {
        let file = out.path().join(format!("slide-{i:02}.png"));
        let img = image::open(&file)
            .unwrap_or_else(|e| panic!("{}: {e}", file.display()))
            .to_rgba8();
        assert_eq!(img.dimensions(), (800, 450));
        assert_not_blank(&img, &file.display().to_string());
    }
    let extra = out
        .path()
        .join(format!("slide-{:02}.png", deck.slides.len() + 1));
    assert!(!extra.exists());
}

#[test]
fn export_without_any_adapter_fails_with_one_line() {
    let out = tempfile::tempdir().unwrap();
    // Metal exists on no Linux machine: wgpu finds no adapter at all.
    let o = Command::new(env!("CARGO_BIN_EXE_lectern"))
        .env("WGPU_BACKEND", "metal")
        .args(["export", "--out"])
        .arg(out.path())
        .output()
        .unwrap();
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    let ours: Vec<&str> = err.lines().filter(|l| l.starts_with("lectern:")).collect();
    assert_eq!(ours.len(), 1, "{err}");
    assert!(ours[0].contains("no graphics adapter"), "{err}");
}

#[test]
fn export_rejects_a_bad_size() {
    let out = tempfile::tempdir().unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_lectern"))
        .args(["export", "--out"])
        .arg(out.path())
        .args(["--size", "wide"])
        .output()
        .unwrap();
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("WIDTHxHEIGHT"));
}
