//! Formula textures for egui, cached by (source, syntax, size, colour), with last-good slots.
//!
//! Typesetting happens in the [`pool`](super::pool), never in the frame. In the live window
//! ([`MathCache::set_wait`]`(false)`) a formula that is not ready yet is asked for and the slot
//! shows its last good picture (or the caller draws a placeholder); the pool repaints when it
//! is done. Headless paths (export, snapshot tests) wait for every formula, bounded by the
//! pool's [`Bounds`](super::Bounds), so their images are deterministic: that is the default.

use std::collections::HashMap;
use std::sync::{Arc, Mutex};

use super::formula::Request;
use super::formula::{MathError, MathStyle, MathSyntax, RenderedFormula};
use super::pool::{Job, Notify, Poll, pool};

#[derive(Debug, Clone, PartialEq, Eq, Hash)]
struct Key {
    src: String,
    syntax: MathSyntax,
    style: MathStyle,
    /// Size in physical pixels per em, as f32 bits (exact-match key).
    size_bits: u32,
    rgba: [u8; 4],
}

impl Key {
    fn request(&self) -> Request {
        Request {
            src: self.src.clone(),
            syntax: self.syntax,
            style: self.style,
            size_px: f32::from_bits(self.size_bits),
            rgba: self.rgba,
        }
    }
}

/// A formula on the GPU. `size_px` is its size in physical pixels when typeset at `em_px`
/// pixels per em, its baseline `baseline_px` below its top; divide by `pixels_per_point` to
/// lay it out in egui points.
#[derive(Clone)]
pub struct Formula {
    pub texture: egui::TextureHandle,
    pub size_px: egui::Vec2,
    pub baseline_px: f32,
    pub em_px: f32,
}

impl Formula {
    /// Its size in physical pixels drawn at `em_px` pixels per em: a last good picture typeset
    /// at another size (the window was resized) is scaled until the new one is ready.
    pub fn size_at(&self, em_px: f32) -> egui::Vec2 {
        if self.em_px > 0.0 && em_px > 0.0 {
            self.size_px * (em_px / self.em_px)
        } else {
            self.size_px
        }
    }
}

/// What a slot shows this frame: the newest good formula (maybe stale) and the error of the
/// newest edit, if it is broken.
#[derive(Clone, Default)]
pub struct MathView {
    pub formula: Option<Formula>,
    /// Set when the current source did not render; `formula` is then the last good one.
    pub error: Option<MathError>,
    /// The current source is still being typeset; `formula` is the last good one, if any.
    pub pending: bool,
}

enum Entry {
    Pending(Arc<Job>),
    Done(Result<Formula, MathError>),
}

/// Cache of typeset formulas. One per egui context is enough: get it with [`MathCache::shared`].
pub struct MathCache {
    entries: HashMap<Key, Entry>,
    last_good: HashMap<String, Formula>,
    /// Block until formulas are ready (headless) instead of showing the last good one.
    wait: bool,
    repaint: Option<Notify>,
    /// Formulas received from the pool (typeset or failed), for reports and tests.
    pub renders: usize,
}

impl Default for MathCache {
    fn default() -> Self {
        Self {
            entries: HashMap::new(),
            last_good: HashMap::new(),
            wait: true,
            repaint: None,
            renders: 0,
        }
    }
}

/// Beyond this many cached formulas the cache is dropped wholesale (slots keep theirs); a deck
/// has a few hundred at most, so this only bounds a session of many edits.
const MAX_ENTRIES: usize = 2048;

impl MathCache {
    pub fn new() -> Self {
        Self::default()
    }

    /// The cache stored in `ctx`, shared by the slide renderer and widgets.
    pub fn shared(ctx: &egui::Context) -> Arc<Mutex<MathCache>> {
        ctx.data_mut(|d| {
            d.get_temp_mut_or_default::<Arc<Mutex<MathCache>>>(egui::Id::NULL.with("lectern::math"))
                .clone()
        })
    }

    /// `false` for the live window: never wait for a formula, show the last good picture (or a
    /// placeholder) and repaint when it is ready. `true` (the default) for export and tests.
    pub fn set_wait(&mut self, wait: bool) {
        self.wait = wait;
    }

    pub fn waits(&self) -> bool {
        self.wait
    }

    /// Forgets every formula and last good picture (as after a fresh start).
    pub fn clear(&mut self) {
        self.entries.clear();
        self.last_good.clear();
    }

    /// The formula for `src` at `size_px` physical pixels per em in `color`, typeset on first
    /// use and cached (errors are cached too, so a broken formula costs nothing per frame).
    /// Always waits for the result (bounded by the pool's time budget).
    pub fn get(
        &mut self,
        ctx: &egui::Context,
        src: &str,
        syntax: MathSyntax,
        size_px: f32,
        color: egui::Color32,
    ) -> Result<Formula, MathError> {
        let key = key(src, syntax, MathStyle::Display, size_px, color);
        self.lookup(ctx, key, true, true)
            .expect("a waiting lookup always has a result")
    }

    /// An inline formula (`$…$` in a paragraph) for `src`: cached like display ones; waits
    /// only where the cache [`waits`](Self::waits), else `None` while it is being typeset.
    pub fn inline(
        &mut self,
        ctx: &egui::Context,
        src: &str,
        syntax: MathSyntax,
        size_px: f32,
        color: egui::Color32,
    ) -> Option<Result<Formula, MathError>> {
        let wait = self.wait;
        let key = key(src, syntax, MathStyle::Inline, size_px, color);
        self.lookup(ctx, key, true, wait)
    }

