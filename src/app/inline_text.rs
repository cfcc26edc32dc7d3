//! Paragraphs of slide text (`Text`, `Bullets`, the captions in columns) with their inline
//! markup, laid out for drawing. A paragraph without maths is one egui galley (egui wraps
//! it). egui's `LayoutJob` cannot hold pictures, so a paragraph with `$…$` is laid out here,
//! run by run: words as galleys, formulas as the textures the typesetting cache holds, wrapped
//! at spaces and each line's runs set on one baseline (the formula's baseline comes from
//! Typst). The slide renderer, `lectern export` and the thumbnails all draw through this.

use std::sync::Arc;

use egui::text::{LayoutJob, TextFormat};
use egui::{Align, Color32, FontId, Pos2, Rect, Vec2, pos2, vec2};

use super::theme::{self, Look, size};
use crate::deck::markup::{Inline, has_inline_math, inline_spans};
use crate::math::{MathCache, MathError, MathSyntax};

/// A laid-out paragraph, positioned relative to its top-left corner.
pub(crate) struct Paragraph {
    layout: Layout,
    size: Vec2,
    first_row_height: f32,
    /// Inline formulas that did not typeset: (character of the formula's source in the
    /// paragraph, 0-based, and the error).
    pub errors: Vec<(usize, MathError)>,
}

enum Layout {
    /// No maths: egui's own galley (`halign` set, so a centred one is drawn from its centre).
    Galley(Arc<egui::Galley>, Align),
    Runs(Vec<Run>),
}

enum Run {
    Text(Arc<egui::Galley>, Vec2),
    Formula(egui::TextureId, Rect),
}

impl Paragraph {
    pub(crate) fn size(&self) -> Vec2 {
        self.size
    }

    /// The height of its first line (a bullet's marker is centred on it).
    pub(crate) fn first_row_height(&self) -> f32 {
        self.first_row_height
    }

    /// Draws it with its top-left corner at `rect`'s (`rect` is as wide as it was laid out).
    pub(crate) fn paint(&self, painter: &egui::Painter, rect: Rect, color: Color32) {
        match &self.layout {
            Layout::Galley(galley, align) => {
                let x = if *align == Align::Center {
                    rect.center().x
                } else {
                    rect.left()
                };
                painter.galley(pos2(x, rect.top()), galley.clone(), color);
            }
            Layout::Runs(runs) => {
                let uv = Rect::from_min_max(pos2(0.0, 0.0), pos2(1.0, 1.0));
                // on whole pixels, text and pictures alike, so baselines stay where laid out
                let ppp = painter.pixels_per_point();
                let snap = |p: Pos2| ((p.to_vec2() * ppp).round() / ppp).to_pos2();
                for run in runs {
                    match run {
                        Run::Text(g, at) => {
                            painter.galley(snap(rect.min + *at), g.clone(), color);
                        }
                        Run::Formula(tex, r) => {
                            let min = snap(rect.min + r.min.to_vec2());
                            let placed = Rect::from_min_size(min, r.size());
                            painter.image(*tex, placed, uv, Color32::WHITE);
                        }
                    }
                }
            }
        }
    }
}

/// The fonts and colours of a paragraph's markup.
struct Style {
    regular: FontId,
    italic: FontId,
    mono: FontId,
    text: Color32,
    emphasis: Color32,
}

impl Style {
    fn new(ctx: &egui::Context, look: &Look) -> Self {
        Self {
            regular: look.font(theme::SERIF, size::BODY, ctx),
            italic: look.font(theme::SERIF_ITALIC, size::BODY, ctx),
            mono: look.font(theme::MONO, size::BODY * 0.85, ctx),
            text: look.palette.text,
            emphasis: look.palette.title,
        }
    }

    fn format(&self, kind: Inline) -> TextFormat {
        match kind {
            Inline::Emphasis => TextFormat::simple(self.italic.clone(), self.emphasis),
            Inline::Code => TextFormat::simple(self.mono.clone(), self.text),
            Inline::Plain | Inline::Math => TextFormat::simple(self.regular.clone(), self.text),
        }
    }
}

/// `text` with its inline markup (its `$…$` in `syntax`), wrapped at `width` points and
/// aligned by `align`.
pub(crate) fn paragraph(
    ui: &egui::Ui,
    (text, syntax): (&str, MathSyntax),
    width: f32,
    look: &Look,
    align: Align,
) -> Paragraph {
    if has_inline_math(text) {
        runs(ui, (text, syntax), width, look, align)
    } else {
        let galley = text_galley(ui, text, width, look, align);
        Paragraph {
            size: galley.size(),
            first_row_height: galley.rows.first().map_or(0.0, |r| r.height()),
            layout: Layout::Galley(galley, align),
            errors: Vec::new(),
        }
    }
}

