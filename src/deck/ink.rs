//! Ink drawn on slides (`D` pen, `H` highlighter): strokes per slide key, in the slide's canvas
//! units (the canvas is 1920 units wide whatever the window), so a stroke stays on the same
//! spot at any window size, on the audience screen, the presenter's and in the export. Keyed by
//! slide id (else title), so inserting a slide does not move ink to the wrong one. No UI types:
//! the app draws [`Stroke`]s with egui, the file ([`super::ink_file`]) keeps them.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::diag::Diagnostic;

/// How many theme colours the digit keys `1`–`5` pick from.
pub const COLOR_COUNT: u8 = 5;

/// A point is kept when it is this far (canvas units) from the last kept one: about a pixel on
/// a 1080p projector, so finer input adds bytes and triangles but nothing the eye sees.
pub const MIN_STEP_UNITS: f32 = 2.0;

/// Points are stored rounded to this (canvas units), which keeps the file short.
const ROUND_UNITS: f32 = 0.1;

/// The most points one stroke keeps (a very long scribble is cut, not refused).
pub const MAX_POINTS: usize = 20_000;

/// The largest |coordinate| a file may hold; a garbage file is refused, not drawn far away.
const MAX_ABS_UNITS: f32 = 100_000.0;

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Tool {
    /// A thin opaque line.
    Pen,
    /// A wide translucent band.
    Highlighter,
}

impl Tool {
    /// The stroke width in canvas units.
    pub fn width_units(self) -> f32 {
        match self {
            Tool::Pen => 6.0,
            Tool::Highlighter => 30.0,
        }
    }
}

/// One stroke: a polyline in canvas units with its tool, theme colour slot and width.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Stroke {
    pub tool: Tool,
    /// The theme's ink colour slot, 0-based (`1` picks slot 0).
    pub color: u8,
    /// Width in canvas units.
    pub width: f32,
    /// Points in canvas units, thinned ([`StrokeBuilder`]); one point is a dot.
    pub points: Vec<[f32; 2]>,
}

/// All ink of a deck: strokes per slide key, oldest first.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Ink {
    pub slides: BTreeMap<String, Vec<Stroke>>,
}

impl Ink {
    /// The strokes on slide `key`, oldest first (none if it has no ink).
    pub fn strokes(&self, key: &str) -> &[Stroke] {
        self.slides.get(key).map_or(&[], Vec::as_slice)
    }

    pub fn add(&mut self, key: &str, stroke: Stroke) {
        if stroke.points.is_empty() {
            return;
        }
        self.slides.entry(key.to_owned()).or_default().push(stroke);
    }

    /// `Ctrl+Z`: removes and returns the newest stroke on slide `key`.
    pub fn undo(&mut self, key: &str) -> Option<Stroke> {
        let strokes = self.slides.get_mut(key)?;
        let last = strokes.pop();
        if strokes.is_empty() {
            self.slides.remove(key);
        }
        last
    }

    /// `Shift+D`: removes every stroke on slide `key`; returns how many there were.
    pub fn clear(&mut self, key: &str) -> usize {
        self.slides.remove(key).map_or(0, |s| s.len())
    }

    /// Strokes on every slide together.
    pub fn stroke_count(&self) -> usize {
        self.slides.values().map(Vec::len).sum()
    }

    pub fn is_empty(&self) -> bool {
        self.slides.is_empty()
    }

    /// The file's text: a comment line, then pretty RON with one stroke per line.
    pub fn to_ron(&self) -> String {
        let pretty = ron::ser::PrettyConfig::new().depth_limit(3);
        let body = ron::ser::to_string_pretty(self, pretty).unwrap_or_else(|_| "()".into());
        format!("// Ink drawn while presenting (D, H); points in slide canvas units.\n{body}\n")
    }

    /// Parses an ink file's text. Syntax errors name the line and column; values no drawing
    /// could have made (not finite, absurdly far, an unknown colour) name the slide and stroke.
    pub fn parse(text: &str, file: &Path) -> Result<Self, Diagnostic> {
        let ink: Ink = ron::Options::default()
            .from_str(text)
            .map_err(|e| Diagnostic::from_ron(file, &e))?;
        for (key, strokes) in &ink.slides {
            for (i, s) in strokes.iter().enumerate() {
                let bad = |what: &str| {
                    Diagnostic::whole_file(file, format!("slide {key:?}, stroke {}: {what}", i + 1))
                };
                if s.color >= COLOR_COUNT {
                    return Err(bad(&format!(
                        "colour {} (there are {COLOR_COUNT}, 0-based)",
                        s.color
                    )));
                }
                if !(s.width.is_finite() && s.width > 0.0 && s.width <= 500.0) {
                    return Err(bad(&format!("width {} (0 < width <= 500)", s.width)));
                }
                if s.points.is_empty() || s.points.len() > MAX_POINTS {
                    return Err(bad(&format!(
                        "{} points (1 to {MAX_POINTS})",
                        s.points.len()
                    )));
                }
                if let Some(p) = s
                    .points
                    .iter()
                    .find(|p| !p.iter().all(|v| v.is_finite() && v.abs() <= MAX_ABS_UNITS))
                {
                    return Err(bad(&format!(
                        "point ({}, {}) is not on any canvas",
                        p[0], p[1]
                    )));
                }
            }
        }
        Ok(ink)
    }
}

