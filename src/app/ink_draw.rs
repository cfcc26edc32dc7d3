//! Painting ink on a slide: strokes with egui's own line shapes (one path per stroke), the
//! stroke being drawn, and the laser pointer's dot with its fading trail. Everything arrives in
//! canvas units and is placed with the slide's [`CanvasFrame`], so every window and the export
//! draw the same ink at the same spot.

use egui::{Color32, Painter, Pos2, Shape};

use super::slide_state::SlideResponse;
use crate::deck::Theme;
use crate::deck::ink::{CanvasFrame, Stroke, Tool};

/// How long (seconds) a laser trail point stays visible.
pub const LASER_TRAIL_SECS: f64 = 0.45;

/// The laser dot's radius in canvas units.
const LASER_RADIUS_UNITS: f32 = 9.0;

/// One position of the laser pointer, in canvas units, with the time (egui seconds) it was seen.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LaserPoint {
    pub at: [f32; 2],
    pub time: f64,
}

/// What ink to paint on one slide.
#[derive(Debug, Clone, Copy, Default)]
pub struct InkView<'a> {
    /// The slide's finished strokes, oldest first.
    pub strokes: &'a [Stroke],
    /// The stroke being drawn right now, if it is on this slide.
    pub live: Option<&'a Stroke>,
    /// The laser pointer's trail on this slide, oldest first; the newest is the dot.
    pub laser: &'a [LaserPoint],
    /// Now, in egui seconds (the trail fades with age).
    pub now: f64,
    /// Strokes without anti-aliased edges. On a software rasteriser the 1-pixel fade egui puts
    /// along every edge triples the triangles and costs ~40 % of the ink's frame time (200
    /// strokes: ~125 -> ~75 ms of CPU); the live window turns it on there, exports never do.
    pub plain_edges: bool,
}

impl InkView<'_> {
    pub fn is_empty(&self) -> bool {
        self.strokes.is_empty() && self.live.is_none() && self.laser.is_empty()
    }
}

/// The five ink colours of a theme (`1`–`5`): the accent first, then red, green, blue and the
/// title colour — all readable on the theme's background.
pub fn ink_colors(theme: Theme) -> [Color32; 5] {
    match theme {
        Theme::Dark => [
            Color32::from_rgb(0xe8, 0xa8, 0x4f),
            Color32::from_rgb(0xff, 0x5c, 0x5c),
            Color32::from_rgb(0x5f, 0xd3, 0x8d),
            Color32::from_rgb(0x5a, 0xa9, 0xff),
            Color32::from_rgb(0xf4, 0xf1, 0xea),
        ],
        Theme::Light => [
            Color32::from_rgb(0xb4, 0x5f, 0x06),
            Color32::from_rgb(0xd6, 0x28, 0x28),
            Color32::from_rgb(0x2a, 0x9d, 0x4a),
            Color32::from_rgb(0x1f, 0x6f, 0xd1),
            Color32::from_rgb(0x17, 0x1a, 0x21),
        ],
    }
}

/// The laser's colour on every theme: a saturated red that no slide element uses.
pub const LASER: Color32 = Color32::from_rgb(0xff, 0x1e, 0x3c);

/// Paints `view` over a slide just drawn in `ui` (clipped to the slide's canvas).
pub fn paint_on_slide(ui: &egui::Ui, resp: &SlideResponse, theme: Theme, view: &InkView) {
    if view.is_empty() {
        return;
    }
    let frame = CanvasFrame {
        min_points: resp.canvas.min.into(),
        points_per_unit: resp.scale,
    };
    let painter = ui
        .painter()
        .with_clip_rect(resp.canvas.intersect(ui.clip_rect()));
    paint_ink(&painter, frame, theme, view);
}

/// Paints `view` with `painter` (clip it to the canvas) on a canvas placed at `frame`.
pub fn paint_ink(painter: &Painter, frame: CanvasFrame, theme: Theme, view: &InkView) {
    let colors = ink_colors(theme);
    let mut plain = view.plain_edges.then(|| {
        let options = egui::epaint::TessellationOptions {
            feathering: false,
            ..Default::default()
        };
        egui::epaint::Tessellator::new(painter.pixels_per_point(), options, [1, 1], Vec::new())
    });
    for stroke in view.strokes.iter().chain(view.live) {
        let shape = stroke_shape(stroke, frame, &colors);
        match (&mut plain, shape) {
            (Some(tessellator), Shape::Path(path)) => {
                let mut mesh = egui::epaint::Mesh::default();
                tessellator.tessellate_path(&path, &mut mesh);
                painter.add(Shape::mesh(mesh));
            }
            (_, shape) => {
                painter.add(shape);
            }
        }
    }
    paint_laser(painter, frame, view.laser, view.now);
}

fn stroke_shape(stroke: &Stroke, frame: CanvasFrame, colors: &[Color32; 5]) -> Shape {
    let base = colors[usize::from(stroke.color).min(colors.len() - 1)];
    let color = match stroke.tool {
        Tool::Pen => base,
        // Translucent, so the text under it stays readable.
        Tool::Highlighter => base.gamma_multiply(0.38),
    };
    let width = stroke.width * frame.points_per_unit;
    let points: Vec<Pos2> = stroke
        .points
        .iter()
        .map(|p| Pos2::from(frame.screen_from_canvas(*p)))
        .collect();
    match points.as_slice() {
        [p] => Shape::circle_filled(*p, width * 0.5, color),
        _ => Shape::line(points, egui::Stroke::new(width, color)),
    }
}

fn paint_laser(painter: &Painter, frame: CanvasFrame, trail: &[LaserPoint], now: f64) {
    let Some(dot) = trail.last() else {
        return;
    };
    let s = frame.points_per_unit;
    let fade = |t: f64| (1.0 - ((now - t) / LASER_TRAIL_SECS) as f32).clamp(0.0, 1.0);
    for w in trail.windows(2) {
        let a = fade(w[0].time);
        if a <= 0.0 {
            continue;
        }
        painter.line_segment(
            [
                Pos2::from(frame.screen_from_canvas(w[0].at)),
                Pos2::from(frame.screen_from_canvas(w[1].at)),
            ],
            egui::Stroke::new(LASER_RADIUS_UNITS * s * a, LASER.gamma_multiply(a * 0.7)),
        );
    }
    let c = Pos2::from(frame.screen_from_canvas(dot.at));
    painter.circle_filled(c, LASER_RADIUS_UNITS * 2.0 * s, LASER.gamma_multiply(0.25));
    painter.circle_filled(c, LASER_RADIUS_UNITS * s, LASER);
    painter.circle_filled(c, LASER_RADIUS_UNITS * 0.4 * s, Color32::WHITE);
}
