//! The live state of the slides being presented — each slide's widgets, made from their specs
//! the first time the slide is drawn and kept (with their tweaks) across frames and reloads —
//! and what drawing a slide gave back. A leaf: the slide renderer, its blocks and the ink all
//! use it, and it uses none of them.

use std::cell::RefCell;
use std::collections::HashMap;
use std::rc::Rc;

use egui::Rect;

use crate::deck::{Deck, Slide};
use crate::widgets::{MadeIn, ParamSnapshot, ProblemFiles, SlideWidget, WidgetSpec, params};

/// The live state of one slide: its widgets, created from their specs the first time the slide
/// is drawn and kept while presenting (so a dragged slider stays where the lecturer left it).
#[derive(Default)]
pub struct SlideState {
    pub(crate) widgets: HashMap<Vec<usize>, WidgetSlot>,
    /// The presenter's previews of widgets whose equation has drafts not shown to the room
    /// yet: a copy of the widget drawing the drafts' equation, by block path.
    previews: HashMap<Vec<usize>, (crate::ode::problem::ProblemDef, WidgetSlot)>,
    /// Problems found while drawing (a formula that does not typeset), from the last frame:
    /// for the presenter's screen, never the audience's.
    problems: Vec<String>,
    /// The deck file, remembered from the last draw: widgets made before the slide is drawn
    /// (bookmarks, restores) resolve their files (problems, tableaux) against it too.
    deck_path: Option<std::path::PathBuf>,
    /// The problem files' one holder, shared by every slide of the deck ([`DeckState`]).
    problem_files: Rc<RefCell<ProblemFiles>>,
}

pub(crate) struct WidgetSlot {
    pub spec: WidgetSpec,
    pub widget: Box<dyn SlideWidget>,
}

impl SlideState {
    /// The widget at block path `path` (indices into the body, then into columns), made from
    /// `spec` if it is new or its spec in the file changed.
    pub(crate) fn widget(
        &mut self,
        path: &[usize],
        spec: &WidgetSpec,
        deck_path: Option<&std::path::Path>,
    ) -> &mut dyn SlideWidget {
        use std::collections::hash_map::Entry;
        let entry = match self.widgets.entry(path.to_vec()) {
            // every frame: nothing to make, no file touched
            Entry::Occupied(slot) if slot.get().spec == *spec => {
                return slot.into_mut().widget.as_mut();
            }
            entry => entry,
        };
        if let Some(source) = spec.ode() {
            self.problem_files.borrow_mut().open(source, deck_path);
        }
        let problems = self.problem_files.borrow();
        let at = MadeIn {
            deck_path,
            problems: Some(&problems),
        };
        let mut fresh = WidgetSlot {
            spec: spec.clone(),
            widget: spec.instantiate(at),
        };
        let slot = match entry {
            // the spec changed in the deck: made again, the lecturer's tweaks carried over
            Entry::Occupied(mut slot) => {
                let old = slot.get_mut();
                let old_file = file_values(&old.spec, at);
                carry_tweaks(&old_file, old.widget.as_mut(), fresh.widget.as_mut());
                *old = fresh;
                slot.into_mut()
            }
            Entry::Vacant(slot) => slot.insert(fresh),
        };
        slot.widget.as_mut()
    }

    /// After files changed on disk: the problem files among them are re-read (once each, by the
    /// deck's holder) and this slide's widgets follow ([`DeckState::reload_problem_files`] does
    /// it for every slide).
    pub fn reload_problem_files(&mut self, changed: &[std::path::PathBuf]) {
        let outcomes = self.problem_files.borrow_mut().on_changes(changed);
        self.apply_problem_files(&outcomes);
    }

