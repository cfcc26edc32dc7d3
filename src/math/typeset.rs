//! Formula → pixels with Typst as a library: no TeX install, no browser, no network.
//!
//! Fonts come embedded (`typst-assets`: New Computer Modern and its maths companion), so a
//! formula renders the same on every machine. This module knows nothing of egui: it returns a
//! premultiplied RGBA buffer that any renderer can upload.

use std::sync::LazyLock;

use typst::diag::{FileError, FileResult, Severity, SourceDiagnostic};
use typst::foundations::{Bytes, Datetime};
use typst::syntax::{FileId, Source};
use typst::text::{Font, FontBook};
use typst::utils::LazyHash;
use typst::{Library, LibraryExt, World, WorldExt};
use typst_layout::PagedDocument;

pub use super::formula::{MathError, MathStyle, MathSyntax, RenderedFormula};

/// The font size formulas are laid out at; the raster scale turns it into the pixels asked for.
const LAYOUT_PT: f64 = 10.0;

/// Definitions that the LaTeX converter's output refers to (mitex maps some commands to helper
/// functions that its own Typst package would define).
/// `\sqrt[n]{x}` arrives as `mitexsqrt(\[n \], x)`: the index still carries LaTeX's brackets
/// (and spaces), which `mitexrootindex` strips so the index reads `n`, not `[n]`.
const LATEX_PRELUDE: &str = r#"#let mitexisedge(c) = c.func() == [ ].func() or (c.has("text") and (c.text == "[" or c.text == "]"))
#let mitexrootindex(it) = if it.has("children") { let cs = it.children; while cs.len() > 0 and mitexisedge(cs.first()) { cs = cs.slice(1) }; while cs.len() > 0 and mitexisedge(cs.last()) { cs = cs.slice(0, -1) }; cs.join() } else { it }
#let mitexsqrt(..a) = { let p = a.pos(); if p.len() == 1 { math.sqrt(p.at(0)) } else { math.root(mitexrootindex(p.at(0)), p.at(1)) } }
#let mitexmathbf(it) = math.bold(math.upright(it))
#let mitexdisplay(it) = math.display(it)
#let mitexcolor(c, it) = text(fill: rgb(c), it)
#let mitexoverbrace(it, ..a) = math.overbrace(it, ..a)
#let mitexunderbrace(it, ..a) = math.underbrace(it, ..a)
#let mitexarray(..a) = math.mat(delim: none, ..a.pos())
#let pmatrix(..a) = math.mat(delim: "(", ..a)
#let bmatrix(..a) = math.mat(delim: "[", ..a)
#let Bmatrix(..a) = math.mat(delim: "{", ..a)
#let vmatrix(..a) = math.mat(delim: "|", ..a)
#let Vmatrix(..a) = math.mat(delim: "‖", ..a)
#let matrix(..a) = math.mat(delim: none, ..a)
#let aligned(..a) = math.display(a.pos().join(linebreak()))
#let textmath(it) = it
#let textbf(it) = text(weight: "bold", it)
#let textit(it) = emph(it)
#let textrm(it) = it
#let mathrm(it) = math.upright(it)
#let operatorname(it) = math.op(math.upright(it))
"#;

struct Fonts {
    book: LazyHash<FontBook>,
    fonts: Vec<Font>,
}

static FONTS: LazyLock<Fonts> = LazyLock::new(|| {
    let fonts: Vec<Font> = typst_assets::fonts()
        .flat_map(|data| Font::iter(Bytes::new(data)))
        .collect();
    Fonts {
        book: LazyHash::new(FontBook::from_fonts(&fonts)),
        fonts,
    }
});

static LIBRARY: LazyLock<LazyHash<Library>> = LazyLock::new(|| LazyHash::new(Library::default()));

/// A one-file Typst world: the formula's document, the standard library and embedded fonts.
struct FormulaWorld {
    source: Source,
}

impl World for FormulaWorld {
    fn library(&self) -> &LazyHash<Library> {
        &LIBRARY
    }
    fn book(&self) -> &LazyHash<FontBook> {
        &FONTS.book
    }
    fn main(&self) -> FileId {
        self.source.id()
    }
    fn source(&self, id: FileId) -> FileResult<Source> {
        if id == self.source.id() {
            Ok(self.source.clone())
        } else {
            Err(FileError::AccessDenied)
        }
    }
    fn file(&self, _id: FileId) -> FileResult<Bytes> {
        // Formulas are self-contained: no images, no packages, no network.
        Err(FileError::AccessDenied)
    }
    fn font(&self, index: usize) -> Option<Font> {
        FONTS.fonts.get(index).cloned()
    }
    fn today(&self, _offset: Option<typst::foundations::Duration>) -> Option<Datetime> {
        None
    }
}

