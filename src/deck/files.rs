//! Every file a deck names — pictures (`Image(path: ..)`), the scene of a `SimulationLoop` or a
//! `Scene` —
//! resolved through [`crate::paths`] (inside the project only), for `lectern check`, with each
//! problem at the line and column of the path string. (Problem and tableau files that widgets
//! name in `ode:` and `methods:` are checked while loading: `Deck::widget_problems`.)

use std::path::Path;

use super::widgets::WidgetSpec;
use super::{Block, Deck};
use crate::diag::Diagnostic;
use crate::ron_tree;

/// What kind of file a deck names, for messages and checks.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FileKind {
    Image,
    Scene,
}

/// One path written in a deck.
#[derive(Debug, Clone, PartialEq)]
pub struct FileRef<'a> {
    pub kind: FileKind,
    /// Where the string is, as a [`ron_tree`] path (`slides[2].body[1].path`).
    pub ron_path: String,
    pub written: &'a str,
}

/// Every path a deck names, in reading order.
pub fn file_refs(deck: &Deck) -> Vec<FileRef<'_>> {
    fn walk<'a>(blocks: &'a [Block], at: &str, out: &mut Vec<FileRef<'a>>) {
        for (i, b) in blocks.iter().enumerate() {
            let here = format!("{at}[{i}]");
            match b {
                Block::Image { path, .. } => out.push(FileRef {
                    kind: FileKind::Image,
                    ron_path: format!("{here}.path"),
                    written: path,
                }),
                Block::Widget(WidgetSpec::SimulationLoop(s)) => out.push(FileRef {
                    kind: FileKind::Scene,
                    ron_path: format!("{here}.scene"),
                    written: &s.scene,
                }),
                Block::Widget(WidgetSpec::Scene(s)) => out.push(FileRef {
                    kind: FileKind::Scene,
                    ron_path: format!("{here}.scene"),
                    written: &s.scene,
                }),
                Block::Columns(cols) => {
                    for (c, col) in cols.iter().enumerate() {
                        walk(col, &format!("{here}[{c}]"), out);
                    }
                }
                _ => {}
            }
        }
    }
    let mut out = Vec::new();
    for (s, slide) in deck.slides.iter().enumerate() {
        walk(&slide.body, &format!("slides[{s}].body"), &mut out);
    }
    out
}

/// 1-based line and column in the deck `text` of the string at `ron_path` (a [`ron_tree`]
/// path): of its character `col` (1-based) if given, else of its first character. `None` if
/// the text has no such string or it is not `written` (the file changed since it was loaded),
/// rather than a wrong position.
pub fn string_position(
    text: &str,
    ron_path: &str,
    written: &str,
    col: Option<usize>,
) -> Option<(usize, usize)> {
    let tree = ron_tree::parse(text).ok()?;
    let node = tree.at(ron_path)?;
    if node.as_str()? != written {
        return None;
    }
    let byte = node.str_offset(text, col.map_or(0, |c| c.saturating_sub(1)))?;
    Some(ron_tree::line_col(text, byte))
}

