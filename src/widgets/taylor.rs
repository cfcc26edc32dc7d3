//! Widget 5: Taylor series: the truncations of order 1, 2, 3, … of a function around a point. Order 1
//! is drawn in Euler's colour, 2 in midpoint's and 4 in RK4's: the order a method matches.

use egui_plot::{Line, Points};

use super::style::{self, fmt_num};
use super::{Param, Readout, SlideWidget};
use crate::deck::widgets::{TaylorFn, TaylorSpec};

impl TaylorFn {
    pub fn eval(self, x: f64) -> f64 {
        match self {
            TaylorFn::Sin => x.sin(),
            TaylorFn::Cos => x.cos(),
            TaylorFn::Exp => x.exp(),
            TaylorFn::Log1p => x.ln_1p(),
        }
    }

    /// The k-th derivative at `a` (NaN outside the domain).
    pub fn derivative(self, k: usize, a: f64) -> f64 {
        match self {
            TaylorFn::Sin => (a + k as f64 * std::f64::consts::FRAC_PI_2).sin(),
            TaylorFn::Cos => (a + k as f64 * std::f64::consts::FRAC_PI_2).cos(),
            TaylorFn::Exp => a.exp(),
            TaylorFn::Log1p => {
                if k == 0 {
                    return a.ln_1p();
                }
                // d^k/dx^k ln(1+x) = (−1)^(k−1) (k−1)! / (1+x)^k
                let fact: f64 = (1..k).map(|i| i as f64).product();
                let sign = if k % 2 == 1 { 1.0 } else { -1.0 };
                sign * fact / (1.0 + a).powi(k as i32)
            }
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            TaylorFn::Sin => "sin t",
            TaylorFn::Cos => "cos t",
            TaylorFn::Exp => "eᵗ",
            TaylorFn::Log1p => "ln(1 + t)",
        }
    }
}

/// The Taylor polynomial of order `n` around `a`, at `x`.
pub fn truncation(f: TaylorFn, a: f64, n: usize, x: f64) -> f64 {
    let h = x - a;
    let mut term = 1.0; // h^k / k!
    let mut sum = 0.0;
    for k in 0..=n {
        if k > 0 {
            term *= h / k as f64;
        }
        sum += f.derivative(k, a) * term;
    }
    sum
}

pub fn order_color(n: usize) -> egui::Color32 {
    match n {
        1 => style::EULER,
        2 => style::MIDPOINT,
        4 => style::RK4,
        3 => style::HEUN,
        _ => egui::Color32::from_gray(130),
    }
}

/// Orders drawn with a legend entry and a printed error.
const PRINTED_ORDERS: usize = 6;

/// Where the errors are printed: one unit right of the expansion point (left of it when that
/// leaves the range), near enough that the orders are still told apart there.
pub fn readout_point(spec: &TaylorSpec) -> f64 {
    if spec.a + 1.0 <= spec.range.1 {
        spec.a + 1.0
    } else {
        spec.a - 1.0
    }
}

/// |Tₙ(t) − f(t)|: the error of the order-`n` truncation at `t`.
pub fn truncation_error(spec: &TaylorSpec, n: usize, t: f64) -> f64 {
    (truncation(spec.function, spec.a, n, t) - spec.function.eval(t)).abs()
}

pub struct Taylor {
    pub spec: TaylorSpec,
    initial: TaylorSpec,
}

impl Taylor {
    pub fn new(spec: TaylorSpec) -> Self {
        Self {
            initial: spec.clone(),
            spec,
        }
    }
}

impl SlideWidget for Taylor {
    fn colours(&self) -> Vec<(String, egui::Color32)> {
        (1..=self.spec.order.min(6))
            .map(|n| (format!("order {n}"), order_color(n)))
            .collect()
    }

