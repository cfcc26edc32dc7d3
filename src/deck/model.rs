//! The deck as the lecturer writes it in RON. Every field beyond the essentials has a default,
//! so a minimal deck is a title and a list of slides.

use std::path::PathBuf;

use serde::{Deserialize, Serialize};

use super::prose::{BulletList, Prose};
use super::widgets::WidgetSpec;

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Deck {
    pub title: String,
    /// Width : height of the logical canvas; slides are laid out on it and scaled to the window.
    #[serde(default)]
    pub aspect: Aspect,
    /// Colour scheme of the slides.
    #[serde(default)]
    pub theme: Theme,
    /// Where widgets' sliders, checkboxes and buttons are: on the slide (`Slide`, the default)
    /// or only on the presenter's side (`Presenter`: the projector shows plots and values).
    #[serde(default)]
    pub controls: Controls,
    pub slides: Vec<Slide>,
    /// Who gives the talk, shown on `layout: Title` slides under the title.
    #[serde(default)]
    pub lecturer: Option<String>,
    /// When (and where) it is given, shown on `layout: Title` slides, e.g. "18 December 2026".
    #[serde(default)]
    pub date: Option<String>,
    /// Prepared tweak states, recalled with the keys 1…9 during the talk.
    #[serde(default)]
    pub bookmarks: Vec<BookmarkDecl>,
    /// The folder the deck was loaded from; image paths are relative to it. Not in the file.
    #[serde(skip)]
    pub base_dir: Option<PathBuf>,
    /// The file the deck was loaded from (to place errors found while drawing, e.g. a formula
    /// over its time budget, at their line and column). Not in the file.
    #[serde(skip)]
    pub file: Option<PathBuf>,
    /// Problems of single widgets found while loading (an equation that does not compile, a
    /// missing problem or tableau file), at the deck's own line and column. They do not stop
    /// the talk: that widget shows its error (or its last good equation), the rest works.
    #[serde(skip)]
    pub widget_problems: Vec<WidgetProblem>,
    /// Slides that did not parse, shown as error slides in their place (the rest of the deck
    /// loads). `lectern check` fails on them; `lectern export` too, unless `--keep-going`.
    #[serde(skip)]
    pub broken_slides: Vec<super::broken::BrokenSlide>,
}

/// A problem of one widget: slide index, block path (indices into the body, then into
/// columns) and the diagnostic at the deck's line and column.
#[derive(Debug, Clone, PartialEq)]
pub struct WidgetProblem {
    pub slide: usize,
    pub block: Vec<usize>,
    pub diagnostic: crate::diag::Diagnostic,
}

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Aspect(pub u32, pub u32);

impl Default for Aspect {
    fn default() -> Self {
        Aspect(16, 9)
    }
}

impl Aspect {
    /// Width over height, guarded against a zero or absurd ratio in the file.
    pub fn ratio(self) -> f32 {
        if self.0 == 0 || self.1 == 0 {
            return 16.0 / 9.0;
        }
        (self.0 as f32 / self.1 as f32).clamp(0.25, 4.0)
    }
}

/// `controls:` of a deck.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum Controls {
    /// Widgets draw their controls on the slide, for the audience to see them move.
    #[default]
    Slide,
    /// Only the presenter view has the controls; the slide shows each control's value.
    Presenter,
}

#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum Theme {
    /// Light text on a near-black background: best in a dimmed lecture hall.
    #[default]
    Dark,
    /// Dark text on an off-white background: best in a bright room.
    Light,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Slide {
    /// Stable identity across edits: keeps the presenter's place and tweaks when slides move.
    #[serde(default)]
    pub id: Option<String>,
    pub title: String,
    /// How the slide is arranged: a content slide (title on top) or a centred title slide.
    #[serde(default)]
    pub layout: Layout,
    #[serde(default)]
    pub body: Vec<Block>,
    /// Speaker notes, shown on the presenter side only.
    #[serde(default)]
    pub notes: String,
    /// Words for students, printed under the slide in the handout (`export --handout`); kept
    /// apart from the speaker notes, which never reach the handout.
    #[serde(default)]
    pub handout: String,
    /// Planned time for this slide.
    #[serde(default)]
    pub seconds: Option<f32>,
    /// An optional slide: paging (→, ←, Space, clicker) passes over it, but `G n`, the overview
    /// and bookmarks reach it, and its time is not part of the plan.
    #[serde(default)]
    pub skip: bool,
}

impl Slide {
    /// What identifies the slide across reloads: its id, else its title.
    pub fn key(&self) -> &str {
        self.id.as_deref().unwrap_or(&self.title)
    }

    /// The seconds this slide adds to the planned talk (none for a skipped slide).
    pub fn planned_secs(&self) -> f32 {
        if self.skip {
            0.0
        } else {
            self.seconds.unwrap_or(0.0)
        }
    }

