//! Slide widgets: live plots and views computed by the project's own integrators.
//!
//! Each widget lives in its own file: a widget struct that owns its spec (from
//! [`crate::deck::widgets`]: what the deck file says, and also the live, tweakable state), caches
//! keyed by it, and draws with `ui`. Tweaks made during the talk are plain values inside the spec, listed by
//! [`SlideWidget::params`] under stable ids, so the presenter view can show them, keep them
//! across reloads ([`params::snapshot`] / [`params::restore`]) and write them back to the deck
//! ([`SlideWidget::spec`]).

/// Implements the spec/reset plumbing shared by every widget whose live values are its spec
/// (`self.spec`, deck values in `self.initial`).
macro_rules! spec_plumbing {
    ($variant:ident) => {
        fn reset(&mut self) {
            self.spec = self.initial.clone();
        }
        fn spec(&self) -> $crate::widgets::WidgetSpec {
            $crate::widgets::WidgetSpec::$variant(self.spec.clone())
        }
    };
}

/// The plumbing of every widget that draws an ODE with a `methods:` list: its live values are
/// the spec (deck values in `self.initial`), the method switches (`self.methods`) and the
/// equation (`self.ode`); `R` resets all three.
macro_rules! ode_plumbing {
    ($variant:ident) => {
        ode_plumbing!($variant, |_: &Self| Vec::new());
    };
    // `$extra`: colours the widget draws besides its `methods:` (work-precision's RK5)
    ($variant:ident, $extra:expr) => {
        fn reset(&mut self) {
            self.spec = self.initial.clone();
            self.methods.reset();
            self.ode.reset();
        }
        fn spec(&self) -> $crate::widgets::WidgetSpec {
            $crate::widgets::WidgetSpec::$variant(self.spec.clone())
        }
        fn ode(&mut self) -> Option<&mut $crate::widgets::LiveOde> {
            Some(&mut self.ode)
        }
        fn problems(&self) -> Vec<String> {
            $crate::widgets::style::problem_lines(self.ode.load_error(), &self.methods.errors)
        }
        fn colours(&self) -> Vec<(String, egui::Color32)> {
            let extra: fn(&Self) -> Vec<(String, egui::Color32)> = $extra;
            let mut v = self.methods.colours();
            v.extend(extra(self));
            v
        }
    };
}

pub mod colors;
pub mod controls;
pub mod convergence;
pub mod energy;
pub mod labels;
pub mod live_ode;
pub mod methods;
pub mod neptune;
pub mod parallel_transport;
pub mod params;
pub mod problem_files;
pub mod rigid_body;
pub mod scene;
pub mod simulation_loop;
pub mod slope_field;
pub mod spiral;
pub mod stability;
pub mod step_construction;
pub mod style;
pub mod taylor;
pub mod work_precision;

pub use crate::deck::widgets::{MethodRef, WidgetSpec};
pub use live_ode::{ExprSlot, LiveOde};
pub use params::{Param, ParamSnapshot, ParamValue, WriteTo};
pub use problem_files::{MadeIn, ProblemFiles};

/// A widget's live state; created from its spec, kept while the slide is on screen.
pub trait SlideWidget: Send {
    /// Draws the widget into the space `ui` offers and handles its mouse and key input.
    fn ui(&mut self, ui: &mut egui::Ui);
    /// The tweakable values, by stable id, as mutable views.
    fn params(&mut self) -> Vec<Param<'_>>;
    /// Back to the values the deck file gave.
    fn reset(&mut self);
    /// The current values as a spec, to write back to the deck file.
    fn spec(&self) -> WidgetSpec;
    /// The widget's equation, live (parameters, typed expressions), if it draws an ODE.
    fn ode(&mut self) -> Option<&mut LiveOde> {
        None
    }
    /// Why the widget cannot draw all it should (its equation or a tableau file did not load).
    fn problems(&self) -> Vec<String> {
        Vec::new()
    }
    /// The method colours it draws, by the name its legend gives (`Euler`, `RK4 (notes' typo)`),
    /// for the deck-wide colour-map test: one name, one colour, on every slide.
    fn colours(&self) -> Vec<(String, egui::Color32)> {
        Vec::new()
    }
    /// Every computed point of its paths (not the decimated draw data), for `export --data`.
    fn data(&mut self) -> Option<PlotData> {
        None
    }
    /// What `export --data` writes: the paths of [`SlideWidget::data`] as CSV, or a widget's
    /// own table where its points are not paths in t (convergence: `series,h,error`;
    /// work-precision: `series,sweep,h_or_tol,f_evals,error`).
    fn csv(&mut self) -> Option<String> {
        self.data().map(|d| d.to_csv())
    }
    /// The numbers the widget prints (errors at the end, stable-h limits, λ, fitted slopes,
    /// matrices), unrounded, for `export --data`'s `-readouts.csv` and tests: what the slide
    /// says, checkable.
    fn readouts(&mut self) -> Vec<Readout> {
        Vec::new()
    }
}

