//! Drawing on the slide while presenting: the tools (`D` pen, `H` highlighter, `L` laser
//! pointer), the colour (`1`–`5` while drawing), the stroke being drawn, and the deck's ink
//! file. The slide renderer paints the ink ([`super::ink_draw`]) and, while a tool is on, gives
//! back the canvas's pointer response ([`super::SlideResponse::ink`]); [`InkState::input_ui`]
//! turns that into strokes in canvas units, saved after each one.

use std::path::{Path, PathBuf};

use super::ink_draw::{InkView, LASER_TRAIL_SECS, LaserPoint};
use super::slide_state::SlideResponse;
use crate::deck::InkFile;
use crate::deck::ink::{CanvasFrame, Stroke, StrokeBuilder, Tool};
use crate::diag::Diagnostic;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum InkTool {
    Pen,
    Highlighter,
    Laser,
}

impl InkTool {
    fn name(self) -> &'static str {
        match self {
            InkTool::Pen => "pen",
            InkTool::Highlighter => "highlighter",
            InkTool::Laser => "laser pointer",
        }
    }
}

pub struct InkState {
    file: InkFile,
    tool: Option<InkTool>,
    /// Colour slot 0…4 for the pen and the highlighter.
    color: u8,
    /// The stroke being drawn.
    live: Option<Live>,
    /// The laser's recent positions. Never saved.
    laser: Option<Laser>,
    /// Paint strokes without anti-aliased edges (see [`InkView::plain_edges`]).
    plain_edges: bool,
}

/// Where a pointer gesture happens: the slide (by key) and the surface, i.e. which window's
/// canvas (the audience's, or the presenter's current-slide view) took the pointer. Both
/// windows show the slide; only the one being drawn on may extend or end the gesture.
#[derive(Debug, Clone, PartialEq)]
struct Place {
    key: String,
    surface: egui::Id,
}

struct Live {
    place: Place,
    builder: StrokeBuilder,
}

struct Laser {
    place: Place,
    trail: Vec<LaserPoint>,
}

impl InkState {
    /// The ink kept beside the deck at `deck_path` (`DECK.ink.ron`).
    pub fn for_deck(deck_path: &Path) -> Self {
        Self {
            file: InkFile::for_deck(deck_path),
            tool: None,
            color: 0,
            live: None,
            laser: None,
            plain_edges: false,
        }
    }

    /// On a software rasteriser: strokes without anti-aliased edges (see
    /// [`InkView::plain_edges`]).
    pub fn set_plain_edges(&mut self, on: bool) {
        self.plain_edges = on;
    }

    pub fn tool(&self) -> Option<InkTool> {
        self.tool
    }

    pub fn is_drawing(&self) -> bool {
        self.tool.is_some()
    }

    pub fn file(&self) -> &InkFile {
        &self.file
    }

    pub fn path(&self) -> &Path {
        self.file.path()
    }

    /// A damaged ink file, or a write that failed (for the presenter's problem list).
    pub fn problem(&self) -> Option<&Diagnostic> {
        self.file.problem()
    }

    /// `D`, `H`, `L`: that tool on, or off if it is the one on. Returns what to say.
    pub fn toggle(&mut self, tool: InkTool) -> String {
        self.finish_live();
        self.laser = None;
        if self.tool == Some(tool) {
            self.tool = None;
            format!("{} off", tool.name())
        } else {
            self.tool = Some(tool);
            match tool {
                InkTool::Laser => "laser pointer (L or Esc to stop)".to_owned(),
                _ => format!(
                    "{} {}: drag on the slide ({} or Esc to stop)",
                    tool.name(),
                    self.color + 1,
                    if tool == InkTool::Pen { "D" } else { "H" }
                ),
            }
        }
    }

    /// `Esc`: leaves drawing; false if no tool was on.
    pub fn stop(&mut self) -> bool {
        self.finish_live();
        self.laser = None;
        self.tool.take().is_some()
    }

    pub fn set_color(&mut self, slot: u8) {
        self.color = slot.min(crate::deck::ink::COLOR_COUNT - 1);
    }

    pub fn color(&self) -> u8 {
        self.color
    }

    /// `Ctrl+Z` on slide `key`: what to say.
    pub fn undo(&mut self, key: &str) -> String {
        self.finish_live();
        match self.file.undo(key) {
            Ok(true) => "stroke undone".to_owned(),
            Ok(false) => "no ink on this slide".to_owned(),
            Err(e) => e.to_string(),
        }
    }

    /// `Shift+D` on slide `key`: what to say.
    pub fn clear(&mut self, key: &str) -> String {
        self.finish_live();
        match self.file.clear(key) {
            Ok(0) => "no ink on this slide".to_owned(),
            Ok(n) => format!("cleared {n} stroke(s)"),
            Err(e) => e.to_string(),
        }
    }

    /// The ink file changed on disk (a batch from the deck folder's watcher).
    pub fn on_changes(&mut self, changed: &[PathBuf]) -> bool {
        self.file.on_changes(changed)
    }