    fn ui(&mut self, ui: &mut egui::Ui) {
        style::projector_text(ui);
        let ink = style::ink(ui);
        let k = style::keys(ui);
        if k.forward {
            self.spec.order = (self.spec.order + 1).min(12);
        }
        if k.back {
            self.spec.order = self.spec.order.saturating_sub(1).max(1);
        }
        let (lo, hi) = self.spec.range;
        ui.horizontal(|ui| {
            style::slider(ui, &mut self.spec.order, 1..=12, "order  [ ]", false);
            style::slider(ui, &mut self.spec.a, lo..=hi, "around a", false);
        });
        let s = self.spec.clone();
        ui.horizontal_wrapped(|ui| {
            ui.label(egui::RichText::new(format!("{} ≈", s.function.name())).strong());
            for n in 1..=s.order.min(PRINTED_ORDERS) {
                ui.colored_label(
                    style::text_color(ui, order_color(n)),
                    egui::RichText::new(format!("order {n}")).strong(),
                );
            }
        });
        let t_err = readout_point(&s);
        ui.horizontal_wrapped(|ui| {
            ui.label(format!("error at t = {}:", style::fmt_signed(t_err)));
            for n in 1..=s.order.min(PRINTED_ORDERS) {
                ui.colored_label(
                    style::text_color(ui, order_color(n)),
                    fmt_num(truncation_error(&s, n, t_err)),
                );
            }
        });
        let xs: Vec<f64> = (0..=400)
            .map(|i| lo + (hi - lo) * i as f64 / 400.0)
            .collect();
        let f_pts: Vec<[f64; 2]> = xs
            .iter()
            .filter_map(|&x| {
                let y = s.function.eval(x);
                y.is_finite().then_some([x, y])
            })
            .collect();
        let (ymin, ymax) = f_pts
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
                (a.min(p[1]), b.max(p[1]))
            });
        let pad = 0.35 * (ymax - ymin).max(1.0);
        let (y0, y1) = (ymin - pad, ymax + pad);
        let u = style::unit(ui);
        style::plot(ui, "taylor", "t")
            .default_x_bounds(lo, hi)
            .default_y_bounds(y0, y1)
            .show(ui, |p| {
                p.set_plot_bounds(egui_plot::PlotBounds::from_min_max([lo, y0], [hi, y1]));
                for n in 1..=s.order.clamp(1, 12) {
                    // clamp far outside the view so the tessellator never sees 1e30
                    let pts: Vec<[f64; 2]> = xs
                        .iter()
                        .map(|&x| {
                            [
                                x,
                                truncation(s.function, s.a, n, x)
                                    .clamp(y0 - 10.0 * pad, y1 + 10.0 * pad),
                            ]
                        })
                        .filter(|p| p[1].is_finite())
                        .collect();
                    let w = if matches!(n, 1 | 2 | 4) {
                        style::PATH_WIDTH * u
                    } else {
                        style::REFERENCE_WIDTH * u
                    };
                    p.line(
                        Line::new(format!("order {n}"), pts)
                            .color(order_color(n))
                            .width(w),
                    );
                    // where the printed error is read off
                    let at = truncation(s.function, s.a, n, t_err);
                    if n <= PRINTED_ORDERS && at.is_finite() && (y0..=y1).contains(&at) {
                        p.points(
                            Points::new(format!("error {n}"), vec![[t_err, at]])
                                .color(order_color(n))
                                .radius(style::MARKER_RADIUS * u),
                        );
                    }
                }
                p.line(
                    Line::new(s.function.name(), f_pts)
                        .color(ink)
                        .width(1.2 * style::PATH_WIDTH * u),
                );
                let fa = s.function.eval(s.a);
                if fa.is_finite() {
                    p.points(
                        Points::new("a", vec![[s.a, fa]])
                            .color(ink)
                            .radius(style::KEY_MARKER_RADIUS * u),
                    );
                }
            });
    }

    fn params(&mut self) -> Vec<Param<'_>> {
        let (lo, hi) = self.spec.range;
        vec![
            Param::usize("order", "highest order", &mut self.spec.order, 1, 12),
            Param::f64("a", "expansion point", &mut self.spec.a, lo, hi),
        ]
    }

    spec_plumbing!(Taylor);

    /// The printed errors: `t` (where), and `error` per order (`order1` …).
    fn readouts(&mut self) -> Vec<Readout> {
        let t = readout_point(&self.spec);
        let mut v = vec![Readout::new("t", "", t)];
        for n in 1..=self.spec.order.min(PRINTED_ORDERS) {
            v.push(Readout::new(
                "error",
                format!("order{n}"),
                truncation_error(&self.spec, n, t),
            ));
        }
        v
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn truncation_error_shrinks_like_the_next_power() {
        for f in [TaylorFn::Sin, TaylorFn::Exp, TaylorFn::Log1p] {
            for n in 1..5 {
                let e = |h: f64| (truncation(f, 0.3, n, 0.3 + h) - f.eval(0.3 + h)).abs();
                let ratio = e(0.02) / e(0.01);
                let expected = 2f64.powi(n as i32 + 1);
                // the next term can vanish (sin's even terms at special points), so allow ≥
                assert!(ratio > expected * 0.8, "{f:?} order {n}: {ratio}");
            }
        }
    }
}
