//! The students' handout, `lectern export DECK --pdf FILE --handout [--per-page 2|3]`: A4 pages
//! of 2 or 3 slides, each picture in the light theme without the widgets' controls, the
//! `handout:` texts searchable, the speaker notes absent, the bundled lecture's file small.
//! Read back with poppler (`pdfinfo`, `pdftotext`, `pdfimages`), which CI installs.

use crate::common;
use common::{export, poppler};

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::atomic::Ordering;

use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use lectern::app::{ShowControls, SlideOptions, SlideState, slide_ui_with};
use lectern::deck::{Deck, Theme, load_deck};
use lectern::widgets::{controls, work_precision};

fn lecture() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("slides/lecture.ron")
}

/// A dark deck of three slides: a title, a slope field (a slider, method checkboxes), bullets
/// without a handout text. Notes and handout texts carry words to search for.
const SMALL_DECK: &str = r#"(
    title: "Small handout deck",
    theme: Dark,
    slides: [
        (id: "one", title: "Opening", layout: Title, body: [Text("Three slides")],
         notes: "SPEAKERCUE press ] now", handout: "HANDOUTWORD first, for students."),
        (id: "two", title: "A slope field",
         body: [Widget(SlopeField((
             ode: Inline((vars: ["x"], rhs: ["-x"], initial: [1.0], t0: 0.0, exact: Some(["exp(-t)"]))),
             h: 0.5, t_end: 4.0, methods: [Euler, Rk4], exact: true)))],
         notes: "SPEAKERCUE drag the start point",
         handout: "Euler's path drifts from the exact curve; RK4 stays on it (ẋ = −x)."),
        (id: "three", title: "Bullets", body: [Bullets(["one", "two"])]),
    ],
)"#;

fn pages(pdf: &Path) -> usize {
    let o = poppler("pdfinfo", &[pdf.as_os_str()]);
    let text = String::from_utf8_lossy(&o.stdout).into_owned();
    (text.lines())
        .find_map(|l| l.strip_prefix("Pages:"))
        .and_then(|v| v.trim().parse().ok())
        .unwrap_or_else(|| panic!("no page count in {text}"))
}

fn text_of(pdf: &Path) -> String {
    let o = poppler("pdftotext", &[pdf.as_os_str(), "-".as_ref()]);
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// The words of `text` made only of ASCII letters (4 or more), in order, joined by spaces:
/// what survives line breaks and font mappings of both the deck's text and `pdftotext`'s.
fn words(text: &str) -> String {
    text.split(|c: char| !c.is_ascii_alphabetic())
        .filter(|w| w.len() >= 4)
        .collect::<Vec<_>>()
        .join(" ")
}

/// The pictures embedded in `pdf`, decoded (`pdfimages -all` writes JPEGs as they are, the
/// rest as PNG).
fn pictures(pdf: &Path, dir: &Path) -> Vec<image::RgbImage> {
    let root = dir.join("img");
    poppler(
        "pdfimages",
        &["-all".as_ref(), pdf.as_os_str(), root.as_os_str()],
    );
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| {
            p.file_name()
                .is_some_and(|n| n.to_string_lossy().starts_with("img-"))
        })
        .collect();
    files.sort();
    files
        .iter()
        .map(|f| {
            image::open(f)
                .unwrap_or_else(|e| panic!("{}: {e}", f.display()))
                .to_rgb8()
        })
        .collect()
}

/// The mean luma of the picture's border (a 6-pixel ring, 2 pixels in from the edge): the
/// slide's background colour, which no content reaches.
fn border_luma(img: &image::RgbImage) -> f64 {
    let (w, h) = img.dimensions();
    let (mut sum, mut n) = (0.0, 0u32);
    for y in 2..h - 2 {
        for x in 2..w - 2 {
            let ring = x < 8 || y < 8 || x >= w - 8 || y >= h - 8;
            if ring {
                let p = img.get_pixel(x, y).0;
                sum +=
                    0.2126 * f64::from(p[0]) + 0.7152 * f64::from(p[1]) + 0.0722 * f64::from(p[2]);
                n += 1;
            }
        }
    }
    sum / f64::from(n.max(1))
}

/// Light: the light theme's off-white background (the dark theme's is below 40).
const LIGHT_LUMA: f64 = 200.0;