/// Converts LaTeX maths to Typst maths (no rendering).
pub fn latex_to_typst(latex: &str) -> Result<String, MathError> {
    mitex::convert_math(latex, None).map_err(|e| MathError {
        message: format!("LaTeX: {}", e.trim_start_matches("error: ")),
        col: None,
    })
}

/// Typesets `src` as display maths, `size_px` pixels per em, in `rgba` (unpremultiplied), on a
/// transparent background with a small margin.
pub fn render_formula(
    src: &str,
    syntax: MathSyntax,
    size_px: f32,
    rgba: [u8; 4],
) -> Result<RenderedFormula, MathError> {
    render_math(src, syntax, MathStyle::Display, size_px, rgba)
}

pub use super::formula::INLINE_MARGIN_Y_EM;
const INLINE_MARGIN: &str = "(x: 0.04em, y: 0.15em)";

/// A zero-width box holding an invisible letter, typeset just before the formula: its text
/// item sits on the line's baseline, which is how [`baseline_pt`] finds it (Typst folds line
/// frames into the page, so their baselines are not kept).
const BASELINE_MARK: &str = "#box(width: 0pt, text(fill: rgb(0, 0, 0, 0))[x])";

/// [`render_formula`] for either style: `Inline` typesets `src` as inline maths (`$x$` in
/// Typst: smaller limits and fractions, as in running text) with a thinner side margin.
pub fn render_math(
    src: &str,
    syntax: MathSyntax,
    style: MathStyle,
    size_px: f32,
    rgba: [u8; 4],
) -> Result<RenderedFormula, MathError> {
    if !(size_px.is_finite() && (1.0..=1000.0).contains(&size_px)) {
        return Err(MathError {
            message: format!("formula size {size_px} px is outside 1..=1000"),
            col: None,
        });
    }
    if src.trim().is_empty() {
        return Err(MathError {
            message: "empty formula".into(),
            col: None,
        });
    }
    let (body, prelude) = match syntax {
        MathSyntax::Typst => (src.to_owned(), ""),
        MathSyntax::Latex => (latex_to_typst(src)?, LATEX_PRELUDE),
    };
    let [r, g, b, a] = rgba;
    // Inline maths is `$x$` with no space inside (Typst's rule), so the source is trimmed;
    // columns still count from the source's first character.
    // (a display formula is its own paragraph: a mark before it would be a line of its own)
    let (margin, open, close, body, skipped) = match style {
        MathStyle::Display => ("0.15em", "$ ".to_owned(), " $", body.as_str(), 0),
        MathStyle::Inline => {
            let trimmed = body.trim_start();
            let skipped = body.len() - trimmed.len();
            // Typst trims an inline formula's height by 0.7 × the paragraph's leading, so tall
            // maths does not push lines apart; here that would clip `x_0` and `T/h`: no leading
            let open = format!("#set par(leading: 0em)\n{BASELINE_MARK}$");
            (INLINE_MARGIN, open, "$", trimmed.trim_end(), skipped)
        }
    };
    let header = format!(
        "{prelude}#set page(width: auto, height: auto, margin: {margin}, fill: none)\n\
         #set text(size: {LAYOUT_PT}pt, fill: rgb({r}, {g}, {b}, {a}))\n{open}"
    );
    let text = format!("{header}{body}{close}\n");
    let world = FormulaWorld {
        source: Source::detached(text),
    };
    let doc = typst::compile::<PagedDocument>(&world)
        .output
        .map_err(|errs| {
            let mut e = first_error(&world, &errs, header.len(), body, syntax);
            if let Some(c) = e.col.as_mut() {
                *c += src.get(..skipped).map_or(0, |s| s.chars().count());
            }
            e
        })?;
    let page = doc.pages().first().ok_or_else(|| MathError {
        message: "formula produced no output".into(),
        col: None,
    })?;
    let opts = typst_render::RenderOptions {
        pixel_per_pt: (size_px as f64 / LAYOUT_PT).into(),
        render_bleed: false,
    };
    let pixmap = typst_render::render(page, &opts);
    let baseline_pt = match style {
        MathStyle::Inline => baseline_pt(&page.frame, typst::layout::Transform::identity()),
        MathStyle::Display => None,
    }
    .unwrap_or(page.frame.height().to_pt());
    let baseline = (baseline_pt * size_px as f64 / LAYOUT_PT).round() as u32;
    Ok(RenderedFormula {
        width: pixmap.width(),
        height: pixmap.height(),
        baseline: baseline.min(pixmap.height()),
        rgba_premultiplied: pixmap.data().to_vec(),
    })
}

