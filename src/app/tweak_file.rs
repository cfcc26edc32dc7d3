//! The live tweak state of a whole deck as a file (`DECK.tweaks.ron`), written by the presenter
//! (`E`, `Ctrl+S`) and read by `lectern export --with-tweaks`, so a handout shows exactly what
//! was presented. Each value is addressed as write-back addresses it: slide key, the widget's
//! index among the slide's widgets in file order, parameter id.

use std::collections::BTreeMap;
use std::path::Path;

use serde::{Deserialize, Serialize};

use super::slide_state::{DeckState, SlideState};
use super::tweaks::widget_paths;
use crate::deck::{Deck, Slide};
use crate::diag::Diagnostic;
use crate::widgets::ParamSnapshot;

/// One tweaked value.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TweakEntry {
    /// Index of the widget among the slide's widgets, in file order (0 = first).
    pub widget: usize,
    pub param: String,
    pub value: ParamSnapshot,
}

/// Tweaked values per slide key (id, else title). Only values that differ from the deck file.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct TweakFile {
    pub slides: BTreeMap<String, Vec<TweakEntry>>,
}

impl TweakFile {
    /// The tweaks of one slide's live state.
    pub fn slide_entries(slide: &Slide, state: &mut SlideState) -> Vec<TweakEntry> {
        let order = widget_paths(slide);
        state
            .tweaked()
            .into_iter()
            .filter_map(|(path, param, value)| {
                let widget = order.iter().position(|p| *p == path)?;
                Some(TweakEntry {
                    widget,
                    param,
                    value,
                })
            })
            .collect()
    }

    /// The tweaks of every slide of `deck` that has live state.
    pub fn from_states(deck: &Deck, states: &mut DeckState) -> Self {
        let mut slides = BTreeMap::new();
        for slide in &deck.slides {
            if let Some(state) = states.existing(slide) {
                let entries = Self::slide_entries(slide, state);
                if !entries.is_empty() {
                    slides.insert(slide.key().to_owned(), entries);
                }
            }
        }
        Self { slides }
    }

    pub fn to_ron(&self) -> String {
        let pretty = ron::ser::PrettyConfig::new().depth_limit(4);
        let body = ron::ser::to_string_pretty(self, pretty).unwrap_or_else(|_| "()".into());
        format!(
            "// Live tweaks written by lectern; `lectern export --with-tweaks` applies them.\n{body}\n"
        )
    }

    /// Reads a tweaks file; a syntax error names the file, line and column.
    pub fn load(path: &Path) -> Result<Self, Diagnostic> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| Diagnostic::whole_file(path, format!("cannot read: {e}")))?;
        ron::Options::default()
            .from_str(&text)
            .map_err(|e| Diagnostic::from_ron(path, &e))
    }

    /// Sets the recorded values of slide `index` of `deck` on `state`. Returns a message per
    /// value that could not be applied (slide changed since: no such widget or parameter,
    /// wrong kind).
    pub fn apply(&self, deck: &Deck, index: usize, state: &mut SlideState) -> Vec<String> {
        let Some(slide) = deck.slides.get(index) else {
            return Vec::new();
        };
        let Some(entries) = self.slides.get(slide.key()) else {
            return Vec::new();
        };
        // Widgets made now must find the deck's files (tableaux) as a draw would.
        state.set_deck_path(deck.file.as_deref());
        state.ensure_widgets(slide);
        let order = widget_paths(slide);
        let mut problems = Vec::new();
        for e in entries {
            let applied = order
                .get(e.widget)
                .is_some_and(|path| state.set_param(path, &e.param, e.value));
            if !applied {
                problems.push(format!(
                    "slide {:?}: widget {} has no parameter {:?} taking {:?}",
                    slide.key(),
                    e.widget,
                    e.param,
                    e.value
                ));
            }
        }
        problems
    }

    /// Slide keys in the file that the deck no longer has.
    pub fn unknown_slides(&self, deck: &Deck) -> Vec<String> {
        self.slides
            .keys()
            .filter(|k| deck.find(k).is_none())
            .cloned()
            .collect()
    }
}

/// `DECK.tweaks.ron` beside the deck file.
pub fn tweak_file_path(deck_path: &Path) -> std::path::PathBuf {
    deck_path.with_extension("tweaks.ron")
}
