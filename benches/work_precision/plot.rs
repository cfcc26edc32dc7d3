//! A small log-log line plot rasteriser on `image`, with text from ab_glyph and egui's
//! bundled Ubuntu font: enough for work-precision diagrams, no plotting crate.

use ab_glyph::{Font, FontRef, PxScale, ScaleFont};
use image::{Rgb, RgbImage};

pub struct Series {
    pub label: String,
    pub color: [u8; 3],
    /// dashed for peers, solid for ours
    pub dashed: bool,
    pub points: Vec<(f64, f64)>,
}

pub const PALETTE: [[u8; 3]; 12] = [
    [31, 119, 180],
    [214, 39, 40],
    [44, 160, 44],
    [148, 103, 189],
    [255, 127, 14],
    [140, 86, 75],
    [227, 119, 194],
    [23, 190, 207],
    [188, 189, 34],
    [80, 80, 80],
    [0, 0, 0],
    [128, 128, 0],
];

struct Canvas<'f> {
    img: RgbImage,
    font: FontRef<'f>,
}

impl Canvas<'_> {
    fn blend(&mut self, x: i64, y: i64, c: [u8; 3], a: f32) {
        if x < 0 || y < 0 || x >= self.img.width() as i64 || y >= self.img.height() as i64 {
            return;
        }
        let p = self.img.get_pixel_mut(x as u32, y as u32);
        for i in 0..3 {
            p.0[i] = (p.0[i] as f32 * (1.0 - a) + c[i] as f32 * a).round() as u8;
        }
    }

    /// A line of width ~w by stamping discs along it; `dash` skips every other 8 px.
    fn line(&mut self, a: (f64, f64), b: (f64, f64), c: [u8; 3], w: f64, dash: bool) {
        let len = ((b.0 - a.0).powi(2) + (b.1 - a.1).powi(2)).sqrt();
        let n = (len * 2.0).ceil().max(1.0) as usize;
        for i in 0..=n {
            let s = i as f64 / n as f64;
            if dash && ((s * len) / 8.0) as usize % 2 == 1 {
                continue;
            }
            let (x, y) = (a.0 + (b.0 - a.0) * s, a.1 + (b.1 - a.1) * s);
            self.disc(x, y, w / 2.0, c);
        }
    }

    fn disc(&mut self, cx: f64, cy: f64, r: f64, c: [u8; 3]) {
        let ri = r.ceil() as i64 + 1;
        for dy in -ri..=ri {
            for dx in -ri..=ri {
                let (x, y) = (cx.round() as i64 + dx, cy.round() as i64 + dy);
                let d = ((x as f64 - cx).powi(2) + (y as f64 - cy).powi(2)).sqrt();
                let a = (r + 0.5 - d).clamp(0.0, 1.0) as f32;
                if a > 0.0 {
                    self.blend(x, y, c, a);
                }
            }
        }
    }

    fn text_width(&self, s: &str, px: f32) -> f32 {
        let f = self.font.as_scaled(PxScale::from(px));
        s.chars().map(|ch| f.h_advance(f.glyph_id(ch))).sum()
    }

    /// Draws text with its baseline-left at (x, y); `rotate` turns it to read bottom-up.
    fn text(&mut self, s: &str, x: f32, y: f32, px: f32, c: [u8; 3], rotate: bool) {
        let scale = PxScale::from(px);
        let scaled = self.font.as_scaled(scale);
        let mut pen = 0.0;
        let mut stamps = Vec::new();
        for ch in s.chars() {
            let id = scaled.glyph_id(ch);
            let glyph = id.with_scale_and_position(scale, ab_glyph::point(pen, 0.0));
            pen += scaled.h_advance(id);
            if let Some(o) = self.font.outline_glyph(glyph) {
                let bb = o.px_bounds();
                o.draw(|gx, gy, cov| {
                    stamps.push((bb.min.x + gx as f32, bb.min.y + gy as f32, cov));
                });
            }
        }
        for (gx, gy, cov) in stamps {
            let (px_, py_) = if rotate {
                (x + gy, y - gx)
            } else {
                (x + gx, y + gy)
            };
            self.blend(px_ as i64, py_ as i64, c, cov.min(1.0));
        }
    }
}

fn decade_label(k: i32) -> String {
    match k {
        0 => "1".into(),
        1 => "10".into(),
        _ => format!("1e{k}"),
    }
}

