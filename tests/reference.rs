//! `docs/reference.md` names every field of the deck, its slides, bookmarks, blocks, every
//! widget, the scene widget's toggles and camera, problem files and tableaux, and every variant
//! of the enums a deck writes — read from the types themselves (serde's own lists of expected
//! names, which `ron` reports for an unknown field or variant), so a field added to a spec type
//! without its line in the reference fails here.

use std::path::Path;

use lectern::deck::widgets::scene::{SceneCameraSpec, SceneToggles, SceneView};
use lectern::deck::widgets::{
    ConvergenceSpec, EnergySpec, NeptuneSpec, ParallelTransportSpec, RigidBodySpec, SceneSpec,
    SimulationLoopSpec, SlopeFieldSpec, SpiralSpec, StabilitySpec, StepSpec, TaylorSpec,
    WidgetSpec, WorkPrecisionSpec,
};
use lectern::deck::{Block, BookmarkDecl, Deck, Layout, Slide, Theme};
use serde::de::DeserializeOwned;

fn reference() -> String {
    std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/reference.md"))
        .unwrap()
}

/// Every field name of the struct `T`, as serde lists them (needs `deny_unknown_fields`, which
/// every deck type has: an unknown field is an error there, with a "did you mean").
fn fields<T: DeserializeOwned + std::fmt::Debug>(struct_text: &str) -> Vec<&'static str> {
    match ron::from_str::<T>(struct_text) {
        Err(e) => match e.code {
            ron::Error::NoSuchStructField { expected, .. } => expected.to_vec(),
            other => panic!("{struct_text}: {other}"),
        },
        Ok(v) => panic!("{struct_text} parsed: {v:?} (is deny_unknown_fields missing?)"),
    }
}

fn struct_fields<T: DeserializeOwned + std::fmt::Debug>() -> Vec<&'static str> {
    fields::<T>("(zz_no_such_field: 0)")
}

/// Every variant name of the enum `T`.
fn variants<T: DeserializeOwned + std::fmt::Debug>() -> Vec<&'static str> {
    match ron::from_str::<T>("ZzNoSuchVariant") {
        Err(e) => match e.code {
            ron::Error::NoSuchEnumVariant { expected, .. } => expected.to_vec(),
            other => panic!("{other}"),
        },
        Ok(v) => panic!("parsed {v:?}"),
    }
}

/// The part of the reference from the line starting with `marker` to the next heading or
/// sub-table introduction (a line starting with a backquoted name and " — ").
fn section<'a>(doc: &'a str, marker: &str) -> &'a str {
    let start = (doc.match_indices(marker))
        .map(|(i, _)| i)
        .find(|&i| i == 0 || doc[..i].ends_with('\n'))
        .unwrap_or_else(|| panic!("docs/reference.md has no line starting with {marker:?}"));
    let rest = &doc[start + marker.len()..];
    let end = rest
        .match_indices('\n')
        .map(|(i, _)| i + 1)
        .find(|&i| {
            let line = &rest[i..];
            line.starts_with('#') || sub_table_intro(line)
        })
        .unwrap_or(rest.len());
    &rest[..end]
}

/// "`SceneToggles` — …": a backquoted name, then a dash.
fn sub_table_intro(line: &str) -> bool {
    line.strip_prefix('`')
        .and_then(|l| l.split_once('`'))
        .is_some_and(|(name, rest)| !name.contains(' ') && rest.starts_with(" — "))
}

/// Each of `names` has a table row of its own in the section at `marker`.
fn has_rows(doc: &str, marker: &str, names: &[&str]) {
    let s = section(doc, marker);
    let missing: Vec<&&str> = names
        .iter()
        .filter(|n| !s.contains(&format!("| `{n}` |")))
        .collect();
    assert!(
        missing.is_empty(),
        "docs/reference.md, section {marker:?}: no row for {missing:?}"
    );
}

/// Each of `names` is mentioned, backquoted, in the section at `marker`.
fn mentions(doc: &str, marker: &str, names: &[&str]) {
    let s = section(doc, marker);
    let missing: Vec<&&str> = names
        .iter()
        .filter(|n| !s.contains(&format!("`{n}`")))
        .collect();
    assert!(
        missing.is_empty(),
        "docs/reference.md, section {marker:?}: {missing:?} not mentioned"
    );
}

#[test]
fn every_deck_level_field_is_in_the_reference() {
    let doc = reference();
    let deck = struct_fields::<Deck>();
    assert!(
        deck.contains(&"aspect") && deck.contains(&"bookmarks"),
        "{deck:?}"
    );
    has_rows(&doc, "## The deck: `Deck`", &deck);
    has_rows(&doc, "## A slide: `Slide`", &struct_fields::<Slide>());
    has_rows(
        &doc,
        "## A bookmark: `BookmarkDecl`",
        &struct_fields::<BookmarkDecl>(),
    );
    mentions(&doc, "## The deck: `Deck`", &variants::<Theme>());
    mentions(&doc, "## A slide: `Slide`", &variants::<Layout>());
}

