//! Headless export: the bundled deck through the window's slide renderer into PNGs and a PDF,
//! on whatever adapter exists (Mesa's software one in CI), compared with committed goldens.
//!
//! Regenerate the goldens after an intended change (then LOOK at them before committing):
//!     UPDATE_SNAPSHOTS=1 cargo test --test suite export::every_slide_matches_its_export_golden

use crate::common;
use common::{export, poppler};

use std::path::{Path, PathBuf};
use std::process::Command;

use std::sync::atomic::Ordering;

use egui_kittest::SnapshotOptions;
use lectern::app::{OffscreenRenderer, SlideState};
use lectern::deck::{Block, Deck, load_deck};
use lectern::widgets::work_precision;

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

/// The slide snapshots' tolerance (`tests/slides.rs`): per-pixel threshold 0.6, 8 pixels.
fn snapshot_options() -> SnapshotOptions {
    SnapshotOptions::new().threshold(0.6).max_failed_pixels(8)
}

/// Every slide through `lectern export`'s renderer, against its committed golden
/// (`tests/snapshots/export-NN-id.png`; regenerate with `UPDATE_SNAPSHOTS=1`).
#[test]
fn every_slide_matches_its_export_golden() {
    work_precision::DETERMINISTIC.store(true, Ordering::Relaxed);
    let deck = load_deck(&lecture()).unwrap();
    let mut r = OffscreenRenderer::software_first().expect("an adapter (lavapipe or llvmpipe)");
    let mut results = egui_kittest::SnapshotResults::new();
    for (i, slide) in deck.slides.iter().enumerate() {
        let img = r
            .render_slide(&deck, i, &mut SlideState::default(), GOLDEN_SIZE)
            .unwrap();
        assert_eq!([img.width(), img.height()], GOLDEN_SIZE);
        let name = format!("export-{:02}-{}", i + 1, slide.key());
        results.add(egui_kittest::try_image_snapshot_options(
            &img,
            name,
            &snapshot_options(),
        ));
    }
    results.unwrap();
}

const GOLDEN_SIZE: [u32; 2] = [800, 450];

/// A size of another shape: the slide is letterboxed into exactly the pixels asked for.
#[test]
fn another_aspect_is_letterboxed_at_the_requested_size() {
    let deck = load_deck(&lecture()).unwrap();
    let mut r = OffscreenRenderer::software_first().unwrap();
    let img = r
        .render_slide(&deck, 1, &mut SlideState::default(), [512, 384])
        .unwrap();
    assert_eq!(img.dimensions(), (512, 384));
    assert_not_blank(&img, "slide 2 at 512x384");
}

/// 16x16-pixel blocks whose mean colour differs by more than 16 (of 255) between `a` and `b`.
fn differing_blocks(a: &image::RgbaImage, b: &image::RgbaImage) -> usize {
    const N: u32 = 16;
    let mean = |img: &image::RgbaImage, bx: u32, by: u32| {
        let mut sum = [0u32; 3];
        for y in by * N..(by + 1) * N {
            for x in bx * N..(bx + 1) * N {
                let p = img.get_pixel(x, y).0;
                (0..3).for_each(|c| sum[c] += u32::from(p[c]));
            }
        }
        sum.map(|v| v as f64 / f64::from(N * N))
    };
    let mut n = 0;
    for by in 0..a.height() / N {
        for bx in 0..a.width() / N {
            let (p, q) = (mean(a, bx, by), mean(b, bx, by));
            let d = (0..3).map(|c| (p[c] - q[c]).abs()).sum::<f64>() / 3.0;
            n += usize::from(d > 16.0);
        }
    }
    n
}

/// The slide scales with the output: a 4K export is the 720p export with nine times the
/// pixels, plots included (same strokes, ticks and line breaks). Downscaled, the two agree to
/// the block; the same slide missing its formula or its plot does not.
#[test]
fn the_same_slide_at_720p_and_4k() {
    let deck = load_deck(&lecture()).unwrap();
    let index = deck
        .find("taylor")
        .expect("the Taylor slide: a formula and a plot");
    let mut r = OffscreenRenderer::software_first().unwrap();
    let mut render = |deck: &Deck, size| {
        r.render_slide(deck, index, &mut SlideState::default(), size)
            .unwrap()
    };
    let small = render(&deck, [1280, 720]);
    let big = render(&deck, [3840, 2160]);
    let down = image::imageops::resize(&big, 1280, 720, image::imageops::FilterType::Triangle);
    let same = differing_blocks(&small, &down);
    assert!(
        same <= 8,
        "720p and downscaled 4K differ in {same} of 3600 blocks"
    );
    // The comparison bites: the 720p slide without its formula, or without its plot.
    for (what, is) in [
        (
            "formula",
            (|b: &Block| matches!(b, Block::Math { .. })) as fn(&Block) -> bool,
        ),
        ("plot", |b: &Block| matches!(b, Block::Widget(_))),
    ] {
        let mut missing = deck.clone();
        let body = &mut missing.slides[index].body;
        let at = body.iter().position(is).unwrap();
        body.remove(at);
        let n = differing_blocks(&render(&missing, [1280, 720]), &down);
        assert!(n >= 100, "without its {what}, only {n} blocks differ");
    }
}

/// `pdfinfo`'s value for `key` ("Pages", "Page size").
fn pdfinfo(pdf: &Path, key: &str) -> String {
    let o = poppler("pdfinfo", &[pdf.as_os_str()]);
    let text = String::from_utf8_lossy(&o.stdout).into_owned();
    text.lines()
        .find_map(|l| l.strip_prefix(&format!("{key}:")))
        .unwrap_or_else(|| panic!("no {key} in {text}"))
        .trim()
        .to_owned()
}

