//! Widget 13: the energy of several methods' paths on one mechanical system, with the work each
//! did. On a stiff system (a mass on a stiff spring and a soft one) it shows why implicit
//! methods exist: explicit Euler and RK4 explode once h·ω passes their stability limit,
//! implicit Euler stays stable but drains the energy (|R(iy)| < 1), implicit midpoint keeps it
//! (|R(iy)| = 1: a quadratic invariant is conserved exactly), and an adaptive implicit method
//! (radau5, rodas5p) takes steps the slow motion allows, not the stiff spring (Baraff & Witkin
//! 1998, "Large steps in cloth simulation").

use super::problem_files::MadeIn;

use egui_plot::{Line, PlotPoint, Points};

use super::live_ode::LiveOde;
use super::methods::{MethodSet, Path, path_to};
use super::neptune::{clip_points, exit_labels_ui, exit_marker};
use super::params::ParamValue;
use super::style;
use super::{Param, PlotData, Readout, SlideWidget};
use crate::deck::widgets::EnergySpec;
use crate::ode::expr::{self, Program};
use crate::ode::problem::Problem;
use crate::ode::{Adaptive, Method, solve_embedded};

const H_RANGE: (f64, f64) = (0.001, 1.0);
const RTOL_RANGE: (f64, f64) = (1e-10, 1e-2);
/// The view shows E/E₀ up to this; a path beyond it has exploded (its marker says where).
const CLAMP: f64 = 2.0;
/// A state beyond this stops a run (`Outcome::Diverged`), long after it left the view.
const BOUND: f64 = 1e6;
/// Fixed-step runs take at most this many steps (h grows to fit).
const MAX_STEPS: usize = 100_000;
/// The reference the end errors are measured against: radau5 at this tolerance.
const REFERENCE_RTOL: f64 = 1e-11;

/// One method's run: its path, the steps it took and the f-evaluations they cost.
#[derive(Debug, Clone)]
pub struct Run {
    pub key: String,
    pub name: String,
    pub color: egui::Color32,
    pub path: Path,
    pub steps: usize,
    pub f_evals: u64,
    /// Chose its own steps (at `rtol`) instead of taking h.
    pub adaptive: bool,
}

type CacheKey = (u64, u64, u64, u64, Vec<bool>, String);

pub struct Energy {
    pub spec: EnergySpec,
    initial: EnergySpec,
    ode: LiveOde,
    methods: MethodSet,
    /// The energy compiled for the live equation, or why it does not compile.
    energy: Option<(u64, String, Result<Program, String>)>,
    cache: Option<(CacheKey, Vec<Run>, Option<Run>)>,
}

/// The energy expression compiled over the equation's variables and parameters.
pub fn compile_energy(src: &str, p: &Problem) -> Result<Program, String> {
    crate::ode::problem::check_expr_size(src).map_err(|e| format!("energy: {e}"))?;
    expr::compile(&[src.to_owned()], &p.vars, &p.params).map_err(|(_, e)| format!("energy: {e}"))
}

/// E(t, x) of a compiled energy.
pub fn energy_at(e: &Program, t: f64, x: &[f64]) -> f64 {
    let mut out = [0.0];
    e.eval(t, x, &mut out);
    out[0]
}

impl Energy {
    pub fn new(spec: EnergySpec, at: MadeIn<'_>) -> Self {
        let deck_path = at.deck_path;
        Self {
            ode: LiveOde::new(&spec.ode, at),
            methods: MethodSet::new(&spec.methods, deck_path),
            initial: spec.clone(),
            spec,
            energy: None,
            cache: None,
        }
    }

    /// The compiled energy of the live equation (recompiled when the equation or the text
    /// changes).
    fn energy(&mut self) -> Result<Program, String> {
        let rev = self.ode.revision();
        let fresh = matches!(&self.energy, Some((r, s, _)) if *r == rev && *s == self.spec.energy);
        if !fresh {
            let compiled = match self.ode.problem() {
                Some(p) => compile_energy(&self.spec.energy, p),
                None => Err("energy: the equation did not load".into()),
            };
            self.energy = Some((rev, self.spec.energy.clone(), compiled));
        }
        match &self.energy {
            Some((_, _, compiled)) => compiled.clone(),
            None => Err("energy: not compiled".into()),
        }
    }

