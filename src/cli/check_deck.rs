//! `lectern check` for one deck: everything its slides will load when presented, through the
//! code the app uses, each problem at the deck's line and column of the value at fault.
//!
//! - the deck parses and validates ([`crate::deck::parse_deck_file`]);
//! - every formula typesets through the bounded typesetting pool the window uses
//!   ([`crate::math::deck`]); a Typst error points at the faulty character inside the `src`
//!   string, a LaTeX one at the formula's start (Typst's column is in mitex's converted text,
//!   which the lecturer never wrote);
//! - every file the deck names (pictures, tableau files, the simulation loop's scene) is inside
//!   the project, exists and loads ([`crate::deck::files`]), reported at the path string;
//! - what the widgets would otherwise clamp or refuse silently: image widths in range, tableaux
//!   written inline valid (at their values), the simulation loop's body present;
//! - bookmarks name a slide the deck has, with a key 1…9.

use std::collections::HashMap;
use std::path::Path;

use crate::deck::{Block, Deck, IMAGE_WIDTH_RANGE, parse_deck_file};
use crate::diag::Diagnostic;
use crate::math::{MathError, MathSyntax};
use crate::ron_tree::{self, Node};
use crate::widgets::{ParamValue, WidgetSpec, WriteTo};

/// Formulas are typeset at this many pixels per em (as `math::deck::check_formulas` does).
const CHECK_EM_PX: f32 = 40.0;

/// Checks decks; keeps the verdict on each formula, so a formula written twice (or a deck
/// checked again) is typeset once.
#[derive(Default)]
pub struct DeckChecker {
    formulas: HashMap<(String, MathSyntax), Result<(), MathError>>,
    /// Typeset formulas (default). Off only where a test needs thousands of decks per second.
    pub skip_typesetting: bool,
}

/// One deck's result: the deck when it parsed, and every problem found.
pub struct DeckCheck {
    pub deck: Option<Deck>,
    pub problems: Vec<Diagnostic>,
    /// What the lecturer should know that is no problem (e.g. which shaders a scene uses).
    pub notes: Vec<String>,
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
                notes: Vec::new(),
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
                    notes: Vec::new(),
                };
            }
        };
        let tree = ron_tree::parse(text).ok();
        let mut walk = Walk {
            text,
            file,
            tree: tree.as_ref(),
            problems: crate::deck::files::check_deck_files(file, text, &deck),
            notes: Vec::new(),
        };
        // equations and tableau files the widgets name, compiled while the deck loaded
        (walk.problems).extend(deck.widget_problems.iter().map(|p| p.diagnostic.clone()));
        // slides that do not parse: error slides in the talk, problems here
        (walk.problems).extend(deck.broken_slides.iter().map(|b| b.diagnostic.clone()));
        self.formulas(&mut walk, &deck);
        for (i, slide) in deck.slides.iter().enumerate() {
            walk.blocks(&slide.body, &format!("slides[{i}].body"));
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
        walk.problems.sort_by_key(|d| (d.line, d.col));
        walk.notes.dedup();
        DeckCheck {
            problems: walk.problems,
            notes: walk.notes,
            deck: Some(deck),
        }
    }

    /// Typesets every formula not seen before through the pool (all queued first, so both
    /// workers stay busy), and reports each that fails at its place.
    fn formulas(&mut self, walk: &mut Walk, deck: &Deck) {
        let all = crate::math::deck::formulas(deck, None);
        let new: Vec<_> = all
            .iter()
            .filter(|f| !self.formulas.contains_key(&(f.src.to_owned(), f.syntax)))
            .filter(|_| !self.skip_typesetting)
            .map(|f| {
                let req = f.request(CHECK_EM_PX, [0, 0, 0, 255]);
                (f, crate::math::pool().submit(req, true, true, None))
            })
            .collect();
        for (f, job) in new {
            let verdict = job.wait().map(|_| ());
            self.formulas.insert((f.src.to_owned(), f.syntax), verdict);
        }
        for f in &all {
            if let Some(Err(e)) = self.formulas.get(&(f.src.to_owned(), f.syntax)) {
                let d = crate::math::deck::diagnostic(walk.file, walk.text, f, e);
                walk.push(d);
            }
        }
    }
}

