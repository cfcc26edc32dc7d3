//! Inline maths (`$…$` in `Text`, `Bullets` and captions): typeset by Typst, set on the
//! text's baseline, drawn the same by the window's renderer, `lectern export` and its PDF,
//! and checked by `lectern check` down to the character.
//!
//! Regenerate the snapshot after an intended change (then LOOK at it before committing):
//!     UPDATE_SNAPSHOTS=1 cargo test --test suite inline_maths::

use std::path::Path;
use std::process::Command;
use std::sync::Arc;

use egui_kittest::{Harness, SnapshotOptions};
use lectern::app::{OffscreenRenderer, SlideState, slide_ui};
use lectern::deck::{Deck, parse_deck};
use lectern::math::{MathStyle, MathSyntax, render_math};

const BLACK: [u8; 4] = [0, 0, 0, 255];

fn deck(body: &str) -> Deck {
    let text = format!(r#"(title: "Inline", slides: [(title: "Steps", body: [{body}])])"#);
    parse_deck(&text, Path::new("inline.ron")).unwrap()
}

/// Rows (top, bottom) holding ink in the `rgba` picture (premultiplied, `width` wide).
fn ink_rows(rgba: &[u8], width: u32) -> (usize, usize) {
    let rows: Vec<usize> = (rgba.chunks(4 * width as usize).enumerate())
        .filter(|(_, row)| row.chunks(4).any(|p| p[3] > 128))
        .map(|(y, _)| y)
        .collect();
    (rows[0], *rows.last().unwrap())
}

/// Typst says where the baseline is: an `x` (no descender) ends on it, `x_0` goes below it,
/// and a leading space in the source still counts in an error's column.
#[test]
fn an_inline_formula_knows_its_baseline() {
    let x = render_math("x", MathSyntax::Typst, MathStyle::Inline, 100.0, BLACK).unwrap();
    let (_, bottom) = ink_rows(&x.rgba_premultiplied, x.width);
    assert!(
        (bottom as i64 + 1 - x.baseline as i64).abs() <= 2,
        "x ends at row {bottom}, baseline {}",
        x.baseline
    );
    let sub = render_math("x_0", MathSyntax::Typst, MathStyle::Inline, 100.0, BLACK).unwrap();
    let (_, bottom) = ink_rows(&sub.rgba_premultiplied, sub.width);
    assert!(
        bottom as u32 > sub.baseline + 10,
        "the subscript hangs below"
    );
    // inline style sets a fraction smaller than display style does
    let frac = |style| {
        render_math("1/2", MathSyntax::Typst, style, 100.0, BLACK)
            .unwrap()
            .height
    };
    assert!(frac(MathStyle::Inline) < frac(MathStyle::Display));
    let e = render_math(
        "  x + nosuch",
        MathSyntax::Typst,
        MathStyle::Inline,
        40.0,
        BLACK,
    )
    .unwrap_err();
    assert_eq!(e.col, Some(7), "{e}");
}

/// Column ranges of ink in `rows` of `img` (pixels far from the background), left to right.
fn ink_clusters(img: &image::RgbaImage, rows: std::ops::Range<u32>) -> Vec<(u32, u32, u32)> {
    let bg = img.get_pixel(img.width() / 2, 2).0;
    let inked = |x: u32, y: u32| {
        let p = img.get_pixel(x, y).0;
        (0..3)
            .map(|i| (p[i] as i32 - bg[i] as i32).abs())
            .sum::<i32>()
            > 200
    };
    let mut out: Vec<(u32, u32, u32)> = Vec::new();
    let mut gap = u32::MAX;
    for x in 0..img.width() {
        let bottom = rows.clone().filter(|&y| inked(x, y)).max();
        match (bottom, out.last_mut()) {
            (Some(b), Some(last)) if gap < 6 => {
                last.1 = x;
                last.2 = last.2.max(b);
                gap = 0;
            }
            (Some(b), _) => {
                out.push((x, x, b));
                gap = 0;
            }
            (None, _) => gap = gap.saturating_add(1),
        }
    }
    out
}

/// At 1080p the formula's baseline is the text's: the plain `xx` and the maths `x^2` beside
/// it end on the same pixel row (within 2 px). Aligning the pictures' tops or centres instead
/// would move the maths `x` by the superscript's height.
#[test]
fn the_formula_sits_on_the_text_baseline_at_1080p() {
    let deck = deck(r#"Text("xx $x^2$")"#);
    let mut r = OffscreenRenderer::software_first().expect("an adapter (lavapipe or llvmpipe)");
    let img = r
        .render_slide(&deck, 0, &mut SlideState::default(), [1920, 1080])
        .unwrap();
    // the body sits between the title's rule and the footer
    let clusters = ink_clusters(&img, 205..950);
    assert!(clusters.len() >= 2, "text and formula: {clusters:?}");
    let (text, maths) = (clusters[0], clusters[clusters.len() - 1]);
    assert!(maths.1 - maths.0 > 30, "the formula is drawn: {clusters:?}");
    assert!(
        (text.2 as i64 - maths.2 as i64).abs() <= 2,
        "text ends at row {}, the formula's x at row {}: {clusters:?}",
        text.2,
        maths.2
    );
}

/// A bullet with inline maths, through the app's slide renderer (the window's and the
/// export's): formulas at the text's size, on its baseline, wrapped with the words.
#[test]
fn a_bullet_with_inline_maths_matches_its_snapshot() {
    let deck = Arc::new(deck(
        r#"Bullets([
            "Start at $x_0$, follow the slope $dot(x) = f(x, t)$ in steps of $h$",
            "The error after one step is $O(h^2)$, after $T/h$ steps $O(h)$: Euler is first order, and past $|1 + h lambda| <= 1$ it runs off to Neptune",
            "A dollar stays a dollar: \\$5, and *emphasis* still works",
        ])"#,
    ));
    let mut state = SlideState::default();
    let mut h = Harness::builder()
        .with_size(egui::vec2(1280.0, 720.0))
        .wgpu()
        .build_ui(move |ui| {
            slide_ui(ui, &deck, 0, &mut state);
        });
    h.run_steps(3);
    h.snapshot_options(
        "inline-maths-bullets",
        &SnapshotOptions::new().threshold(0.6).max_failed_pixels(8),
    );
}

