//! Inaccuracy: explicit Euler on the circle ẋ = (−y, x) spirals outwards; the radius grows by
//! √(1 + h²) per step.

use egui_plot::{Line, Plot, PlotPoints};
use serde::{Deserialize, Serialize};

use super::SlideWidget;
use crate::ode::{ExplicitRk, FnSystem, Tableau};

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SpiralSpec {
    #[serde(default = "default_h")]
    pub h: f64,
    #[serde(default = "default_turns")]
    pub turns: f64,
}

fn default_h() -> f64 {
    0.1
}
fn default_turns() -> f64 {
    3.0
}

pub struct Spiral {
    pub spec: SpiralSpec,
}

impl Spiral {
    pub fn new(spec: SpiralSpec) -> Self {
        Self { spec }
    }

    /// The Euler path from (1, 0) over `turns` revolutions.
    pub fn euler_path(&self) -> Vec<[f64; 2]> {
        let sys = FnSystem::new(2, |_t, x: &[f64], d: &mut [f64]| {
            d[0] = -x[1];
            d[1] = x[0];
        });
        let h = self.spec.h.clamp(1e-4, 2.0);
        let steps = ((self.spec.turns * std::f64::consts::TAU / h).ceil() as usize).min(100_000);
        let mut rk = ExplicitRk::new(Tableau::euler(), 2);
        let mut x = [1.0, 0.0];
        let mut pts = Vec::with_capacity(steps + 1);
        pts.push(x);
        for i in 0..steps {
            rk.step(&sys, i as f64 * h, &mut x, h);
            pts.push(x);
        }
        pts
    }
}

impl SlideWidget for Spiral {
    fn ui(&mut self, ui: &mut egui::Ui) {
        ui.add(
            egui::Slider::new(&mut self.spec.h, 0.01..=1.0)
                .logarithmic(true)
                .text("h"),
        );
        let circle: PlotPoints = (0..=256)
            .map(|i| {
                let a = i as f64 / 256.0 * std::f64::consts::TAU;
                [a.cos(), a.sin()]
            })
            .collect();
        let euler = PlotPoints::from(self.euler_path());
        Plot::new("spiral").data_aspect(1.0).show(ui, |p| {
            p.line(Line::new("exact", circle));
            p.line(Line::new("Euler", euler));
        });
    }
}
