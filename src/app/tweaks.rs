//! Live tweaks beyond one frame: bookmarks (`Ctrl+1…9` store, `1…9` recall, or declared in the
//! deck) and write-back of the current values into the deck file as its new defaults.

use std::path::Path;

use super::slide_view::{SlideState, TweakSnapshot};
use crate::deck::write_back::{ValueEdit, apply_edits, write_atomic};
use crate::deck::{Block, BookmarkDecl, Slide};
use crate::widgets::ParamSnapshot;

/// Stored tweak states, one per digit key.
#[derive(Debug, Default, Clone)]
pub struct Bookmarks {
    slots: [Option<(String, TweakSnapshot)>; 9],
}

impl Bookmarks {
    /// `Ctrl+key`: remembers `slide`'s current values under `key` (1…9).
    pub fn store(&mut self, key: u8, slide: &Slide, state: &mut SlideState) {
        if let Some(slot) = self.slots.get_mut(usize::from(key).wrapping_sub(1)) {
            state.ensure_widgets(slide);
            *slot = Some((slide.key().to_owned(), state.tweak_snapshot()));
        }
    }

    /// The slide key and values stored under `key`, if any.
    pub fn get(&self, key: u8) -> Option<&(String, TweakSnapshot)> {
        self.slots.get(usize::from(key).wrapping_sub(1))?.as_ref()
    }
}

/// Applies a bookmark declared in the deck to `state` (the slide's widgets).
pub fn apply_declared(decl: &BookmarkDecl, slide: &Slide, state: &mut SlideState) {
    state.ensure_widgets(slide);
    let paths: Vec<Vec<usize>> = widget_paths(slide);
    for (id, value) in &decl.set {
        for path in &paths {
            let v = match state.param(path, id) {
                Some(ParamSnapshot::F64(_)) => ParamSnapshot::F64(*value),
                Some(ParamSnapshot::Bool(_)) => ParamSnapshot::Bool(*value != 0.0),
                Some(ParamSnapshot::Usize(_)) => {
                    ParamSnapshot::Usize(value.max(0.0).round() as usize)
                }
                None => continue,
            };
            state.set_param(path, id, v);
        }
    }
}

/// Paths of the widget blocks of `slide`, in file order.
pub fn widget_paths(slide: &Slide) -> Vec<Vec<usize>> {
    fn walk(blocks: &[Block], path: &mut Vec<usize>, out: &mut Vec<Vec<usize>>) {
        for (i, b) in blocks.iter().enumerate() {
            path.push(i);
            match b {
                Block::Widget(_) => out.push(path.clone()),
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
    walk(&slide.body, &mut Vec::new(), &mut out);
    out
}

/// The edits that write `state`'s tweaked values of `slide` into the deck file.
pub fn edits_for(slide: &Slide, state: &mut SlideState) -> Result<Vec<ValueEdit>, String> {
    let id = slide
        .id
        .clone()
        .ok_or("write-back needs the slide to have an `id` in the file")?;
    let order = widget_paths(slide);
    Ok(state
        .tweaked()
        .into_iter()
        .filter_map(|(path, param, v)| {
            let widget = order.iter().position(|p| *p == path)?;
            Some(ValueEdit {
                slide: id.clone(),
                widget,
                param,
                value: match v {
                    ParamSnapshot::F64(x) => format!("{x:?}"),
                    ParamSnapshot::Bool(b) => b.to_string(),
                    ParamSnapshot::Usize(n) => n.to_string(),
                },
            })
        })
        .collect())
}

/// Writes the current slide's tweaks into `deck_path` (atomically); returns how many values
/// were written.
pub fn write_back(
    deck_path: &Path,
    slide: &Slide,
    state: &mut SlideState,
) -> Result<usize, String> {
    let edits = edits_for(slide, state)?;
    if edits.is_empty() {
        return Ok(0);
    }
    let text = std::fs::read_to_string(deck_path)
        .map_err(|e| format!("cannot read {}: {e}", deck_path.display()))?;
    let new = apply_edits(&text, &edits)?;
    write_atomic(deck_path, &new)
        .map_err(|e| format!("cannot write {}: {e}", deck_path.display()))?;
    Ok(edits.len())
}
