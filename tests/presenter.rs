//! The presenter's side: tweaks that survive reloads, write-back that changes only the tweaked
//! bytes, pacing arithmetic, and a snapshot of the presenter view.

use std::path::{Path, PathBuf};

use lectern::app::pacing::Pacing;
use lectern::app::presenter::{PresenterInfo, presenter_ui};
use lectern::app::tweaks::{Bookmarks, apply_declared, write_back};
use lectern::app::{DeckState, SlideState};
use lectern::deck::write_back::write_atomic_with;
use lectern::deck::{Deck, DeckSession, load_deck, parse_deck};
use lectern::reload::Reloaded;
use lectern::widgets::ParamSnapshot;

const H: &str = "h";

fn deck_text(h: &str, turns: &str, extra_title: &str) -> String {
    format!(
        "// spiral deck\n(\n    title: \"t\",\n    slides: [\n        (id: \"intro\", title: \"Intro{extra_title}\", seconds: 60),\n        (\n            id: \"spiral\",\n            title: \"Spiral\",\n            body: [Widget(Spiral((h: {h}, turns: {turns}, compare: true)))], // keep\n            notes: \"Drag h.\",\n            seconds: 90,\n        ),\n    ],\n    bookmarks: [(key: 1, slide: \"spiral\", label: \"big h\", set: [(\"h\", 0.8)])],\n)\n"
    )
}

fn session(text: &str) -> (tempfile::TempDir, PathBuf, DeckSession) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("talk.ron");
    std::fs::write(&path, text).unwrap();
    let s = DeckSession::open(&path).unwrap();
    (dir, path, s)
}

fn h_of(states: &mut DeckState, deck: &Deck) -> f64 {
    let slide = &deck.slides[1];
    let state = states.slide(slide);
    state.ensure_widgets(slide);
    match state.param(&[0], H) {
        Some(ParamSnapshot::F64(h)) => h,
        other => panic!("{other:?}"),
    }
}

fn reload(s: &mut DeckSession, path: &Path, text: &str) {
    std::fs::write(path, text).unwrap();
    assert_eq!(
        s.apply_changed(&[path.to_path_buf()]),
        Some(Reloaded::Updated)
    );
}

#[test]
fn tweak_survives_unrelated_edit_file_wins_when_it_changes_the_value_and_reset_restores() {
    let (_dir, path, mut s) = session(&deck_text("0.1", "3.0", ""));
    let mut states = DeckState::default();
    assert_eq!(h_of(&mut states, s.deck()), 0.1);
    let slide = s.deck().slides[1].clone();
    assert!(
        states
            .slide(&slide)
            .set_param(&[0], H, ParamSnapshot::F64(0.5))
    );

    // An unrelated edit elsewhere in the deck: the tweak stays.
    reload(&mut s, &path, &deck_text("0.1", "3.0", " (edited)"));
    assert_eq!(h_of(&mut states, s.deck()), 0.5);
    // An edit to another value of the same widget: that value comes from the file, h stays.
    reload(&mut s, &path, &deck_text("0.1", "2.0", " (edited)"));
    assert_eq!(h_of(&mut states, s.deck()), 0.5);
    let slide = s.deck().slides[1].clone();
    let turns = states.slide(&slide).param(&[0], "turns");
    assert_eq!(turns, Some(ParamSnapshot::F64(2.0)));
    // The file changes h itself: the file wins.
    reload(&mut s, &path, &deck_text("0.3", "2.0", " (edited)"));
    assert_eq!(h_of(&mut states, s.deck()), 0.3);
    // Tweak again, then R: back to the file's value.
    let slide = s.deck().slides[1].clone();
    states
        .slide(&slide)
        .set_param(&[0], H, ParamSnapshot::F64(0.9));
    assert_eq!(h_of(&mut states, s.deck()), 0.9);
    states.slide(&slide).reset();
    assert_eq!(h_of(&mut states, s.deck()), 0.3);
}

#[test]
fn bookmarks_store_recall_and_declared() {
    let (_dir, _path, s) = session(&deck_text("0.1", "3.0", ""));
    let slide = s.deck().slides[1].clone();
    let mut state = SlideState::default();
    state.ensure_widgets(&slide);
    state.set_param(&[0], H, ParamSnapshot::F64(0.5));
    let mut marks = Bookmarks::default();
    marks.store(3, &slide, &mut state);
    state.set_param(&[0], H, ParamSnapshot::F64(0.05));
    let (key, snap) = marks.get(3).unwrap().clone();
    assert_eq!(key, "spiral");
    state.restore(&slide, &snap);
    assert_eq!(state.param(&[0], H), Some(ParamSnapshot::F64(0.5)));
    // Declared in the deck: key 1 sets h = 0.8.
    let decl = s.deck().bookmarks[0].clone();
    apply_declared(&decl, &slide, &mut state);
    assert_eq!(state.param(&[0], H), Some(ParamSnapshot::F64(0.8)));
}

