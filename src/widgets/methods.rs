//! The methods the widgets compare, mapped onto the numerics core (`ode::Method`, or a
//! `Tableau` through `ode::solve_tableau`), and drawable fixed-step paths that stop cleanly when
//! a solution blows up (`Outcome::Diverged`).

use std::path::Path as FsPath;
use std::sync::OnceLock;

use super::params::{Param, WriteTo};
use super::style;
use crate::deck::widgets::{MethodRef, ResolvedMethod};
use crate::ode::{Outcome, Scheme, Solution, System, Tableau, solve_fixed, solve_tableau};

/// RK4 as the notes print it: the last stage samples at `x0 + k3/2` (ERRATA 1), from the
/// numerics core (`slides/tableaux/rk4-typo.ron` is the same tableau as a file).
pub fn rk4_typo() -> &'static Tableau {
    static TYPO: OnceLock<Tableau> = OnceLock::new();
    TYPO.get_or_init(Tableau::rk4_typo)
}

/// Whether `t` has the coefficients of the notes' RK4 typo (whatever the file named it).
pub fn is_rk4_typo(t: &Tableau) -> bool {
    let typo = rk4_typo();
    let close = |x: &[f64], y: &[f64]| {
        x.len() == y.len() && x.iter().zip(y).all(|(a, b)| (a - b).abs() <= 1e-12)
    };
    close(&t.b, &typo.b)
        && close(&t.c, &typo.c)
        && t.a.len() == typo.a.len()
        && t.a.iter().zip(&typo.a).all(|(x, y)| close(x, y))
}

/// One method of a widget: runnable, coloured, and switched on or off live.
pub struct MethodEntry {
    pub method: ResolvedMethod,
    pub color: egui::Color32,
    pub shown: bool,
}

/// A widget's `methods:` list made runnable. Tableau files that do not load are left out and
/// named in `errors` (the widget shows them; the rest still draws).
pub struct MethodSet {
    pub entries: Vec<MethodEntry>,
    pub errors: Vec<String>,
}

impl MethodSet {
    pub fn new(refs: &[MethodRef], deck_path: Option<&FsPath>) -> Self {
        let mut entries = Vec::new();
        let mut errors = Vec::new();
        let mut extra = 0;
        for r in refs {
            match r.resolve(deck_path) {
                Ok(method) => {
                    let color = match (method.builtin(), &method.tableau) {
                        (Some(m), _) => style::method_color(m),
                        (None, Some(t)) if is_rk4_typo(t) => style::RK4_TYPO,
                        (None, _) => {
                            extra += 1;
                            style::EXTRA_COLORS[(extra - 1) % style::EXTRA_COLORS.len()]
                        }
                    };
                    entries.push(MethodEntry {
                        method,
                        color,
                        shown: true,
                    });
                }
                Err(e) => errors.push(e),
            }
        }
        Self { entries, errors }
    }

    /// Every method's legend name and colour, in the deck's order.
    pub fn colours(&self) -> Vec<(String, egui::Color32)> {
        self.entries
            .iter()
            .map(|e| (e.method.name.clone(), e.color))
            .collect()
    }

    /// The methods switched on, in the deck's order.
    pub fn shown(&self) -> impl Iterator<Item = &MethodEntry> {
        self.entries.iter().filter(|e| e.shown)
    }

    /// Which are on, for cache keys.
    pub fn switches(&self) -> Vec<bool> {
        self.entries.iter().map(|e| e.shown).collect()
    }

    /// All on again (`R`).
    pub fn reset(&mut self) {
        self.entries.iter_mut().for_each(|e| e.shown = true);
    }

    /// One live switch per method, by its key (`euler`, `rk4-typo`); never written to the deck.
    pub fn params(&mut self) -> Vec<Param<'_>> {
        self.entries
            .iter_mut()
            .map(|e| {
                Param::bool(e.method.key.clone(), e.method.name.clone(), &mut e.shown)
                    .writing_to(WriteTo::Nowhere)
            })
            .collect()
    }

    /// One checkbox per method, labelled in its colour.
    /// (Where controls are the presenter's: the shown ones as a legend.)
    pub fn toggles_ui(&mut self, ui: &mut egui::Ui) {
        for e in &mut self.entries {
            let color = super::style::text_color(ui, e.color);
            super::style::toggle(
                ui,
                &mut e.shown,
                egui::RichText::new(&e.method.name).color(color).strong(),
            );
        }
    }
}

