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

pub mod convergence;
pub mod methods;
pub mod neptune;
pub mod parallel_transport;
pub mod params;
pub mod problems;
pub mod rigid_body;
pub mod simulation_loop;
pub mod slope_field;
pub mod spiral;
pub mod stability;
pub mod step_construction;
pub mod style;
pub mod taylor;
pub mod work_precision;

pub use crate::deck::widgets::{MethodId, WidgetSpec};
pub use params::{Param, ParamSnapshot, ParamValue};

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
}

impl WidgetSpec {
    pub fn instantiate(&self) -> Box<dyn SlideWidget> {
        self.instantiate_in(None)
    }

    /// Like [`instantiate`](Self::instantiate), resolving files the spec names (tableaux)
    /// against `base_dir`, the deck's folder.
    pub fn instantiate_in(&self, base_dir: Option<&std::path::Path>) -> Box<dyn SlideWidget> {
        match self {
            WidgetSpec::SlopeField(s) => Box::new(slope_field::SlopeField::new(s.clone())),
            WidgetSpec::StepConstruction(s) => {
                Box::new(step_construction::StepConstruction::new(s.clone()))
            }
            WidgetSpec::Spiral(s) => Box::new(spiral::Spiral::new(s.clone())),
            WidgetSpec::Neptune(s) => Box::new(neptune::Neptune::new(s.clone())),
            WidgetSpec::Taylor(s) => Box::new(taylor::Taylor::new(s.clone())),
            WidgetSpec::Convergence(s) => Box::new(convergence::Convergence::new(s.clone())),
            WidgetSpec::WorkPrecision(s) => Box::new(work_precision::WorkPrecision::new(s.clone())),
            WidgetSpec::Stability(s) => Box::new(stability::Stability::new_in(s.clone(), base_dir)),
            WidgetSpec::RigidBody(s) => Box::new(rigid_body::RigidBodyView::new(s.clone())),
            WidgetSpec::ParallelTransport(s) => {
                Box::new(parallel_transport::ParallelTransport::new(s.clone()))
            }
            WidgetSpec::SimulationLoop(s) => {
                Box::new(simulation_loop::SimulationLoop::new_in(s.clone(), base_dir))
            }
        }
    }
}