    /// Asks for a formula the lecturer will probably see soon (the next slides), at low
    /// priority; never waits.
    pub fn prefetch(
        &mut self,
        ctx: &egui::Context,
        src: &str,
        syntax: MathSyntax,
        style: MathStyle,
        size_px: f32,
        color: egui::Color32,
    ) {
        let _ = self.lookup(ctx, key(src, syntax, style, size_px, color), false, false);
    }

    /// The cached result for `key`, asking the pool for it if needed; `None` while pending
    /// (only when not `wait`ing).
    fn lookup(
        &mut self,
        ctx: &egui::Context,
        key: Key,
        urgent: bool,
        wait: bool,
    ) -> Option<Result<Formula, MathError>> {
        let pending = match self.entries.get(&key) {
            Some(Entry::Done(r)) => return Some(r.clone()),
            Some(Entry::Pending(job)) => Some(job.clone()),
            None => None,
        };
        let job = match pending.as_ref().map(|job| job.poll()) {
            Some(Poll::Done(r)) => return Some(self.receive(ctx, key, r)),
            Some(Poll::Pending) => {
                let job = pending.expect("polled");
                job.want(urgent, urgent.then(|| self.repaint(ctx)));
                job
            }
            Some(Poll::Expired) | None => self.submit(ctx, &key, urgent, wait),
        };
        if wait {
            let r = job.wait();
            Some(self.receive(ctx, key, r))
        } else {
            None
        }
    }

    fn submit(&mut self, ctx: &egui::Context, key: &Key, urgent: bool, keep: bool) -> Arc<Job> {
        if self.entries.len() >= MAX_ENTRIES {
            self.entries.clear();
        }
        let notify = urgent.then(|| self.repaint(ctx));
        let job = pool().submit(key.request(), urgent, keep, notify);
        self.entries
            .insert(key.clone(), Entry::Pending(job.clone()));
        job
    }

    fn repaint(&mut self, ctx: &egui::Context) -> Notify {
        self.repaint
            .get_or_insert_with(|| {
                let ctx = ctx.clone();
                Arc::new(move || ctx.request_repaint())
            })
            .clone()
    }

    /// Uploads a finished formula and caches the result.
    fn receive(
        &mut self,
        ctx: &egui::Context,
        key: Key,
        result: Result<RenderedFormula, MathError>,
    ) -> Result<Formula, MathError> {
        let result = result.map(|r| {
            let size = [r.width as usize, r.height as usize];
            let image = egui::ColorImage::from_rgba_premultiplied(size, &r.rgba_premultiplied);
            let name = format!("math:{}", self.renders);
            Formula {
                texture: ctx.load_texture(name, image, egui::TextureOptions::LINEAR),
                size_px: egui::vec2(r.width as f32, r.height as f32),
                baseline_px: r.baseline as f32,
                em_px: f32::from_bits(key.size_bits),
            }
        });
        self.renders += 1;
        self.entries.insert(key, Entry::Done(result.clone()));
        result
    }

    /// Like [`get`](Self::get), remembering per `slot` (e.g. "slide-id/3") the last formula
    /// that rendered, so a broken edit keeps showing the previous picture with the error beside.
    /// In the live window (not [`waits`](Self::waits)) a formula still being typeset shows the
    /// slot's last good picture, with `pending` set.
    pub fn get_slot(
        &mut self,
        ctx: &egui::Context,
        slot: &str,
        src: &str,
        syntax: MathSyntax,
        size_px: f32,
        color: egui::Color32,
    ) -> MathView {
        let wait = self.wait;
        match self.lookup(
            ctx,
            key(src, syntax, MathStyle::Display, size_px, color),
            true,
            wait,
        ) {
            Some(Ok(f)) => {
                self.last_good.insert(slot.to_owned(), f.clone());
                MathView {
                    formula: Some(f),
                    error: None,
                    pending: false,
                }
            }
            Some(Err(e)) => MathView {
                formula: self.last_good.get(slot).cloned(),
                error: Some(e),
                pending: false,
            },
            None => MathView {
                formula: self.last_good.get(slot).cloned(),
                error: None,
                pending: true,
            },
        }
    }
}

/// For the live window: formulas drawn in `ctx` are never waited for (see
/// [`MathCache::set_wait`]).
pub fn never_wait(ctx: &egui::Context) {
    if let Ok(mut cache) = MathCache::shared(ctx).lock() {
        cache.set_wait(false);
    }
}

fn key(src: &str, syntax: MathSyntax, style: MathStyle, size_px: f32, color: egui::Color32) -> Key {
    Key {
        src: src.to_owned(),
        syntax,
        style,
        size_bits: size_px.to_bits(),
        rgba: color.to_srgba_unmultiplied(),
    }
}

/// Draws display maths centred in `ui`, `em_points` points per em, keeping the last good
/// rendering of `slot`. Returns the error of the current source, for the presenter's screen.
pub fn math_ui(
    ui: &mut egui::Ui,
    slot: &str,
    src: &str,
    syntax: MathSyntax,
    em_points: f32,
    color: egui::Color32,
) -> Option<MathError> {
    let ppp = ui.ctx().pixels_per_point();
    let cache = MathCache::shared(ui.ctx());
    let view = cache
        .lock()
        .map(|mut c| c.get_slot(ui.ctx(), slot, src, syntax, em_points * ppp, color))
        .unwrap_or_default();
    if let Some(f) = &view.formula {
        let mut size = f.size_at(em_points * ppp) / ppp;
        // Never overflow the slide: shrink to the width offered.
        let avail = ui.available_width();
        if size.x > avail && avail > 1.0 {
            size *= avail / size.x;
        }
        ui.vertical_centered(|ui| {
            ui.add(egui::Image::new((f.texture.id(), size)));
        });
    }
    view.error
}