/// `DECK.ink.ron` beside the deck file.
pub fn ink_file_path(deck_path: &Path) -> PathBuf {
    deck_path.with_extension("ink.ron")
}

/// Where a slide's canvas lies on some screen: its top-left corner and its scale. Turns pointer
/// positions into canvas units and back, so ink does not depend on the window's size.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CanvasFrame {
    /// The canvas's top-left corner in screen points.
    pub min_points: [f32; 2],
    /// Screen points per canvas unit.
    pub points_per_unit: f32,
}

impl CanvasFrame {
    pub fn canvas_from_screen(&self, p: [f32; 2]) -> [f32; 2] {
        let s = self.points_per_unit.max(1e-6);
        [
            (p[0] - self.min_points[0]) / s,
            (p[1] - self.min_points[1]) / s,
        ]
    }

    pub fn screen_from_canvas(&self, p: [f32; 2]) -> [f32; 2] {
        [
            self.min_points[0] + p[0] * self.points_per_unit,
            self.min_points[1] + p[1] * self.points_per_unit,
        ]
    }
}

/// A stroke being drawn: takes every pointer position and keeps one point per
/// [`MIN_STEP_UNITS`], plus the last one when the stroke ends.
#[derive(Debug, Clone)]
pub struct StrokeBuilder {
    stroke: Stroke,
    /// The newest input point, kept only if the stroke ends there.
    pending: Option<[f32; 2]>,
}

impl StrokeBuilder {
    pub fn new(tool: Tool, color: u8, start: [f32; 2]) -> Self {
        Self {
            stroke: Stroke {
                tool,
                color: color.min(COLOR_COUNT - 1),
                width: tool.width_units(),
                points: vec![round(start)],
            },
            pending: None,
        }
    }

    /// Adds an input point (canvas units).
    pub fn push(&mut self, p: [f32; 2]) {
        if !(p[0].is_finite() && p[1].is_finite()) || self.stroke.points.len() >= MAX_POINTS {
            return;
        }
        let last = self.stroke.points[self.stroke.points.len() - 1];
        if dist(last, p) >= MIN_STEP_UNITS {
            self.stroke.points.push(round(p));
            self.pending = None;
        } else {
            self.pending = Some(p);
        }
    }

    /// The stroke so far (to draw while the pointer is still down).
    pub fn preview(&self) -> &Stroke {
        &self.stroke
    }

    /// The finished stroke: the end point kept, then straight runs simplified (points that lie
    /// within a tenth of the width of the line through their neighbours are dropped).
    pub fn finish(mut self) -> Stroke {
        if let Some(p) = self.pending.take() {
            let last = self.stroke.points[self.stroke.points.len() - 1];
            if dist(last, p) >= ROUND_UNITS {
                self.stroke.points.push(round(p));
            }
        }
        let tolerance = (self.stroke.width * 0.1).clamp(0.3, 1.0);
        self.stroke.points = simplify(&self.stroke.points, tolerance);
        self.stroke
    }
}

fn round(p: [f32; 2]) -> [f32; 2] {
    p.map(|v| (v / ROUND_UNITS).round() * ROUND_UNITS)
}

fn dist(a: [f32; 2], b: [f32; 2]) -> f32 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// Ramer–Douglas–Peucker: the fewest points whose polyline stays within `tolerance` of `points`.
pub fn simplify(points: &[[f32; 2]], tolerance: f32) -> Vec<[f32; 2]> {
    if points.len() < 3 {
        return points.to_vec();
    }
    let mut keep = vec![false; points.len()];
    keep[0] = true;
    keep[points.len() - 1] = true;
    // An explicit stack, so a long stroke cannot overflow the call stack.
    let mut stack = vec![(0, points.len() - 1)];
    while let Some((a, b)) = stack.pop() {
        let (mut worst, mut at) = (0.0f32, a);
        for i in a + 1..b {
            let d = distance_to_segment(points[i], points[a], points[b]);
            if d > worst {
                (worst, at) = (d, i);
            }
        }
        if worst > tolerance {
            keep[at] = true;
            stack.push((a, at));
            stack.push((at, b));
        }
    }
    points
        .iter()
        .zip(keep)
        .filter_map(|(p, k)| k.then_some(*p))
        .collect()
}

fn distance_to_segment(p: [f32; 2], a: [f32; 2], b: [f32; 2]) -> f32 {
    let ab = [b[0] - a[0], b[1] - a[1]];
    let len2 = ab[0] * ab[0] + ab[1] * ab[1];
    let t = if len2 > 0.0 {
        (((p[0] - a[0]) * ab[0] + (p[1] - a[1]) * ab[1]) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    dist(p, [a[0] + t * ab[0], a[1] + t * ab[1]])
}

#[cfg(test)]
#[path = "ink_tests.rs"]
mod tests;