    /// Every widget block of the slide with its block path (indices into the body, then into
    /// columns), in file order.
    pub fn widgets(&self) -> Vec<(Vec<usize>, &WidgetSpec)> {
        fn walk<'a>(
            blocks: &'a [Block],
            path: &mut Vec<usize>,
            out: &mut Vec<(Vec<usize>, &'a WidgetSpec)>,
        ) {
            for (i, b) in blocks.iter().enumerate() {
                path.push(i);
                match b {
                    Block::Widget(spec) => out.push((path.clone(), spec)),
                    Block::Columns(cols) => {
                        for (c, col) in cols.iter().enumerate() {
                            path.push(c);
                            walk(col, path, out);
                            path.pop();
                        }
                    }
                    _ => {}
                }
                path.pop();
            }
        }
        let mut out = Vec::new();
        walk(&self.body, &mut Vec::new(), &mut out);
        out
    }
}

/// The [`crate::ron_tree`] path of a block of slide `slide`: `slides[3].body[2][1][0]`.
pub fn block_tree_path(slide: usize, block: &[usize]) -> String {
    let mut s = format!("slides[{slide}].body");
    for i in block {
        s.push_str(&format!("[{i}]"));
    }
    s
}

#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum Layout {
    /// Title at the top, blocks below it.
    #[default]
    Content,
    /// Large centred title with the body beneath: the opening slide or a section divider.
    Title,
}

/// The widths an image block may ask for, as a fraction of the canvas (the slide clamps to
/// them; `lectern check` reports a width outside).
pub const IMAGE_WIDTH_RANGE: std::ops::RangeInclusive<f32> = 0.05..=1.0;

/// One piece of slide content, laid out top to bottom.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Block {
    /// A paragraph: `Text("..")`, or `Text((src: "..", latex: true))` for LaTeX `$…$`.
    Text(
        #[serde(
            deserialize_with = "super::prose::deserialize_prose",
            serialize_with = "super::prose::serialize_prose"
        )]
        Prose,
    ),
    /// A bulleted list: `Bullets([..])`, or `Bullets((items: [..], latex: true))`.
    Bullets(
        #[serde(
            deserialize_with = "super::prose::deserialize_bullets",
            serialize_with = "super::prose::serialize_bullets"
        )]
        BulletList,
    ),
    /// Display maths (Typst syntax by default; `latex: true` for LaTeX input).
    Math {
        src: String,
        #[serde(default)]
        latex: bool,
    },
    /// A picture from a file inside the project folder; `width` is a fraction of the canvas.
    Image {
        path: String,
        #[serde(default)]
        width: Option<f32>,
    },
    /// A live plot or 3-D widget computed by the project's own integrators.
    Widget(WidgetSpec),
    /// Side-by-side columns, each a list of blocks.
    Columns(Vec<Vec<Block>>),
    /// A table: a header row set apart from the data, then rows of cells (inline markup as in
    /// `Text`). Every row has as many cells as the header (`lectern check` says where not).
    Table {
        header: Vec<String>,
        rows: Vec<Vec<String>>,
    },
}

/// A bookmark written in the deck: key `1`…`9` jumps to `slide` and sets its widgets'
/// parameters, e.g. `(key: 1, slide: "neptune", label: "h = 0.5 blows up", set: [("h", 0.5)])`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BookmarkDecl {
    pub key: u8,
    pub slide: String,
    #[serde(default)]
    pub label: String,
    /// (parameter id, value); a value applies to every widget on the slide with that id
    /// (booleans: 0 or 1; counts: rounded).
    #[serde(default)]
    pub set: Vec<(String, f64)>,
}

impl Deck {
    /// The planned length of the talk: the sum of the slides' budgets.
    pub fn planned_secs(&self) -> f32 {
        self.slides.iter().map(Slide::planned_secs).sum()
    }

    /// The page counter of slide `index` (0-based) as the footer and the presenter show it:
    /// "7 / 20", where 20 is the number of the last slide paging reaches, so the talk's last
    /// page reads "20 / 20"; an optional (`skip: true`) slide reads "23 · optional". The
    /// numbers are the ones `G n` takes.
    pub fn counter(&self, index: usize) -> String {
        let last_main = self
            .slides
            .iter()
            .rposition(|s| !s.skip)
            .map_or(self.slides.len(), |i| i + 1);
        match self.slides.get(index) {
            Some(s) if s.skip => format!("{} · optional", index + 1),
            _ => format!("{} / {last_main}", index + 1),
        }
    }

    /// The index of the slide whose [`Slide::key`] is `key`.
    pub fn find(&self, key: &str) -> Option<usize> {
        self.slides.iter().position(|s| s.key() == key)
    }
}
