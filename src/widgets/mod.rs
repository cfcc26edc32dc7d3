//! Slide widgets: live plots and views computed by the project's own integrators.
//! Each widget lives in its own file: a `*Spec` (what the deck file says) and a state that
//! owns the live, tweakable values and draws itself with `ui`.

use serde::{Deserialize, Serialize};

pub mod spiral;

/// Which widget a slide shows, with its parameters from the deck file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum WidgetSpec {
    /// Euler turns the circle x'' = -x into a spiral (the "inaccuracy" picture).
    Spiral(spiral::SpiralSpec),
}

/// A widget's live state; created from its spec, kept while the slide is on screen.
pub trait SlideWidget {
    /// Draws the widget into the space `ui` offers and handles its input.
    fn ui(&mut self, ui: &mut egui::Ui);
}

impl WidgetSpec {
    pub fn instantiate(&self) -> Box<dyn SlideWidget> {
        match self {
            WidgetSpec::Spiral(s) => Box::new(spiral::Spiral::new(s.clone())),
        }
    }
}
