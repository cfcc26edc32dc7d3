//! Display maths on a slide: formulas fetched from the shared typesetting cache (never waiting
//! in the live window), prefetched for the next slides, and drawn — or a placeholder, or the
//! source in a quiet frame when it never typeset.

use egui::{Rect, Sense, Stroke, vec2};

use super::block_ctx::BlockCtx;
use super::block_problems::formula_problem;
use super::slide_state::SlideState;
use super::theme::{self, Look, size};

/// A typeset formula, as laid out on the slide.
pub(crate) struct Typeset {
    texture: egui::TextureId,
    /// Its size in physical pixels at the slide's current em (a stale picture is scaled).
    size_px: egui::Vec2,
}

impl Typeset {
    /// Its size in points, shrunk to `width` if wider (never overflow the slide).
    pub(crate) fn size(&self, ui: &egui::Ui, width: f32) -> egui::Vec2 {
        let size = self.size_px / ui.ctx().pixels_per_point();
        if size.x > width && width > 1.0 {
            size * (width / size.x)
        } else {
            size
        }
    }
}

/// What a Math block shows this frame.
pub(crate) struct FormulaView {
    /// The current formula, or the last good one of this slot (broken or pending edit).
    pub typeset: Option<Typeset>,
    /// The current source is still being typeset (live window only).
    pub pending: bool,
    pub error: Option<crate::math::MathError>,
}

/// Formulas are typeset at this many physical pixels per em.
fn em_px(ctx: &egui::Context, look: &Look) -> f32 {
    look.scaled(size::MATH) * ctx.pixels_per_point()
}

/// The formula for `src` from the shared cache. In the live window this never waits: a formula
/// still being typeset shows the slot's last good picture, or nothing yet (`pending`).
pub(crate) fn formula(
    ui: &egui::Ui,
    bctx: &BlockCtx,
    path: &[usize],
    src: &str,
    latex: bool,
) -> FormulaView {
    use crate::math::MathCache;
    let ctx = ui.ctx();
    let em = em_px(ctx, &bctx.look);
    let slot = format!("{}/{path:?}", bctx.slide_key);
    let cache = MathCache::shared(ctx);
    let Ok(mut cache) = cache.lock() else {
        return FormulaView {
            typeset: None,
            pending: true,
            error: None,
        };
    };
    let view = cache.get_slot(
        ctx,
        &slot,
        src,
        crate::math::deck::syntax_of(latex),
        em,
        bctx.look.palette.title,
    );
    FormulaView {
        typeset: view.formula.map(|f| Typeset {
            texture: f.texture.id(),
            size_px: f.size_at(em),
        }),
        pending: view.pending,
        error: view.error,
    }
}

/// Asks for the formulas of `slides` at the size `look` draws them, so that paging there
/// finds them typeset. Only in the live window: headless paths wait for what they draw.
pub(crate) fn prefetch_formulas(
    ctx: &egui::Context,
    deck: &crate::deck::Deck,
    slides: std::ops::Range<usize>,
    look: &Look,
) {
    let cache = crate::math::MathCache::shared(ctx);
    let Ok(mut cache) = cache.lock() else { return };
    if cache.waits() {
        return;
    }
    let em = em_px(ctx, look);
    // inline formulas are set at the body text's size and colour (see `inline_text`)
    let inline_em = look.scaled(size::BODY) * ctx.pixels_per_point();
    for f in crate::math::deck::formulas(deck, Some(slides)) {
        let (em, color) = match f.style {
            crate::math::MathStyle::Display => (em, look.palette.title),
            crate::math::MathStyle::Inline => (inline_em, look.palette.text),
        };
        cache.prefetch(ctx, f.src, f.syntax, f.style, em, color);
    }
}

pub(crate) fn math_source_height(src: &str, look: &Look) -> f32 {
    let lines = src.lines().count().max(1) as f32;
    look.scaled(size::MATH * 1.3 * lines + 48.0)
}

/// The height a formula is likely to take before it is typeset (so the blocks below it move
/// little when it arrives).
pub(crate) fn placeholder_height(src: &str, look: &Look) -> f32 {
    look.scaled(size::MATH * crate::math::estimated_height_em(src))
}

/// Display maths, typeset by Typst (`crate::math`) and centred. A formula still being typeset
/// (live window) keeps its last good picture, or a quiet placeholder of about its height; one
/// that never rendered shows its source in a quiet monospace frame; a broken edit keeps the last
/// good picture. Errors go to the slide's problems, for the presenter's screen.
pub(crate) fn math_ui(
    ui: &mut egui::Ui,
    bctx: &BlockCtx,
    path: &[usize],
    src: &str,
    latex: bool,
    state: &mut SlideState,
) {
    let look = &bctx.look;
    let width = ui.available_width();
    let view = formula(ui, bctx, path, src, latex);
    if let Some(e) = &view.error {
        state.note_problem(formula_problem(ui.ctx(), bctx, path, src, latex, e));
    }
    if let Some(f) = &view.typeset {
        let size = f.size(ui, width);
        let (row, _) = ui.allocate_exact_size(vec2(width, size.y), Sense::hover());
        let rect = Rect::from_center_size(row.center(), size);
        ui.painter().image(
            f.texture,
            rect,
            Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0)),
            egui::Color32::WHITE,
        );
        return;
    }
    if view.pending {
        let h = placeholder_height(src, look);
        let (row, _) = ui.allocate_exact_size(vec2(width, h), Sense::hover());
        let quiet = Rect::from_center_size(row.center(), vec2(width * 0.4, h * 0.6));
        ui.painter().rect_filled(
            quiet,
            look.scaled(10.0),
            look.palette.panel.gamma_multiply(0.5),
        );
        return;
    }
    let h = math_source_height(src, look);
    let (rect, _) = ui.allocate_exact_size(vec2(width, h), Sense::hover());
    let font = look.font(theme::MONO, size::MATH * 0.9, ui.ctx());
    let galley = ui
        .painter()
        .layout(src.trim().to_owned(), font, look.palette.title, width);
    let frame = Rect::from_center_size(
        rect.center(),
        vec2(
            (galley.size().x + look.scaled(64.0)).min(width),
            rect.height(),
        ),
    );
    ui.painter()
        .rect_filled(frame, look.scaled(10.0), look.palette.panel);
    ui.painter().rect_stroke(
        frame,
        look.scaled(10.0),
        Stroke::new(look.scaled(1.5), look.palette.dim.gamma_multiply(0.5)),
        egui::StrokeKind::Inside,
    );
    ui.painter().galley(
        frame.center() - galley.size() * 0.5,
        galley,
        look.palette.title,
    );
}