#[test]
fn write_back_changes_only_the_tweaked_bytes_and_failure_leaves_the_original() {
    let original = deck_text("0.1", "3.0", "");
    let (_dir, path, s) = session(&original);
    let slide = s.deck().slides[1].clone();
    let mut state = SlideState::default();
    state.ensure_widgets(&slide);
    state.set_param(&[0], H, ParamSnapshot::F64(0.625));
    state.set_param(&[0], "turns", ParamSnapshot::F64(4.5));

    // A write that fails half-way (disk full): the deck is untouched, no temp file is left.
    let failed = write_atomic_with(&path, "partial", |tmp, bytes| {
        std::fs::write(tmp, &bytes[..3])?;
        Err(std::io::Error::other("disk full"))
    });
    assert!(failed.is_err());
    assert_eq!(std::fs::read_to_string(&path).unwrap(), original);
    let leftovers: Vec<_> = std::fs::read_dir(path.parent().unwrap())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(leftovers.len(), 1, "{leftovers:?}");

    assert_eq!(write_back(&path, &slide, &mut state), Ok(2));
    let written = std::fs::read_to_string(&path).unwrap();
    assert_eq!(
        written,
        original
            .replace("h: 0.1,", "h: 0.625,")
            .replace("turns: 3.0", "turns: 4.5"),
        "only the two values changed"
    );
    let deck = parse_deck(&written, &path).unwrap();
    let mut states = DeckState::default();
    assert_eq!(h_of(&mut states, &deck), 0.625);
    // Nothing tweaked any more relative to the new file.
    let slide = deck.slides[1].clone();
    let mut fresh = SlideState::default();
    fresh.ensure_widgets(&slide);
    assert_eq!(write_back(&path, &slide, &mut fresh), Ok(0));
}

#[test]
fn write_back_into_the_bundled_lecture_keeps_every_other_byte() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("slides/lecture.ron");
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("lecture.ron");
    std::fs::copy(&src, &path).unwrap();
    let original = std::fs::read_to_string(&path).unwrap();
    let deck = load_deck(&path).unwrap();
    let i = deck
        .slides
        .iter()
        .position(|s| {
            s.body.iter().any(|b| {
                matches!(
                    b,
                    lectern::deck::Block::Widget(lectern::widgets::WidgetSpec::Spiral(_))
                )
            })
        })
        .expect("the lecture has the spiral slide");
    let slide = deck.slides[i].clone();
    let mut state = SlideState::default();
    state.ensure_widgets(&slide);
    let path_of_widget = lectern::app::tweaks::widget_paths(&slide)[0].clone();
    assert!(state.set_param(&path_of_widget, H, ParamSnapshot::F64(0.25)));
    assert_eq!(write_back(&path, &slide, &mut state), Ok(1));
    let written = std::fs::read_to_string(&path).unwrap();
    // Exactly one span differs: a common prefix and suffix cover everything else.
    let prefix = original
        .bytes()
        .zip(written.bytes())
        .take_while(|(a, b)| a == b)
        .count();
    let suffix = original
        .bytes()
        .rev()
        .zip(written.bytes().rev())
        .take_while(|(a, b)| a == b)
        .count();
    assert_eq!(&original[prefix..original.len() - suffix], "1");
    assert_eq!(&written[prefix..written.len() - suffix], "25");
    let again = load_deck(&path).unwrap();
    let mut states = DeckState::default();
    let s = &again.slides[i];
    let st = states.slide(s);
    st.ensure_widgets(s);
    assert_eq!(st.param(&path_of_widget, H), Some(ParamSnapshot::F64(0.25)));
}

#[test]
fn pacing_ahead_behind_with_pauses() {
    let text = deck_text("0.1", "3.0", "");
    let deck = parse_deck(&text, Path::new("t.ron")).unwrap(); // budgets 60 + 90
    let mut p = Pacing::new(&deck);
    p.tick(0.0);
    p.tick(40.0); // 40 s on slide 1 (budget 60)
    let r = p.report();
    assert_eq!((r.slide_elapsed, r.slide_left), (40.0, 20.0));
    assert_eq!(r.ahead, 0.0, "within the slide's budget you are on plan");
    p.toggle_pause(40.0);
    p.tick(500.0); // paused: counts nowhere
    p.toggle_pause(500.0);
    assert_eq!(p.report().total_elapsed, 40.0);
    p.goto(1, 510.0); // 10 more seconds on slide 1, then slide 2
    let r = p.report();
    assert_eq!(r.total_elapsed, 50.0);
    assert_eq!(
        r.ahead, 10.0,
        "left slide 1 after 50 of its 60 s: 10 s ahead"
    );
    p.tick(620.0); // 110 s on slide 2 (budget 90)
    let r = p.report();
    assert_eq!(r.slide_left, -20.0);
    assert_eq!(r.planned_total, 150.0);
    assert_eq!(r.total_elapsed, 160.0);
    assert_eq!(
        r.ahead, -10.0,
        "planned 60 + 90 = 150, spent 160: 10 s behind"
    );
    assert_eq!(r.total_left, -10.0);
    p.reset(620.0);
    assert_eq!(p.report().total_elapsed, 0.0);
    let rec = p.rehearsal_ron(&deck);
    assert!(
        rec.contains("spiral") && rec.contains("planned_secs"),
        "{rec}"
    );
}

#[test]
fn presenter_view_snapshot() {
    use egui_kittest::{Harness, SnapshotOptions};
    let text = deck_text("0.1", "3.0", "");
    let deck = parse_deck(&text, Path::new("t.ron")).unwrap();
    let mut p = Pacing::new(&deck);
    p.tick(0.0);
    p.tick(75.0); // 15 s over the first slide's minute
    let mut states = DeckState::default();
    let mut harness = Harness::builder()
        .with_size([1280.0, 800.0])
        .wgpu()
        .build_ui(|ui| {
            let info = PresenterInfo {
                pace: p.report(),
                problems: &[],
                bookmarks: &[(1, "big h (spiral)".to_owned())],
            };
            presenter_ui(ui, &deck, 0, &mut states, &info);
        });
    harness.run_steps(3);
    harness.snapshot_options(
        "presenter-view",
        &SnapshotOptions::new().threshold(2.0).max_failed_pixels(40),
    );
}
