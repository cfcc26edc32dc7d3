//! `lectern check` for one deck: everything its slides will load when presented, through the
//! code the app uses, each problem at the deck's line and column of the value at fault.
//!
//! - the deck parses and validates ([`crate::deck::parse_deck_file`]);
//! - every formula typesets ([`crate::math::render_formula`]); a Typst error points at the
//!   faulty character inside the `src` string, a LaTeX one at the formula's start (Typst's
//!   column is in mitex's converted text, which the lecturer never wrote);
//! - every image resolves inside the project ([`crate::paths::resolve_for`]) and decodes
//!   ([`crate::image_file::decode`]); its width is in the range the slide clamps to;
//! - every file a widget names (tableaux, the simulation loop's scene) exists and parses,
//!   reported at the path string;
//!   tableaux written inline are validated at their values;
//! - bookmarks name a slide the deck has, with a key 1…9.

use std::collections::HashMap;
use std::path::Path;

use crate::deck::{Block, Deck, IMAGE_WIDTH_RANGE, parse_deck_file};
use crate::diag::Diagnostic;
use crate::math::{MathError, MathSyntax, render_formula};
use crate::ode::Tableau;
use crate::ron_tree::{self, Node};
use crate::widgets::WidgetSpec;

/// Formulas are typeset at this many pixels per em: the size does not change whether Typst
/// accepts a formula, and a small raster keeps the check fast.
const CHECK_EM_PX: f32 = 24.0;

/// Checks decks; keeps the verdict on each formula, so a formula written twice (or a deck
/// checked again) is typeset once.
#[derive(Default)]
pub struct DeckChecker {
    formulas: HashMap<(String, bool), Result<(), MathError>>,
    /// Typeset formulas (default). Off only where a test needs thousands of decks per second.
    pub skip_typesetting: bool,
}

/// One deck's result: the deck when it parsed, and every problem found.
pub struct DeckCheck {
    pub deck: Option<Deck>,
    pub problems: Vec<Diagnostic>,
}

impl DeckChecker {
    pub fn new() -> Self {
        Self::default()
    }

    /// Reads and checks the deck at `file`.
    pub fn check_file(&mut self, file: &Path) -> DeckCheck {
        match std::fs::read_to_string(file) {
            Ok(text) => self.check_text(&text, file),
            Err(e) => DeckCheck {
                deck: None,
                problems: vec![Diagnostic::whole_file(file, format!("cannot read: {e}"))],
            },
        }
    }

    /// Checks deck `text`, read from `file` (the file also anchors relative paths).
    pub fn check_text(&mut self, text: &str, file: &Path) -> DeckCheck {
        let deck = match parse_deck_file(text, file) {
            Ok(deck) => deck,
            Err(d) => {
                return DeckCheck {
                    deck: None,
                    problems: vec![d],
                };
            }
        };
        let tree = ron_tree::parse(text).ok();
        let mut walk = Walk {
            text,
            file,
            tree: tree.as_ref(),
            problems: Vec::new(),
        };
        for (i, slide) in deck.slides.iter().enumerate() {
            self.blocks(&mut walk, &slide.body, &format!("slides[{i}].body"));
        }
        for (i, b) in deck.bookmarks.iter().enumerate() {
            if !(1..=9).contains(&b.key) {
                walk.at(
                    &format!("bookmarks[{i}].key"),
                    format!("bookmark key {} must be 1…9", b.key),
                );
            }
            if deck.find(&b.slide).is_none() {
                walk.at(
                    &format!("bookmarks[{i}].slide"),
                    format!(
                        "bookmark {}: the deck has no slide with id or title {:?}",
                        b.key, b.slide
                    ),
                );
            }
        }
        DeckCheck {
            problems: walk.problems,
            deck: Some(deck),
        }
    }

    fn blocks(&mut self, walk: &mut Walk, blocks: &[Block], at: &str) {
        for (j, block) in blocks.iter().enumerate() {
            let at = format!("{at}[{j}]");
            match block {
                Block::Text(_) | Block::Bullets(_) => {}
                Block::Math { src, latex } => self.formula(walk, src, *latex, &at),
                Block::Image { path, width } => walk.image(path, *width, &at),
                Block::Widget(spec) => walk.widget(spec, &at),
                Block::Columns(cols) => {
                    for (c, col) in cols.iter().enumerate() {
                        self.blocks(walk, col, &format!("{at}[{c}]"));
                    }
                }
            }
        }
    }

