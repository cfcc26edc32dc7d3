//! Drawing the stability widget: the regions' fill image (each method's colour, composited),
//! their boundary curves, the z = hλ markers and the legend, in a plot whose box comes from
//! [`crate::ode::stability_box`].

use egui_plot::{Line, PlotImage, PlotPoint};

use super::{C, Stability, limit_text, stability_kinds};
use crate::deck::widgets::Aspect;
use crate::ode::stability_box::{equal_aspect_box, expand_to_shape};
use crate::ode::stability_region::{self, Bounds};
use crate::widgets::style;

/// Opacity of one method's stable region: light enough that the contours and the axes stay
/// readable through it on a dark slide, and overlaps read as deeper.
pub(super) const FILL_ALPHA: f32 = 0.22;

pub(super) const RES: usize = 360;

impl Stability {
    /// Fill image over `bounds` (each method's colour at FILL_ALPHA where it is stable,
    /// composited "over" in premultiplied alpha, so it works on light and dark slides alike;
    /// an unbounded region shades the whole box outside its boundary).
    pub fn fill(&self, bounds: Bounds) -> egui::ColorImage {
        let grid = stability_region::Grid {
            bounds,
            nx: RES,
            ny: RES,
        };
        // premultiplied (r, g, b, a) in 0..=1
        let mut rgba = vec![[0f32; 4]; RES * RES];
        for (_, _, color, f) in self.entries() {
            let vals = grid.values(|z| f.abs(z));
            for (k, v) in vals.iter().enumerate() {
                if *v <= 0.0 {
                    let p = &mut rgba[k];
                    let src = [
                        color.r() as f32 / 255.0 * FILL_ALPHA,
                        color.g() as f32 / 255.0 * FILL_ALPHA,
                        color.b() as f32 / 255.0 * FILL_ALPHA,
                        FILL_ALPHA,
                    ];
                    for c in 0..4 {
                        p[c] = src[c] + p[c] * (1.0 - FILL_ALPHA);
                    }
                }
            }
        }
        let pixels: Vec<egui::Color32> = rgba
            .iter()
            .map(|p| {
                let q = |x: f32| (x * 255.0).round().clamp(0.0, 255.0) as u8;
                egui::Color32::from_rgba_premultiplied(q(p[0]), q(p[1]), q(p[2]), q(p[3]))
            })
            .collect();
        egui::ColorImage {
            size: [RES, RES],
            source_size: egui::vec2(RES as f32, RES as f32),
            pixels,
        }
    }

    /// The fill image over `bounds`, made again when the box changes.
    fn texture_for(&mut self, ctx: &egui::Context, bounds: Bounds) -> egui::TextureHandle {
        match &self.texture {
            Some((b, tex)) if *b == bounds => tex.clone(),
            _ => {
                let tex = ctx.load_texture(
                    "stability-regions",
                    self.fill(bounds),
                    egui::TextureOptions::LINEAR,
                );
                self.texture = Some((bounds, tex.clone()));
                tex
            }
        }
    }
}