/// The y (in pt, from the page's top) of [`BASELINE_MARK`]'s invisible letter: the baseline
/// of the formula's line. `page_from_frame` places `frame` on the page.
fn baseline_pt(
    frame: &typst::layout::Frame,
    page_from_frame: typst::layout::Transform,
) -> Option<f64> {
    use typst::layout::{FrameItem, Transform};
    use typst::visualize::Paint;
    for (pos, item) in frame.items() {
        match item {
            FrameItem::Text(t) if matches!(&t.fill, Paint::Solid(c) if c.alpha() == Some(0.0)) => {
                return Some(pos.transform(page_from_frame).y.to_pt());
            }
            FrameItem::Group(g) => {
                let at = Transform::translate(pos.x, pos.y).pre_concat(g.transform);
                if let Some(y) = baseline_pt(&g.frame, page_from_frame.pre_concat(at)) {
                    return Some(y);
                }
            }
            _ => {}
        }
    }
    None
}

pub use super::formula::estimated_height_em;

fn first_error(
    world: &FormulaWorld,
    errs: &[SourceDiagnostic],
    body_start: usize,
    body: &str,
    syntax: MathSyntax,
) -> MathError {
    let diag = errs
        .iter()
        .find(|d| d.severity == Severity::Error)
        .or(errs.first());
    let Some(diag) = diag else {
        return MathError {
            message: "unknown Typst error".into(),
            col: None,
        };
    };
    // Columns only make sense against what the lecturer typed, i.e. for Typst input.
    let col = match syntax {
        MathSyntax::Typst => world
            .range(diag.span)
            .filter(|r| r.start >= body_start && r.start <= body_start + body.len())
            .map(|r| body[..r.start - body_start].chars().count() + 1),
        MathSyntax::Latex => None,
    };
    let mut message = diag.message.to_string();
    for hint in &diag.hints {
        message.push_str("; hint: ");
        message.push_str(&hint.v);
    }
    MathError { message, col }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn renders_a_fraction_with_ink() {
        let f = render_formula(
            "x(t+h) = x + h/2 dot(x)",
            MathSyntax::Typst,
            40.0,
            [0, 0, 0, 255],
        )
        .unwrap();
        assert!(
            f.width > f.height && f.height > 20,
            "{}x{}",
            f.width,
            f.height
        );
        assert_eq!(
            f.rgba_premultiplied.len(),
            (f.width * f.height * 4) as usize
        );
        let inked = f
            .rgba_premultiplied
            .chunks(4)
            .filter(|p| p[3] > 128)
            .count();
        assert!(inked > 100, "only {inked} opaque pixels");
    }

    #[test]
    fn height_estimates_are_near_the_typeset_heights() {
        // (source, typeset height in em at 26.7 px/em, from the bundled deck)
        for (src, em) in [
            ("dot(x) = f(x, t)", 1.31),
            (
                "vec(bold(x), bold(v)) quad arrow.r quad dot(vec(bold(x), bold(v))) = vec(bold(v), bold(F) \\/ m)",
                2.92,
            ),
            (
                "bold(X) = vec(bold(x), bold(q), bold(P), bold(L)) quad (3 + 4 + 3 + 3) N = 13 N",
                5.33,
            ),
            ("y_(n+1) = R(h lambda) thin y_n, quad |R(z)| <= 1", 1.35),
            (
                "x(t + h) = x_0 + 1/6 k_1 + 1/3 k_2 + 1/3 k_3 + 1/6 k_4",
                2.36,
            ),
            (
                "bold(omega)^* = mat(0, -omega_z, omega_y; omega_z, 0, -omega_x; -omega_y, omega_x, 0)",
                4.35,
            ),
        ] {
            let est = estimated_height_em(src);
            assert!(
                (est / em - 1.0).abs() < 0.25,
                "{src}: {est} em, typeset {em}"
            );
        }
    }

    #[test]
    fn bad_typst_reports_the_column() {
        let err = render_formula("x = frac(1, ", MathSyntax::Typst, 30.0, [0; 4]).unwrap_err();
        assert!(err.col.is_some(), "{err}");
    }

    #[test]
    fn latex_input_renders() {
        let f = render_formula(
            r"\dot{x} = \frac{1}{2} \omega q",
            MathSyntax::Latex,
            30.0,
            [0, 0, 0, 255],
        );
        assert!(f.is_ok(), "{f:?}");
    }
}
