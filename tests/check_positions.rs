//! Every error `lectern check` reports about a value has that value's line and column: each
//! value of each bundled deck, scene, problem and tableau file is replaced in turn by wrong
//! values (numbers out of range, NaN, empty or odd strings, unknown names, emptied lists), and
//! every resulting problem must carry a position a text editor can jump to.

use std::path::{Path, PathBuf};

use lectern::cli::check::{Kind, Report, check_text};
use lectern::cli::check_deck::DeckChecker;
use lectern::ron_tree::{self, Node, Value};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The bundled files whose values are perturbed, with their kind.
fn bundled() -> Vec<(Kind, PathBuf)> {
    let mut files = vec![
        (Kind::Deck, root().join("slides/lecture.ron")),
        (Kind::Scene, root().join("scenes/water.ron")),
    ];
    for (dir, kind) in [("problems", Kind::Problem), ("tableaux", Kind::Tableau)] {
        let mut in_dir: Vec<PathBuf> = std::fs::read_dir(root().join("slides").join(dir))
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.extension().is_some_and(|e| e == "ron"))
            .collect();
        in_dir.sort();
        files.extend(in_dir.into_iter().map(|p| (kind, p)));
    }
    files
}

/// (byte span, replacement) for every value in the tree.
fn mutations(node: &Node, out: &mut Vec<(std::ops::Range<usize>, &'static str)>) {
    let span = node.span.clone();
    match &node.value {
        Value::Number(_) => {
            for r in [
                "0", "-1", "0.5", "3", "1e30", "-1e30", "NaN", "inf", "100000",
            ] {
                out.push((span.clone(), r));
            }
        }
        Value::Str { .. } => {
            for r in [
                "\"\"",
                "\"x y\"",
                "\"#\"",
                "\"../../../x\"",
                "\"2x\"",
                "\"sin\"",
            ] {
                out.push((span.clone(), r));
            }
        }
        Value::Ident(_) => {
            for r in ["Nope", "true", "None"] {
                out.push((span.clone(), r));
            }
        }
        Value::Char(_) => {}
        Value::List(items) => {
            out.push((span.clone(), "[]"));
            items.iter().for_each(|n| mutations(n, out));
        }
        Value::Seq { items, .. } => items.iter().for_each(|n| mutations(n, out)),
        Value::Struct { fields, .. } => fields.iter().for_each(|f| mutations(&f.value, out)),
        Value::Map(entries) => {
            out.push((span.clone(), "{}"));
            for (k, v) in entries {
                mutations(k, out);
                mutations(v, out);
            }
        }
    }
}

/// Faults that have no single place in the file.
fn positionless_is_fine(message: &str) -> bool {
    message.contains("problem file is empty")
}

#[test]
fn every_error_from_a_perturbed_value_has_a_line_and_column() {
    let mut decks = DeckChecker::new();
    let mut without_position = Vec::new();
    let (mut mutants, mut with_errors) = (0usize, 0usize);
    for (kind, file) in bundled() {
        let text = std::fs::read_to_string(&file).unwrap();
        let tree = ron_tree::parse(&text).unwrap();
        let mut all = Vec::new();
        mutations(&tree, &mut all);
        for (span, replacement) in all {
            let mutated = format!("{}{replacement}{}", &text[..span.start], &text[span.end..]);
            let problems = check_text(kind, &mutated, &file, &mut decks, &mut Report::default());
            mutants += 1;
            with_errors += usize::from(!problems.is_empty());
            for d in problems {
                if (d.line == 0 || d.col == 0) && !positionless_is_fine(&d.message) {
                    let (line, col) = ron_tree::line_col(&text, span.start);
                    without_position.push(format!(
                        "{}:{line}:{col} := {replacement}: {d}",
                        file.strip_prefix(root()).unwrap_or(&file).display()
                    ));
                }
            }
        }
    }
    println!("{mutants} mutants, {with_errors} with errors");
    assert!(
        mutants > 3000 && with_errors > 1000,
        "{mutants} / {with_errors}"
    );
    assert!(
        without_position.is_empty(),
        "{} errors without a position:\n{}",
        without_position.len(),
        without_position.join("\n")
    );
}

#[test]
fn the_bundled_project_passes() {
    let report = lectern::cli::check::check_paths(
        &["slides", "scenes", "shaders"].map(|d| Path::new(env!("CARGO_MANIFEST_DIR")).join(d)),
        false,
    );
    assert!(report.problems.is_empty(), "{:?}", report.problems);
    assert_eq!(report.deck_lines.len(), 1);
}
