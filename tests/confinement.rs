//! Pictures on a slide, as the app draws them: only files inside the project are shown, a
//! picture whose header claims huge dimensions is refused before decoding, and each refusal is
//! a slide problem at the deck's line and column of the path string.

use std::path::{Path, PathBuf};

use egui::TextureId;
use egui::epaint::Shape;
use egui_kittest::Harness;
use lectern::app::{SlideState, slide_ui};
use lectern::deck::load_deck;

/// A valid PNG signature and IHDR claiming `w × h` RGBA pixels, and no pixel data.
fn png_header(w: u32, h: u32) -> Vec<u8> {
    let mut ihdr = b"IHDR".to_vec();
    ihdr.extend(w.to_be_bytes());
    ihdr.extend(h.to_be_bytes());
    ihdr.extend([8, 6, 0, 0, 0]);
    let mut c = 0xffff_ffffu32;
    for &b in &ihdr {
        c ^= b as u32;
        for _ in 0..8 {
            c = if c & 1 != 0 {
                0xedb8_8320 ^ (c >> 1)
            } else {
                c >> 1
            };
        }
    }
    let mut out = b"\x89PNG\r\n\x1a\n".to_vec();
    out.extend(13u32.to_be_bytes());
    out.extend(ihdr);
    out.extend((!c).to_be_bytes());
    out
}

/// `project/slides/deck.ron` with `figures/ok.png`, `figures/huge.png` (header only) and a
/// symbolic link `figures/link.png` to a picture outside the project.
fn project(deck: &str) -> (tempfile::TempDir, tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let figures = dir.path().join("slides/figures");
    std::fs::create_dir_all(&figures).unwrap();
    image::RgbaImage::from_pixel(40, 20, image::Rgba([200, 40, 40, 255]))
        .save(figures.join("ok.png"))
        .unwrap();
    std::fs::write(figures.join("huge.png"), png_header(100_000, 100_000)).unwrap();
    let outside = tempfile::tempdir().unwrap();
    image::RgbaImage::from_pixel(4, 4, image::Rgba([0, 0, 255, 255]))
        .save(outside.path().join("secret.png"))
        .unwrap();
    #[cfg(unix)]
    std::os::unix::fs::symlink(outside.path().join("secret.png"), figures.join("link.png"))
        .unwrap();
    let path = dir.path().join("slides/deck.ron");
    std::fs::write(&path, deck).unwrap();
    (dir, outside, path)
}

fn position(text: &str, needle: &str) -> (usize, usize) {
    let byte = text.find(needle).unwrap() + 1; // inside the quotes
    let line = text[..byte].matches('\n').count() + 1;
    let col = byte - text[..byte].rfind('\n').map_or(0, |n| n + 1) + 1;
    (line, col)
}

const DECK: &str = r#"(
    title: "Pictures",
    slides: [
        (title: "Pictures", body: [
            Columns([
                [Image(path: "figures/ok.png", width: Some(0.5))],
                [Image(path: "../../../../etc/passwd", width: Some(0.5))],
            ]),
            Columns([
                [Image(path: "figures/huge.png", width: Some(0.3))],
                [Image(path: "figures/link.png", width: Some(0.3))],
            ]),
        ]),
    ],
)"#;

#[test]
fn only_pictures_inside_the_project_are_shown_and_refusals_name_their_line() {
    let (_dir, _outside, path) = project(DECK);
    let deck = load_deck(&path).unwrap();
    let mut h = Harness::builder()
        .with_size([1280.0, 720.0])
        .build_ui_state(
            |ui, state: &mut SlideState| {
                slide_ui(ui, &deck, 0, state);
            },
            SlideState::default(),
        );
    h.run_steps(3);
    let problems = h.state().problems().to_vec();
    let shown = Path::new(&path).display().to_string();
    for (needle, why) in [
        ("\"../../../../etc", "leads outside the project"),
        ("\"figures/huge", "too large"),
        ("\"figures/link", "symbolic link"),
    ] {
        let (line, col) = position(DECK, needle);
        let want = format!("{shown}:{line}:{col}: ");
        let found = problems
            .iter()
            .any(|p| p.starts_with(&want) && p.contains(why));
        assert!(found, "no {want}…{why} in {problems:#?}");
    }
    assert_eq!(problems.len(), 3, "{problems:#?}");

    // exactly one picture drawn: the one inside the project
    let mut textured = 0;
    fn walk(s: &Shape, n: &mut usize) {
        match s {
            Shape::Vec(v) => v.iter().for_each(|s| walk(s, n)),
            Shape::Mesh(m) if m.texture_id != TextureId::default() => *n += 1,
            _ => {}
        }
    }
    for s in &h.output().shapes {
        walk(&s.shape, &mut textured);
    }
    assert_eq!(textured, 1);
}