/// A paragraph as one galley: `*emphasis*` in italics, `` `code` `` in monospace, and `$…$`
/// kept as written (for places that do not typeset maths, such as table cells).
pub(crate) fn text_galley(
    ui: &egui::Ui,
    text: &str,
    width: f32,
    look: &Look,
    align: Align,
) -> Arc<egui::Galley> {
    let style = Style::new(ui.ctx(), look);
    let mut job = LayoutJob {
        halign: align,
        ..Default::default()
    };
    job.wrap.max_width = width.max(1.0);
    for (span, kind) in inline_spans(text) {
        if kind == Inline::Math {
            let format = style.format(kind);
            job.append("$", 0.0, format.clone());
            job.append(span, 0.0, format.clone());
            job.append("$", 0.0, format);
        } else {
            job.append(span, 0.0, style.format(kind));
        }
    }
    ui.painter().layout_job(job)
}

/// One unbreakable piece of a line: a word (or part of one, in one format) or a formula.
struct Piece {
    run: Run,
    size: Vec2,
    /// From the piece's top down to its baseline.
    baseline: f32,
    /// Space above and below its ink that the line's height leaves out (a formula's margin).
    inset_y: f32,
}

/// What a paragraph is made of, in order.
enum Token {
    Piece(Piece),
    /// Whitespace between pieces: a place to wrap, `f32` points wide.
    Space(f32),
    Newline,
}

fn runs(
    ui: &egui::Ui,
    (text, syntax): (&str, MathSyntax),
    width: f32,
    look: &Look,
    align: Align,
) -> Paragraph {
    let ctx = ui.ctx();
    let style = Style::new(ctx, look);
    let mut errors = Vec::new();
    let mut tokens = Vec::new();
    for (span, kind) in inline_spans(text) {
        if kind == Inline::Math {
            let start = span.as_ptr() as usize - text.as_ptr() as usize;
            let start_char = text[..start].chars().count();
            match formula_piece(ctx, (span, syntax), look, &style) {
                Ok(p) => tokens.push(Token::Piece(p)),
                Err(e) => {
                    if let Some(e) = e {
                        errors.push((start_char, e));
                    }
                    // not typeset (yet): the source as written stands in for it
                    let shown = format!("${span}$");
                    tokens.push(Token::Piece(word(ui, &shown, style.format(Inline::Code))));
                }
            }
            continue;
        }
        let format = style.format(kind);
        let space_w = word(ui, " ", format.clone()).size.x;
        let mut rest = span;
        while !rest.is_empty() {
            let ws = rest.len() - rest.trim_start().len();
            if ws > 0 {
                for line in rest[..ws].split('\n').enumerate() {
                    if line.0 > 0 {
                        tokens.push(Token::Newline);
                    }
                    let n = line.1.chars().count();
                    if n > 0 {
                        tokens.push(Token::Space(space_w * n as f32));
                    }
                }
                rest = &rest[ws..];
                continue;
            }
            let end = rest.find(char::is_whitespace).unwrap_or(rest.len());
            tokens.push(Token::Piece(word(ui, &rest[..end], format.clone())));
            rest = &rest[end..];
        }
    }
    // every line is at least as tall as a line of plain text (a strut, as in TeX), so a line
    // holding only a small formula does not crowd the one above
    let strut = word(ui, " ", style.format(Inline::Plain));
    let strut = (strut.baseline, strut.size.y - strut.baseline);
    let (runs, size, first_row_height) = wrap(tokens, width, align, strut);
    Paragraph {
        layout: Layout::Runs(runs),
        size,
        first_row_height,
        errors,
    }
}

fn word(ui: &egui::Ui, text: &str, format: TextFormat) -> Piece {
    let mut job = LayoutJob::default();
    job.append(text, 0.0, format);
    job.wrap.max_width = f32::INFINITY;
    let galley = ui.painter().layout_job(job);
    let baseline = galley.rows.first().map_or(galley.size().y * 0.8, |r| {
        r.pos.y + r.row.glyphs.first().map_or(r.height() * 0.8, |g| g.pos.y)
    });
    Piece {
        size: galley.size(),
        baseline,
        inset_y: 0.0,
        run: Run::Text(galley, Vec2::ZERO),
    }
}