    fn opts(rtol: f64) -> Adaptive {
        Adaptive {
            rtol,
            atol: rtol * 1e-3,
            bound: BOUND,
            ..Default::default()
        }
    }

    /// Every shown method's run and the reference (radau5 at rtol 1e-11), cached on what
    /// they depend on.
    pub fn runs(&mut self) -> (Vec<Run>, Option<Run>) {
        let key: CacheKey = (
            self.ode.revision(),
            self.spec.h.to_bits(),
            self.spec.t_end.to_bits(),
            self.spec.rtol.to_bits(),
            self.methods.switches(),
            self.spec.energy.clone(),
        );
        if let Some((k, runs, reference)) = &self.cache
            && *k == key
        {
            return (runs.clone(), reference.clone());
        }
        let Some(p) = self.ode.problem().cloned() else {
            return (Vec::new(), None);
        };
        let h = self.spec.h.clamp(H_RANGE.0, H_RANGE.1);
        let rtol = self.spec.rtol.clamp(RTOL_RANGE.0, RTOL_RANGE.1);
        let t_end = self.spec.t_end;
        let runs: Vec<Run> = self
            .methods
            .shown()
            .map(|m| {
                let key = m.method.key.clone();
                let name = m.method.name.clone();
                match m.method.adaptive() {
                    Some(method) => adaptive_run(&p, method, t_end, rtol, key, name, m.color),
                    None => {
                        let path = path_to(
                            &p,
                            m.method.scheme(),
                            p.t0,
                            &p.initial,
                            h,
                            t_end,
                            MAX_STEPS,
                            BOUND,
                        );
                        // the points inside the bound, and the step that left it
                        let left = usize::from(path.diverged_at.is_some());
                        Run {
                            key,
                            name,
                            color: m.color,
                            steps: path.ts.len().saturating_sub(1) + left,
                            f_evals: path.f_evals as u64,
                            path,
                            adaptive: false,
                        }
                    }
                }
            })
            .collect();
        let reference = (t_end > p.t0).then(|| {
            adaptive_run(
                &p,
                Method::Radau5,
                t_end,
                REFERENCE_RTOL,
                "reference".into(),
                "reference".into(),
                style::EXACT,
            )
        });
        self.cache = Some((key, runs.clone(), reference.clone()));
        (runs, reference)
    }
}

fn adaptive_run(
    p: &Problem,
    method: Method,
    t_end: f64,
    rtol: f64,
    key: String,
    name: String,
    color: egui::Color32,
) -> Run {
    let sol = solve_embedded(p, method, p.t0, &p.initial, t_end, Energy::opts(rtol));
    let path = Path::from_solution(&sol, BOUND);
    Run {
        key,
        name,
        color,
        steps: sol.steps,
        f_evals: sol.f_evals,
        path,
        adaptive: true,
    }
}

/// E/E₀ along a path (E itself when E₀ = 0).
fn energy_ratio(e: &Program, path: &Path) -> Vec<[f64; 2]> {
    let (Some(&t0), Some(x0)) = (path.ts.first(), path.xs.first()) else {
        return Vec::new();
    };
    let e0 = energy_at(e, t0, x0);
    let scale = if e0 != 0.0 { e0 } else { 1.0 };
    path.ts
        .iter()
        .zip(&path.xs)
        .map(|(t, x)| [*t, energy_at(e, *t, x) / scale])
        .collect()
}

/// How a run reads beside its name: "100 steps, 400 f" and, if it blew up, "|x| > 10⁶ at t = 2.1".
pub fn work_text(r: &Run) -> String {
    let mut s = format!("{} steps, {} f", r.steps, r.f_evals);
    if let Some(t) = r.path.diverged_at {
        s.push_str(&format!(", |x| > 10⁶ at t = {}", style::fmt_signed(t)));
    }
    s
}

