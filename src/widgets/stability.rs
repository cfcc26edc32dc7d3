//! Widget 8: Stability regions: where |R(z)| ≤ 1 in the complex plane, z = hλ, for Euler, midpoint,
//! RK4 and any tableau written in the deck. R is the method's stability function, evaluated
//! from its Butcher tableau, so a tableau in the deck gets its true region.

use egui_plot::{Line, PlotImage, PlotPoint};

use super::methods::{MethodSet, is_rk4_typo};
use super::style;
use super::{Param, Readout, SlideWidget};
use crate::deck::widgets::{StabilitySpec, WidgetSpec};
use crate::ode::Tableau;
use crate::ode::stability::cabs;
use crate::ode::stability_region::{self, Bounds, Region};

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
    cache: Option<(StabilitySpec, egui::TextureHandle, Geometry)>,
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
        }
    }

    /// (name, key, colour, tableau) of every method drawn: the deck's list, then inline tableaux.
    pub fn entries(&self) -> Vec<(String, String, egui::Color32, Tableau)> {
        let mut v: Vec<_> = self
            .methods
            .entries
            .iter()
            // methods without a tableau (implicit built-ins) get no region here yet
            .filter_map(|e| {
                Some((
                    e.method.name.clone(),
                    e.method.key.clone(),
                    e.color,
                    e.method.tableau.clone()?,
                ))
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
            v.push((t.name.clone(), slug(&t.name), color, t.clone()));
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
            .map(|(name, key, color, t)| MethodRegion {
                region: stability_region::region(|z| t.stability(z)),
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

    /// Fill image over `g.bounds` (each method's colour at FILL_ALPHA where it is stable,
    /// composited "over" in premultiplied alpha, so it works on light and dark slides alike).
    pub fn fill(&self, g: &Geometry) -> egui::ColorImage {
        let grid = stability_region::Grid {
            bounds: g.bounds,
            nx: RES,
            ny: RES,
        };
        // premultiplied (r, g, b, a) in 0..=1
        let mut rgba = vec![[0f32; 4]; RES * RES];
        for (_, _, color, tab) in self.entries() {
            let vals = grid.values(|z| cabs(tab.stability(z)));
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
            .map(|(name, key, color, t)| {
                let lim = stable_h_limit(|z| stability_abs(&t, z), C(lr, li), H_LIMIT_MAX);
                (name, key, color, lim)
            })
            .collect()
    }

    fn ensure_cache(&mut self, ctx: &egui::Context) {
        let same = self.cache.as_ref().is_some_and(|(s, ..)| {
            s.methods == self.spec.methods
                && s.tableaux == self.spec.tableaux
                && s.view == self.spec.view
        });
        if !same {
            let g = self.geometry();
            let tex = ctx.load_texture(
                "stability-regions",
                self.fill(&g),
                egui::TextureOptions::LINEAR,
            );
            self.cache = Some((self.spec.clone(), tex, g));
        }
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

/// The union of the bounded regions' boxes (an unbounded region only when all are), with the
/// origin, widened by a tenth on each side and symmetric about the real axis.
fn fitted_bounds(regions: &[MethodRegion]) -> Bounds {
    let all: Vec<&Region> = regions.iter().filter_map(|m| m.region.as_ref()).collect();
    let bounded: Vec<&&Region> = all.iter().filter(|r| !r.unbounded).collect();
    let chosen: Vec<Bounds> = if bounded.is_empty() {
        all.iter().map(|r| r.bounds).collect()
    } else {
        bounded.iter().map(|r| r.bounds).collect()
    };
    let b = chosen
        .into_iter()
        .fold((0.0_f64, 0.0_f64, 0.0_f64, 0.0_f64), |a, b| {
            (a.0.min(b.0), a.1.max(b.1), a.2.min(b.2), a.3.max(b.3))
        });
    stability_region::pad_symmetric(b, 0.1)
}

impl SlideWidget for Stability {
    fn ui(&mut self, ui: &mut egui::Ui) {
        style::projector_text(ui);
        let ink = style::ink(ui);
        self.ensure_cache(ui.ctx());
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
        if let Some((lr, li)) = self.spec.lambda {
            let limits = self.stable_h();
            ui.horizontal(|ui| {
                ui.label(format!(
                    "λ = {lr} {} {}i, stable for",
                    if li < 0.0 { "−" } else { "+" },
                    li.abs()
                ));
                for (name, _, color, lim) in &limits {
                    ui.colored_label(
                        style::text_color(ui, *color),
                        format!("{name}: {}", limit_text(*lim)),
                    );
                }
            });
        }
        let Some((_, tex, g)) = &self.cache else {
            return;
        };
        let (x0, x1, y0, y1) = g.bounds;
        let (px0, px1, py0, py1) = self.plot_bounds(g);
        let markers = self.markers();
        // Keep circles round (aspect 1) and show the whole box: widen whichever axis the
        // plot's shape leaves room for, instead of letting the plot crop the other one.
        let u = style::unit(ui);
        style::y_name_ui(ui, "Im z");
        let avail = ui.available_size();
        let shape = f64::from((avail.x / avail.y.max(1.0)).clamp(0.2, 5.0));
        let (cx, cy) = ((px0 + px1) / 2.0, (py0 + py1) / 2.0);
        let half_w = ((px1 - px0) / 2.0).max((py1 - py0) / 2.0 * shape);
        let half_h = ((py1 - py0) / 2.0).max((px1 - px0) / 2.0 / shape);
        style::plot(ui, "stability", "Re z")
            .data_aspect(1.0)
            .default_x_bounds(cx - half_w, cx + half_w)
            .default_y_bounds(cy - half_h, cy + half_h)
            .show(ui, |p| {
                p.add(PlotImage::new(
                    "regions",
                    tex.id(),
                    PlotPoint::new((x0 + x1) / 2.0, (y0 + y1) / 2.0),
                    egui::vec2((x1 - x0) as f32, (y1 - y0) as f32),
                ));
                let (ax0, ax1) = (cx - half_w, cx + half_w);
                let (ay0, ay1) = (cy - half_h, cy + half_h);
                p.line(
                    Line::new("axis", vec![[ax0, 0.0], [ax1, 0.0]])
                        .color(egui::Color32::GRAY)
                        .width(1.0),
                );
                p.line(
                    Line::new("axis", vec![[0.0, ay0], [0.0, ay1]])
                        .color(egui::Color32::GRAY)
                        .width(1.0),
                );
                for m in &g.regions {
                    for line in m.region.iter().flat_map(|r| &r.boundary) {
                        let pts: Vec<[f64; 2]> = line.iter().map(|z| [z.0, z.1]).collect();
                        p.line(
                            Line::new(m.name.clone(), pts)
                                .color(m.color)
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
            });
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
        };
        let w = Stability::new_in(spec, Some(&deck));
        let entries = w.entries();
        assert_eq!(entries.len(), 2);
        // the typo'd RK4 is a different method: its region on the real axis ends elsewhere
        let typo = &entries[1].3;
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
        };
        let w = Stability::new(spec);
        let g = w.geometry();
        let img = w.fill(&g);
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
}
