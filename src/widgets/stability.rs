//! Widget 8: Stability regions: where |R(z)| ≤ 1 in the complex plane, z = hλ, for Euler, midpoint,
//! RK4, any tableau written in the deck, and the implicit methods (implicit Euler, implicit
//! midpoint, radau5, rodas5p). R is the method's stability function (`ode::Method::stability`;
//! a tableau's evaluated from its coefficients, so a tableau in the deck gets its true region).
//! An implicit method's region is unbounded: the plotted box is shaded outside its boundary
//! curve, and the legend says which methods are A-stable (the whole left half-plane) and
//! L-stable (|R(z)| → 0 as z → −∞).

use egui_plot::{Line, PlotImage, PlotPoint};

use super::methods::{MethodSet, is_rk4_typo};
use super::style;
use super::{Param, Readout, SlideWidget};
use crate::deck::widgets::{Aspect, StabilitySpec, WidgetSpec};
use crate::ode::stability::{Complex, cabs};
use crate::ode::stability_region::{self, Bounds, Region};
use crate::ode::{Method, Tableau};

/// A point of the complex plane, for the widget's geometry (the stability function itself is
/// `ode::Tableau::stability`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct C(pub f64, pub f64);

impl C {
    fn scale(self, s: f64) -> C {
        C(self.0 * s, self.1 * s)
    }
}

/// |R(z)| of a tableau, by the numerics core.
pub fn stability_abs(t: &Tableau, z: C) -> f64 {
    cabs(t.stability((z.0, z.1)))
}

/// Where a region's stability function comes from: a built-in method (explicit or implicit)
/// or a tableau (a file or written in the deck).
#[derive(Debug, Clone, PartialEq)]
pub enum StabilityFn {
    Method(Method),
    Tableau(Tableau),
}

impl StabilityFn {
    /// R(z); a method without one (never listed: see `Stability::entries`) reads as unstable.
    pub fn r(&self, z: Complex) -> Complex {
        match self {
            StabilityFn::Method(m) => m.stability(z).unwrap_or((f64::INFINITY, 0.0)),
            StabilityFn::Tableau(t) => t.stability(z),
        }
    }

    pub fn abs(&self, z: Complex) -> f64 {
        cabs(self.r(z))
    }

    /// A-stable: stable on the whole left half-plane (checked on the imaginary axis and far
    /// out to the left, where an explicit method's polynomial blows up).
    pub fn a_stable(&self) -> bool {
        let stable = |z: Complex| self.abs(z) <= 1.0 + 1e-9;
        (0..=200).all(|k| {
            let y = 1e-2 * 1.1_f64.powi(k);
            stable((0.0, y)) && stable((-y, y)) && stable((-y, 0.0))
        })
    }

    /// L-stable: A-stable and |R(z)| → 0 as z → −∞ (|R(−1e8)| < 1e-6).
    pub fn l_stable(&self) -> bool {
        self.a_stable() && self.abs((-1e8, 0.0)) < 1e-6
    }
}

/// One line of the legend: which of the shown methods are A- and L-stable.
pub fn stability_kinds(entries: &[(String, String, egui::Color32, StabilityFn)]) -> String {
    let names = |keep: &dyn Fn(&StabilityFn) -> bool| -> Vec<&str> {
        entries
            .iter()
            .filter(|e| keep(&e.3))
            .map(|e| e.0.as_str())
            .collect()
    };
    let l = names(&|f| f.l_stable());
    let a_only = names(&|f| f.a_stable() && !f.l_stable());
    let mut parts = Vec::new();
    if !a_only.is_empty() {
        parts.push(format!("A-stable (all of Re z < 0): {}", a_only.join(", ")));
    }
    if !l.is_empty() {
        parts.push(format!(
            "L-stable (A-stable, |R| → 0 as z → −∞): {}",
            l.join(", ")
        ));
    }
    parts.join("; ")
}