/// The formula `src` typeset inline at the body's size and colour: `Err(None)` while it is
/// still being typeset (live window), `Err(Some(e))` when it does not typeset.
fn formula_piece(
    ctx: &egui::Context,
    (src, syntax): (&str, MathSyntax),
    look: &Look,
    style: &Style,
) -> Result<Piece, Option<MathError>> {
    let ppp = ctx.pixels_per_point();
    let em_px = style.regular.size * ppp;
    let cache = MathCache::shared(ctx);
    let found = match cache.lock() {
        Ok(mut c) => c.inline(ctx, src, syntax, em_px, look.palette.text),
        Err(_) => None,
    };
    match found {
        Some(Ok(f)) => {
            let size = f.size_at(em_px) / ppp;
            let baseline = f.baseline_px * (size.y / f.size_px.y.max(1.0));
            Ok(Piece {
                run: Run::Formula(f.texture.id(), Rect::from_min_size(Pos2::ZERO, size)),
                size,
                baseline,
                inset_y: crate::math::INLINE_MARGIN_Y_EM * style.regular.size,
            })
        }
        Some(Err(e)) => Err(Some(e)),
        None => Err(None),
    }
}

/// Sets `tokens` in lines at most `width` wide (a piece wider than that gets a line of its
/// own), each line's pieces on one baseline, each line at least the strut's (ascent, descent)
/// tall; returns the runs placed, the paragraph's size and
/// its first line's height.
fn wrap(
    tokens: Vec<Token>,
    width: f32,
    align: Align,
    (strut_ascent, strut_descent): (f32, f32),
) -> (Vec<Run>, Vec2, f32) {
    struct Line {
        pieces: Vec<(Piece, f32)>,
        width: f32,
    }
    let mut lines = vec![Line {
        pieces: Vec::new(),
        width: 0.0,
    }];
    let mut space = 0.0;
    // pieces with no space between them (a formula and its comma) wrap together
    let mut glued: Vec<Piece> = Vec::new();
    let flush = |glued: &mut Vec<Piece>, lines: &mut Vec<Line>, space: &mut f32| {
        if glued.is_empty() {
            return;
        }
        let w: f32 = glued.iter().map(|p| p.size.x).sum();
        let line = lines.last_mut().expect("one line at least");
        let gap = if line.pieces.is_empty() { 0.0 } else { *space };
        if !line.pieces.is_empty() && line.width + gap + w > width {
            lines.push(Line {
                pieces: Vec::new(),
                width: 0.0,
            });
        }
        let line = lines.last_mut().expect("one line at least");
        let mut x = line.width + if line.pieces.is_empty() { 0.0 } else { *space };
        for p in glued.drain(..) {
            let w = p.size.x;
            line.pieces.push((p, x));
            x += w;
        }
        line.width = x;
        *space = 0.0;
    };
    for token in tokens {
        match token {
            Token::Piece(p) => glued.push(p),
            Token::Space(w) => {
                flush(&mut glued, &mut lines, &mut space);
                space += w;
            }
            Token::Newline => {
                flush(&mut glued, &mut lines, &mut space);
                lines.push(Line {
                    pieces: Vec::new(),
                    width: 0.0,
                });
            }
        }
    }
    flush(&mut glued, &mut lines, &mut space);

    let mut runs = Vec::new();
    let mut y = 0.0;
    let mut widest = 0.0f32;
    let mut first_row_height = 0.0;
    for (i, line) in lines.into_iter().enumerate() {
        let ascent = (line.pieces.iter())
            .map(|(p, _)| p.baseline - p.inset_y)
            .fold(strut_ascent, f32::max);
        let descent = (line.pieces.iter())
            .map(|(p, _)| p.size.y - p.inset_y - p.baseline)
            .fold(strut_descent, f32::max);
        let x0 = match align {
            Align::Center => (width - line.width) * 0.5,
            Align::Max => width - line.width,
            Align::Min => 0.0,
        };
        widest = widest.max(line.width);
        for (p, x) in line.pieces {
            let at = vec2(x0 + x, y + ascent - p.baseline);
            runs.push(match p.run {
                Run::Text(g, _) => Run::Text(g, at),
                Run::Formula(t, r) => Run::Formula(t, r.translate(at)),
            });
        }
        if i == 0 {
            first_row_height = ascent + descent;
        }
        y += ascent + descent;
    }
    (runs, vec2(widest, y), first_row_height)
}
