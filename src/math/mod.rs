//! Typeset maths for slides, off the UI thread and bounded.
//!
//! [`typeset`] turns a formula (Typst or LaTeX syntax) into premultiplied RGBA pixels with Typst
//! as a library and embedded fonts; it knows nothing of egui. [`pool`] runs it in worker
//! processes ([`worker`], talking [`wire`] frames) with a time and memory bound per formula.
//! [`MathCache`] asks the pool for formulas, uploads them as egui textures, caches them by
//! (source, syntax, size, colour), and keeps the last good rendering of each slot while an edit
//! is broken or still being typeset. [`deck`] typesets a deck's formulas for `lectern check`
//! and places their errors at the formula's line and column in the deck file.
//!
//! In the web player (`wasm32`) there is no Typst, no process and no thread: its pool
//! ([`prerendered`]) answers from the formulas `lectern export --web` typeset into the bundle,
//! through the same [`MathCache`].

mod cache;
pub mod deck;
mod fonts;
pub mod formula;
#[cfg(not(target_arch = "wasm32"))]
pub mod pool;
#[cfg(target_arch = "wasm32")]
#[path = "prerendered.rs"]
pub mod pool;
#[cfg(not(target_arch = "wasm32"))]
pub mod typeset;
#[cfg(not(target_arch = "wasm32"))]
pub mod wire;
#[cfg(not(target_arch = "wasm32"))]
pub mod worker;

pub use cache::{Formula, MathCache, MathView, math_ui, never_wait};
#[cfg(target_arch = "wasm32")]
pub use fonts::set_bundled_fonts;
#[cfg(not(target_arch = "wasm32"))]
pub use fonts::web_fonts;
pub use fonts::{add_fallback_fonts, fallback_fonts, install_egui_fallback_fonts, slide_fonts};
pub use formula::{
    INLINE_MARGIN_Y_EM, MathError, MathStyle, MathSyntax, RenderedFormula, Request,
    estimated_height_em,
};
#[cfg(not(target_arch = "wasm32"))]
pub use pool::{pool, set_worker_program, worker_program};
#[cfg(not(target_arch = "wasm32"))]
pub use typeset::{latex_to_typst, render_formula, render_math};
#[cfg(not(target_arch = "wasm32"))]
pub use worker::Bounds;