    /// After problem files changed on disk and their holder re-read them (`outcomes`, by file
    /// key): widgets whose equation comes from a file that loaded again are made again from it
    /// (their tweaks carried over); those whose file's save is broken keep their last good
    /// equation and show the file's error.
    fn apply_problem_files(&mut self, outcomes: &crate::widgets::problem_files::FileOutcomes) {
        use crate::reload::{Reloaded, file_key};
        let deck_path = self.deck_path.clone();
        let problems = self.problem_files.clone();
        let problems = problems.borrow();
        let at = MadeIn {
            deck_path: deck_path.as_deref(),
            problems: Some(&problems),
        };
        for slot in self.widgets.values_mut() {
            let file = (slot.widget.ode()).and_then(|o| o.file().map(file_key));
            let Some((_, outcome)) = file.and_then(|f| outcomes.iter().find(|(key, _)| *key == f))
            else {
                continue;
            };
            match outcome {
                Reloaded::Updated => {}
                Reloaded::Failed(d) => {
                    if let Some(ode) = slot.widget.ode() {
                        ode.set_file_error(Some(d.to_string()));
                    }
                    continue;
                }
                Reloaded::Untouched | Reloaded::Waiting => continue,
            }
            // the file's values as they were before this save (the old spec made now would
            // read the new version): a value the file changed is not a tweak to keep
            let mut old_file = file_values(&slot.spec, at);
            if let Some(def) = slot.widget.ode().and_then(|o| o.file_def()) {
                for (name, value) in &def.params {
                    match old_file.iter_mut().find(|(id, _)| id == name) {
                        Some(entry) => entry.1 = ParamSnapshot::F64(*value),
                        None => old_file.push((name.clone(), ParamSnapshot::F64(*value))),
                    }
                }
            }
            let mut widget = slot.spec.instantiate(at);
            carry_tweaks(&old_file, slot.widget.as_mut(), widget.as_mut());
            slot.widget = widget;
        }
    }

    /// The live equations of the slide's widgets, by block path (the presenter's editor).
    pub fn odes(&mut self) -> Vec<(Vec<usize>, &'static str, &mut crate::widgets::LiveOde)> {
        let mut slots: Vec<(&Vec<usize>, &mut WidgetSlot)> = self.widgets.iter_mut().collect();
        slots.sort_by(|a, b| a.0.cmp(b.0));
        slots
            .into_iter()
            .filter_map(|(path, slot)| {
                let kind = slot.spec.kind();
                slot.widget.ode().map(|o| (path.clone(), kind, o))
            })
            .collect()
    }

    /// The presenter's preview of the widget at `path` while its equation has drafts that
    /// compile: a copy with the live tweaks and the drafts' equation, remade when the drafts
    /// change. `None` (and the copy forgotten) without such drafts.
    pub fn preview_widget(&mut self, path: &[usize]) -> Option<&mut dyn SlideWidget> {
        let deck_path = self.deck_path.clone();
        let live = self.widgets.get_mut(path)?;
        let Some((def, _)) = live.widget.ode().and_then(|o| o.draft_problem()) else {
            self.previews.remove(path);
            return None;
        };
        let fresh = !matches!(self.previews.get(path), Some((d, _)) if *d == def);
        if fresh {
            let problems = self.problem_files.borrow();
            let at = MadeIn {
                deck_path: deck_path.as_deref(),
                problems: Some(&problems),
            };
            let mut widget = live.spec.instantiate(at);
            let old_file = file_values(&live.spec, at);
            carry_tweaks(&old_file, live.widget.as_mut(), widget.as_mut());
            widget.ode()?.show_def(def.clone());
            let slot = WidgetSlot {
                spec: live.spec.clone(),
                widget,
            };
            self.previews.insert(path.to_vec(), (def, slot));
        }
        Some(self.previews.get_mut(path)?.1.widget.as_mut())
    }

    /// The widget at block path `path`, if it was made.
    /// Whether a typed equation's preview was drawn (the presenter then gives it more room).
    pub fn has_preview(&self) -> bool {
        !self.previews.is_empty()
    }

    pub fn widget_at(&mut self, path: &[usize]) -> Option<&mut dyn SlideWidget> {
        Some(self.widgets.get_mut(path)?.widget.as_mut())
    }

    /// At the start of drawing the slide: forget last frame's problems, remember the deck file.
    pub(crate) fn begin_frame(&mut self, deck_file: Option<&std::path::Path>) {
        self.problems.clear();
        self.set_deck_path(deck_file);
    }

    pub(crate) fn note_problem(&mut self, problem: String) {
        if !self.problems.contains(&problem) {
            self.problems.push(problem);
        }
    }

    /// Problems found while drawing the slide the last time (e.g. a formula with an error).
    pub fn problems(&self) -> &[String] {
        &self.problems
    }

    /// The deck file whose folder the widgets' files are in (for widgets made before the
    /// slide is first drawn).
    pub fn set_deck_path(&mut self, deck: Option<&std::path::Path>) {
        self.deck_path = deck.map(std::path::Path::to_path_buf);
    }

    /// Makes every widget of `slide` (so tweaks can be set before it is first drawn).
    pub fn ensure_widgets(&mut self, slide: &Slide) {
        let deck = self.deck_path.clone();
        for (path, spec) in slide.widgets() {
            self.widget(&path, spec, deck.as_deref());
        }
    }