/// The largest h with |R(h λ)| ≤ 1 for all smaller h (bisection after a coarse scan);
/// 0 when no positive h is stable, ∞ (capped at `h_max`) when all are.
pub fn stable_h_limit(abs_r: impl Fn(C) -> f64, lambda: C, h_max: f64) -> f64 {
    let stable = |h: f64| abs_r(lambda.scale(h)) <= 1.0 + 1e-12;
    let n = 4000;
    let mut last_ok = 0.0;
    for i in 1..=n {
        let h = h_max * i as f64 / n as f64;
        if !stable(h) {
            let (mut lo, mut hi) = (last_ok, h);
            if lo == 0.0 && !stable(h * 1e-6) {
                return 0.0;
            }
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if stable(mid) { lo = mid } else { hi = mid }
            }
            // below a thousandth of the range it is round-off at the origin, not stability
            return if lo < 1e-3 * h_max { 0.0 } else { lo };
        }
        last_ok = h;
    }
    h_max
}

/// Opacity of one method's stable region: light enough that the contours and the axes stay
/// readable through it on a dark slide, and overlaps read as deeper.
const FILL_ALPHA: f32 = 0.22;

const RES: usize = 360;

/// One method's region: name, key (CSV series), colour, and its geometry (`None` when the
/// method has no stability function or no stable point).
pub struct MethodRegion {
    pub name: String,
    pub key: String,
    pub color: egui::Color32,
    pub region: Option<Region>,
}

/// Everything drawn that does not depend on h: each method's region and the box of the fill
/// image (the regions' extent, padded), fitted to the regions unless the deck gives `view`.
pub struct Geometry {
    pub regions: Vec<MethodRegion>,
    pub bounds: Bounds,
}

pub struct Stability {
    pub spec: StabilitySpec,
    initial: StabilitySpec,
    /// The spec's `methods`, resolved once (tableau files read relative to the deck).
    methods: MethodSet,
    /// The geometry, for the spec it was computed from.
    cache: Option<(StabilitySpec, Geometry)>,
    /// The fill image, for the box it covers.
    texture: Option<(Bounds, egui::TextureHandle)>,
    /// Width over height of the plot's frame (inside its axes) the last time it was drawn:
    /// with `Equal` the box is widened to it, so one unit is as long on both axes.
    frame_shape: Option<f64>,
}

/// A series name from a deck tableau's name: `Ralston (2)` → `ralston-2`.
fn slug(name: &str) -> String {
    let s: String = name
        .chars()
        .map(|c| {
            if c.is_alphanumeric() {
                c.to_ascii_lowercase()
            } else {
                '-'
            }
        })
        .collect();
    s.split('-')
        .filter(|p| !p.is_empty())
        .collect::<Vec<_>>()
        .join("-")
}

impl Stability {
    pub fn new(spec: StabilitySpec) -> Self {
        Self::new_in(spec, None)
    }

    /// Resolves the spec's tableau files relative to the deck at `deck_path`.
    pub fn new_in(spec: StabilitySpec, deck_path: Option<&std::path::Path>) -> Self {
        Self {
            methods: MethodSet::new(&spec.methods, deck_path),
            initial: spec.clone(),
            spec,
            cache: None,
            texture: None,
            frame_shape: None,
        }
    }

    /// (name, key, colour, stability function) of every method drawn: the deck's list (those
    /// with a stability function: not the symplectic splittings), then inline tableaux.
    pub fn entries(&self) -> Vec<(String, String, egui::Color32, StabilityFn)> {
        let mut v: Vec<_> = self
            .methods
            .entries
            .iter()
            .filter_map(|e| {
                let f = match (e.method.builtin(), &e.method.tableau) {
                    (Some(m), _) => {
                        m.stability((0.0, 0.0))?;
                        StabilityFn::Method(m)
                    }
                    (None, Some(t)) => StabilityFn::Tableau(t.clone()),
                    (None, None) => return None,
                };
                Some((e.method.name.clone(), e.method.key.clone(), e.color, f))
            })
            .collect();
        let mut i = v
            .iter()
            .filter(|(_, _, c, _)| style::EXTRA_COLORS.contains(c))
            .count();
        for t in &self.spec.tableaux {
            let color = if is_rk4_typo(t) {
                style::RK4_TYPO
            } else {
                i += 1;
                style::EXTRA_COLORS[(i - 1) % style::EXTRA_COLORS.len()]
            };
            v.push((
                t.name.clone(),
                slug(&t.name),
                color,
                StabilityFn::Tableau(t.clone()),
            ));
        }
        v
    }