/// A fixed-step path for drawing: `ts[i]` and the state `xs[i]`; `diverged_at` is set when
/// the run reported `Outcome::Diverged` (the state left `|x| ≤ bound` or became non-finite).
/// The path stops at the last state inside the bound, so nothing draws NaN or 1e300.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Path {
    pub ts: Vec<f64>,
    pub xs: Vec<Vec<f64>>,
    pub f_evals: usize,
    pub diverged_at: Option<f64>,
}

impl Path {
    pub fn last(&self) -> &[f64] {
        self.xs.last().map(|v| v.as_slice()).unwrap_or(&[])
    }

    /// The drawable part of a solution from `ode::solve_fixed` / `solve_tableau`.
    pub fn from_solution(sol: &Solution, bound: f64) -> Self {
        let inside = |x: &[f64]| x.iter().all(|v| v.is_finite() && v.abs() <= bound);
        let mut path = Path {
            f_evals: sol.f_evals as usize,
            diverged_at: match sol.outcome {
                Outcome::Finished => None,
                Outcome::Diverged { t } | Outcome::Failed { t, .. } | Outcome::Stiff { t } => {
                    Some(t)
                }
            },
            ..Default::default()
        };
        for (i, &t) in sol.ts.iter().enumerate() {
            let x = sol.state(i);
            if !inside(x) {
                break;
            }
            path.ts.push(t);
            path.xs.push(x.to_vec());
        }
        path
    }
}

/// Integrates from `(t0, x0)` with `steps` steps of size `h` by the numerics core's fixed-step
/// driver, stopping at the bound.
pub fn fixed_path<S: System + ?Sized>(
    sys: &S,
    scheme: Scheme<'_>,
    t0: f64,
    x0: &[f64],
    h: f64,
    steps: usize,
    bound: f64,
) -> Path {
    let t_end = t0 + steps as f64 * h;
    let sol = match scheme {
        Scheme::Method(m) => solve_fixed(sys, m, t0, x0, h, t_end, bound),
        Scheme::Tableau(t) => solve_tableau(sys, t, t0, x0, h, t_end, bound),
    };
    Path::from_solution(&sol, bound)
}

/// Integrates from `(t0, x0)` to exactly `t_end` with steps of `h` (the last one shorter when
/// h does not divide the interval, as the numerics core's drivers do), at most `cap` steps
/// (h grows to fit), stopping at the bound: a readout "at the end" is at the end.
#[allow(clippy::too_many_arguments)]
pub fn path_to<S: System + ?Sized>(
    sys: &S,
    scheme: Scheme<'_>,
    t0: f64,
    x0: &[f64],
    h: f64,
    t_end: f64,
    cap: usize,
    bound: f64,
) -> Path {
    if !(h > 0.0) || !(t_end > t0) {
        return Path {
            ts: vec![t0],
            xs: vec![x0.to_vec()],
            ..Default::default()
        };
    }
    let h = h.max((t_end - t0) / cap.max(1) as f64);
    let sol = match scheme {
        Scheme::Method(m) => solve_fixed(sys, m, t0, x0, h, t_end, bound),
        Scheme::Tableau(t) => solve_tableau(sys, t, t0, x0, h, t_end, bound),
    };
    Path::from_solution(&sol, bound)
}

/// The exact (or reference) path of a system, sampled finely for drawing.
pub fn reference_path<S: System + ?Sized>(sys: &S, t0: f64, x0: &[f64], t_end: f64) -> Path {
    let h = ((t_end - t0) / 2000.0).max(1e-6);
    let n = steps_for(t0, t_end, h, 4000);
    fixed_path(
        sys,
        Scheme::Method(crate::ode::Method::Rk4),
        t0,
        x0,
        h,
        n,
        1e12,
    )
}

/// The true state at `t` of the solution through `(t0, x0)`: the problem's exact solution, or
/// else `reference` (when it ends at `t`) or a fine RK4 solve to `t`.
pub fn truth_at(
    p: &crate::ode::problem::Problem,
    t0: f64,
    x0: &[f64],
    t: f64,
    reference: &Path,
) -> Vec<f64> {
    if let Some(x) = p.exact_from(t0, x0, t) {
        return x;
    }
    let ref_end = *reference.ts.last().unwrap_or(&t0);
    if (t - ref_end).abs() <= 1e-9 * t.abs().max(1.0) && !reference.xs.is_empty() {
        reference.last().to_vec()
    } else {
        reference_path(p, t0, x0, t).last().to_vec()
    }
}