/// One number a widget prints: what it is (`error_at_end`, `stable_h`), of which series
/// (a method's key, or empty), and its value.
#[derive(Debug, Clone, PartialEq)]
pub struct Readout {
    pub name: String,
    pub series: String,
    pub value: f64,
}

impl Readout {
    pub fn new(name: impl Into<String>, series: impl Into<String>, value: f64) -> Self {
        Self {
            name: name.into(),
            series: series.into(),
            value,
        }
    }

    /// `readout,series,value`, one row each, numbers in round-trip form (∞ as `inf`).
    pub fn to_csv(readouts: &[Readout]) -> String {
        use std::fmt::Write;
        let mut out = String::from("readout,series,value\n");
        for r in readouts {
            let _ = writeln!(out, "{},{},{:?}", r.name, r.series, r.value);
        }
        out
    }
}

/// The paths a plot widget computed, by series (`euler`, `rk4`, `exact`, a tableau's stem).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PlotData {
    pub vars: Vec<String>,
    pub series: Vec<(String, methods::Path)>,
}

impl PlotData {
    /// Long-format CSV: the header `series,t,<var1>[,<var2>…]`, one row per computed point,
    /// numbers in Rust's shortest round-trip form (read back, they are the same f64).
    pub fn to_csv(&self) -> String {
        use std::fmt::Write;
        let mut out = format!("series,t,{}\n", self.vars.join(","));
        for (name, path) in &self.series {
            for (t, x) in path.ts.iter().zip(&path.xs) {
                let _ = write!(out, "{name},{t:?}");
                for v in x {
                    let _ = write!(out, ",{v:?}");
                }
                out.push('\n');
            }
        }
        out
    }
}

impl WidgetSpec {
    /// The widget, its files (problem and tableau files) resolved relative to the deck at
    /// `deck_path` (or the current folder).
    pub fn instantiate_in(&self, deck_path: Option<&std::path::Path>) -> Box<dyn SlideWidget> {
        self.instantiate(MadeIn::deck(deck_path))
    }

    /// The widget, made where `at` says (while presenting: from the problem files' holder).
    pub fn instantiate(&self, at: MadeIn<'_>) -> Box<dyn SlideWidget> {
        let deck_path = at.deck_path;
        match self {
            WidgetSpec::SlopeField(s) => Box::new(slope_field::SlopeField::new(s.clone(), at)),
            WidgetSpec::StepConstruction(s) => {
                Box::new(step_construction::StepConstruction::new(s.clone(), at))
            }
            WidgetSpec::Spiral(s) => Box::new(spiral::Spiral::new(s.clone(), at)),
            WidgetSpec::Neptune(s) => Box::new(neptune::Neptune::new(s.clone(), at)),
            WidgetSpec::Taylor(s) => Box::new(taylor::Taylor::new(s.clone())),
            WidgetSpec::Convergence(s) => Box::new(convergence::Convergence::new(s.clone(), at)),
            WidgetSpec::WorkPrecision(s) => {
                Box::new(work_precision::WorkPrecision::new(s.clone(), at))
            }
            WidgetSpec::Stability(s) => {
                Box::new(stability::Stability::new_in(s.clone(), deck_path))
            }
            WidgetSpec::RigidBody(s) => Box::new(rigid_body::RigidBodyView::new(s.clone())),
            WidgetSpec::ParallelTransport(s) => {
                Box::new(parallel_transport::ParallelTransport::new(s.clone()))
            }
            WidgetSpec::SimulationLoop(s) => Box::new(simulation_loop::SimulationLoop::new_in(
                s.clone(),
                deck_path.and_then(std::path::Path::parent),
            )),
            WidgetSpec::Scene(s) => Box::new(scene::SceneWidget::new_in(
                s.clone(),
                deck_path.and_then(std::path::Path::parent),
            )),
            WidgetSpec::Energy(s) => Box::new(energy::Energy::new(s.clone(), at)),
        }
    }
}
