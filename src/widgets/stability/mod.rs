//! Widget 8: Stability regions: where |R(z)| ≤ 1 in the complex plane, z = hλ, for Euler, midpoint,
//! RK4, any tableau written in the deck, and the implicit methods (implicit Euler, implicit
//! midpoint, radau5, rodas5p). R is the method's stability function (`ode::Method::stability`;
//! a tableau's evaluated from its coefficients, so a tableau in the deck gets its true region).
//! An implicit method's region is unbounded: the plotted box is shaded outside its boundary
//! curve, and the legend says which methods are A-stable (the whole left half-plane) and
//! L-stable (|R(z)| → 0 as z → −∞).

mod draw;

use super::methods::{MethodSet, is_rk4_typo};
use super::style;
use super::{Param, Readout, SlideWidget};
use crate::deck::widgets::{Aspect, StabilitySpec, WidgetSpec};
use crate::ode::stability_box::fitted_bounds;
use crate::ode::stability_region::{self, Bounds, Region};
// the numerics live in `ode`; neptune and the tests name them through this widget too
pub use crate::ode::stability_fn::{C, StabilityFn, stability_abs, stable_h_limit};

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
        let bounds = self.spec.view.unwrap_or_else(|| {
            let drawn: Vec<&Region> = regions.iter().filter_map(|m| m.region.as_ref()).collect();
            fitted_bounds(&drawn)
        });
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

impl SlideWidget for Stability {
    fn ui(&mut self, ui: &mut egui::Ui) {
        draw::stability_ui(self, ui);
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
    use super::draw::{FILL_ALPHA, RES};
    use super::*;
    use crate::deck::widgets::MethodRef;
    use crate::ode::{Method, Tableau};

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
}
