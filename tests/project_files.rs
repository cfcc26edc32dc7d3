//! The one source of project files: with an in-memory bundle installed (as the web player
//! does), the bundled lecture loads — deck, problem files, tableaux, scene — and so do a picture
//! and an ink file, from paths that exist nowhere on disk. A loader that still read the disk
//! directly would fail here. (Its own test binary: the source is installed once per process.)

use std::path::{Path, PathBuf};

use lectern::deck::ink::{Ink, Stroke, Tool};
use lectern::project_files::{self, Bundle};

/// Every file under `dir` (recursively), as (path relative to `root`, bytes).
fn files_under(root: &Path, dir: &Path, out: &mut Vec<(PathBuf, Vec<u8>)>) {
    for e in std::fs::read_dir(root.join(dir)).unwrap().flatten() {
        let rel = dir.join(e.file_name());
        if e.path().is_dir() {
            files_under(root, &rel, out);
        } else {
            out.push((rel, std::fs::read(e.path()).unwrap()));
        }
    }
}

#[test]
fn the_lecture_a_picture_and_ink_load_from_a_bundle_with_nothing_on_disk() {
    let repo = Path::new(env!("CARGO_MANIFEST_DIR"));
    let fake_root = PathBuf::from("/nonexistent-lectern-bundle/course");
    assert!(!fake_root.exists());
    let mut files = Vec::new();
    files_under(repo, Path::new("slides"), &mut files);
    files_under(repo, Path::new("scenes"), &mut files);
    let mut bundle = Bundle::new();
    for (rel, bytes) in files {
        bundle.insert(fake_root.join(rel), bytes);
    }
    // a picture and an ink file beside the deck, made here
    let mut png = Vec::new();
    image::RgbaImage::from_pixel(3, 2, image::Rgba([9, 8, 7, 255]))
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .unwrap();
    bundle.insert(fake_root.join("slides/figures/dot.png"), png);
    let deck_path = fake_root.join("slides/lecture.ron");
    let mut ink = Ink::default();
    ink.add(
        "euler",
        Stroke {
            tool: Tool::Pen,
            color: 0,
            width: 6.0,
            points: vec![[10.0, 20.0], [30.0, 40.0]],
        },
    );
    bundle.insert(
        lectern::deck::ink::ink_file_path(&deck_path),
        ink.to_ron().into_bytes(),
    );
    project_files::install(bundle).unwrap();

    // the deck, through the same live holder the app uses, and every file its widgets name
    let session = lectern::deck::DeckSession::open(&deck_path).expect("deck from the bundle");
    let deck = session.deck();
    assert!(deck.slides.len() > 20, "{}", deck.slides.len());
    let problems: Vec<String> = deck
        .widget_problems
        .iter()
        .map(|p| p.diagnostic.to_string())
        .collect();
    assert!(problems.is_empty(), "{problems:#?}");
    let text = project_files::read_to_string(&deck_path).unwrap();
    let file_problems = lectern::deck::files::check_deck_files(&deck_path, &text, deck);
    assert!(file_problems.is_empty(), "{file_problems:#?}");
    // the scene the Scene slides draw
    let scene = lectern::scene::load_scene(&fake_root.join("scenes/water.ron"));
    assert!(scene.is_ok(), "{:?}", scene.err());

    let picture = lectern::image_file::decode(&fake_root.join("slides/figures/dot.png")).unwrap();
    assert_eq!(picture.dimensions(), (3, 2));

    let ink_file = lectern::deck::InkFile::for_deck(&deck_path);
    assert_eq!(ink_file.ink().stroke_count(), 1);
    assert!(ink_file.problem().is_none());

    // and what is not in the bundle is missing, not read from disk behind its back
    let real = repo.join("slides/lecture.ron");
    assert!(real.is_file());
    assert!(!project_files::is_file(&real));
    assert!(lectern::deck::load_deck(&real).is_err());
}