/// A small dark deck: 3 slides make 2 pages at 2 a page and 1 at 3; every picture has the
/// light background although the deck is dark (its plain `--pdf` pictures are dark: the check
/// bites); the handout texts are in the text, the speaker notes are not.
#[test]
fn a_small_dark_deck_prints_light_with_its_handout_texts() {
    let dir = tempfile::tempdir().unwrap();
    let deck_file = dir.path().join("small.ron");
    std::fs::write(&deck_file, SMALL_DECK).unwrap();
    for (per_page, want_pages) in [("2", 2), ("3", 1)] {
        let pdf = dir.path().join(format!("handout-{per_page}.pdf"));
        export(&[
            deck_file.as_os_str(),
            "--pdf".as_ref(),
            pdf.as_os_str(),
            "--handout".as_ref(),
            "--per-page".as_ref(),
            per_page.as_ref(),
        ]);
        assert_eq!(pages(&pdf), want_pages, "{per_page} a page");
        let text = text_of(&pdf);
        assert!(text.contains("HANDOUTWORD first, for students."), "{text}");
        assert!(
            text.contains("Euler's path drifts from the exact curve; RK4 stays on it (ẋ = −x)."),
            "{text}"
        );
        assert!(text.contains("Small handout deck"), "the header: {text}");
        assert!(!text.contains("SPEAKERCUE"), "a speaker note: {text}");
        assert_light_pictures(&pdf, &dir.path().join(format!("img-{per_page}")), 3);
    }
    // the same deck's slides PDF shows its own (dark) theme
    let slides_pdf = dir.path().join("slides.pdf");
    export(&[
        deck_file.as_os_str(),
        "--pdf".as_ref(),
        slides_pdf.as_os_str(),
        "--size".as_ref(),
        "320x180".as_ref(),
    ]);
    let dark_dir = dir.path().join("dark");
    std::fs::create_dir(&dark_dir).unwrap();
    for img in pictures(&slides_pdf, &dark_dir) {
        assert!(
            border_luma(&img) < 60.0,
            "the slides PDF keeps the dark theme"
        );
    }
}

/// `--per-page` takes 2 or 3 and needs `--handout`; `--handout` needs `--pdf`.
#[test]
fn per_page_is_2_or_3_and_belongs_to_the_handout() {
    let run = |args: &[&str]| {
        let o = Command::new(env!("CARGO_BIN_EXE_lectern"))
            .arg("export")
            .args(args)
            .output()
            .unwrap();
        (
            o.status.success(),
            String::from_utf8_lossy(&o.stderr).into_owned(),
        )
    };
    let (ok, err) = run(&["--pdf", "x.pdf", "--handout", "--per-page", "4"]);
    assert!(!ok && err.contains("per-page"), "{err}");
    let (ok, err) = run(&["--pdf", "x.pdf", "--per-page", "2"]);
    assert!(!ok && err.contains("--handout"), "{err}");
    let (ok, err) = run(&["--handout"]);
    assert!(!ok && err.contains("--pdf"), "{err}");
    assert!(!Path::new("x.pdf").exists());
}

/// The bundled lecture at 2 and 3 a page: ⌈29 / n⌉ pages, at most 3 MB, every slide's
/// handout text found by `pdftotext`, no speaker note's words, every picture light.
#[test]
fn the_bundled_lecture_handout_is_small_light_and_has_every_text() {
    let deck = load_deck(&lecture()).unwrap();
    let n = deck.slides.len();
    assert!(
        deck.slides.iter().all(|s| !s.handout.trim().is_empty()),
        "every bundled slide has a handout text"
    );
    let dir = tempfile::tempdir().unwrap();
    for per_page in [2usize, 3] {
        let pdf = dir.path().join(format!("lecture-{per_page}.pdf"));
        let said = export(&[
            lecture().as_os_str(),
            "--pdf".as_ref(),
            pdf.as_os_str(),
            "--handout".as_ref(),
            "--per-page".as_ref(),
            per_page.to_string().as_ref(),
        ]);
        assert!(
            !said.contains("handout text has"),
            "{per_page} a page: {said}"
        );
        assert_eq!(pages(&pdf), n.div_ceil(per_page), "{per_page} a page");
        let bytes = std::fs::metadata(&pdf).unwrap().len();
        assert!(
            bytes <= 3_000_000,
            "{per_page} a page: {bytes} bytes, over the 3 MB the handout may take"
        );
        let text = words(&text_of(&pdf));
        for (i, slide) in deck.slides.iter().enumerate() {
            let want = words(&slide.handout);
            assert!(
                text.contains(&want),
                "slide {} ({}): its handout text is not in the PDF: {want:?}",
                i + 1,
                slide.key()
            );
        }
        // a speaker-only cue: the notes tell the lecturer which keys to press
        let cue = words("Press ] to build the step: the tangent at x0, then the step along it.");
        assert!(
            deck.slides.iter().any(|s| words(&s.notes).contains(&cue)),
            "the cue is a speaker note"
        );
        assert!(
            !text.contains(&cue),
            "{per_page} a page: a speaker note is printed"
        );
        assert_light_pictures(&pdf, &dir.path().join(format!("img-{per_page}")), n);
    }
}

