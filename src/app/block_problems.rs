//! Problems found while drawing a slide's blocks (a formula that does not typeset, a missing
//! image), placed at their `file:line:col` in the deck for the presenter's screen.

use super::block_ctx::BlockCtx;

/// `slides[3].body[1][0]`: the [`crate::ron_tree`] path of the block at `path` on a slide.
pub(crate) fn block_ron_path(slide: usize, path: &[usize]) -> String {
    let mut p = format!("slides[{slide}].body");
    for i in path {
        p.push_str(&format!("[{i}]"));
    }
    p
}

/// A problem with the string `written` at `ron_path` in the deck (its character `col`, 1-based,
/// if given) as `file:line:col: message` when the deck came from a file that still has that
/// string there, else the message alone. Cached per problem (it reads the deck file).
pub(crate) fn located_problem(
    ctx: &egui::Context,
    bctx: &BlockCtx,
    ron_path: &str,
    written: &str,
    col: Option<usize>,
    message: String,
) -> String {
    let Some(file) = bctx.deck_file else {
        return message;
    };
    let id =
        egui::Id::unique(("lectern-located-problem", file, ron_path, written, col)).with(&message);
    if let Some(line) = ctx.data(|d| d.get_temp::<String>(id)) {
        return line;
    }
    let diag = crate::project_files::read_to_string(file)
        .ok()
        .and_then(|text| crate::math::deck::position(&text, ron_path, written, col))
        .map_or_else(
            || crate::diag::Diagnostic::whole_file(file, &message),
            |(line, col)| crate::diag::Diagnostic::new(file, line, col, &message),
        );
    let line = diag.to_string();
    ctx.data_mut(|d| d.insert_temp(id, line.clone()));
    line
}

/// The problem line for a formula's error, at the formula's character in the deck file.
pub(crate) fn formula_problem(
    ctx: &egui::Context,
    bctx: &BlockCtx,
    path: &[usize],
    src: &str,
    latex: bool,
    err: &crate::math::MathError,
) -> String {
    let at = format!("{}.src", block_ron_path(bctx.slide_index, path));
    // Columns only make sense against what the lecturer typed, i.e. for Typst input.
    let col = if latex { None } else { err.col };
    let message = match (bctx.deck_file, col) {
        (Some(_), _) | (None, None) => crate::math::deck::message(err),
        (None, Some(c)) => format!("formula {path:?}, column {c}: {}", err.message),
    };
    located_problem(ctx, bctx, &at, src, col, message)
}