#[test]
fn every_block_and_its_fields_are_in_the_reference() {
    let doc = reference();
    let blocks = variants::<Block>();
    assert_eq!(blocks.len(), 7, "{blocks:?}");
    has_rows(&doc, "## Blocks", &blocks);
    // the struct variants' fields, in their rows
    for (variant, text) in [
        ("Math", "Math(zz_no_such_field: 0)"),
        ("Image", "Image(zz_no_such_field: 0)"),
        // the field forms of a paragraph and a list
        ("Text", "Text((zz_no_such_field: 0))"),
        ("Bullets", "Bullets((zz_no_such_field: 0))"),
    ] {
        let names = fields::<Block>(text);
        let row = section(&doc, "## Blocks")
            .lines()
            .find(|l| l.starts_with(&format!("| `{variant}` |")))
            .unwrap();
        for n in names {
            assert!(
                row.contains(&format!("`{n}`")),
                "{variant}: `{n}` not in {row}"
            );
        }
    }
}

#[test]
fn every_widget_and_every_widget_field_is_in_the_reference() {
    let doc = reference();
    let widgets = variants::<WidgetSpec>();
    assert_eq!(widgets.len(), 13, "{widgets:?}");
    let fields_of: Vec<(&str, Vec<&str>)> = vec![
        ("SlopeField", struct_fields::<SlopeFieldSpec>()),
        ("StepConstruction", struct_fields::<StepSpec>()),
        ("Spiral", struct_fields::<SpiralSpec>()),
        ("Neptune", struct_fields::<NeptuneSpec>()),
        ("Taylor", struct_fields::<TaylorSpec>()),
        ("Convergence", struct_fields::<ConvergenceSpec>()),
        ("WorkPrecision", struct_fields::<WorkPrecisionSpec>()),
        ("Stability", struct_fields::<StabilitySpec>()),
        ("RigidBody", struct_fields::<RigidBodySpec>()),
        (
            "ParallelTransport",
            struct_fields::<ParallelTransportSpec>(),
        ),
        ("SimulationLoop", struct_fields::<SimulationLoopSpec>()),
        ("Scene", struct_fields::<SceneSpec>()),
        ("Energy", struct_fields::<EnergySpec>()),
    ];
    // every variant has its spec listed here (a new widget needs a line above and a section)
    let listed: Vec<&str> = fields_of.iter().map(|(w, _)| *w).collect();
    assert_eq!(listed, widgets);
    for (widget, names) in &fields_of {
        has_rows(&doc, &format!("### `{widget}`"), names);
        assert!(
            section(&doc, &format!("### `{widget}`")).contains(&format!("Example: `{widget}((")),
            "{widget} has no example"
        );
    }
    has_rows(&doc, "`SceneToggles` — ", &struct_fields::<SceneToggles>());
    has_rows(
        &doc,
        "`SceneCameraSpec` — ",
        &struct_fields::<SceneCameraSpec>(),
    );
    mentions(&doc, "### `Scene`", &variants::<SceneView>());
    mentions(
        &doc,
        "### `Taylor`",
        &variants::<lectern::deck::widgets::TaylorFn>(),
    );
}

#[test]
fn every_problem_file_and_tableau_field_is_in_the_reference() {
    let doc = reference();
    let problem = struct_fields::<lectern::ode::problem::ProblemDef>();
    assert!(
        problem.contains(&"exact") && problem.contains(&"ranges"),
        "{problem:?}"
    );
    has_rows(&doc, "## A problem file: `ProblemDef`", &problem);
    has_rows(
        &doc,
        "## A tableau file: `Tableau`",
        &struct_fields::<lectern::ode::Tableau>(),
    );
}

#[test]
fn every_built_in_method_is_named_in_the_widgets_introduction() {
    let doc = reference();
    let names: Vec<String> = lectern::ode::Method::ALL
        .iter()
        .map(|m| format!("{m:?}"))
        .collect();
    let names: Vec<&str> = names.iter().map(String::as_str).collect();
    mentions(&doc, "## Widgets", &names);
}

#[test]
fn a_field_missing_from_the_reference_is_caught() {
    // the check bites: a reference without the slope field's `exact` row fails
    let doc = reference().replace("| `exact` | bool |", "| exact | bool |");
    let result = std::panic::catch_unwind(|| {
        has_rows(&doc, "### `SlopeField`", &struct_fields::<SlopeFieldSpec>())
    });
    assert!(result.is_err());
}
