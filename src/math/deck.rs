//! The formulas of a deck: where each sits (slide, block path, and the line and column of its
//! `src` string in the deck file) and `lectern check`'s typesetting of them all, through the
//! bounded pool, so a formula that computes too much is reported, never waited for.

use std::path::Path;

use super::formula::Request;
use super::formula::{MathError, MathStyle, MathSyntax};
use super::pool::pool;
use crate::deck::markup::inline_formulas;
use crate::deck::{Block, Deck};
use crate::diag::Diagnostic;

/// One formula of a deck: a `Math` block, or `$…$` inside a `Text` or `Bullets` item.
#[derive(Debug, Clone, PartialEq)]
pub struct DeckFormula<'a> {
    pub slide: usize,
    /// Indices into the slide's body, then into columns (as the slide renderer numbers them).
    pub path: Vec<usize>,
    pub src: &'a str,
    pub syntax: MathSyntax,
    pub style: MathStyle,
    /// The string the formula is written in (a Math block's `src`, a paragraph or a bullet),
    /// its [`crate::ron_tree`] path, and the formula's first character in it (0-based).
    pub written: &'a str,
    pub written_at: String,
    pub start_char: usize,
}

impl DeckFormula<'_> {
    /// `slides[3].body[1][0][2].src`: where the string holding the formula is in the RON tree.
    pub fn ron_path(&self) -> String {
        self.written_at.clone()
    }

    /// What to ask the pool for, at `size_px` pixels per em in `rgba`.
    pub fn request(&self, size_px: f32, rgba: [u8; 4]) -> Request {
        Request {
            src: self.src.to_owned(),
            syntax: self.syntax,
            style: self.style,
            size_px,
            rgba,
        }
    }

    /// Line and column in the deck `text` of the formula's character `col` (1-based, as
    /// [`MathError::col`]), or of its first character.
    pub fn position(&self, text: &str, col: Option<usize>) -> Option<(usize, usize)> {
        let in_written = self.start_char + col.unwrap_or(1);
        position(text, &self.written_at, self.written, Some(in_written))
    }
}

/// `latex: true` on a block: its formulas are LaTeX.
pub fn syntax_of(latex: bool) -> MathSyntax {
    if latex {
        MathSyntax::Latex
    } else {
        MathSyntax::Typst
    }
}

/// The [`ron_tree`] path of the block at `path` on slide `slide`.
fn block_path(slide: usize, path: &[usize]) -> String {
    let mut p = format!("slides[{slide}].body");
    for i in path {
        p.push_str(&format!("[{i}]"));
    }
    p
}

/// The [`ron_tree`] path of the `src` of the Math block at `path` on slide `slide`.
pub fn ron_path(slide: usize, path: &[usize]) -> String {
    block_path(slide, path) + ".src"
}

/// Every formula of `slides` (all of them when `None`), in reading order. Inline ones
/// (`$…$`) are Typst unless their block has `latex: true`.
pub fn formulas(deck: &Deck, slides: Option<std::ops::Range<usize>>) -> Vec<DeckFormula<'_>> {
    fn inline<'a>(
        slide: usize,
        path: &[usize],
        (written, latex): (&'a str, bool),
        written_at: String,
        out: &mut Vec<DeckFormula<'a>>,
    ) {
        for (src, start_char) in inline_formulas(written) {
            out.push(DeckFormula {
                slide,
                path: path.to_vec(),
                src,
                syntax: syntax_of(latex),
                style: MathStyle::Inline,
                written,
                written_at: written_at.clone(),
                start_char,
            });
        }
    }
    fn walk<'a>(
        slide: usize,
        blocks: &'a [Block],
        path: &mut Vec<usize>,
        out: &mut Vec<DeckFormula<'a>>,
    ) {
        for (i, b) in blocks.iter().enumerate() {
            path.push(i);
            match b {
                Block::Math { src, latex } => out.push(DeckFormula {
                    slide,
                    path: path.clone(),
                    src,
                    syntax: syntax_of(*latex),
                    style: MathStyle::Display,
                    written: src,
                    written_at: ron_path(slide, path),
                    start_char: 0,
                }),
                Block::Text(t) => {
                    let at = block_path(slide, path) + t.tree_suffix();
                    inline(slide, path, (&t.src, t.latex), at, out)
                }
                Block::Bullets(list) => {
                    for (k, t) in list.items.iter().enumerate() {
                        let at = block_path(slide, path) + &list.item_tree_suffix(k);
                        inline(slide, path, (t, list.latex), at, out);
                    }
                }
                Block::Columns(cols) => {
                    for (c, col) in cols.iter().enumerate() {
                        path.push(c);
                        walk(slide, col, path, out);
                        path.pop();
                    }
                }
                _ => {}
            }
            path.pop();
        }
    }
    let range = slides.unwrap_or(0..deck.slides.len());
    let mut out = Vec::new();
    for (i, slide) in deck.slides.iter().enumerate().skip(range.start) {
        if i >= range.end {
            break;
        }
        walk(i, &slide.body, &mut Vec::new(), &mut out);
    }
    out
}

/// 1-based line and column in the deck `text` of the formula at `ron_path` (see [`ron_path`]):
/// of its character `col` (1-based, as [`MathError::col`]) if given, else of the string's
/// first character; `None` if the text no longer has `src` there.
pub fn position(
    text: &str,
    ron_path: &str,
    src: &str,
    col: Option<usize>,
) -> Option<(usize, usize)> {
    crate::deck::files::string_position(text, ron_path, src, col)
}

