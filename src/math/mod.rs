//! Typeset maths for slides, in-process and offline.
//!
//! [`typeset`] turns a formula (Typst or LaTeX syntax) into premultiplied RGBA pixels with Typst
//! as a library and embedded fonts; it knows nothing of egui. [`MathCache`] uploads those pixels
//! as egui textures, caches them by (source, syntax, size, colour), and keeps the last good
//! rendering of each slot while the lecturer's edit is broken.

mod cache;
mod fonts;
pub mod typeset;

pub use cache::{Formula, MathCache, MathView, math_ui};
pub use fonts::{add_fallback_fonts, install_egui_fallback_fonts};
pub use typeset::{MathError, MathSyntax, RenderedFormula, latex_to_typst, render_formula};
