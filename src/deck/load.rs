//! Reading a deck from RON with errors that point at the fault.

use std::collections::HashMap;
use std::path::Path;

use super::Deck;
use crate::diag::Diagnostic;

/// Parses deck text; `file` only names the source in errors.
pub fn parse_deck(text: &str, file: &Path) -> Result<Deck, Diagnostic> {
    let deck: Deck = ron::Options::default()
        .with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME)
        .from_str(text)
        .map_err(|e| at_token(text, Diagnostic::from_ron(file, &e)))?;
    validate(&deck, text, file)?;
    Ok(deck)
}

/// Loads a deck file; image paths in it are resolved against its folder.
pub fn load_deck(path: &Path) -> Result<Deck, Diagnostic> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| Diagnostic::whole_file(path, format!("cannot read: {e}")))?;
    parse_deck_file(&text, path)
}

/// Like [`parse_deck`], for text read from `path`: image paths resolve against its folder.
/// (A [`crate::reload::Parser`], so a deck hot-reloads through [`crate::reload::LiveFile`].)
pub fn parse_deck_file(text: &str, path: &Path) -> Result<Deck, Diagnostic> {
    let mut deck = parse_deck(text, path)?;
    deck.base_dir = path.parent().map(Path::to_path_buf);
    deck.file = Some(path.to_path_buf());
    Ok(deck)
}

/// What RON's types cannot say: a deck needs slides, ids must be unique (they keep the
/// presenter's place and tweaks across reloads), budgets must be sensible numbers.
fn validate(deck: &Deck, text: &str, file: &Path) -> Result<(), Diagnostic> {
    if deck.slides.is_empty() {
        return Err(Diagnostic::whole_file(file, "the deck has no slides"));
    }
    let mut seen: HashMap<&str, usize> = HashMap::new();
    for (i, slide) in deck.slides.iter().enumerate() {
        if let Some(id) = slide.id.as_deref() {
            if let Some(first) = seen.insert(id, i) {
                let (line, col) = locate_nth(text, &format!("\"{id}\""), 1).unwrap_or((0, 0));
                return Err(Diagnostic::new(
                    file,
                    line,
                    col,
                    format!(
                        "slide id \"{id}\" is used by slides {} and {}; ids must be unique",
                        first + 1,
                        i + 1
                    ),
                ));
            }
        }
        if let Some(s) = slide.seconds {
            if !s.is_finite() || s < 0.0 {
                return Err(Diagnostic::whole_file(
                    file,
                    format!(
                        "slide {} (\"{}\"): seconds must be a non-negative number, got {s}",
                        i + 1,
                        slide.title
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// RON reports some errors at the whitespace before the offending token (`title: 42` points
/// after the colon); move such a position onto the token, which is what an editor should show.
fn at_token(text: &str, mut d: Diagnostic) -> Diagnostic {
    if d.line == 0 {
        return d;
    }
    let mut lines = text.lines().skip(d.line - 1);
    let Some(line) = lines.next() else { return d };
    let rest: Vec<char> = line.chars().skip(d.col.saturating_sub(1)).collect();
    if let Some(skip) = rest.iter().position(|c| !c.is_whitespace()) {
        d.col += skip;
    }
    d
}

/// 1-based line and column of the `nth` (0-based) occurrence of `needle`.
fn locate_nth(text: &str, needle: &str, nth: usize) -> Option<(usize, usize)> {
    let offset = text.match_indices(needle).nth(nth)?.0;
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    Some((line, col))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bundled_deck_parses() {
        let path = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/slides/lecture.ron"));
        let deck = load_deck(path).unwrap();
        assert!(deck.slides.len() >= 3);
    }

    #[test]
    fn malformed_deck_points_at_the_fault() {
        let text = "(\n  title: \"x\",\n  slides: [\n    ( title: 3 ),\n  ],\n)";
        let err = parse_deck(text, Path::new("d.ron")).unwrap_err();
        assert_eq!(err.line, 4, "{err}");
    }

    #[test]
    fn duplicate_ids_point_at_the_second() {
        let text = "(title: \"x\", slides: [\n (id: \"a\", title: \"1\"),\n  (id: \"a\", title: \"2\"),\n])";
        let err = parse_deck(text, Path::new("d.ron")).unwrap_err();
        assert_eq!((err.line, err.col), (3, 8), "{err}");
    }
}
