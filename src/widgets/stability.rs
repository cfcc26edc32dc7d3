//! Widget 8: Stability regions: where |R(z)| ≤ 1 in the complex plane, z = hλ, for Euler, midpoint,
//! RK4 and any tableau written in the deck. R is the method's stability function, evaluated
//! from its Butcher tableau, so a tableau in the deck gets its true region.

use egui_plot::{Line, PlotImage, PlotPoint};

use super::methods::{MethodSet, is_rk4_typo};
use super::style;
use super::{Param, SlideWidget};
use crate::deck::widgets::{StabilitySpec, WidgetSpec};
use crate::ode::Tableau;
use crate::ode::stability::cabs;

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

/// Each method's |R| = 1 contour as segments, with its name and colour.
pub type Contours = Vec<(String, egui::Color32, Vec<[[f64; 2]; 2]>)>;

pub struct Stability {
    pub spec: StabilitySpec,
    initial: StabilitySpec,
    /// The spec's `methods`, resolved once (tableau files read relative to the deck).
    methods: MethodSet,
    cache: Option<(StabilitySpec, egui::TextureHandle, Contours)>,
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

    /// (name, colour, tableau) of every method drawn: the deck's list, then inline tableaux.
    pub fn entries(&self) -> Vec<(String, egui::Color32, Tableau)> {
        let mut v: Vec<_> = self
            .methods
            .entries
            .iter()
            // methods without a tableau (implicit built-ins) get no region here yet
            .filter_map(|e| Some((e.method.name.clone(), e.color, e.method.tableau.clone()?)))
            .collect();
        let mut i = v
            .iter()
            .filter(|(_, c, _)| style::EXTRA_COLORS.contains(c))
            .count();
        for t in &self.spec.tableaux {
            let color = if is_rk4_typo(t) {
                style::RK4_TYPO
            } else {
                i += 1;
                style::EXTRA_COLORS[(i - 1) % style::EXTRA_COLORS.len()]
            };
            v.push((t.name.clone(), color, t.clone()));
        }
        v
    }

    /// Fill image (each method's colour at FILL_ALPHA where it is stable, composited "over" in
    /// premultiplied alpha, so it works on light and dark slides alike) and the |R| = 1 contours
    /// by marching squares, both on a RES × RES grid over the view.
    pub fn regions(&self) -> (egui::ColorImage, Contours) {
        let (x0, x1, y0, y1) = self.spec.view;
        let at = |i: usize, j: usize| {
            C(
                x0 + (x1 - x0) * i as f64 / (RES - 1) as f64,
                y1 - (y1 - y0) * j as f64 / (RES - 1) as f64,
            )
        };
        // premultiplied (r, g, b, a) in 0..=1
        let mut rgba = vec![[0f32; 4]; RES * RES];
        let mut contours = Vec::new();
        for (name, color, tab) in self.entries() {
            let vals: Vec<f64> = (0..RES * RES)
                .map(|k| stability_abs(&tab, at(k % RES, k / RES)) - 1.0)
                .collect();
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
            contours.push((name, color, marching_squares(&vals, at)));
        }
        let pixels: Vec<egui::Color32> = rgba
            .iter()
            .map(|p| {
                let q = |x: f32| (x * 255.0).round().clamp(0.0, 255.0) as u8;
                egui::Color32::from_rgba_premultiplied(q(p[0]), q(p[1]), q(p[2]), q(p[3]))
            })
            .collect();
        let image = egui::ColorImage {
            size: [RES, RES],
            source_size: egui::vec2(RES as f32, RES as f32),
            pixels,
        };
        (image, contours)
    }

    fn build(&self, ctx: &egui::Context) -> (egui::TextureHandle, Contours) {
        let (image, contours) = self.regions();
        (
            ctx.load_texture("stability-regions", image, egui::TextureOptions::LINEAR),
            contours,
        )
    }
}

/// Segments of the zero level set of `vals` (RES × RES, row-major), in plot coordinates.
fn marching_squares(vals: &[f64], at: impl Fn(usize, usize) -> C) -> Vec<[[f64; 2]; 2]> {
    let mut segs = Vec::new();
    let lerp = |a: C, b: C, va: f64, vb: f64| {
        let t = va / (va - vb);
        [a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1)]
    };
    for j in 0..RES - 1 {
        for i in 0..RES - 1 {
            let corners = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)];
            let v: Vec<f64> = corners.iter().map(|&(a, b)| vals[b * RES + a]).collect();
            let mut pts = Vec::with_capacity(4);
            for e in 0..4 {
                let (a, b) = (e, (e + 1) % 4);
                if (v[a] <= 0.0) != (v[b] <= 0.0) {
                    pts.push(lerp(
                        at(corners[a].0, corners[a].1),
                        at(corners[b].0, corners[b].1),
                        v[a],
                        v[b],
                    ));
                }
            }
            if pts.len() >= 2 {
                segs.push([pts[0], pts[1]]);
            }
            if pts.len() == 4 {
                segs.push([pts[2], pts[3]]);
            }
        }
    }
    segs
}