/// `lectern check` typesets inline formulas and reports a Typst error inside `$…$` at the
/// file:line:col of its character.
#[test]
fn check_reports_an_inline_error_at_its_character() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("inline.ron");
    let text = "(title: \"Inline\", slides: [(title: \"Steps\", body: [\n    Bullets([\"fine $h$\", \"ω then $x + nosuchthing(2)$\"]),\n])])";
    std::fs::write(&file, text).unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_lectern"))
        .arg("check")
        .arg(&file)
        .env_remove("XDG_RUNTIME_DIR")
        .output()
        .unwrap();
    let out = String::from_utf8_lossy(&o.stdout).into_owned() + &String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "{out}");
    let line = text.lines().nth(1).unwrap();
    let byte = line.find("nosuchthing").unwrap();
    let col = line[..byte].chars().count() + 1;
    let want = format!("inline.ron:2:{col}: formula:");
    assert!(out.contains(&want), "want {want} in {out}");
    assert!(out.contains("nosuchthing"), "{out}");
}

/// `latex: true` on a paragraph or a list: its `$…$` are LaTeX (the plain string form stays
/// Typst); `check` typesets them so and reports a LaTeX error at its formula's first character
/// (mitex gives no column inside the formula).
#[test]
fn latex_paragraphs_typeset_as_latex_and_check_places_their_error() {
    use lectern::deck::Block;
    let latex = deck(r#"Text((src: r"where $\alpha \le 1$ holds", latex: true))"#);
    let formulas = lectern::math::deck::formulas(&latex, None);
    assert_eq!(formulas.len(), 1);
    assert_eq!(
        (formulas[0].src, formulas[0].syntax),
        (r"\alpha \le 1", MathSyntax::Latex)
    );
    let plain = deck(r#"Bullets(["$alpha$"]), Bullets((items: ["$\\beta$"], latex: true))"#);
    let syntaxes: Vec<MathSyntax> = (lectern::math::deck::formulas(&plain, None).iter())
        .map(|f| f.syntax)
        .collect();
    assert_eq!(syntaxes, [MathSyntax::Typst, MathSyntax::Latex]);
    assert!(matches!(&plain.slides[0].body[1], Block::Bullets(b) if b.latex));

    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("inline.ron");
    let text = concat!(
        "(title: \"Inline\", slides: [(title: \"Steps\", body: [\n",
        "    Text((src: r\"fine $\\alpha$\", latex: true)),\n",
        "    Bullets((items: [\"ok\", r\"ω then $x + \\notacommand{x}$ and\"], latex: true)),\n",
        "])])"
    );
    std::fs::write(&file, text).unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_lectern"))
        .arg("check")
        .arg(&file)
        .env_remove("XDG_RUNTIME_DIR")
        .output()
        .unwrap();
    let out = String::from_utf8_lossy(&o.stdout).into_owned() + &String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "{out}");
    let line = text.lines().nth(2).unwrap();
    let byte = line.find(r"x + \notacommand").unwrap();
    let col = line[..byte].chars().count() + 1;
    let want = format!("inline.ron:3:{col}: formula:");
    assert!(out.contains(&want), "want {want} in {out}");
    assert!(
        !out.contains("inline.ron:2:"),
        "the good LaTeX paragraph passes: {out}"
    );
}

/// The PDF handout keeps the maths: its page image is the PNG export (formula included), and
/// differs from the same slide with the formula left out.
#[test]
fn the_pdf_handout_keeps_the_maths() {
    let dir = tempfile::tempdir().unwrap();
    let write = |name: &str, body: &str| {
        let file = dir.path().join(name);
        let text = format!(r#"(title: "Inline", slides: [(title: "Steps", body: [{body}])])"#);
        std::fs::write(&file, text).unwrap();
        file
    };
    let with = write("with.ron", r#"Text("the step $h^2/2 dot.double(x)$ here")"#);
    let without = write("without.ron", r#"Text("the step here")"#);
    let export = |deck: &Path, out: &str| {
        let pdf = dir.path().join(format!("{out}.pdf"));
        let o = Command::new(env!("CARGO_BIN_EXE_lectern"))
            .arg("export")
            .arg(deck)
            .arg("--pdf")
            .arg(&pdf)
            .args(["--size", "960x540"])
            .env_remove("XDG_RUNTIME_DIR")
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let prefix = dir.path().join(out);
        let o = Command::new("pdfimages")
            .arg("-png")
            .arg(&pdf)
            .arg(&prefix)
            .output()
            .expect("pdfimages (poppler-utils) reads the PDF back");
        assert!(o.status.success());
        image::open(dir.path().join(format!("{out}-000.png")))
            .unwrap()
            .to_rgba8()
    };
    let page = export(&with, "with");
    let plain = export(&without, "without");
    let mut r = OffscreenRenderer::software_first().expect("an adapter");
    let png = r
        .render_slide(
            &deck(r#"Text("the step $h^2/2 dot.double(x)$ here")"#),
            0,
            &mut SlideState::default(),
            [960, 540],
        )
        .unwrap();
    assert_eq!(page.dimensions(), png.dimensions());
    let differ = |a: &image::RgbaImage, b: &image::RgbaImage| {
        (a.pixels().zip(b.pixels()))
            .filter(|(p, q)| (0..3).any(|i| (p.0[i] as i32 - q.0[i] as i32).abs() > 40))
            .count()
    };
    assert!(differ(&page, &png) <= 8, "the PDF's page is the export");
    assert!(
        differ(&page, &plain) > 300,
        "the formula is on the PDF's page"
    );
}
