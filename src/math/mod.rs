//! Typeset maths for slides, off the UI thread and bounded.
//!
//! [`typeset`] turns a formula (Typst or LaTeX syntax) into premultiplied RGBA pixels with Typst
//! as a library and embedded fonts; it knows nothing of egui. [`pool`] runs it in worker
//! processes ([`worker`], talking [`wire`] frames) with a time and memory bound per formula.
//! [`MathCache`] asks the pool for formulas, uploads them as egui textures, caches them by
//! (source, syntax, size, colour), and keeps the last good rendering of each slot while an edit
//! is broken or still being typeset. [`deck`] typesets a deck's formulas for `lectern check`
//! and places their errors at the formula's line and column in the deck file.

mod cache;
pub mod deck;
mod fonts;
pub mod pool;
pub mod typeset;
pub mod wire;
pub mod worker;

pub use cache::{Formula, MathCache, MathView, math_ui, never_wait};
pub use fonts::{add_fallback_fonts, install_egui_fallback_fonts};
pub use pool::{pool, set_worker_program, worker_program};
pub use typeset::{
    INLINE_MARGIN_Y_EM, MathError, MathStyle, MathSyntax, RenderedFormula, latex_to_typst,
    render_formula, render_math,
};
pub use worker::Bounds;
