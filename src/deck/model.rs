//! The deck as the lecturer writes it in RON. Every field beyond the essentials has a default,
//! so a minimal deck is a title and a list of slides.

use serde::{Deserialize, Serialize};

use crate::widgets::WidgetSpec;

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Deck {
    pub title: String,
    /// Width : height of the logical canvas; slides are laid out on it and scaled to the window.
    #[serde(default)]
    pub aspect: Aspect,
    pub slides: Vec<Slide>,
}

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Aspect(pub u32, pub u32);

impl Default for Aspect {
    fn default() -> Self {
        Aspect(16, 9)
    }
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Slide {
    /// Stable identity across edits: keeps the presenter's place and tweaks when slides move.
    #[serde(default)]
    pub id: Option<String>,
    pub title: String,
    #[serde(default)]
    pub body: Vec<Block>,
    /// Speaker notes, shown on the presenter side only.
    #[serde(default)]
    pub notes: String,
    /// Planned time for this slide.
    #[serde(default)]
    pub seconds: Option<f32>,
}

/// One piece of slide content, laid out top to bottom.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum Block {
    /// A paragraph.
    Text(String),
    /// A bulleted list.
    Bullets(Vec<String>),
    /// Display maths (Typst syntax by default; `latex: true` for LaTeX input).
    Math {
        src: String,
        #[serde(default)]
        latex: bool,
    },
    /// A picture from a file inside the project folder; `width` is a fraction of the canvas.
    Image {
        path: String,
        #[serde(default)]
        width: Option<f32>,
    },
    /// A live plot or 3-D widget computed by the project's own integrators.
    Widget(WidgetSpec),
    /// Side-by-side columns, each a list of blocks.
    Columns(Vec<Vec<Block>>),
}