    /// Each method's whole region (`ode::stability_region`: a box grown until it holds the
    /// region, the contour traced on it) and the box the plot shows: the deck's `view`, else
    /// the bounded regions' extent with the origin, padded by a tenth.
    pub fn geometry(&self) -> Geometry {
        let regions: Vec<MethodRegion> = self
            .entries()
            .into_iter()
            .map(|(name, key, color, f)| MethodRegion {
                region: stability_region::region(|z| f.r(z)),
                name,
                key,
                color,
            })
            .collect();
        let bounds = self.spec.view.unwrap_or_else(|| fitted_bounds(&regions));
        Geometry { regions, bounds }
    }

    /// The box the plot shows at the current h: the geometry's, widened to hold the z = hλ
    /// markers.
    pub fn plot_bounds(&self, g: &Geometry) -> Bounds {
        let (mut x0, mut x1, mut y0, mut y1) = g.bounds;
        for z in self.markers() {
            let m = 0.05 * (x1 - x0);
            x0 = x0.min(z[0] - m);
            x1 = x1.max(z[0] + m);
            y0 = y0.min(z[1] - m);
            y1 = y1.max(z[1] + m);
        }
        (x0, x1, y0, y1)
    }

    /// z = hλ and its conjugate, when the deck gives λ.
    fn markers(&self) -> Vec<[f64; 2]> {
        self.spec
            .lambda
            .map(|(a, b)| {
                let h = self.spec.h;
                vec![[a * h, b * h], [a * h, -b * h]]
            })
            .unwrap_or_default()
    }

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

    /// Each method's largest stable h for the deck's λ (0: never stable; `H_LIMIT_MAX`: stable
    /// for every h tried).
    pub fn stable_h(&self) -> Vec<(String, String, egui::Color32, f64)> {
        let Some((lr, li)) = self.spec.lambda else {
            return Vec::new();
        };
        self.entries()
            .into_iter()
            .map(|(name, key, color, f)| {
                let lim = stable_h_limit(|z| f.abs((z.0, z.1)), C(lr, li), H_LIMIT_MAX);
                (name, key, color, lim)
            })
            .collect()
    }