    fn formula(&mut self, walk: &mut Walk, src: &str, latex: bool, at: &str) {
        let verdict = match self.formulas.get(&(src.to_owned(), latex)) {
            Some(v) => v.clone(),
            None if self.skip_typesetting => Ok(()),
            None => {
                let syntax = if latex {
                    MathSyntax::Latex
                } else {
                    MathSyntax::Typst
                };
                let v = render_formula(src, syntax, CHECK_EM_PX, [0, 0, 0, 255]).map(|_| ());
                self.formulas.insert((src.to_owned(), latex), v.clone());
                v
            }
        };
        let Err(e) = verdict else { return };
        let node = walk.node(&format!("{at}.src"));
        // Typst's column counts characters of what the lecturer wrote; for LaTeX it would
        // count mitex's output, so the formula's start is the honest place.
        let (char_at, what) = match (latex, e.col) {
            (false, Some(col)) => (col - 1, "formula"),
            (false, None) => (0, "formula"),
            (true, _) => (0, "LaTeX formula"),
        };
        let message = format!("{what}: {}", e.message);
        match node.and_then(|n| n.str_offset(walk.text, char_at)) {
            Some(offset) => walk.push(Diagnostic::at_offset(walk.text, walk.file, offset, message)),
            None => walk.at(at, message),
        }
    }
}

/// Where the walk is: the deck's text, its tree, and the problems so far.
struct Walk<'a> {
    text: &'a str,
    file: &'a Path,
    tree: Option<&'a Node>,
    problems: Vec<Diagnostic>,
}

impl Walk<'_> {
    fn node(&self, path: &str) -> Option<&Node> {
        self.tree.and_then(|t| t.at(path))
    }

    fn push(&mut self, d: Diagnostic) {
        self.problems.push(d);
    }

    /// A problem at the value `path`.
    fn at(&mut self, path: &str, message: String) {
        let d = Diagnostic::at_value(self.tree, self.text, self.file, path, message);
        self.problems.push(d);
    }

    fn image(&mut self, written: &str, width: Option<f32>, at: &str) {
        if let Some(w) = width
            && !IMAGE_WIDTH_RANGE.contains(&w)
        {
            self.at(
                &format!("{at}.width"),
                format!(
                    "image width {w} is outside {}..={} (a fraction of the slide's width)",
                    IMAGE_WIDTH_RANGE.start(),
                    IMAGE_WIDTH_RANGE.end()
                ),
            );
        }
        let path_at = format!("{at}.path");
        match crate::paths::resolve_for(self.file, written) {
            Err(e) => self.at(&path_at, format!("image: {e}")),
            Ok(full) if !full.is_file() => {
                self.at(&path_at, format!("image {} does not exist", shown(&full)))
            }
            Ok(full) => {
                if let Err(e) = crate::image_file::decode(&full) {
                    self.at(&path_at, e);
                }
            }
        }
    }

    fn widget(&mut self, spec: &WidgetSpec, at: &str) {
        if let WidgetSpec::SimulationLoop(s) = spec {
            self.simulation_scene(&s.scene, s.body, at);
        }
        if let WidgetSpec::Stability(s) = spec {
            for (k, t) in s.tableaux.iter().enumerate() {
                if let Err((value, m)) = t.validate_at() {
                    self.at(
                        &format!("{at}.tableaux[{k}].{value}"),
                        format!("tableau: {m}"),
                    );
                }
            }
            for (k, written) in s.files.iter().enumerate() {
                self.tableau_file(written, &format!("{at}.files[{k}]"));
            }
        }
    }

    /// The scene a simulation-loop widget names: it must load and have floating body `body`.
    /// (`scene` may be left to its default: then the position is the widget's.)
    fn simulation_scene(&mut self, written: &str, body: usize, at: &str) {
        let scene_at = format!("{at}.scene");
        let scene_at = if self.node(&scene_at).is_some() {
            scene_at
        } else {
            at.to_owned()
        };
        let full = match crate::paths::resolve_for(self.file, written) {
            Err(e) => return self.at(&scene_at, format!("scene file: {e}")),
            Ok(full) if !full.is_file() => {
                return self.at(
                    &scene_at,
                    format!("scene file {} does not exist", shown(&full)),
                );
            }
            Ok(full) => full,
        };
        let scene = match crate::scene::load_scene(&full) {
            Ok(scene) => scene,
            Err(d) => {
                return self.at(
                    &scene_at,
                    format!("scene file `{written}` does not load: {d}"),
                );
            }
        };
        let level = scene.water.level;
        let floating = (scene.objects.iter().enumerate())
            .filter(|(i, o)| {
                crate::scene::bodies::FloatingBody::from_object(*i, o, level).is_some()
            })
            .count();
        if body >= floating {
            let body_at = format!("{at}.body");
            let body_at = if self.node(&body_at).is_some() {
                body_at
            } else {
                scene_at
            };
            self.at(
                &body_at,
                format!("{written} has {floating} floating bodies: body {body} does not exist (counting from 0)"),
            );
        }
    }

    /// A tableau file a widget names: it must exist inside the project and load.
    fn tableau_file(&mut self, written: &str, at: &str) {
        match crate::paths::resolve_for(self.file, written) {
            Err(e) => self.at(at, format!("tableau file: {e}")),
            Ok(full) if !full.is_file() => {
                self.at(at, format!("tableau file {} does not exist", shown(&full)))
            }
            Ok(full) => {
                if let Err(d) = Tableau::load(&full) {
                    self.at(at, format!("tableau file `{written}` does not load: {d}"));
                }
            }
        }
    }
}

