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