    /// Every live value, by widget path and parameter id (a bookmark).
    pub fn tweak_snapshot(&mut self) -> TweakSnapshot {
        let mut out: TweakSnapshot = self
            .widgets
            .iter_mut()
            .map(|(path, slot)| (path.clone(), params::snapshot(slot.widget.as_mut())))
            .collect();
        out.sort_by(|a, b| a.0.cmp(&b.0));
        out
    }

    /// Sets the values of a [`Self::tweak_snapshot`] (unknown widgets or ids are skipped).
    pub fn restore(&mut self, slide: &Slide, snapshot: &TweakSnapshot) {
        self.ensure_widgets(slide);
        for (path, values) in snapshot {
            if let Some(slot) = self.widgets.get_mut(path) {
                params::restore(slot.widget.as_mut(), values);
            }
        }
    }

    /// Sets one value by widget path and parameter id; false if there is no such parameter.
    pub fn set_param(&mut self, path: &[usize], id: &str, value: ParamSnapshot) -> bool {
        let Some(slot) = self.widgets.get_mut(path) else {
            return false;
        };
        params::find_param(slot.widget.params(), id).is_some_and(|mut p| p.set(value).is_ok())
    }

    /// One value by widget path and parameter id.
    pub fn param(&mut self, path: &[usize], id: &str) -> Option<ParamSnapshot> {
        let slot = self.widgets.get_mut(path)?;
        params::find_param(slot.widget.params(), id).map(|p| p.get())
    }

    /// `R`: every widget back to the file's values.
    pub fn reset(&mut self) {
        for slot in self.widgets.values_mut() {
            slot.widget.reset();
        }
    }

    /// Where write-back writes parameter `id` of the widget at `path`.
    pub fn write_target(&mut self, path: &[usize], id: &str) -> Option<crate::widgets::WriteTo> {
        let slot = self.widgets.get_mut(path)?;
        params::find_param(slot.widget.params(), id).map(|p| p.write)
    }

    /// The values that differ from the file's, by widget path: what write-back writes.
    pub fn tweaked(&mut self) -> Vec<(Vec<usize>, String, ParamSnapshot)> {
        let mut out = Vec::new();
        let deck = self.deck_path.clone();
        let problems = self.problem_files.borrow();
        let at = MadeIn {
            deck_path: deck.as_deref(),
            problems: Some(&problems),
        };
        for (path, slot) in &mut self.widgets {
            let file = file_values(&slot.spec, at);
            for (id, v) in params::snapshot(slot.widget.as_mut()) {
                if file.iter().any(|(fid, fv)| *fid == id && *fv != v) {
                    out.push((path.clone(), id, v));
                }
            }
        }
        out.sort_by(|a, b| (&a.0, &a.1).cmp(&(&b.0, &b.1)));
        out
    }

    /// The live controls of every widget on the slide (the presenter's panel).
    pub fn controls_ui(&mut self, ui: &mut egui::Ui) {
        let mut paths: Vec<Vec<usize>> = self.widgets.keys().cloned().collect();
        paths.sort();
        for path in paths {
            let Some(slot) = self.widgets.get_mut(&path) else {
                continue;
            };
            ui.label(egui::RichText::new(slot.spec.kind()).strong());
            ui.push_id(&path, |ui| {
                for mut p in slot.widget.params() {
                    p.ui(ui);
                }
            });
            ui.add_space(6.0);
        }
    }

    /// How many widgets are alive (for tests of the keep-alive rule).
    pub fn widget_count(&self) -> usize {
        self.widgets.len()
    }
}

/// A slide's live values: per widget path, (parameter id, value).
pub type TweakSnapshot = Vec<(Vec<usize>, Vec<(String, ParamSnapshot)>)>;

/// The values the files give a widget made from `spec` (its "untweaked" values).
fn file_values(spec: &WidgetSpec, at: MadeIn<'_>) -> Vec<(String, ParamSnapshot)> {
    params::snapshot(spec.instantiate(at).as_mut())
}

