//! Deck parsing and navigation, through the public API.

use std::path::{Path, PathBuf};

use lectern::deck::{Deck, Nav, load_deck, parse_deck};

fn bundled_decks() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("slides");
    let mut decks: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "ron"))
        .collect();
    decks.sort();
    decks
}

#[test]
fn every_bundled_deck_parses() {
    let decks = bundled_decks();
    assert!(
        decks.iter().any(|p| p.ends_with("lecture.ron")),
        "{decks:?}"
    );
    for path in decks {
        let deck = load_deck(&path).unwrap_or_else(|e| panic!("{e}"));
        assert!(!deck.slides.is_empty(), "{}", path.display());
        assert!(deck.base_dir.is_some());
    }
}

#[test]
fn bundled_lecture_has_title_bullets_and_a_live_plot() {
    use lectern::deck::Block;
    let deck =
        load_deck(&Path::new(env!("CARGO_MANIFEST_DIR")).join("slides/lecture.ron")).unwrap();
    let blocks: Vec<&Block> = deck.slides.iter().flat_map(|s| &s.body).collect();
    assert!(blocks.iter().any(|b| matches!(b, Block::Bullets(_))));
    assert!(blocks.iter().any(|b| matches!(b, Block::Widget(_))));
}

/// The error must point at the line and column of the fault, not at the start of the file.
#[test]
fn malformed_deck_reports_line_and_column_of_the_fault() {
    let cases: &[(&str, usize, usize)] = &[
        // a number where the title string belongs
        (
            "(\n  title: \"t\",\n  slides: [\n    (title: 42),\n  ],\n)",
            4,
            13,
        ),
        // an unknown block kind
        (
            "(\n  title: \"t\",\n  slides: [\n    (title: \"a\", body: [Txt(\"x\")]),\n  ],\n)",
            4,
            25,
        ),
        // a missing comma between slides
        (
            "(\n  title: \"t\",\n  slides: [\n    (title: \"a\")\n    (title: \"b\"),\n  ],\n)",
            5,
            5,
        ),
    ];
    for (i, (text, line, col)) in cases.iter().enumerate() {
        // a fault inside one slide fails only that slide (it is shown as an error slide); a
        // syntax error fails the deck
        let err = match parse_deck(text, Path::new("talk.ron")) {
            Ok(deck) if i < 2 => deck.broken_slides[0].diagnostic.clone(),
            Err(err) if i == 2 => err,
            other => panic!("{text}: {other:?}"),
        };
        assert_eq!((err.line, err.col), (*line, *col), "{err}\n{text}");
        assert!(
            err.to_string()
                .starts_with(&format!("talk.ron:{line}:{col}: ")),
            "{err}"
        );
    }
}

#[test]
fn a_deck_without_slides_is_an_error() {
    let err = parse_deck("(title: \"t\", slides: [])", Path::new("e.ron")).unwrap_err();
    assert!(err.message.contains("no slides"), "{err}");
}

#[test]
fn minimal_deck_gets_defaults() {
    let deck = parse_deck(
        "(title: \"t\", slides: [(title: \"only\")])",
        Path::new("m.ron"),
    )
    .unwrap();
    assert_eq!(deck.aspect.ratio(), 16.0 / 9.0);
    assert_eq!(deck.slides[0].key(), "only");
    assert_eq!(deck.planned_secs(), 0.0);
}

fn deck(keys: &[&str]) -> Deck {
    let slides: Vec<String> = keys
        .iter()
        .map(|k| format!("(id: \"{k}\", title: \"Slide {k}\")"))
        .collect();
    parse_deck(
        &format!("(title: \"t\", slides: [{}])", slides.join(",")),
        Path::new("t.ron"),
    )
    .unwrap()
}