    fn ensure_cache(&mut self) {
        let same = self.cache.as_ref().is_some_and(|(s, _)| {
            s.methods == self.spec.methods
                && s.tableaux == self.spec.tableaux
                && s.view == self.spec.view
        });
        if !same {
            self.cache = Some((self.spec.clone(), self.geometry()));
            self.texture = None;
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

    fn aspect(&self) -> Aspect {
        self.spec.aspect.unwrap_or(Aspect::Equal)
    }
}

/// The stable-h search goes up to this h; a method stable there reads "every h".
pub const H_LIMIT_MAX: f64 = 10.0;

/// How a stable-h limit reads: "never" for an empty interval, "every h" when nothing
/// tried was unstable, else "h < 2.83".
pub fn limit_text(lim: f64) -> String {
    if lim <= 0.0 {
        "never".into()
    } else if lim >= H_LIMIT_MAX {
        "every h".into()
    } else {
        format!("h < {}", style::fmt_num(lim))
    }
}

/// The box the regions need: the union of the bounded regions' boxes and of the unbounded
/// ones' closed boundary curves (implicit Euler's circle |z − 1| = 1, radau5's island in
/// Re z > 0), with the origin; when an unbounded region is drawn the box reaches as far left
/// of the origin as right of it, so the shaded left half-plane shows. Widened by a tenth on
/// each side and symmetric about the real axis.
fn fitted_bounds(regions: &[MethodRegion]) -> Bounds {
    let all: Vec<&Region> = regions.iter().filter_map(|m| m.region.as_ref()).collect();
    let boxes = all.iter().filter_map(|r| {
        if r.unbounded {
            stability_region::closed_boundary_bounds(r)
        } else {
            Some(r.bounds)
        }
    });
    let (mut x0, x1, y0, y1) = boxes.fold((0.0_f64, 0.0_f64, 0.0_f64, 0.0_f64), |a, b| {
        (a.0.min(b.0), a.1.max(b.1), a.2.min(b.2), a.3.max(b.3))
    });
    if all.iter().any(|r| r.unbounded) {
        // the shaded left half-plane shows: at least a unit, and half as far as the right
        x0 = x0.min(-0.5 * x1).min(-1.0);
    }
    let y = y0
        .abs()
        .max(y1.abs())
        .max(if x0 < -0.5 { 1.0 } else { 0.0 });
    stability_region::pad_symmetric((x0, x1.max(0.0), -y, y), 0.1)
}

/// `b` widened (about its centre) to the shape `shape` (width over height): never cropped.
pub fn expand_to_shape(b: Bounds, shape: f64) -> Bounds {
    let (x0, x1, y0, y1) = b;
    let (w, h) = ((x1 - x0).max(1e-9), (y1 - y0).max(1e-9));
    let (cx, cy) = ((x0 + x1) / 2.0, (y0 + y1) / 2.0);
    let (w, h) = if w / h < shape {
        (h * shape, h)
    } else {
        (w, w / shape.max(1e-9))
    };
    (cx - w / 2.0, cx + w / 2.0, cy - h / 2.0, cy + h / 2.0)
}

/// `b` (re_min, re_max, im_min, im_max) made to fit a plot `shape` (width over height, in
/// points) with one unit the same length on both axes: the box's short side is padded (about
/// its centre) towards the plot's shape, but never beyond the long side — a wide, low slot
/// gets a square box and blank space beside the plot, not a complex plane three times as
/// wide as the regions. Returns the box and the fraction (width, height) of the slot the plot
/// then takes.
pub fn equal_aspect_box(b: Bounds, shape: f64) -> (Bounds, (f32, f32)) {
    let (x0, x1, y0, y1) = b;
    let (w, h) = ((x1 - x0).max(1e-9), (y1 - y0).max(1e-9));
    let long = w.max(h);
    let (cx, cy) = ((x0 + x1) / 2.0, (y0 + y1) / 2.0);
    let (w2, h2) = if shape > w / h {
        // the slot is wider than the box: widen the box, up to square
        ((h * shape).min(long), h)
    } else {
        (w, (w / shape).min(long))
    };
    let bounds = (cx - w2 / 2.0, cx + w2 / 2.0, cy - h2 / 2.0, cy + h2 / 2.0);
    // the plot's share of the slot at that box's aspect
    let frac = if shape > w2 / h2 {
        ((w2 / h2 / shape) as f32, 1.0)
    } else {
        (1.0, (shape / (w2 / h2)) as f32)
    };
    (bounds, frac)
}

impl SlideWidget for Stability {
    fn ui(&mut self, ui: &mut egui::Ui) {
        style::projector_text(ui);
        let ink = style::ink(ui);
        self.ensure_cache();
        let entries = self.entries();
        style::problems_ui(ui, None, &self.methods.errors);
        ui.horizontal(|ui| {
            ui.label("|R(hλ)| ≤ 1:");
            for (name, _, color, _) in &entries {
                ui.colored_label(
                    style::text_color(ui, *color),
                    egui::RichText::new(name).strong(),
                );
            }
            if self.spec.lambda.is_some() {
                style::slider(ui, &mut self.spec.h, 0.01..=4.0, "h", false);
            }
        });
        let kinds = stability_kinds(&entries);
        if !kinds.is_empty() {
            ui.label(kinds);
        }
        if let Some((lr, li)) = self.spec.lambda {
            let limits = self.stable_h();
            ui.horizontal(|ui| {
                ui.label(format!(
                    "{}, stable for",
                    super::neptune::lambda_text(C(lr, li))
                ));
                for (name, _, color, lim) in &limits {
                    ui.colored_label(
                        style::text_color(ui, *color),
                        format!("{name}: {}", limit_text(*lim)),
                    );
                }
            });
        }
        let Some((_, g)) = &self.cache else {
            return;
        };
        let wanted = self.plot_bounds(g);
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
        let markers = self.markers();
        let u = style::unit(ui);
        style::y_name_ui(ui, "Im z");
        let avail = ui.available_size();
        let shape = f64::from((avail.x / avail.y.max(1.0)).clamp(0.2, 5.0));
        let aspect = self.aspect();
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
                expand_to_shape((x0, x1, y0, y1), self.frame_shape.unwrap_or(guess))
            }
            Aspect::Free => (x0, x1, y0, y1),
        };
        // the image covers the box shown, with a pixel or two to spare at its edges
        let (mx, my) = (0.01 * (x1 - x0), 0.01 * (y1 - y0));
        let (fx0, fx1, fy0, fy1) = (x0 - mx, x1 + mx, y0 - my, y1 + my);
        let tex = self.texture_for(ui.ctx(), (fx0, fx1, fy0, fy1));
        let shown = ui.horizontal(|ui| {
            ui.add_space(((avail.x - w) / 2.0).max(0.0));
            let plot = style::plot(ui, "stability", "Re z")
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
            self.frame_shape = Some(f64::from(frame.width() / frame.height()));
        }
    }

    fn params(&mut self) -> Vec<Param<'_>> {
        vec![Param::f64_log(
            "h",
            "step h (for the λ marker)",
            &mut self.spec.h,
            0.01,
            4.0,
        )]
    }