/// Checks every file `deck` (read from `file`, with text `text`) names: inside the project,
/// present, and readable as what it is (pictures decoded with [`crate::image_file`]'s limits,
/// tableaux parsed). One diagnostic per problem, at the path string.
pub fn check_deck_files(file: &Path, text: &str, deck: &Deck) -> Vec<Diagnostic> {
    let mut out = Vec::new();
    for r in file_refs(deck) {
        let resolved = crate::paths::resolve_for(file, r.written);
        // a scene widget left at the default scene draws the bundled one when the project has
        // none (the deck check's notes say so)
        let resolved = match r.kind {
            FileKind::Scene => crate::bundled::scene_file(resolved, r.written).map(|f| f.path),
            FileKind::Image => resolved.map_err(|e| e.to_string()),
        };
        let problem = match resolved {
            Err(e) => Some(e),
            Ok(path) if !crate::project_files::is_file(&path) => {
                Some(format!("`{}`: no such file", r.written))
            }
            Ok(path) => match r.kind {
                FileKind::Image => crate::image_file::decode(&path).err(),
                FileKind::Scene => crate::scene::load_scene(&path).err().map(|d| d.to_string()),
            },
        };
        if let Some(message) = problem {
            let what = match r.kind {
                FileKind::Image => "image",
                FileKind::Scene => "scene file",
            };
            let message = format!("{what}: {message}");
            out.push(match string_position(text, &r.ron_path, r.written, None) {
                Some((line, col)) => Diagnostic::new(file, line, col, message),
                None => Diagnostic::whole_file(file, message),
            });
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::deck::parse_deck_file;

    /// A project: `slides/deck.ron` naming pictures and tableaux inside and outside it.
    fn project(deck: &str) -> (tempfile::TempDir, std::path::PathBuf) {
        let dir = tempfile::tempdir().unwrap();
        let slides = dir.path().join("slides");
        std::fs::create_dir_all(slides.join("figures")).unwrap();
        std::fs::create_dir_all(slides.join("tableaux")).unwrap();
        image::RgbaImage::from_pixel(2, 2, image::Rgba([1, 2, 3, 255]))
            .save(slides.join("figures/ok.png"))
            .unwrap();
        std::fs::copy(
            Path::new(env!("CARGO_MANIFEST_DIR")).join("slides/tableaux/rk4-typo.ron"),
            slides.join("tableaux/t.ron"),
        )
        .unwrap();
        let path = slides.join("deck.ron");
        std::fs::write(&path, deck).unwrap();
        (dir, path)
    }

    /// What `lectern check` reports about files: the paths checked here, and the tableau
    /// (and problem) files widgets name, checked while loading (`Deck::widget_problems`).
    fn check(path: &Path) -> Vec<Diagnostic> {
        let text = std::fs::read_to_string(path).unwrap();
        let deck = parse_deck_file(&text, path).unwrap();
        let mut ds = check_deck_files(path, &text, &deck);
        ds.extend(deck.widget_problems.iter().map(|p| p.diagnostic.clone()));
        ds.sort_by_key(|d| (d.line, d.col));
        ds
    }

    /// The (line, col) of the first occurrence of `needle` in `text`, plus one column (inside
    /// the quotes).
    fn at(text: &str, needle: &str) -> (usize, usize) {
        let byte = text.find(needle).unwrap() + 1;
        ron_tree::line_col(text, byte)
    }

    #[test]
    fn paths_inside_the_project_work_including_subfolders() {
        let (_dir, path) = project(
            r#"(title: "t", slides: [(title: "a", body: [
                Image(path: "figures/ok.png"),
                Columns([[Image(path: "./figures/../figures/ok.png")], []]),
                Widget(Stability((methods: [Tableau("tableaux/t.ron")]))),
            ])])"#,
        );
        assert_eq!(check(&path), vec![]);
    }

    #[test]
    fn escapes_are_refused_for_every_kind_of_file_at_the_path_string() {
        let outside = tempfile::tempdir().unwrap();
        let secret = outside.path().join("secret.png");
        image::RgbaImage::new(1, 1).save(&secret).unwrap();
        let text = format!(
            r#"(title: "t", slides: [(title: "a", body: [
    Image(path: "../../../../etc/passwd"),
    Image(path: "{abs}"),
    Columns([[Text("x")], [Image(path: "figures/link.png")]]),
    Widget(Stability((methods: [Tableau("tableaux/t.ron"), Tableau("../../t.ron")]))),
    Image(path: "figures/missing.png"),
    Widget(SimulationLoop((scene: "../../water.ron"))),
])])"#,
            abs = secret.display()
        );
        let (_dir, path) = project(&text);
        #[cfg(unix)]
        std::os::unix::fs::symlink(&secret, path.parent().unwrap().join("figures/link.png"))
            .unwrap();
        let ds = check(&path);
        let got: Vec<_> = ds
            .iter()
            .map(|d| ((d.line, d.col), d.message.as_str()))
            .collect();
        assert_eq!(ds.len(), 6, "{got:#?}");
        assert_eq!((ds[0].line, ds[0].col), at(&text, "\"../../../../etc"));
        assert!(ds[0].message.contains("outside the project"), "{}", ds[0]);
        assert_eq!(
            (ds[1].line, ds[1].col),
            at(&text, &format!("\"{}", secret.display()))
        );
        assert!(ds[1].message.contains("absolute"), "{}", ds[1]);
        assert_eq!((ds[2].line, ds[2].col), at(&text, "\"figures/link"));
        assert!(ds[2].message.contains("symbolic link"), "{}", ds[2]);
        assert_eq!((ds[3].line, ds[3].col), at(&text, "\"../../t.ron"));
        assert!(ds[3].message.starts_with("tableau file"), "{}", ds[3]);
        assert_eq!((ds[4].line, ds[4].col), at(&text, "\"figures/missing"));
        assert!(ds[4].message.contains("no such file"), "{}", ds[4]);
        assert_eq!((ds[5].line, ds[5].col), at(&text, "\"../../water"));
        assert!(ds[5].message.starts_with("scene file"), "{}", ds[5]);
    }
}
