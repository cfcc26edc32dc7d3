//! What every block of a slide needs to draw itself (a leaf shared by the block renderers).

use std::path::Path;

use super::theme::Look;

/// What every block needs to draw itself.
pub(crate) struct BlockCtx<'a> {
    pub look: Look,
    /// The slide's key, to name formula slots (each keeps its last good rendering).
    pub slide_key: &'a str,
    /// The deck's folder; image paths are relative to it.
    pub base_dir: Option<&'a Path>,
    /// The deck's file (widgets resolve their problem and tableau files against it) and the
    /// slide's index in it, to place a formula's error at its line.
    pub deck_file: Option<&'a Path>,
    pub slide_index: usize,
    /// The slide's content area (the canvas inside its margins, above the footer): every
    /// block's slot must stay inside it.
    pub content: egui::Rect,
}