    fn reset(&mut self) {
        self.spec = self.initial.clone();
    }

    fn spec(&self) -> WidgetSpec {
        WidgetSpec::Stability(self.spec.clone())
    }

    fn problems(&self) -> Vec<String> {
        self.methods.errors.clone()
    }

    /// `series,re,im`: each method's region edge as a closed polyline (the main region under
    /// its key, islands as `key.2`, …), then the z = hλ markers as `z`.
    fn csv(&mut self) -> Option<String> {
        use std::fmt::Write;
        let g = self.geometry();
        let mut out = String::from("series,re,im\n");
        for m in &g.regions {
            for (k, line) in m.region.iter().flat_map(|r| &r.boundary).enumerate() {
                let series = if k == 0 {
                    m.key.clone()
                } else {
                    format!("{}.{}", m.key, k + 1)
                };
                for z in line {
                    let _ = writeln!(out, "{series},{:?},{:?}", z.0, z.1);
                }
            }
        }
        for z in self.markers() {
            let _ = writeln!(out, "z,{:?},{:?}", z[0], z[1]);
        }
        Some(out)
    }

    /// The stable-h limit of each method for the deck's λ (0 = "never"), λ itself, h, and the
    /// box the plot shows at least (`plot_re_min` … `plot_im_max`).
    fn readouts(&mut self) -> Vec<Readout> {
        let g = self.geometry();
        let mut v = Vec::new();
        if let Some((lr, li)) = self.spec.lambda {
            v.push(Readout::new("lambda_re", "", lr));
            v.push(Readout::new("lambda_im", "", li));
            v.push(Readout::new("h", "", self.spec.h));
            for (_, key, _, lim) in self.stable_h() {
                v.push(Readout::new("stable_h", key, lim));
            }
        }
        let (x0, x1, y0, y1) = self.plot_bounds(&g);
        for (name, value) in [
            ("plot_re_min", x0),
            ("plot_re_max", x1),
            ("plot_im_min", y0),
            ("plot_im_max", y1),
        ] {
            v.push(Readout::new(name, "", value));
        }
        v
    }

