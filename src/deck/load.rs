//! Reading a deck from RON with errors that point at the fault.

use std::path::Path;

use super::Deck;
use crate::diag::Diagnostic;

/// Parses deck text; `file` only names the source in errors.
pub fn parse_deck(text: &str, file: &Path) -> Result<Deck, Diagnostic> {
    let deck: Deck = ron::Options::default()
        .with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME)
        .from_str(text)
        .map_err(|e| Diagnostic::from_ron(file, &e))?;
    if deck.slides.is_empty() {
        return Err(Diagnostic::whole_file(file, "the deck has no slides"));
    }
    Ok(deck)
}

pub fn load_deck(path: &Path) -> Result<Deck, Diagnostic> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| Diagnostic::whole_file(path, format!("cannot read: {e}")))?;
    parse_deck(&text, path)
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
}