impl SlideWidget for Energy {
    fn ui(&mut self, ui: &mut egui::Ui) {
        style::projector_text(ui);
        let ink = style::ink(ui);
        let k = style::keys(ui);
        k.step_h(&mut self.spec.h, H_RANGE);
        ui.horizontal(|ui| {
            style::h_slider(ui, &mut self.spec.h, H_RANGE);
            for p in self.ode.params() {
                if let ParamValue::F64 {
                    value, min, max, ..
                } = p.value
                {
                    // stiffness spans decades: a logarithmic slider when the range allows one
                    style::slider(ui, value, min..=max, &p.label, min > 0.0);
                }
            }
        });
        ui.horizontal(|ui| self.methods.toggles_ui(ui));
        let energy = self.energy();
        let energy_error = energy.as_ref().err().cloned();
        style::problems_ui(
            ui,
            self.ode.load_error().or(energy_error.as_deref()),
            &self.methods.errors,
        );
        let Ok(energy) = energy else { return };
        let (runs, _) = self.runs();
        ui.horizontal_wrapped(|ui| {
            for r in &runs {
                let how = if r.adaptive { " (adaptive)" } else { "" };
                ui.colored_label(
                    style::text_color(ui, r.color),
                    egui::RichText::new(format!("{}{how}: {}", r.name, work_text(r))).strong(),
                );
            }
        });
        let Some(p) = self.ode.problem().cloned() else {
            return;
        };
        let t0 = p.t0;
        let t_end = self.spec.t_end.max(t0 + 1e-9);
        let lines: Vec<_> = runs
            .iter()
            .map(|r| {
                let pts = energy_ratio(&energy, &r.path);
                let (pts, exit) = clip_points(&pts, r.path.diverged_at, CLAMP);
                (
                    r,
                    super::methods::decimate(&pts, super::methods::MAX_DRAWN_POINTS),
                    exit,
                )
            })
            .collect();
        let u = style::unit(ui);
        style::y_name_ui(ui, "E / E₀");
        let mut labels = Vec::new();
        let mut obstacles_at = Vec::new();
        let top = CLAMP * 1.1;
        // room under E = 0, so its tick label stays clear of the t axis's first one
        let bottom = -0.1 * CLAMP;
        let shown = style::plot(ui, "energy", "t")
            .default_x_bounds(t0, t_end)
            .default_y_bounds(bottom, top)
            .show(ui, |pl| {
                pl.set_plot_bounds(egui_plot::PlotBounds::from_min_max(
                    [t0, bottom],
                    [t_end, top],
                ));
                pl.line(
                    Line::new("E₀", vec![[t0, 1.0], [t_end, 1.0]])
                        .color(ink)
                        .width(style::REFERENCE_WIDTH * u),
                );
                for (i, (r, pts, exit)) in lines.iter().enumerate() {
                    pl.line(
                        Line::new(r.name.as_str(), pts.clone())
                            .color(r.color)
                            .width(style::stacked_width(i, lines.len()) * u),
                    );
                    if r.adaptive && pts.len() <= super::methods::MAX_STEP_MARKERS {
                        // the adaptive method's steps, to see how large they are
                        pl.points(
                            Points::new(r.name.as_str(), pts.clone())
                                .color(r.color)
                                .radius(0.8 * style::MARKER_RADIUS * u),
                        );
                    }
                    if let Some(e) = exit {
                        labels.push(exit_marker(pl, *e, format!("{} explodes", r.name), u));
                        obstacles_at.push(PlotPoint::new(e[0], e[1]));
                    }
                }
            });
        // labels keep off every drawn line: E₀ and each method's ratio
        let mut drawn = vec![vec![[t0, 1.0], [t_end, 1.0]]];
        drawn.extend(lines.iter().map(|(_, pts, _)| pts.clone()));
        exit_labels_ui(ui, &shown.transform, &labels, &obstacles_at, &drawn, u);
    }