/// "formula: unknown variable: q", or the bounds' own "formula stopped after 2 s …".
pub fn message(err: &MathError) -> String {
    if err.message.starts_with("formula ") {
        err.message.clone()
    } else {
        format!("formula: {}", err.message)
    }
}

/// The error of a formula as a diagnostic at its place in `file` (whose text is `text`).
pub fn diagnostic(file: &Path, text: &str, f: &DeckFormula, err: &MathError) -> Diagnostic {
    let col = match f.syntax {
        MathSyntax::Typst => err.col,
        MathSyntax::Latex => None,
    };
    let message = message(err);
    match f.position(text, col) {
        Some((line, col)) => Diagnostic::new(file, line, col, message),
        None => Diagnostic::whole_file(file, format!("slide {}, {message}", f.slide + 1)),
    }
}

/// Typesets every formula of `deck` (read from `file`, whose text is `text`) through the
/// pool, within its bounds, and returns a diagnostic per formula that fails.
pub fn check_formulas(file: &Path, text: &str, deck: &Deck) -> Vec<Diagnostic> {
    let all = formulas(deck, None);
    // Queue them all first: both workers stay busy, and one slow formula costs its budget once.
    let jobs: Vec<_> = all
        .iter()
        .map(|f| pool().submit(f.request(40.0, [0, 0, 0, 255]), true, true, None))
        .collect();
    all.iter()
        .zip(jobs)
        .filter_map(|(f, job)| job.wait().err().map(|e| diagnostic(file, text, f, &e)))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::deck::parse_deck;

    const DECK: &str = r##"(
    title: "t",
    slides: [
        (title: "a", body: [Text("x"), Math(src: "a + b")]),
        (title: "b", body: [
            Columns([
                [Text("left")],
                [Math(src: "c", latex: true), Math(src: r#"x + undefinedthing(2)"#)],
            ]),
        ]),
    ],
)"##;

    #[test]
    fn formulas_are_found_with_their_paths_and_positions() {
        let deck = parse_deck(DECK, Path::new("d.ron")).unwrap();
        let fs = formulas(&deck, None);
        let paths: Vec<_> = fs.iter().map(|f| (f.slide, f.path.clone())).collect();
        assert_eq!(
            paths,
            vec![(0, vec![1]), (1, vec![0, 1, 0]), (1, vec![0, 1, 1])]
        );
        assert_eq!(fs[1].syntax, MathSyntax::Latex);
        assert_eq!(formulas(&deck, Some(1..2)).len(), 2);
        // the string's first character, and a column inside it (raw string)
        let line4 = DECK.lines().nth(3).unwrap();
        let col = line4.find("a + b").unwrap() + 1;
        assert_eq!(
            position(DECK, &fs[0].ron_path(), "a + b", None),
            Some((4, col))
        );
        let (line, col) = position(DECK, &fs[2].ron_path(), fs[2].src, Some(5)).unwrap();
        let line_text = DECK.lines().nth(line - 1).unwrap();
        assert!(
            line_text[col - 1..].starts_with("undefinedthing"),
            "{line_text}"
        );
        // a stale text (the formula changed since) gives no position rather than a wrong one
        assert_eq!(position(DECK, &fs[0].ron_path(), "a + c", None), None);
    }

    #[test]
    fn check_places_a_typst_error_at_its_character() {
        let deck = parse_deck(DECK, Path::new("d.ron")).unwrap();
        let ds = check_formulas(Path::new("d.ron"), DECK, &deck);
        assert_eq!(ds.len(), 1, "{ds:?}");
        let d = &ds[0];
        let line_text = DECK.lines().nth(d.line - 1).unwrap();
        assert!(line_text[d.col - 1..].starts_with("undefinedthing"), "{d}");
        assert!(d.message.contains("unknown"), "{d}");
    }

    #[test]
    fn check_places_an_inline_typst_error_at_its_character() {
        let deck_text = r##"(
    title: "t",
    slides: [
        (title: "a", body: [
            Text("where $h$ is the step"),
            Columns([[Bullets(["plain", "ω and $x + undefinedthing(2)$, \\$5"])]]),
        ]),
    ],
)"##;
        let deck = parse_deck(deck_text, Path::new("d.ron")).unwrap();
        let fs = formulas(&deck, None);
        let found: Vec<_> = fs
            .iter()
            .map(|f| (f.src, f.style, f.path.clone()))
            .collect();
        assert_eq!(
            found,
            vec![
                ("h", MathStyle::Inline, vec![0]),
                ("x + undefinedthing(2)", MathStyle::Inline, vec![1, 0, 0]),
            ]
        );
        let (line, col) = fs[0].position(deck_text, None).unwrap();
        assert!(deck_text.lines().nth(line - 1).unwrap()[col - 1..].starts_with("h$ is"));
        let ds = check_formulas(Path::new("d.ron"), deck_text, &deck);
        assert_eq!(ds.len(), 1, "{ds:?}");
        let line_text = deck_text.lines().nth(ds[0].line - 1).unwrap();
        let from_col: String = line_text.chars().skip(ds[0].col - 1).collect();
        assert!(
            from_col.starts_with("undefinedthing"),
            "{}: {line_text}",
            ds[0]
        );
    }
}