/// At most this many points of a path are drawn: a plot line is a few hundred pixels wide, and
/// tessellating 20 000 points every frame stalls the software renderer.
pub const MAX_DRAWN_POINTS: usize = 2048;

/// Step markers are drawn only up to this many steps; beyond it they merge into the line.
pub const MAX_STEP_MARKERS: usize = 200;

/// Every k-th point of `pts` (k chosen so at most `max` remain), always keeping the first and
/// last, so a long path draws at bounded cost and still ends where the solve ended.
pub fn decimate(pts: &[[f64; 2]], max: usize) -> Vec<[f64; 2]> {
    let max = max.max(2);
    if pts.len() <= max {
        return pts.to_vec();
    }
    let stride = (pts.len() - 1).div_ceil(max - 1);
    let mut out: Vec<[f64; 2]> = pts.iter().step_by(stride).copied().collect();
    if (pts.len() - 1) % stride != 0 {
        out.push(*pts.last().expect("non-empty"));
    }
    out
}

/// Steps needed to reach `t_end` from `t0` with step `h`, capped so a tiny `h` cannot stall
/// a frame.
pub fn steps_for(t0: f64, t_end: f64, h: f64, cap: usize) -> usize {
    if !(h > 0.0) || !(t_end > t0) {
        return 0;
    }
    (((t_end - t0) / h).round() as usize).clamp(1, cap)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ode::{FnSystem, Method};

    #[test]
    fn decimate_bounds_the_count_and_keeps_both_ends() {
        let pts: Vec<[f64; 2]> = (0..20_001).map(|i| [i as f64, 0.0]).collect();
        for max in [2, 3, 2000, 20_001, 30_000] {
            let d = decimate(&pts, max);
            assert!(d.len() <= max.max(2), "{max}: {}", d.len());
            assert_eq!(d[0], pts[0]);
            assert_eq!(d.last(), pts.last());
        }
        assert_eq!(decimate(&pts[..10], 2000), pts[..10].to_vec());
        let d = decimate(&pts[..10_000], 2000);
        // an integer stride keeps at least half the budget
        assert!(d.len() <= 2000 && d.len() > 1000, "{}", d.len());
    }

    #[test]
    fn typo_rk4_is_only_first_order() {
        // Error ratio when halving h on x' = x: 2^order.
        let sys = FnSystem::new(1, |_t, x: &[f64], d: &mut [f64]| d[0] = x[0]);
        let err = |scheme: Scheme<'_>, h: f64| {
            let n = steps_for(0.0, 1.0, h, 1 << 20);
            let p = fixed_path(&sys, scheme, 0.0, &[1.0], h, n, 1e9);
            (p.last()[0] - 1f64.exp()).abs()
        };
        let cases = [
            (Scheme::Method(Method::Euler), 1.0),
            (Scheme::Method(Method::Midpoint), 2.0),
            (Scheme::Method(Method::Rk4), 4.0),
            (Scheme::Tableau(rk4_typo()), 1.0),
        ];
        for (m, want) in cases {
            let order = (err(m, 0.02) / err(m, 0.01)).log2();
            assert!((order - want).abs() < 0.2, "{}: {order}", m.label());
        }
    }

    #[test]
    fn a_path_ends_at_t_end_whatever_h() {
        let sys = FnSystem::new(1, |t, _x: &[f64], d: &mut [f64]| d[0] = t.cos());
        for h in [0.7071, 0.5, 3.0, 10.0] {
            let p = path_to(
                &sys,
                Scheme::Method(Method::Rk4),
                0.0,
                &[0.0],
                h,
                8.0,
                4000,
                1e9,
            );
            assert_eq!(*p.ts.last().unwrap(), 8.0, "h = {h}");
            // every step but the last is h long
            assert!((p.ts[1] - p.ts[0] - h.min(8.0)).abs() < 1e-12, "h = {h}");
        }
    }

    #[test]
    fn divergence_stops_the_path() {
        let sys = FnSystem::new(1, |_t, x: &[f64], d: &mut [f64]| d[0] = -50.0 * x[0]);
        let p = fixed_path(
            &sys,
            Scheme::Method(Method::Euler),
            0.0,
            &[1.0],
            0.1,
            1000,
            1e6,
        );
        assert!(p.diverged_at.is_some());
        assert!(
            p.xs.iter()
                .flatten()
                .all(|v| v.is_finite() && v.abs() <= 1e6)
        );
    }
}