    /// What to paint on slide `key` at time `now`.
    pub fn view(&self, key: &str, now: f64) -> InkView<'_> {
        InkView {
            strokes: self.file.ink().strokes(key),
            live: self
                .live
                .as_ref()
                .filter(|l| l.place.key == key)
                .map(|l| l.builder.preview()),
            laser: self
                .laser
                .as_ref()
                .filter(|l| l.place.key == key)
                .map_or(&[], |l| l.trail.as_slice()),
            now,
            plain_edges: self.plain_edges,
        }
    }

    /// Takes this frame's pointer input on slide `key` (drawn with `resp`): strokes grow, end
    /// and are saved; the laser follows the pointer. Returns a message to show (a failed save)
    /// and asks for the repaints drawing needs (the other window shows the ink too).
    pub fn input_ui(
        &mut self,
        ctx: &egui::Context,
        key: &str,
        resp: &SlideResponse,
    ) -> Option<String> {
        let (Some(tool), Some(r)) = (self.tool, resp.ink.as_ref()) else {
            return None;
        };
        let frame = CanvasFrame {
            min_points: resp.canvas.min.into(),
            points_per_unit: resp.scale,
        };
        let to_canvas = |p: egui::Pos2| frame.canvas_from_screen(p.into());
        let here = Place {
            key: key.to_owned(),
            surface: r.id,
        };
        if tool == InkTool::Laser {
            let now = ctx.input(|i| i.time);
            self.laser_input(ctx, here, r, to_canvas, now);
            return None;
        }
        if r.hovered() || r.is_pointer_button_down_on() {
            ctx.set_cursor_icon(egui::CursorIcon::Crosshair);
        }
        let pen = match tool {
            InkTool::Highlighter => Tool::Highlighter,
            _ => Tool::Pen,
        };
        let down = r.is_pointer_button_down_on();
        let mine = self.live.as_ref().is_some_and(|l| l.place == here);
        if (down || r.clicked()) && !mine {
            let failed = self.finish_live();
            let start = ctx
                .input(|i| i.pointer.press_origin())
                .or(r.interact_pointer_pos());
            if let Some(start) = start {
                self.live = Some(Live {
                    place: here.clone(),
                    builder: StrokeBuilder::new(pen, self.color, to_canvas(start)),
                });
            }
            if failed.is_some() {
                return failed;
            }
        }
        let live = self.live.as_mut().filter(|l| l.place == here)?;
        // Every position the pointer passed this frame, not just the last: a slow frame must
        // not turn a circle into a polygon.
        ctx.input(|i| {
            for e in &i.events {
                if let egui::Event::PointerMoved(p) = e {
                    live.builder.push(to_canvas(*p));
                }
            }
        });
        if let Some(p) = r.interact_pointer_pos() {
            live.builder.push(to_canvas(p));
        }
        // Both windows show the stroke as it grows.
        ctx.request_repaint();
        if !down {
            return self.finish_live();
        }
        None
    }

    fn laser_input(
        &mut self,
        ctx: &egui::Context,
        here: Place,
        r: &egui::Response,
        to_canvas: impl Fn(egui::Pos2) -> [f32; 2],
        now: f64,
    ) {
        match r.hover_pos() {
            Some(p) => {
                ctx.set_cursor_icon(egui::CursorIcon::None);
                let laser = self.laser.get_or_insert_with(|| Laser {
                    place: here.clone(),
                    trail: Vec::new(),
                });
                if laser.place != here {
                    laser.place = here;
                    laser.trail.clear();
                }
                let at = to_canvas(p);
                if laser.trail.last().is_none_or(|l| l.at != at) {
                    laser.trail.push(LaserPoint { at, time: now });
                }
            }
            // The pointer left this canvas: the dot goes (another window's dot stays).
            None => {
                if self.laser.as_ref().is_some_and(|l| l.place == here) {
                    self.laser = None;
                }
                return;
            }
        }
        let Some(laser) = self.laser.as_mut() else {
            return;
        };
        // Keep the dot (the newest point) and what has not faded yet.
        let newest = laser.trail.len().saturating_sub(1);
        let mut i = 0;
        laser.trail.retain(|p| {
            i += 1;
            i - 1 == newest || now - p.time < LASER_TRAIL_SECS
        });
        if laser.trail.len() > 1 {
            // The trail is still fading: draw again shortly; once only the dot is left, the
            // app is idle until the pointer moves.
            ctx.request_repaint_after(std::time::Duration::from_millis(16));
        }
    }

    /// Ends the stroke being drawn, saving it; returns the error to show if the save failed.
    fn finish_live(&mut self) -> Option<String> {
        let live = self.live.take()?;
        let stroke: Stroke = live.builder.finish();
        self.file
            .add(&live.place.key, stroke)
            .err()
            .map(|e| e.to_string())
    }
}