#[test]
fn navigation_edges() {
    let d = deck(&["a", "b", "c", "d"]);
    let mut nav = Nav::new(&d);
    assert_eq!(nav.index(), 0);
    assert!(!nav.prev(&d), "prev on the first slide stays");
    assert_eq!(nav.index(), 0);
    assert!(nav.last(&d));
    assert_eq!(nav.index(), 3);
    assert!(!nav.next(&d), "next on the last slide stays");
    assert_eq!(nav.index(), 3);
    assert!(!nav.last(&d), "End on the last slide does not move");
    assert!(nav.first(&d));
    assert_eq!(nav.index(), 0);
    assert!(!nav.first(&d));
    nav.goto_number(&d, 3).unwrap();
    assert_eq!(nav.index(), 2);
    assert!(nav.goto_number(&d, 0).is_err());
    assert!(nav.goto_number(&d, 5).is_err());
    assert_eq!(nav.index(), 2, "a refused jump leaves the position alone");
    nav.go(&d, 99);
    assert_eq!(nav.index(), 3, "go clamps into the deck");
}

#[test]
fn reload_that_inserts_before_keeps_the_same_slide() {
    let old = deck(&["a", "b", "c"]);
    let mut nav = Nav::new(&old);
    nav.go(&old, 1); // on "b"
    let new = deck(&["intro", "a", "extra", "b", "c"]);
    nav.on_reload(&new);
    assert_eq!(nav.index(), 3);
    assert_eq!(new.slides[nav.index()].key(), "b");
}

#[test]
fn reload_that_deletes_the_current_slide_keeps_the_index() {
    let old = deck(&["a", "b", "c"]);
    let mut nav = Nav::new(&old);
    nav.go(&old, 1);
    let new = deck(&["a", "c"]);
    nav.on_reload(&new);
    assert_eq!(nav.index(), 1, "same index when the slide is gone");
    let shorter = deck(&["z"]);
    nav.on_reload(&shorter);
    assert_eq!(nav.index(), 0, "clamped when the deck got shorter");
}

#[test]
fn slides_without_ids_are_followed_by_title() {
    let old = parse_deck(
        "(title: \"t\", slides: [(title: \"one\"), (title: \"two\")])",
        Path::new("t.ron"),
    )
    .unwrap();
    let mut nav = Nav::new(&old);
    nav.next(&old);
    let new = parse_deck(
        "(title: \"t\", slides: [(title: \"zero\"), (title: \"one\"), (title: \"two\")])",
        Path::new("t.ron"),
    )
    .unwrap();
    nav.on_reload(&new);
    assert_eq!(nav.index(), 2);
}

/// Every string literal in a RON tree, except inside fields named in `private` (speaker notes
/// are the lecturer's own; everything else can reach the audience: titles, text, bullets,
/// maths, widget labels, the names of tableaux and problems shown in legends).
fn audience_strings(node: &lectern::ron_tree::Node, private: &[&str], out: &mut Vec<String>) {
    use lectern::ron_tree::Value;
    match &node.value {
        Value::Str { value, .. } => out.push(value.clone()),
        Value::Struct { fields, .. } => {
            for f in fields
                .iter()
                .filter(|f| !private.contains(&f.name.as_str()))
            {
                audience_strings(&f.value, private, out);
            }
        }
        Value::Seq { items, .. } | Value::List(items) => {
            for item in items {
                audience_strings(item, private, out);
            }
        }
        Value::Map(entries) => {
            for (k, v) in entries {
                audience_strings(k, private, out);
                audience_strings(v, private, out);
            }
        }
        Value::Ident(_) | Value::Number(_) | Value::Char(_) => {}
    }
}

#[test]
fn nothing_the_audience_sees_mentions_our_errata() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("slides");
    let mut files = bundled_decks();
    for sub in ["problems", "tableaux"] {
        for entry in std::fs::read_dir(root.join(sub)).unwrap() {
            files.push(entry.unwrap().path());
        }
    }
    let mut checked = 0;
    for file in files
        .iter()
        .filter(|p| p.extension().is_some_and(|e| e == "ron"))
    {
        let text = std::fs::read_to_string(file).unwrap();
        let tree = lectern::ron_tree::parse(&text).unwrap();
        let mut strings = Vec::new();
        audience_strings(&tree, &["notes"], &mut strings);
        checked += strings.len();
        for s in strings {
            assert!(
                !s.to_lowercase().contains("errata"),
                "{}: audience-visible text mentions the errata: {s:?}",
                file.display()
            );
        }
    }
    assert!(checked > 100, "the walk found only {checked} strings");
}