/// A resolved path as the lecturer would write it (without the `./` of a relative project).
fn shown(path: &Path) -> String {
    path.strip_prefix(".").unwrap_or(path).display().to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(text: &str) -> Vec<Diagnostic> {
        let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("slides/test-deck.ron");
        DeckChecker::new().check_text(text, &file).problems
    }

    fn deck(body: &str) -> String {
        format!(
            "(\n  title: \"t\",\n  slides: [\n    (title: \"s\", body: [\n{body}\n    ]),\n  ],\n)"
        )
    }

    #[test]
    fn typst_error_at_the_faulty_character() {
        let p = check(&deck(r#"      Math(src: "dot(x) = #nosuchfn(x)"),"#));
        assert_eq!(p.len(), 1, "{p:?}");
        // line 5; the string's content starts at column 18, `nosuchfn` is its 11th character
        assert_eq!((p[0].line, p[0].col), (5, 28), "{}", p[0]);
        assert!(p[0].message.contains("nosuchfn"), "{}", p[0]);
    }

    #[test]
    fn typst_error_in_a_raw_string_inside_columns() {
        let p = check(&deck(
            "      Columns([[Text(\"a\")], [\n        Math(src: r#\"x = frac(1\"#),\n      ]]),",
        ));
        assert_eq!(p.len(), 1, "{p:?}");
        assert_eq!(p[0].line, 6, "{}", p[0]);
        assert!(p[0].col >= 20, "{}", p[0]);
    }

    #[test]
    fn latex_error_at_the_formula_start() {
        let p = check(&deck(
            r#"      Math(src: "x + \\notacommand{x}", latex: true),"#,
        ));
        assert_eq!(p.len(), 1, "{p:?}");
        assert_eq!((p[0].line, p[0].col), (5, 18), "{}", p[0]);
        assert!(p[0].message.starts_with("LaTeX formula"), "{}", p[0]);
    }

    #[test]
    fn images_must_exist_decode_and_stay_inside() {
        let p = check(&deck(
            "      Image(path: \"nope.png\"),\n      Image(path: \"../../../etc/passwd\"),\n      Image(path: \"lecture.ron\", width: Some(3.0)),",
        ));
        let at: Vec<(usize, usize)> = p.iter().map(|d| (d.line, d.col)).collect();
        assert_eq!(at, [(5, 19), (6, 19), (7, 46), (7, 19)], "{p:?}");
        assert!(p[0].message.contains("does not exist"), "{}", p[0]);
        assert!(p[1].message.contains("outside the project"), "{}", p[1]);
        assert!(p[2].message.contains("width 3"), "{}", p[2]);
        assert!(p[3].message.contains("decode"), "{}", p[3]);
    }

    #[test]
    fn tableau_files_and_inline_tableaux() {
        let p = check(&deck(concat!(
            "      Widget(Stability((files: [\"tableaux/rk4.ron\", \"tableaux/nope.ron\"],\n",
            "        tableaux: [(name: \"bad\", a: [[0.0, 0.0], [0.5, 0.5]], b: [0.5, 0.5], c: [0.0, 0.5])]))),",
        )));
        let at: Vec<(usize, usize)> = p.iter().map(|d| (d.line, d.col)).collect();
        assert_eq!(at, [(6, 56), (5, 53)], "{p:?}");
        assert!(p[0].message.contains("a[2][2]"), "{}", p[0]);
        assert!(p[1].message.contains("does not exist"), "{}", p[1]);
    }

    #[test]
    fn the_simulation_loop_scene_and_body() {
        let p = check(&deck(concat!(
            "      Widget(SimulationLoop((scene: \"../scenes/nope.ron\"))),\n",
            "      Widget(SimulationLoop((body: 9))),",
        )));
        let at: Vec<(usize, usize)> = p.iter().map(|d| (d.line, d.col)).collect();
        assert_eq!(at, [(5, 37), (6, 36)], "{p:?}");
        assert!(p[0].message.contains("does not exist"), "{}", p[0]);
        assert!(p[1].message.contains("body 9"), "{}", p[1]);
    }

    #[test]
    fn bookmarks_name_real_slides() {
        let text = deck("").replace(
            "  ],\n)",
            "  ],\n  bookmarks: [(key: 12, slide: \"gone\")],\n)",
        );
        let p = check(&text);
        assert_eq!(p.len(), 2, "{p:?}");
        assert_eq!((p[0].line, p[0].col), (8, 21), "{}", p[0]);
        assert_eq!((p[1].line, p[1].col), (8, 32), "{}", p[1]);
    }

    #[test]
    fn the_bundled_deck_is_clean() {
        let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("slides/lecture.ron");
        let c = DeckChecker::new().check_file(&file);
        assert!(c.problems.is_empty(), "{:?}", c.problems);
        assert!(c.deck.is_some());
    }
}