/// The roles of egui's controls in its accessibility tree.
const CONTROL_ROLES: [Role; 6] = [
    Role::Slider,
    Role::CheckBox,
    Role::Button,
    Role::RadioButton,
    Role::SpinButton,
    Role::TextInput,
];

/// Slide `index` of `deck` drawn in a test harness with `controls`: the control rects the
/// slide listed (`controls::control_rects`) and the rects of the controls egui's accessibility
/// tree has.
fn controls_of(
    deck: &Deck,
    index: usize,
    controls: ShowControls,
) -> (Vec<egui::Rect>, Vec<egui::Rect>) {
    let deck = deck.clone();
    let mut state = SlideState::default();
    let mut h = Harness::builder()
        .with_size(egui::vec2(1280.0, 720.0))
        .build_ui(move |ui| {
            let options = SlideOptions {
                controls,
                ..SlideOptions::default()
            };
            slide_ui_with(ui, &deck, index, &mut state, options);
        });
    h.run_steps(3);
    let listed = controls::control_rects(&h.ctx);
    let mut in_tree = Vec::new();
    for role in CONTROL_ROLES {
        in_tree.extend(h.query_all_by_role(role).map(|n| n.rect()));
    }
    (listed, in_tree)
}

/// The handout's pictures have no slider, tick box or button: every slide of the bundled
/// lecture (in the light theme, as printed) lists no control rect and has no control in its
/// accessibility tree when drawn as the handout draws it; drawn with its controls, the same
/// slides list them, and every control in the tree lies inside a listed rect (so the list is
/// complete: a widget drawing a control past `controls::control` fails here).
#[test]
fn handout_slides_draw_no_controls_and_every_control_is_listed() {
    work_precision::DETERMINISTIC.store(true, Ordering::Relaxed);
    let mut deck = load_deck(&lecture()).unwrap();
    deck.theme = Theme::Light;
    let (mut with_controls, mut in_tree_controls) = (0, 0);
    for (i, slide) in deck.slides.iter().enumerate() {
        if slide.widgets().is_empty() {
            continue;
        }
        let (listed, in_tree) = controls_of(&deck, i, ShowControls::Always);
        for r in &in_tree {
            assert!(
                listed.iter().any(|l| l.expand(1.0).contains_rect(*r)),
                "slide {} ({}): a control at {r:?} is not in the list {listed:?}",
                i + 1,
                slide.key()
            );
        }
        with_controls += usize::from(!listed.is_empty());
        in_tree_controls += in_tree.len();
        let (listed, in_tree) = controls_of(&deck, i, ShowControls::Never);
        assert!(
            listed.is_empty() && in_tree.is_empty(),
            "slide {} ({}): in the handout {} listed control(s), {} in the tree",
            i + 1,
            slide.key(),
            listed.len(),
            in_tree.len()
        );
    }
    // the plot slides have sliders: slope field, Euler, spirals, Neptune, stability, Taylor, …
    assert!(
        with_controls >= 12,
        "only {with_controls} slides drew controls"
    );
    // the containment check above had controls to check
    assert!(
        in_tree_controls >= 30,
        "{in_tree_controls} controls in the trees"
    );
}

/// The PDF's slide pictures (extracted into `imgs_dir`) are `n`, each on a light background.
fn assert_light_pictures(pdf: &Path, imgs_dir: &Path, n: usize) {
    std::fs::create_dir(imgs_dir).unwrap();
    let imgs = pictures(pdf, imgs_dir);
    assert_eq!(imgs.len(), n, "one picture per slide");
    for (i, img) in imgs.iter().enumerate() {
        let luma = border_luma(img);
        assert!(
            luma > LIGHT_LUMA,
            "slide {}: background luma {luma:.0}",
            i + 1
        );
    }
}