    fn params(&mut self) -> Vec<Param<'_>> {
        let mut v = vec![
            Param::step_h(&mut self.spec.h, H_RANGE),
            Param::f64_log(
                "rtol",
                "rtol (adaptive)",
                &mut self.spec.rtol,
                RTOL_RANGE.0,
                RTOL_RANGE.1,
            ),
        ];
        v.extend(self.methods.params());
        v.extend(self.ode.params());
        v
    }

    ode_plumbing!(Energy);

    /// Every method's steps (`series,t,<vars…>`), and the radau5 reference as `reference`.
    fn data(&mut self) -> Option<PlotData> {
        let vars = self.ode.problem()?.vars.clone();
        let (runs, reference) = self.runs();
        let series = runs
            .into_iter()
            .chain(reference)
            .map(|r| (r.key, r.path))
            .collect();
        Some(PlotData { vars, series })
    }

    /// h, rtol, and per method its `steps`, `f_evals`, `energy_end` (E/E₀ at t_end),
    /// `error_at_end` (max-norm against the reference) or `diverged_at`.
    fn readouts(&mut self) -> Vec<Readout> {
        let mut v = vec![
            Readout::new("h", "", self.spec.h),
            Readout::new("rtol", "", self.spec.rtol),
        ];
        let energy = self.energy().ok();
        let (runs, reference) = self.runs();
        for r in &runs {
            v.push(Readout::new("steps", &r.key, r.steps as f64));
            v.push(Readout::new("f_evals", &r.key, r.f_evals as f64));
            if let Some(t) = r.path.diverged_at {
                v.push(Readout::new("diverged_at", &r.key, t));
                continue;
            }
            if let Some(e) = &energy
                && let Some(&[_, ratio]) = energy_ratio(e, &r.path).last()
            {
                v.push(Readout::new("energy_end", &r.key, ratio));
            }
            if let Some(reference) = &reference {
                let err = r
                    .path
                    .last()
                    .iter()
                    .zip(reference.path.last())
                    .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
                v.push(Readout::new("error_at_end", &r.key, err));
            }
        }
        v
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path as FsPath;

    fn widget() -> Energy {
        let deck = FsPath::new(concat!(env!("CARGO_MANIFEST_DIR"), "/slides/lecture.ron"));
        let spec = r#"(ode: File("problems/stiff-spring.ron"), energy: "0.5*(v1*v1 + v2*v2) + 0.5*x1*x1 + 0.5*k*(x2 - x1)^2", methods: [Rk4, ImplicitMidpoint, Radau5])"#;
        Energy::new(
            ron::from_str(spec).unwrap(),
            crate::widgets::MadeIn::deck(Some(deck)),
        )
    }

    #[test]
    fn a_bad_energy_says_where() {
        let p = widget().ode.problem().cloned().unwrap();
        let e = compile_energy("0.5*v1*v1 + q", &p).unwrap_err();
        assert!(
            e.starts_with("energy: unknown name") && e.contains("column 13"),
            "{e}"
        );
        assert!(compile_energy("0.5*k*(x2 - x1)^2", &p).is_ok());
    }

    #[test]
    fn steps_and_work_are_counted_and_rk4_is_stable_below_its_limit() {
        let mut w = widget();
        w.spec.h = 0.01;
        let (runs, reference) = w.runs();
        let rk4 = &runs[0];
        assert!(!rk4.adaptive && rk4.path.diverged_at.is_none());
        assert_eq!(rk4.steps, 1000);
        assert_eq!(rk4.f_evals, 4000);
        let radau = &runs[2];
        assert!(radau.adaptive && radau.steps < 200, "{}", radau.steps);
        assert_eq!(radau.steps + 1, radau.path.ts.len());
        assert!(reference.is_some());
        // past the limit the blow-up is counted too: the step that left the bound is a step
        w.spec.h = 0.1;
        let (runs, _) = w.runs();
        let rk4 = &runs[0];
        assert!(rk4.path.diverged_at.is_some());
        assert_eq!(rk4.f_evals as usize, 4 * rk4.steps);
        assert!(
            work_text(rk4).contains("|x| > 10⁶ at t ="),
            "{}",
            work_text(rk4)
        );
    }
}
