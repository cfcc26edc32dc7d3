//! Reading a deck from RON with errors that point at the fault.

use std::collections::HashMap;
use std::path::Path;

use super::broken::{blank_broken_slides, error_slide, ron_options};
use super::widgets::{OdeSource, WidgetSpec};
use super::{Deck, WidgetProblem, block_tree_path};
use crate::diag::Diagnostic;
use crate::ron_tree;

/// Parses deck text; `file` only names the source in errors.
/// A slide that does not parse on its own (a misspelt widget name, a missing field) does not
/// fail the deck: it becomes an error slide and is listed in `Deck::broken_slides`
/// ([`super::broken`]).
pub fn parse_deck(text: &str, file: &Path) -> Result<Deck, Diagnostic> {
    let written = text;
    let (mut deck, text, broken) = match ron_options().from_str::<Deck>(written) {
        Ok(deck) => (deck, std::borrow::Cow::Borrowed(written), Vec::new()),
        Err(e) => {
            let whole = at_token(written, Diagnostic::from_ron(file, &e));
            let Some((blanked, broken)) = blank_broken_slides(written, file) else {
                return Err(whole);
            };
            match ron_options().from_str::<Deck>(&blanked) {
                Ok(deck) => (deck, std::borrow::Cow::Owned(blanked), broken),
                // a deck-level fault remains: that is the one to report
                Err(e) => return Err(at_token(&blanked, Diagnostic::from_ron(file, &e))),
            }
        }
    };
    if !broken.is_empty() {
        let tree = ron_tree::parse(written).ok();
        for b in &broken {
            let node = (tree.as_ref()).and_then(|t| t.at(&format!("slides[{}]", b.slide)));
            if let Some(slot) = deck.slides.get_mut(b.slide) {
                *slot = error_slide(node, b);
            }
        }
    }
    validate(&deck, &text, file)?;
    deck.widget_problems = widget_problems(&deck, &text, file);
    deck.broken_slides = broken;
    Ok(deck)
}