/// Where the walk is: the deck's text, its tree, and the problems so far.
struct Walk<'a> {
    text: &'a str,
    file: &'a Path,
    tree: Option<&'a Node>,
    problems: Vec<Diagnostic>,
    notes: Vec<String>,
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

    /// What the widgets and blocks would clamp or refuse silently (files and formulas are
    /// checked beforehand, by the app's own modules).
    fn blocks(&mut self, blocks: &[Block], at: &str) {
        for (j, block) in blocks.iter().enumerate() {
            let at = format!("{at}[{j}]");
            match block {
                Block::Image { width: Some(w), .. } if !IMAGE_WIDTH_RANGE.contains(w) => self.at(
                    &format!("{at}.width"),
                    format!(
                        "image width {w} is outside {}..={} (a fraction of the slide's width)",
                        IMAGE_WIDTH_RANGE.start(),
                        IMAGE_WIDTH_RANGE.end()
                    ),
                ),
                Block::Table { header, rows } => {
                    for (r, row) in rows.iter().enumerate() {
                        if row.len() != header.len() {
                            self.at(
                                &format!("{at}.rows[{r}]"),
                                format!(
                                    "table row {} has {} cells, the header {}",
                                    r + 1,
                                    row.len(),
                                    header.len()
                                ),
                            );
                        }
                    }
                }
                Block::Widget(spec) => self.widget(spec, &at),
                Block::Columns(cols) => {
                    for (c, col) in cols.iter().enumerate() {
                        self.blocks(col, &format!("{at}[{c}]"));
                    }
                }
                _ => {}
            }
        }
    }

    fn widget(&mut self, spec: &WidgetSpec, at: &str) {
        match spec {
            WidgetSpec::SimulationLoop(s) => self.simulation_body(&s.scene, s.body, at),
            // the scene file itself is checked with the deck's files
            WidgetSpec::Scene(s) => {
                self.scene_shaders(&s.scene, at);
                for (field, message) in s.range_problems() {
                    let value_at = format!("{at}.{field}");
                    let value_at = if self.node(&value_at).is_some() {
                        value_at
                    } else {
                        at.to_owned()
                    };
                    self.at(&value_at, format!("scene: {message}"));
                }
            }
            WidgetSpec::Energy(s) => {
                // the energy compiles against the equation it measures (which loaded: its
                // own faults are reported with the deck's files)
                if let Ok(loaded) = s.ode.load(Some(self.file))
                    && let Err(m) =
                        crate::widgets::energy::compile_energy(&s.energy, &loaded.problem)
                {
                    self.at(&format!("{at}.energy"), m);
                }
            }
            WidgetSpec::Stability(s) => {
                for (k, t) in s.tableaux.iter().enumerate() {
                    if let Err((value, m)) = t.validate_at() {
                        self.at(
                            &format!("{at}.tableaux[{k}].{value}"),
                            format!("tableau: {m}"),
                        );
                    }
                }
            }
            _ => {}
        }
        self.slider_ranges(spec, at);
    }

    /// A value the deck sets outside the range of its presenter slider: the widget would clamp
    /// it silently when drawing, so the lecturer is told instead. The ranges are the widgets'
    /// own (`SlideWidget::params`), the ones the sliders and the clamping use.
    fn slider_ranges(&mut self, spec: &WidgetSpec, at: &str) {
        let mut widget = spec.instantiate_in(Some(self.file));
        let mut faults = Vec::new();
        for p in widget.params() {
            // ODE parameters carry their range in the problem, checked with it
            if p.write != WriteTo::Spec {
                continue;
            }
            let (value, lo, hi) = match p.value {
                ParamValue::F64 {
                    value, min, max, ..
                } => (*value, min, max),
                ParamValue::Usize { value, min, max } => (*value as f64, min as f64, max as f64),
                ParamValue::Bool(_) => continue,
            };
            if !(lo..=hi).contains(&value) {
                faults.push((
                    p.id.clone(),
                    format!(
                        "{} = {value} is outside {lo}..={hi}, the range its presenter slider allows",
                        p.id
                    ),
                ));
            }
        }
        for (id, message) in faults {
            let path = format!("{at}.{id}");
            let path = if self.node(&path).is_some() {
                path
            } else {
                at.to_owned()
            };
            let d = Diagnostic::at_value(self.tree, self.text, self.file, &path, message);
            // a widget's own check may have said it already, in its words: one fault, one line
            if !(self.problems.iter()).any(|p| (p.line, p.col) == (d.line, d.col)) {
                self.push(d);
            }
        }
    }

    /// The shaders a Scene widget's renderer is built from, checked the way the renderer
    /// builds them (every technique's file present, naga, then its pipelines on a headless
    /// adapter): the project's `shaders/`, or the bundled ones when it has none (said in a
    /// note). A missing or broken shader is a problem at the widget's scene path, so a deck
    /// that checks is a deck whose scene starts.
    fn scene_shaders(&mut self, written: &str, at: &str) {
        let Ok(scene_path) = crate::paths::resolve_for(self.file, written) else {
            return;
        };
        let scene_at = format!("{at}.scene");
        let scene_at = if self.node(&scene_at).is_some() {
            scene_at
        } else {
            at.to_owned()
        };
        let folder = match crate::bundled::shader_folder_for_scene(&scene_path) {
            Ok(f) => f,
            Err(e) => return self.at(&scene_at, format!("scene: {e}")),
        };
        if folder.bundled {
            self.notes.push(format!(
                "{}: the scene uses the shaders built into lectern ({} has no shaders/ folder; `lectern new --with-shaders` writes a copy to edit)",
                self.file.display(),
                crate::paths::project_root(self.file).display()
            ));
        }
        let mut broken = Vec::new();
        for name in crate::render::pipeline::TECHNIQUE_SHADERS {
            let path = folder.dir.join(name);
            if !path.is_file() {
                broken.push(format!("{name} is missing"));
                continue;
            }
            let problems = crate::render::check_shader_file(&path);
            if !problems.is_empty() {
                broken.push(format!(
                    "{name} has {} problem(s), listed at the shader",
                    problems.len()
                ));
                self.problems.extend(problems);
            }
        }
        if !broken.is_empty() {
            self.at(
                &scene_at,
                format!(
                    "scene: the renderer cannot start with the shaders in {}: {}",
                    folder.dir.display(),
                    broken.join(", ")
                ),
            );
        }
    }

    /// The simulation loop's body must exist in its scene (the scene file itself is checked
    /// with the deck's files; a scene that does not load is reported there).
    fn simulation_body(&mut self, written: &str, body: usize, at: &str) {
        let Ok(full) = crate::paths::resolve_for(self.file, written) else {
            return;
        };
        let Ok(scene) = crate::scene::load_scene(&full) else {
            return;
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
                at.to_owned()
            };
            self.at(
                &body_at,
                format!(
                    "{written} has {floating} floating bodies: body {body} does not exist (counting from 0)"
                ),
            );
        }
    }
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
        assert!(p[0].message.contains("LaTeX"), "{}", p[0]);
    }

    #[test]
    fn images_must_exist_decode_and_stay_inside() {
        let p = check(&deck(
            "      Image(path: \"nope.png\"),\n      Image(path: \"../../../etc/passwd\"),\n      Image(path: \"lecture.ron\", width: Some(3.0)),",
        ));
        let at: Vec<(usize, usize)> = p.iter().map(|d| (d.line, d.col)).collect();
        // at the path's first character; the width at its value
        assert_eq!(at, [(5, 20), (6, 20), (7, 20), (7, 46)], "{p:?}");
        assert!(p[0].message.contains("no such file"), "{}", p[0]);
        assert!(p[1].message.contains("outside the project"), "{}", p[1]);
        assert!(p[2].message.contains("decode"), "{}", p[2]);
        assert!(p[3].message.contains("width 3"), "{}", p[3]);
    }

    #[test]
    fn tableau_files_and_inline_tableaux() {
        let p = check(&deck(concat!(
            "      Widget(Stability((methods: [Tableau(\"tableaux/rk4.ron\"), Tableau(\"tableaux/nope.ron\")],\n",
            "        tableaux: [(name: \"bad\", a: [[0.0, 0.0], [0.5, 0.5]], b: [0.5, 0.5], c: [0.0, 0.5])]))),",
        )));
        let at: Vec<(usize, usize)> = p.iter().map(|d| (d.line, d.col)).collect();
        assert_eq!(at, [(5, 73), (6, 56)], "{p:?}");
        assert!(p[0].message.contains("no such file"), "{}", p[0]);
        assert!(p[1].message.contains("a[2][2]"), "{}", p[1]);
    }

    #[test]
    fn the_simulation_loop_scene_and_body() {
        let p = check(&deck(concat!(
            "      Widget(SimulationLoop((scene: \"../scenes/nope.ron\"))),\n",
            "      Widget(SimulationLoop((body: 9))),",
        )));
        let at: Vec<(usize, usize)> = p.iter().map(|d| (d.line, d.col)).collect();
        assert_eq!(at, [(5, 38), (6, 36)], "{p:?}");
        assert!(p[0].message.contains("no such file"), "{}", p[0]);
        assert!(p[1].message.contains("body 9"), "{}", p[1]);
    }

    #[test]
    fn values_outside_their_sliders_range_at_the_value() {
        let p = check(&deck(concat!(
            "      Widget(SlopeField((ode: File(\"problems/forced.ron\"), h: 5.0, t_end: 5.0))),\n",
            "      Widget(ParallelTransport((fish: 400))),",
        )));
        let at: Vec<(usize, usize)> = p.iter().map(|d| (d.line, d.col)).collect();
        assert_eq!(at, [(5, 63), (6, 39)], "{p:?}");
        assert!(
            p[0].message.contains("h = 5 is outside 0.01..=2"),
            "{}",
            p[0]
        );
        assert!(p[1].message.contains("fish = 400"), "{}", p[1]);
    }

    #[test]
    fn the_scene_widget_file_and_ranges() {
        let p = check(&deck(concat!(
            "      Widget(Scene((scene: \"../scenes/nope.ron\"))),\n",
            "      Widget(Scene((camera: (pitch_deg: 95.0), height: 0.0))),\n",
            "      Widget(Scene((view: Normals, time_s: 2.5))),",
        )));
        let at: Vec<(usize, usize)> = p.iter().map(|d| (d.line, d.col)).collect();
        // the missing file at its path's first character, the values at themselves
        assert_eq!(at, [(5, 29), (6, 41), (6, 56)], "{p:?}");
        assert!(p[0].message.contains("no such file"), "{}", p[0]);
        assert!(p[1].message.contains("pitch 95"), "{}", p[1]);
        assert!(p[2].message.contains("height 0"), "{}", p[2]);
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