/// One CLI run writes the PNGs and the PDF: one page per slide, shaped like the slide; the
/// image embedded in each page equals its PNG within the snapshot tolerance (`pdfimages`), and
/// each page rasterised back (`pdftoppm`) shows it in the right place (poppler resamples the
/// picture, so that comparison is block by block).
#[test]
fn export_cli_writes_pngs_and_a_pdf_of_the_same_slides() {
    let out = tempfile::tempdir().unwrap();
    let pdf = out.path().join("handout.pdf");
    export(&[
        lecture().as_os_str(),
        "--out".as_ref(),
        out.path().as_os_str(),
        "--pdf".as_ref(),
        pdf.as_os_str(),
        "--size".as_ref(),
        "640x360".as_ref(),
    ]);
    let deck = load_deck(&lecture()).unwrap();
    let n = deck.slides.len();
    assert_eq!(pdfinfo(&pdf, "Pages"), n.to_string());
    assert_eq!(pdfinfo(&pdf, "Page size"), "720 x 405 pts");
    assert!(!out.path().join(format!("slide-{:02}.png", n + 1)).exists());
    let (embedded, raster) = (out.path().join("img"), out.path().join("page"));
    poppler(
        "pdfimages",
        &["-png".as_ref(), pdf.as_os_str(), embedded.as_os_str()],
    );
    // 720 pt at 64 dpi is 640 pixels: the page's raster has the PNG's size
    poppler(
        "pdftoppm",
        &[
            "-r".as_ref(),
            "64".as_ref(),
            "-png".as_ref(),
            pdf.as_os_str(),
            raster.as_os_str(),
        ],
    );
    let digits = n.to_string().len();
    let open = |file: PathBuf| {
        image::open(&file)
            .unwrap_or_else(|e| panic!("{}: {e}", file.display()))
            .to_rgba8()
    };
    for i in 1..=n {
        let png = open(out.path().join(format!("slide-{i:02}.png")));
        assert_eq!(png.dimensions(), (640, 360));
        let image = open(out.path().join(format!("img-{:03}.png", i - 1)));
        let wrong = dify::diff::get_results(png.clone(), image, 0.6, true, None, &None, &None)
            .map_or(0, |(n, _)| n);
        assert!(
            wrong <= 8,
            "page {i}'s image differs from slide-{i:02}.png in {wrong} pixels"
        );
        let page = open(out.path().join(format!("page-{i:0digits$}.png")));
        assert_eq!(page.dimensions(), png.dimensions(), "page {i}");
        let blocks = differing_blocks(&png, &page);
        assert!(
            blocks <= 8,
            "page {i} differs from slide-{i:02}.png in {blocks} blocks"
        );
    }
}

/// `--notes`: A4 pages with the slide on top and the notes below as text a reader can search
/// and copy, Unicode included; markup characters in notes stay text.
#[test]
fn notes_handout_has_searchable_unicode_notes() {
    let dir = tempfile::tempdir().unwrap();
    let deck_file = dir.path().join("notes.ron");
    std::fs::write(
        &deck_file,
        r#"(title: "Notes", slides: [
            (title: "One", body: [Math(src: "dot(x) = omega x")],
             notes: "The state derivative ẋ = ω² x; *not bold* #not-code $not-maths$."),
            (title: "Two", body: [Text("second")], notes: "Second slide's notes."),
        ])"#,
    )
    .unwrap();
    let pdf = dir.path().join("handout.pdf");
    export(&[
        deck_file.as_os_str(),
        "--pdf".as_ref(),
        pdf.as_os_str(),
        "--notes".as_ref(),
        "--size".as_ref(),
        "640x360".as_ref(),
    ]);
    assert_eq!(pdfinfo(&pdf, "Pages"), "2");
    assert!(pdfinfo(&pdf, "Page size").contains("(A4)"));
    let text = poppler("pdftotext", &[pdf.as_os_str(), "-".as_ref()]);
    let text = String::from_utf8_lossy(&text.stdout);
    let pages: Vec<&str> = text.split('\u{c}').collect();
    assert!(
        pages[0].contains("ẋ = ω² x; *not bold* #not-code $not-maths$."),
        "{text}"
    );
    assert!(pages[0].contains("Slide 1 of 2: One"), "{text}");
    assert!(pages[1].contains("Second slide's notes."), "{text}");
}

#[test]
fn a_failed_formula_or_widget_fails_the_export_unless_keep_going() {
    let dir = tempfile::tempdir().unwrap();
    let deck_file = dir.path().join("bad.ron");
    std::fs::write(
        &deck_file,
        r#"(title: "Bad", slides: [
            (title: "One", body: [Math(src: "dot(x) = #nosuchfn(x)")]),
            (title: "Two", body: [Widget(Stability((methods: [Tableau("tableaux/nope.ron")])))]),
        ])"#,
    )
    .unwrap();
    let out = dir.path().join("png");
    let run = |extra: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_lectern"))
            .arg("export")
            .arg(&deck_file)
            .arg("--out")
            .arg(&out)
            .args(["--size", "320x180"])
            .args(extra)
            .output()
            .unwrap()
    };
    let o = run(&[]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "{err}");
    assert!(err.contains("slide 1") && err.contains("nosuchfn"), "{err}");
    assert!(err.contains("slide 2") && err.contains("nope.ron"), "{err}");
    // the images are written all the same
    assert!(out.join("slide-01.png").exists() && out.join("slide-02.png").exists());
    let o = run(&["--keep-going"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
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