/// Loads a deck file; image paths in it are resolved against its folder.
pub fn load_deck(path: &Path) -> Result<Deck, Diagnostic> {
    let text = crate::project_files::read_to_string(path)
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
/// presenter's place and tweaks across reloads), budgets must be sensible numbers. Each error
/// points at the value at fault.
fn validate(deck: &Deck, text: &str, file: &Path) -> Result<(), Diagnostic> {
    let tree = ron_tree::parse(text).ok();
    let at = |path: &str, message: String| {
        Diagnostic::at_value(tree.as_ref(), text, file, path, message)
    };
    if deck.slides.is_empty() {
        return Err(at("slides", "the deck has no slides".into()));
    }
    let mut seen: HashMap<&str, usize> = HashMap::new();
    for (i, slide) in deck.slides.iter().enumerate() {
        if let Some(id) = slide.id.as_deref()
            && let Some(first) = seen.insert(id, i)
        {
            return Err(at(
                &format!("slides[{i}].id"),
                format!(
                    "slide id \"{id}\" is used by slides {} and {}; ids must be unique",
                    first + 1,
                    i + 1
                ),
            ));
        }
        if let Some(s) = slide.seconds
            && (!s.is_finite() || s < 0.0)
        {
            return Err(at(
                &format!("slides[{i}].seconds"),
                format!(
                    "slide {} (\"{}\"): seconds must be a non-negative number, got {s}",
                    i + 1,
                    slide.title
                ),
            ));
        }
    }
    Ok(())
}

/// Per-widget problems, which do not stop the deck from loading: every ODE source is read and
/// compiled and every named tableau file read, and each fault is put at the deck's own line and
/// column (inside the expression string, at the faulty character). `file` is the deck: files it
/// names resolve against it.
pub fn widget_problems(deck: &Deck, text: &str, file: &Path) -> Vec<WidgetProblem> {
    let mut out = Vec::new();
    let tree = crate::ron_tree::parse(text).ok();
    for (i, slide) in deck.slides.iter().enumerate() {
        for (block, spec) in slide.widgets() {
            let base = block_tree_path(i, &block);
            let mut push = |diagnostic: Diagnostic| {
                out.push(WidgetProblem {
                    slide: i,
                    block: block.clone(),
                    diagnostic,
                })
            };
            if let Some(ode) = spec.ode()
                && let Err(e) = ode.load(Some(file))
            {
                // a File source's path: the string inside File(..)
                let at = match ode {
                    OdeSource::File(_) => format!("{base}.ode.0"),
                    OdeSource::Inline(_) => format!("{base}.ode"),
                };
                push(e.diagnostic(text, &at, file));
            }
            let list = match spec {
                WidgetSpec::StepConstruction(_) => "method".to_string(),
                _ => "methods".to_string(),
            };
            for (k, m) in spec.methods().iter().enumerate() {
                if let Err(msg) = m.resolve(Some(file)) {
                    let at = if list == "method" {
                        format!("{base}.method.0")
                    } else {
                        format!("{base}.{list}[{k}].0")
                    };
                    let (line, col) = tree
                        .as_ref()
                        .and_then(|t| t.at(&at))
                        .and_then(|n| n.str_offset(text, 0))
                        .map_or((0, 0), |b| crate::ron_tree::line_col(text, b));
                    push(Diagnostic::new(
                        file,
                        line,
                        col,
                        format!("tableau file: {msg}"),
                    ));
                }
            }
        }
    }
    out
}

/// RON reports some errors at the whitespace before the offending token (`title: 42` points
/// after the colon); move such a position onto the token, which is what an editor should show.
pub(super) fn at_token(text: &str, mut d: Diagnostic) -> Diagnostic {
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
        // a deck-level fault fails the deck
        let text = "(\n  title: 3,\n  slides: [\n    ( title: \"s\" ),\n  ],\n)";
        let err = parse_deck(text, Path::new("d.ron")).unwrap_err();
        assert_eq!((err.line, err.col), (2, 10), "{err}");
        // a fault inside one slide fails only that slide
        let text = "(\n  title: \"x\",\n  slides: [\n    ( title: 3 ),\n  ],\n)";
        let deck = parse_deck(text, Path::new("d.ron")).unwrap();
        let broken = &deck.broken_slides[0].diagnostic;
        assert_eq!((broken.line, broken.col), (4, 14), "{broken}");
    }

    #[test]
    fn a_misspelt_widget_fails_only_its_slide_at_its_name_with_a_did_you_mean() {
        let text = concat!(
            "(title: \"t\", slides: [\n",
            "  (id: \"a\", title: \"One\", body: [Text(\"ok\")]),\n",
            "  (id: \"b\", title: \"Two ∑\", body: [Text(\"é\"),\n",
            "     Widget(SlopeFeld((ode: File(\"p.ron\"), t_end: 1.0)))]),\n",
            "  (id: \"c\", title: \"Three\", body: [Math(src: \"x\", latx: true)]),\n",
            "  (id: \"d\", title: \"Four\", seconds: 5),\n",
            "])",
        );
        let deck = parse_deck(text, Path::new("d.ron")).unwrap();
        assert_eq!(deck.slides.len(), 4);
        let titles: Vec<&str> = deck.slides.iter().map(|s| s.title.as_str()).collect();
        assert_eq!(titles, ["One", "⚠ Two ∑", "⚠ Three", "Four"]);
        // the error slides keep their ids (the presenter's place survives the fix)
        assert_eq!(deck.slides[1].id.as_deref(), Some("b"));
        assert_eq!(deck.slides[3].seconds, Some(5.0));
        let b: Vec<_> = deck.broken_slides.iter().map(|b| &b.diagnostic).collect();
        assert_eq!(b.len(), 2);
        assert_eq!((b[0].line, b[0].col), (4, 13), "{}", b[0]);
        assert!(
            b[0].message.contains("did you mean `SlopeField`?"),
            "{}",
            b[0]
        );
        assert!(
            b[0].message.starts_with("slide 2 does not load"),
            "{}",
            b[0]
        );
        assert_eq!(b[1].line, 5, "{}", b[1]);
        assert!(b[1].message.contains("did you mean `latex`?"), "{}", b[1]);
        // the error slide says it, with the place
        let shown = format!("{:?}", deck.slides[1].body);
        assert!(shown.contains("d.ron:4:13"), "{shown}");
    }

    #[test]
    fn duplicate_ids_point_at_the_second() {
        let text = "(title: \"x\", slides: [\n (id: \"a\", title: \"1\"),\n  (id: \"a\", title: \"2\"),\n])";
        let err = parse_deck(text, Path::new("d.ron")).unwrap_err();
        assert_eq!((err.line, err.col), (3, 8), "{err}");
    }

    #[test]
    fn semantic_errors_point_at_the_value() {
        let text =
            "(title: \"x\", slides: [\n (title: \"1\"),\n  (title: \"2\", seconds: -3.0),\n])";
        let err = parse_deck(text, Path::new("d.ron")).unwrap_err();
        assert_eq!((err.line, err.col), (3, 25), "{err}");
        let err = parse_deck("(title: \"x\",\n slides: [])", Path::new("d.ron")).unwrap_err();
        assert_eq!((err.line, err.col), (2, 10), "{err}");
    }
}