/// Draws series as a log-log plot and writes a PNG.
pub fn loglog(
    path: &std::path::Path,
    title: &str,
    xlabel: &str,
    ylabel: &str,
    series: &[Series],
) -> image::ImageResult<()> {
    let (w, h) = (1000u32, 680u32);
    let (left, right, top, bottom) = (90.0, 250.0, 50.0, 70.0);
    let font = FontRef::try_from_slice(epaint_default_fonts::UBUNTU_LIGHT).expect("bundled font");
    let mut cv = Canvas {
        img: RgbImage::from_pixel(w, h, Rgb([255, 255, 255])),
        font,
    };
    let pts: Vec<(f64, f64)> = series
        .iter()
        .flat_map(|s| s.points.iter().copied())
        .filter(|(x, y)| *x > 0.0 && *y > 0.0 && x.is_finite() && y.is_finite())
        .collect();
    let lx = |v: f64| v.log10();
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for &(x, y) in &pts {
        x0 = x0.min(lx(x));
        x1 = x1.max(lx(x));
        y0 = y0.min(lx(y));
        y1 = y1.max(lx(y));
    }
    let (x0, x1, y0, y1) = (
        x0.floor(),
        x1.ceil().max(x0.floor() + 1.0),
        y0.floor(),
        y1.ceil().max(y0.floor() + 1.0),
    );
    let pw = w as f64 - left - right;
    let ph = h as f64 - top - bottom;
    let to_px = |x: f64, y: f64| {
        (
            left + (lx(x) - x0) / (x1 - x0) * pw,
            top + (y1 - lx(y)) / (y1 - y0) * ph,
        )
    };
    let grey = [225, 225, 225];
    let dark = [40, 40, 40];
    let xstep = ((x1 - x0) / 12.0).ceil().max(1.0) as i32;
    for k in (x0 as i32..=x1 as i32).step_by(xstep as usize) {
        let (px, _) = to_px(10f64.powi(k), 1.0);
        cv.line((px, top), (px, top + ph), grey, 1.0, false);
        let lbl = decade_label(k);
        let tw = cv.text_width(&lbl, 15.0);
        cv.text(
            &lbl,
            px as f32 - tw / 2.0,
            (top + ph + 20.0) as f32,
            15.0,
            dark,
            false,
        );
    }
    for k in y0 as i32..=y1 as i32 {
        let (_, py) = to_px(1.0, 10f64.powi(k));
        cv.line((left, py), (left + pw, py), grey, 1.0, false);
        let lbl = decade_label(k);
        let tw = cv.text_width(&lbl, 15.0);
        cv.text(
            &lbl,
            (left - 8.0) as f32 - tw,
            py as f32 + 5.0,
            15.0,
            dark,
            false,
        );
    }
    // frame
    for (a, b) in [
        ((left, top), (left + pw, top)),
        ((left + pw, top), (left + pw, top + ph)),
        ((left + pw, top + ph), (left, top + ph)),
        ((left, top + ph), (left, top)),
    ] {
        cv.line(a, b, dark, 1.2, false);
    }
    for s in series {
        let mut prev: Option<(f64, f64)> = None;
        for &(x, y) in &s.points {
            if !(x > 0.0 && y > 0.0 && x.is_finite() && y.is_finite()) {
                prev = None;
                continue;
            }
            let p = to_px(x, y);
            if let Some(q) = prev {
                cv.line(q, p, s.color, 2.2, s.dashed);
            }
            cv.disc(p.0, p.1, 3.2, s.color);
            prev = Some(p);
        }
    }
    let tw = cv.text_width(title, 20.0);
    cv.text(
        title,
        (left + pw / 2.0) as f32 - tw / 2.0,
        32.0,
        20.0,
        dark,
        false,
    );
    let tw = cv.text_width(xlabel, 16.0);
    cv.text(
        xlabel,
        (left + pw / 2.0) as f32 - tw / 2.0,
        (h as f64 - 20.0) as f32,
        16.0,
        dark,
        false,
    );
    let tw = cv.text_width(ylabel, 16.0);
    cv.text(
        ylabel,
        25.0,
        (top + ph / 2.0) as f32 + tw / 2.0,
        16.0,
        dark,
        true,
    );
    // legend
    let lx0 = left + pw + 15.0;
    for (i, s) in series.iter().enumerate() {
        let y = top + 12.0 + i as f64 * 24.0;
        cv.line((lx0, y), (lx0 + 30.0, y), s.color, 2.2, s.dashed);
        cv.disc(lx0 + 15.0, y, 3.2, s.color);
        cv.text(
            &s.label,
            (lx0 + 38.0) as f32,
            y as f32 + 5.0,
            14.0,
            dark,
            false,
        );
    }
    cv.img.save(path)
}