impl SlideWidget for Stability {
    fn ui(&mut self, ui: &mut egui::Ui) {
        style::projector_text(ui);
        let ink = style::ink(ui);
        if !self.cache.as_ref().is_some_and(|(s, ..)| {
            s.methods == self.spec.methods
                && s.tableaux == self.spec.tableaux
                && s.view == self.spec.view
        }) {
            let (tex, contours) = self.build(ui.ctx());
            self.cache = Some((self.spec.clone(), tex, contours));
        }
        let entries = self.entries();
        style::problems_ui(ui, None, &self.methods.errors);
        ui.horizontal(|ui| {
            ui.label("|R(hλ)| ≤ 1:");
            for (name, color, _) in &entries {
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
            ui.horizontal(|ui| {
                ui.label(format!(
                    "λ = {lr} {} {}i, stable for h <",
                    if li < 0.0 { "−" } else { "+" },
                    li.abs()
                ));
                for (name, color, t) in &entries {
                    let lim = stable_h_limit(|z| stability_abs(t, z), C(lr, li), 10.0);
                    ui.colored_label(
                        style::text_color(ui, *color),
                        format!("{name}: {}", style::fmt_num(lim)),
                    );
                }
            });
        }
        let Some((_, tex, contours)) = &self.cache else {
            return;
        };
        let (x0, x1, y0, y1) = self.spec.view;
        let z = self
            .spec
            .lambda
            .map(|(a, b)| [a * self.spec.h, b * self.spec.h]);
        // Keep circles round (aspect 1) and show the whole view: widen whichever axis the
        // plot's shape leaves room for, instead of letting the plot crop the other one.
        let u = style::unit(ui);
        style::y_name_ui(ui, "Im z");
        let avail = ui.available_size();
        let shape = f64::from((avail.x / avail.y.max(1.0)).clamp(0.2, 5.0));
        let (cx, cy) = ((x0 + x1) / 2.0, (y0 + y1) / 2.0);
        let half_w = ((x1 - x0) / 2.0).max((y1 - y0) / 2.0 * shape);
        let half_h = ((y1 - y0) / 2.0).max((x1 - x0) / 2.0 / shape);
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
                p.line(
                    Line::new("axis", vec![[x0, 0.0], [x1, 0.0]])
                        .color(egui::Color32::GRAY)
                        .width(1.0),
                );
                p.line(
                    Line::new("axis", vec![[0.0, y0], [0.0, y1]])
                        .color(egui::Color32::GRAY)
                        .width(1.0),
                );
                for (name, color, segs) in contours {
                    for s in segs {
                        p.line(
                            Line::new(name.clone(), s.to_vec())
                                .color(*color)
                                .width(style::PATH_WIDTH * u)
                                .allow_hover(false),
                        );
                    }
                }
                if let Some(z) = z {
                    p.points(
                        egui_plot::Points::new("z = hλ", vec![z, [z[0], -z[1]]])
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

    fn colours(&self) -> Vec<(String, egui::Color32)> {
        self.entries().into_iter().map(|(n, c, _)| (n, c)).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::deck::widgets::MethodRef;
    use crate::deck::widgets::stability::default_view;
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
            view: default_view(),
            lambda: None,
            h: 1.0,
        };
        let w = Stability::new_in(spec, Some(&deck));
        let entries = w.entries();
        assert_eq!(entries.len(), 2);
        // the typo'd RK4 is a different method: its region on the real axis ends elsewhere
        let typo = &entries[1].2;
        assert_eq!(typo, &Tableau::rk4_typo());
        assert_eq!(entries[1].1, style::RK4_TYPO, "the typo keeps its colour");
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
            view: default_view(),
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
            view: default_view(),
            lambda: None,
            h: 1.0,
        };
        let (img, _) = Stability::new(spec).regions();
        let px = |re: f64, im: f64| {
            let (x0, x1, y0, y1) = default_view();
            let i = ((re - x0) / (x1 - x0) * (RES - 1) as f64).round() as usize;
            let j = ((y1 - im) / (y1 - y0) * (RES - 1) as f64).round() as usize;
            img.pixels[j * RES + i]
        };
        // z = −1 is inside Euler's disc: Euler's colour at FILL_ALPHA; z = 1 is outside: clear
        let inside = px(-1.0, 0.0);
        let a = (FILL_ALPHA * 255.0).round() as u8;
        assert_eq!(inside.a(), a);
        let e = style::EULER;
        let pm = |c: u8| (c as f32 * FILL_ALPHA).round() as u8;
        assert_eq!(
            (inside.r(), inside.g(), inside.b()),
            (pm(e.r()), pm(e.g()), pm(e.b()))
        );
        assert_eq!(px(1.0, 0.0), egui::Color32::TRANSPARENT);
    }
}