/// The widget's `ui`: legend, h slider and stable-h line, then the plot.
pub(super) fn stability_ui(widget: &mut Stability, ui: &mut egui::Ui) {
    style::projector_text(ui);
    let ink = style::ink(ui);
    widget.ensure_cache();
    let entries = widget.entries();
    style::problems_ui(ui, None, &widget.methods.errors);
    ui.horizontal(|ui| {
        ui.label("|R(hλ)| ≤ 1:");
        for (name, _, color, _) in &entries {
            ui.colored_label(
                style::text_color(ui, *color),
                egui::RichText::new(name).strong(),
            );
        }
        if widget.spec.lambda.is_some() {
            style::slider(ui, &mut widget.spec.h, 0.01..=4.0, "h", false);
        }
    });
    let kinds = stability_kinds(&entries);
    if !kinds.is_empty() {
        ui.label(kinds);
    }
    if let Some((lr, li)) = widget.spec.lambda {
        let limits = widget.stable_h();
        ui.horizontal(|ui| {
            ui.label(format!(
                "{}, stable for",
                crate::widgets::neptune::lambda_text(C(lr, li))
            ));
            for (name, _, color, lim) in &limits {
                ui.colored_label(
                    style::text_color(ui, *color),
                    format!("{name}: {}", limit_text(*lim)),
                );
            }
        });
    }
    let Some((_, g)) = &widget.cache else {
        return;
    };
    let wanted = widget.plot_bounds(g);
    let regions: Vec<(String, egui::Color32, Vec<Vec<[f64; 2]>>)> = g
        .regions
        .iter()
        .map(|m| {
            let lines = m
                .region
                .iter()
                .flat_map(|r| &r.boundary)
                .map(|l| l.iter().map(|z| [z.0, z.1]).collect())
                .collect();
            (m.name.clone(), m.color, lines)
        })
        .collect();
    let markers = widget.markers();
    let u = style::unit(ui);
    style::y_name_ui(ui, "Im z");
    let avail = ui.available_size();
    let shape = f64::from((avail.x / avail.y.max(1.0)).clamp(0.2, 5.0));
    let aspect = widget.aspect();
    let ((x0, x1, y0, y1), frac) = match aspect {
        Aspect::Equal => equal_aspect_box(wanted, shape),
        Aspect::Free => (wanted, (1.0, 1.0)),
    };
    let (w, h) = (avail.x * frac.0, avail.y * frac.1);
    let (x0, x1, y0, y1) = match aspect {
        Aspect::Equal => {
            // inside the axes the frame is a little wider than the plot: first guess
            // two text lines under it and three characters beside it
            let line = f64::from(ui.text_style_height(&egui::TextStyle::Body));
            let guess = (f64::from(w) - 3.0 * line) / (f64::from(h) - 2.0 * line).max(1.0);
            expand_to_shape((x0, x1, y0, y1), widget.frame_shape.unwrap_or(guess))
        }
        Aspect::Free => (x0, x1, y0, y1),
    };
    // the image covers the box shown, with a pixel or two to spare at its edges
    let (mx, my) = (0.01 * (x1 - x0), 0.01 * (y1 - y0));
    let (fx0, fx1, fy0, fy1) = (x0 - mx, x1 + mx, y0 - my, y1 + my);
    let tex = widget.texture_for(ui.ctx(), (fx0, fx1, fy0, fy1));
    let shown = ui.horizontal(|ui| {
        ui.add_space(((avail.x - w) / 2.0).max(0.0));
        let plot = style::plot(ui, "stability", "Re z")
            // a unit's ticks on a narrow equal-aspect plane, as on the Im axis
            .custom_x_axes(vec![style::x_axis(ui, "Re z", 40.0)])
            .width(w)
            .height(h)
            .default_x_bounds(x0, x1)
            .default_y_bounds(y0, y1);
        // the box is set exactly, already at the frame's shape with `Equal` (egui_plot's
        // own equal aspect would crop it to its frame when the first guess is off)
        plot.show(ui, |p| {
            p.set_plot_bounds(egui_plot::PlotBounds::from_min_max([x0, y0], [x1, y1]));
            p.add(PlotImage::new(
                "regions",
                tex.id(),
                PlotPoint::new((fx0 + fx1) / 2.0, (fy0 + fy1) / 2.0),
                egui::vec2((fx1 - fx0) as f32, (fy1 - fy0) as f32),
            ));
            p.line(
                Line::new("axis", vec![[fx0, 0.0], [fx1, 0.0]])
                    .color(egui::Color32::GRAY)
                    .width(1.0),
            );
            p.line(
                Line::new("axis", vec![[0.0, fy0], [0.0, fy1]])
                    .color(egui::Color32::GRAY)
                    .width(1.0),
            );
            for (name, color, lines) in &regions {
                for pts in lines {
                    p.line(
                        Line::new(name.clone(), pts.clone())
                            .color(*color)
                            .width(style::PATH_WIDTH * u)
                            .allow_hover(false),
                    );
                }
            }
            if !markers.is_empty() {
                p.points(
                    egui_plot::Points::new("z = hλ", markers.clone())
                        .color(ink)
                        .radius(style::KEY_MARKER_RADIUS * u),
                );
            }
        })
    });
    let frame = shown.inner.transform.frame();
    if frame.height() > 0.0 {
        widget.frame_shape = Some(f64::from(frame.width() / frame.height()));
    }
}