    fn colours(&self) -> Vec<(String, egui::Color32)> {
        self.entries()
            .into_iter()
            .map(|(n, _, c, _)| (n, c))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::deck::widgets::MethodRef;
    use crate::ode::Method;

    #[test]
    fn known_stability_limits() {
        // real axis: Euler and midpoint 2, RK4 ≈ 2.785; imaginary axis: RK4 2√2, Euler 0
        let lim = |t: Tableau, l: C| stable_h_limit(|z| stability_abs(&t, z), l, 10.0);
        assert!((lim(Tableau::euler(), C(-1.0, 0.0)) - 2.0).abs() < 1e-9);
        assert!((lim(Tableau::midpoint(), C(-1.0, 0.0)) - 2.0).abs() < 1e-9);
        assert!((lim(Tableau::rk4(), C(-1.0, 0.0)) - 2.785_293_563).abs() < 1e-6);
        assert!((lim(Tableau::rk4(), C(0.0, 1.0)) - 8f64.sqrt()).abs() < 1e-9);
        assert_eq!(lim(Tableau::euler(), C(0.0, 1.0)), 0.0);
    }

    #[test]
    fn deck_tableau_files_load_and_a_missing_one_is_an_error() {
        let deck = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("slides/lecture.ron");
        let spec = StabilitySpec {
            methods: vec![
                MethodRef::Builtin(Method::Rk4),
                MethodRef::Tableau("tableaux/rk4-typo.ron".into()),
                MethodRef::Tableau("tableaux/nope.ron".into()),
            ],
            tableaux: vec![],
            view: None,
            lambda: None,
            h: 1.0,
            aspect: None,
        };
        let w = Stability::new_in(spec, Some(&deck));
        let entries = w.entries();
        assert_eq!(entries.len(), 2);
        // the typo'd RK4 is a different method: its region on the real axis ends elsewhere
        let StabilityFn::Tableau(typo) = &entries[1].3 else {
            panic!("a tableau file's region comes from its tableau")
        };
        assert_eq!(typo, &Tableau::rk4_typo());
        assert_eq!(entries[1].2, style::RK4_TYPO, "the typo keeps its colour");
        let lim = |t: &Tableau| stable_h_limit(|z| stability_abs(t, z), C(-1.0, 0.0), 10.0);
        assert!((lim(typo) - lim(&Tableau::rk4())).abs() > 0.05);
        let err = &w.methods.errors[0];
        assert!(err.contains("nope.ron"), "{err}");
    }

    /// Tableau files are confined to the project like every path a deck names.
    #[test]
    fn tableau_files_outside_the_project_are_refused() {
        let deck = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("slides/lecture.ron");
        let spec = StabilitySpec {
            methods: vec![
                MethodRef::Tableau("../../outside.ron".into()),
                MethodRef::Tableau("/etc/passwd".into()),
            ],
            tableaux: vec![],
            view: None,
            lambda: None,
            h: 1.0,
            aspect: None,
        };
        let w = Stability::new_in(spec, Some(&deck));
        let errs = &w.methods.errors;
        assert!(errs[0].contains("outside the project"), "{}", errs[0]);
        assert!(errs[1].contains("absolute"), "{}", errs[1]);
    }

    #[test]
    fn regions_are_translucent_method_colours() {
        let spec = StabilitySpec {
            methods: vec![MethodRef::Builtin(Method::Euler)],
            tableaux: vec![],
            view: None,
            lambda: None,
            h: 1.0,
            aspect: None,
        };
        let w = Stability::new(spec);
        let g = w.geometry();
        let img = w.fill(g.bounds);
        let (x0, x1, y0, y1) = g.bounds;
        // fitted to Euler's disc: −2 … 0 and ±1, padded by a tenth
        assert!(
            x0 < -2.0 && x0 > -2.4 && x1 > 0.0 && x1 < 0.4,
            "{:?}",
            g.bounds
        );
        assert!(
            (y0 + y1).abs() < 1e-12 && y1 > 1.0 && y1 < 1.5,
            "{:?}",
            g.bounds
        );
        let px = |re: f64, im: f64| {
            let i = ((re - x0) / (x1 - x0) * (RES - 1) as f64).round() as usize;
            let j = ((y1 - im) / (y1 - y0) * (RES - 1) as f64).round() as usize;
            img.pixels[j * RES + i]
        };
        // z = −1 is inside Euler's disc: Euler's colour at FILL_ALPHA; z = 0.2 is outside: clear
        let inside = px(-1.0, 0.0);
        let a = (FILL_ALPHA * 255.0).round() as u8;
        assert_eq!(inside.a(), a);
        let e = style::EULER;
        let pm = |c: u8| (c as f32 * FILL_ALPHA).round() as u8;
        assert_eq!(
            (inside.r(), inside.g(), inside.b()),
            (pm(e.r()), pm(e.g()), pm(e.b()))
        );
        assert_eq!(px(0.2, 0.0), egui::Color32::TRANSPARENT);
    }

    #[test]
    fn never_and_every_h_read_as_words() {
        assert_eq!(limit_text(0.0), "never");
        assert_eq!(limit_text(H_LIMIT_MAX), "every h");
        assert_eq!(limit_text(2.8284271), "h < 2.828");
    }

    #[test]
    fn a_and_l_stability_are_read_from_r() {
        let f = |m: Method| StabilityFn::Method(m);
        for m in [Method::Euler, Method::Rk4, Method::Dopri5] {
            assert!(!f(m).a_stable(), "{m}");
        }
        assert!(f(Method::ImplicitMidpoint).a_stable());
        assert!(!f(Method::ImplicitMidpoint).l_stable(), "|R(−∞)| = 1");
        for m in [Method::ImplicitEuler, Method::Radau5, Method::Rodas5p] {
            assert!(f(m).l_stable(), "{m}");
        }
    }

    #[test]
    fn implicit_regions_are_drawn_by_their_boundaries() {
        let spec = StabilitySpec {
            methods: vec![
                MethodRef::Builtin(Method::ImplicitEuler),
                MethodRef::Builtin(Method::ImplicitMidpoint),
                MethodRef::Builtin(Method::Radau5),
            ],
            tableaux: vec![],
            view: None,
            lambda: None,
            h: 1.0,
            aspect: None,
        };
        let w = Stability::new(spec);
        let g = w.geometry();
        let ie = g.regions[0].region.as_ref().unwrap();
        assert!(ie.unbounded);
        for z in &ie.boundary[0] {
            assert!(((z.0 - 1.0).hypot(z.1) - 1.0).abs() < 1e-9, "{z:?}");
        }
        // fitted to the closed curves (not the ±24 search box), reaching left of the origin
        let (x0, x1, y0, y1) = g.bounds;
        assert!(
            x1 > 2.0 && x1 < 20.0 && x0 < -1.0 && x0 > -12.0,
            "{:?}",
            g.bounds
        );
        assert!(y1 < 15.0 && (y0 + y1).abs() < 1e-12, "{:?}", g.bounds);
        // shaded outside implicit Euler's disc, not inside it
        let b = (-3.0, 3.0, -3.0, 3.0);
        let img = w.fill(b);
        let px = |re: f64, im: f64| {
            let i = ((re - b.0) / (b.1 - b.0) * (RES - 1) as f64).round() as usize;
            let j = ((b.3 - im) / (b.3 - b.2) * (RES - 1) as f64).round() as usize;
            img.pixels[j * RES + i]
        };
        assert!(px(-2.5, 2.5).a() > 0 && px(2.5, 2.5).a() > 0);
        // z = 1: inside implicit Euler's disc, right of the axis, and (for radau5) on its island
        assert_eq!(px(1.0, 0.0), egui::Color32::TRANSPARENT);
        let kinds = stability_kinds(&w.entries());
        assert!(
            kinds.contains("A-stable (all of Re z < 0): Implicit midpoint")
                && kinds.contains("Implicit Euler, Radau IIA 5"),
            "{kinds}"
        );
    }

    /// With `Equal` a wide, low slot pads the box's short side only up to its long side: slide
    /// 8's regions at 1280×720 used to be shown on −16 … 12.
    #[test]
    fn equal_aspect_pads_the_short_side_only_up_to_the_long_one() {
        let slide_8 = (-4.4, 0.4, -3.3, 3.3);
        let ((x0, x1, y0, y1), frac) = equal_aspect_box(slide_8, 4.3);
        assert!((x1 - x0 - 6.6).abs() < 1e-9 && (y1 - y0 - 6.6).abs() < 1e-9);
        assert!((x0 + x1 - (-4.0)).abs() < 1e-9, "about the box's centre");
        assert!(
            (frac.0 - 1.0 / 4.3).abs() < 1e-6 && frac.1 == 1.0,
            "{frac:?}"
        );
        // a wide box in a wide slot keeps its long side; a tall slot pads the height
        let ((a, b, _, _), _) = equal_aspect_box((-10.0, 10.0, -1.0, 1.0), 3.0);
        assert_eq!((a, b), (-10.0, 10.0));
        let ((_, _, c, d), frac) = equal_aspect_box((-1.0, 1.0, -1.0, 1.0), 0.5);
        assert_eq!((c, d), (-1.0, 1.0), "a square box stays square");
        assert!((frac.1 - 0.5).abs() < 1e-6);
        // never cropped
        let e = expand_to_shape((0.0, 1.0, 0.0, 4.0), 2.0);
        assert!(
            e.0 <= 0.0 && e.1 >= 1.0 && e.2 <= 0.0 && e.3 >= 4.0,
            "{e:?}"
        );
        assert!(((e.1 - e.0) / (e.3 - e.2) - 2.0).abs() < 1e-12);
    }
}
