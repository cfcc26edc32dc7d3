//! Live tweaks beyond one frame: bookmarks (`Ctrl+1…9` store, `1…9` recall, or declared in the
//! deck) and write-back of the current values into the deck file as its new defaults.

use std::path::{Path, PathBuf};

use super::slide_state::{SlideState, TweakSnapshot};
use crate::deck::write_back::{NewValue, ValueEdit, apply_at, apply_edits, write_atomic};
use crate::deck::{BookmarkDecl, Slide};
use crate::widgets::{ParamSnapshot, WriteTo};

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
    slide.widgets().into_iter().map(|(p, _)| p).collect()
}

/// Where each tweak of a slide goes: edits of the deck, and of problem files (equations that
/// come from `File(..)`), and how many live-only switches were left out.
#[derive(Debug, Default)]
pub struct Edits {
    pub deck: Vec<ValueEdit>,
    pub files: Vec<(PathBuf, Vec<(String, NewValue)>)>,
    pub skipped: usize,
}

impl Edits {
    pub fn count(&self) -> usize {
        self.deck.len() + self.files.iter().map(|(_, e)| e.len()).sum::<usize>()
    }

    fn push_file_edit(&mut self, file: &Path, at: String, value: NewValue) {
        match self.files.iter_mut().find(|(f, _)| f == file) {
            Some((_, edits)) => edits.push((at, value)),
            None => self.files.push((file.to_path_buf(), vec![(at, value)])),
        }
    }
}

/// The edits that write `state`'s tweaked values (and typed equations) of `slide` back.
pub fn edits_for(slide: &Slide, state: &mut SlideState) -> Result<Edits, String> {
    let id = slide
        .id
        .clone()
        .ok_or("write-back needs the slide to have an `id` in the file")?;
    let mut out = Edits::default();
    let raw = |v: ParamSnapshot| {
        NewValue::Raw(match v {
            ParamSnapshot::F64(x) => format!("{x:?}"),
            ParamSnapshot::Bool(b) => b.to_string(),
            ParamSnapshot::Usize(n) => n.to_string(),
        })
    };
    for (path, param, v) in state.tweaked() {
        let target = state.write_target(&path, &param).unwrap_or(WriteTo::Spec);
        let ode_file = state
            .widget_at(&path)
            .and_then(|w| w.ode())
            .and_then(|o| o.file().map(Path::to_path_buf));
        match target {
            WriteTo::Nowhere => out.skipped += 1,
            WriteTo::Spec => out.deck.push(ValueEdit {
                slide: id.clone(),
                block: path,
                param,
                value: raw(v),
            }),
            WriteTo::OdeParam(name) => match ode_file {
                Some(file) => out.push_file_edit(&file, format!("params.{name}"), raw(v)),
                None => out.deck.push(ValueEdit {
                    slide: id.clone(),
                    block: path,
                    param: format!("ode.params.{name}"),
                    value: raw(v),
                }),
            },
        }
    }
    for (path, _, ode) in state.odes() {
        let file = ode.file().map(Path::to_path_buf);
        // a typed right-hand side whose file's exact solution was dropped: it goes from the
        // file too, or the next load would measure the new equation against the old solution
        if ode.drops_files_exact() {
            match &file {
                Some(f) => out.push_file_edit(f, "exact".into(), NewValue::RemoveField),
                None => out.deck.push(ValueEdit {
                    slide: id.clone(),
                    block: path.clone(),
                    param: "ode.exact".into(),
                    value: NewValue::RemoveField,
                }),
            }
        }
        for (slot, text) in ode.typed() {
            match &file {
                Some(f) => out.push_file_edit(f, slot.def_path(), NewValue::Str(text)),
                None => out.deck.push(ValueEdit {
                    slide: id.clone(),
                    block: path.clone(),
                    param: format!("ode.{}", slot.def_path()),
                    value: NewValue::Str(text),
                }),
            }
        }
    }
    Ok(out)
}

/// Writes the current slide's tweaks (and typed equations) into `deck_path` and the problem
/// files they come from (each atomically, and none unless all can be written); returns how
/// many values were written.
pub fn write_back(
    deck_path: &Path,
    slide: &Slide,
    state: &mut SlideState,
) -> Result<usize, String> {
    let edits = edits_for(slide, state)?;
    let mut writes: Vec<(PathBuf, String)> = Vec::new();
    let read = |p: &Path| {
        std::fs::read_to_string(p).map_err(|e| format!("cannot read {}: {e}", p.display()))
    };
    if !edits.deck.is_empty() {
        let text = read(deck_path)?;
        writes.push((deck_path.to_path_buf(), apply_edits(&text, &edits.deck)?));
    }
    for (file, at) in &edits.files {
        let text = read(file)?;
        let new = apply_at(&text, at).map_err(|e| format!("{}: {e}", file.display()))?;
        writes.push((file.clone(), new));
    }
    for (file, text) in &writes {
        write_atomic(file, text).map_err(|e| format!("cannot write {}: {e}", file.display()))?;
    }
    Ok(edits.count())
}