/// After a reload changed a widget's spec (or a file it reads): `old_file` is what the files
/// gave the old widget; the new widget takes the live values the lecturer
/// tweaked, except where the file changed that very value (then the file wins). Its equation
/// keeps what was typed live the same way, and the last good equation if the new one is broken.
fn carry_tweaks(
    old_file: &[(String, ParamSnapshot)],
    live: &mut dyn SlideWidget,
    new: &mut dyn SlideWidget,
) {
    if let (Some(old), Some(fresh)) = (live.ode(), new.ode()) {
        fresh.carry_from(old);
    }
    let new_file = params::snapshot(new);
    let keep: Vec<(String, ParamSnapshot)> = params::snapshot(live)
        .into_iter()
        .filter(|(id, v)| {
            let was = old_file.iter().find(|(i, _)| i == id).map(|(_, v)| *v);
            let now = new_file.iter().find(|(i, _)| i == id).map(|(_, v)| *v);
            was != Some(*v) && was == now
        })
        .collect();
    params::restore(new, &keep);
}

/// The states of every slide of a deck, by slide key (id, else title), so they survive moving
/// between slides and reloads that insert slides.
#[derive(Default)]
pub struct DeckState {
    slides: HashMap<String, SlideState>,
    /// The problem files every slide's widgets read, each held once.
    problems: Rc<RefCell<ProblemFiles>>,
}

impl DeckState {
    pub fn slide(&mut self, slide: &Slide) -> &mut SlideState {
        let problems = &self.problems;
        self.slides
            .entry(slide.key().to_owned())
            .or_insert_with(|| SlideState {
                problem_files: problems.clone(),
                ..SlideState::default()
            })
    }

    /// The state of `slide` if it was ever drawn or tweaked.
    pub fn existing(&mut self, slide: &Slide) -> Option<&mut SlideState> {
        self.slides.get_mut(slide.key())
    }

    /// Files changed on disk: each problem file among them is re-read once, and the widgets
    /// made from it follow ([`SlideState::apply_problem_files`]).
    pub fn reload_problem_files(&mut self, changed: &[std::path::PathBuf]) {
        let outcomes = self.problems.borrow_mut().on_changes(changed);
        if outcomes.is_empty() {
            return;
        }
        for state in self.slides.values_mut() {
            state.apply_problem_files(&outcomes);
        }
    }

    /// The problem files held while presenting (tests).
    pub fn problem_files(&self) -> std::cell::Ref<'_, ProblemFiles> {
        self.problems.borrow()
    }

    /// After a reload: forget the states of slides that no longer exist. Widgets whose spec
    /// changed are recreated lazily by [`SlideState::widget`].
    pub fn retain_deck(&mut self, deck: &Deck) {
        self.slides.retain(|key, _| deck.find(key).is_some());
    }
}

/// What drawing a slide gave back.
pub struct SlideResponse {
    /// Where the canvas landed, in points.
    pub canvas: Rect,
    /// Points per canvas unit.
    pub scale: f32,
    /// The slide's background: `clicked()` is a click that hit no widget.
    pub background: egui::Response,
    /// While drawing: the whole canvas, on top of its widgets, sensing clicks and drags.
    pub ink: Option<egui::Response>,
}

/// Where a widget was drawn in the last pass: the slot the slide gave it, the rect it used,
/// and the slide's content area (for the test that every widget stays inside its slot and
/// every slot inside the slide, above the footer).
#[derive(Debug, Clone, PartialEq)]
pub struct DrawnWidget {
    pub slide: usize,
    pub path: Vec<usize>,
    pub kind: &'static str,
    pub slot: Rect,
    pub drawn: Rect,
    pub content: Rect,
    pass: u64,
}

fn drawn_widgets_id() -> egui::Id {
    egui::Id::unique("lectern-drawn-widgets")
}

/// Notes where a widget was drawn this pass (see [`drawn_widgets`]).
pub(crate) fn record_drawn_widget(
    ctx: &egui::Context,
    slide: usize,
    path: &[usize],
    kind: &'static str,
    slot: Rect,
    drawn: Rect,
    content: Rect,
) {
    let pass = ctx.cumulative_pass_nr();
    ctx.data_mut(|d| {
        let v = d.get_temp_mut_or_default::<Vec<DrawnWidget>>(drawn_widgets_id());
        v.retain(|w| w.pass + 1 >= pass);
        v.push(DrawnWidget {
            slide,
            path: path.to_vec(),
            kind,
            slot,
            drawn,
            content,
            pass,
        });
    });
}

/// The widgets drawn in the latest pass of `ctx`, where they were drawn.
pub fn drawn_widgets(ctx: &egui::Context) -> Vec<DrawnWidget> {
    let v: Vec<DrawnWidget> = ctx.data(|d| d.get_temp(drawn_widgets_id()).unwrap_or_default());
    let last = v.iter().map(|w| w.pass).max().unwrap_or(0);
    v.into_iter().filter(|w| w.pass == last).collect()
}
