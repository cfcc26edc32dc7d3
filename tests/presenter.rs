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

use crate::common;

const H: &str = "h";

fn deck_text(h: &str, turns: &str, extra_title: &str) -> String {
    format!(
        "// spiral deck\n(\n    title: \"t\",\n    slides: [\n        (id: \"intro\", title: \"Intro{extra_title}\", seconds: 60),\n        (\n            id: \"spiral\",\n            title: \"Spiral\",\n            body: [Widget(Spiral(({circle}, h: {h}, turns: {turns}, compare: true)))], // keep\n            notes: \"Drag h.\",\n            seconds: 90,\n        ),\n    ],\n    bookmarks: [(key: 1, slide: \"spiral\", label: \"big h\", set: [(\"h\", 0.8)])],\n)\n",
        circle = common::CIRCLE
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

/// A parameter written `ζ` in the equation answers to `zeta` in a bookmark (and the other way
/// round, `ω` for `omega`), as names in expressions do: no Greek keyboard needed.
#[test]
fn bookmarks_name_greek_parameters_in_ascii_and_the_other_way_round() {
    let text = r#"(
    title: "t",
    slides: [(id: "osc", title: "Osc", body: [Widget(SlopeField((ode: Inline((vars: ["x", "v"], rhs: ["v", "-2*ζ*omega*v - omega^2*x"], params: {"ζ": 0.15, "omega": 2.0}, ranges: {"ζ": (0.0, 1.5), "omega": (0.5, 4.0)}, initial: [1.0, 0.0])), h: 0.1, t_end: 5.0, exact: false)))])],
    bookmarks: [(key: 1, slide: "osc", set: [("zeta", 0.5), ("ω", 3.0)])],
)"#;
    let (_dir, _path, s) = session(text);
    let slide = s.deck().slides[0].clone();
    let mut state = SlideState::default();
    apply_declared(&s.deck().bookmarks[0], &slide, &mut state);
    assert_eq!(state.param(&[0], "ζ"), Some(ParamSnapshot::F64(0.5)));
    assert_eq!(state.param(&[0], "omega"), Some(ParamSnapshot::F64(3.0)));
    // the tweaks' own lookups take either spelling too
    assert!(state.set_param(&[0], "ω", ParamSnapshot::F64(2.5)));
    assert_eq!(state.param(&[0], "omega"), Some(ParamSnapshot::F64(2.5)));
    assert_eq!(state.param(&[0], "zeta"), Some(ParamSnapshot::F64(0.5)));
    assert_eq!(state.param(&[0], "eta"), None, "no near miss");
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
    let (_dir, path) = common::lecture_copy();
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
            let marks = [(1, "big h (spiral)".to_owned())];
            let info = PresenterInfo::new(p.report(), &[], &marks);
            presenter_ui(ui, &deck, 0, &mut states, &info, None);
        });
    harness.run_steps(3);
    harness.snapshot_options(
        "presenter-view",
        &SnapshotOptions::new().threshold(2.0).max_failed_pixels(40),
    );
}

/// In scene mode the presenter's left side is the scene panel, not the slide and its controls.
#[test]
fn presenter_view_in_scene_mode_shows_the_scene_panel() {
    use egui_kittest::Harness;
    use egui_kittest::kittest::Queryable as _;
    let text = deck_text("0.1", "3.0", "");
    let deck = parse_deck(&text, Path::new("t.ron")).unwrap();
    let p = Pacing::new(&deck);
    let mut states = DeckState::default();
    let mut scene_mode = true;
    let mut harness = Harness::builder()
        .with_size([1280.0, 800.0])
        .build_ui(|ui| {
            let info = PresenterInfo::new(p.report(), &[], &[]);
            let mut panel = |ui: &mut egui::Ui| {
                ui.label("scene panel: fish count");
            };
            let scene: Option<lectern::app::presenter::SceneControls> =
                scene_mode.then_some(&mut panel);
            presenter_ui(ui, &deck, 1, &mut states, &info, scene);
        });
    harness.run_steps(2);
    assert!(harness.query_by_label("scene panel: fish count").is_some());
    assert!(
        harness.query_by_label_contains("Live controls").is_none(),
        "scene mode: the slide's controls give way to the scene panel"
    );
    drop(harness);
    // The same view in slide mode shows the slide's controls and no scene panel.
    scene_mode = false;
    let mut harness = Harness::builder()
        .with_size([1280.0, 800.0])
        .build_ui(|ui| {
            let info = PresenterInfo::new(p.report(), &[], &[]);
            let mut panel = |ui: &mut egui::Ui| {
                ui.label("scene panel: fish count");
            };
            let scene: Option<lectern::app::presenter::SceneControls> =
                scene_mode.then_some(&mut panel);
            presenter_ui(ui, &deck, 1, &mut states, &info, scene);
        });
    harness.run_steps(2);
    assert!(harness.query_by_label("scene panel: fish count").is_none());
    assert!(harness.query_by_label_contains("Live controls").is_some());
}

fn app_harness(path: &Path) -> egui_kittest::Harness<'static, lectern::app::LecternApp> {
    let app = lectern::app::LecternApp::new(DeckSession::open(path).unwrap());
    egui_kittest::Harness::builder()
        .with_size([960.0, 540.0])
        .wgpu()
        .build_ui_state(
            |ui, app: &mut lectern::app::LecternApp| app.frame_ui(ui),
            app,
        )
}

/// Sets the spiral slide's `h` in the running app, as a drag of its slider would.
fn tweak_h(h: &mut egui_kittest::Harness<'static, lectern::app::LecternApp>, value: f64) {
    let slide = h.state().session().deck().slides[1].clone();
    let state = h.state_mut().slide_state(1).unwrap();
    state.ensure_widgets(&slide);
    assert!(state.set_param(&[0], H, ParamSnapshot::F64(value)));
}

/// `Ctrl+S` pressed in the app: the deck file gets the tweaked value and nothing else changes;
/// the live tweaks are also saved for `export --with-tweaks`.
#[test]
fn ctrl_s_in_the_app_writes_back_the_tweak() {
    use lectern::app::tweak_file::{TweakEntry, TweakFile};
    let (dir, path, _) = session(&deck_text("0.1", "3.0", ""));
    let mut h = app_harness(&path);
    h.run_steps(2);
    h.key_press(egui::Key::ArrowRight);
    h.run_steps(2);
    assert_eq!(h.state().nav().index(), 1);
    tweak_h(&mut h, 0.5);
    h.run_steps(1);
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::S);
    h.run_steps(2);
    let written = std::fs::read_to_string(&path).unwrap();
    assert_eq!(
        written,
        deck_text("0.5", "3.0", ""),
        "only the bytes of h change"
    );
    let tweaks = TweakFile::load(&dir.path().join("talk.tweaks.ron")).unwrap();
    assert_eq!(
        tweaks.slides.get("spiral"),
        Some(&vec![TweakEntry {
            widget: 0,
            param: H.to_owned(),
            value: ParamSnapshot::F64(0.5)
        }])
    );
    // Without a tweak, Ctrl+S leaves the file alone.
    let mut h2 = app_harness(&path);
    h2.run_steps(2);
    h2.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::S);
    h2.run_steps(2);
    assert_eq!(std::fs::read_to_string(&path).unwrap(), written);
}

fn mean_abs_diff(a: &image::RgbaImage, b: &image::RgbaImage) -> f64 {
    assert_eq!(a.dimensions(), b.dimensions());
    let sum: u64 = a
        .as_raw()
        .iter()
        .zip(b.as_raw())
        .map(|(x, y)| u64::from(x.abs_diff(*y)))
        .sum();
    sum as f64 / a.as_raw().len() as f64
}

/// `E` pressed in the app exports the slide as shown (tweak included) and the tweak state;
/// `lectern export --with-tweaks` then renders the same image, and without the tweaks a
/// different one.
#[test]
fn e_in_the_app_and_export_with_tweaks_show_what_was_presented() {
    let (dir, path, _) = session(&deck_text("0.1", "3.0", ""));
    let mut h = app_harness(&path);
    h.run_steps(2);
    h.key_press(egui::Key::ArrowRight);
    h.run_steps(2);
    tweak_h(&mut h, 0.8);
    h.run_steps(1);
    h.key_press(egui::Key::E);
    h.run_steps(2);
    let live_file = dir.path().join("spiral-live.png");
    let live = image::open(&live_file)
        .unwrap_or_else(|e| panic!("{}: {e}", live_file.display()))
        .to_rgba8();
    let tweaks = dir.path().join("talk.tweaks.ron");
    assert!(tweaks.exists(), "E also saves the live tweaks");

    let export = |out: &str, with: Option<&Path>| {
        let mut cmd = std::process::Command::new(env!("CARGO_BIN_EXE_lectern"));
        cmd.arg("export")
            .arg(&path)
            .arg("--out")
            .arg(dir.path().join(out));
        if let Some(file) = with {
            cmd.arg("--with-tweaks").arg(file);
        }
        let o = cmd.output().unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        image::open(dir.path().join(out).join("slide-02.png"))
            .unwrap()
            .to_rgba8()
    };
    let tweaked = export("tweaked", Some(&tweaks));
    let plain = export("plain", None);
    let same = mean_abs_diff(&tweaked, &live);
    let other = mean_abs_diff(&plain, &live);
    eprintln!("mean |diff| per channel: with tweaks {same:.4}, without {other:.4}");
    assert!(
        same < 0.05,
        "export --with-tweaks differs from the live render by {same}"
    );
    assert!(
        other > 0.5,
        "the tweak must change the image (diff {other})"
    );
}

#[test]
fn a_broken_tweaks_file_names_its_line_and_stale_entries_are_reported() {
    use lectern::app::tweak_file::TweakFile;
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("bad.tweaks.ron");
    std::fs::write(
        &bad,
        "(\n  slides: {\n    \"spiral\": [(widget: 0, param: \"h\", value: F64(0.5)\n",
    )
    .unwrap();
    let err = TweakFile::load(&bad).unwrap_err().to_string();
    assert!(err.contains("bad.tweaks.ron:"), "{err}");

    let good = dir.path().join("good.tweaks.ron");
    std::fs::write(
        &good,
        "(slides: {\"spiral\": [(widget: 0, param: \"h\", value: F64(0.5)), (widget: 3, param: \"h\", value: F64(0.5))], \"gone\": []})",
    )
    .unwrap();
    let tweaks = TweakFile::load(&good).unwrap();
    let deck = parse_deck(&deck_text("0.1", "3.0", ""), Path::new("t.ron")).unwrap();
    assert_eq!(tweaks.unknown_slides(&deck), vec!["gone".to_owned()]);
    let mut state = SlideState::default();
    let problems = tweaks.apply(&deck, 1, &mut state);
    assert_eq!(problems.len(), 1, "{problems:?}");
    assert_eq!(state.param(&[0], H), Some(ParamSnapshot::F64(0.5)));
}

/// On an optional (`skip: true`) slide the presenter's timer says it is outside the plan, not
/// "of 0:00".
#[test]
fn an_optional_slide_is_timed_outside_the_plan() {
    use egui::epaint::Shape;
    use egui_kittest::Harness;
    let text = r#"(title: "T", slides: [
        (title: "One", body: [Text("a")], seconds: 60),
        (title: "Extra", body: [Text("b")], skip: true),
    ])"#;
    let deck = parse_deck(text, Path::new("t.ron")).unwrap();
    let timer_lines = |index: usize| {
        let mut p = Pacing::new(&deck);
        p.tick(0.0);
        p.goto(index, 5.0);
        p.tick(12.0);
        let mut states = DeckState::default();
        let mut harness = Harness::builder()
            .with_size([1280.0, 800.0])
            .build_ui(|ui| {
                let info = PresenterInfo::new(p.report(), &[], &[]);
                presenter_ui(ui, &deck, index, &mut states, &info, None);
            });
        harness.run_steps(2);
        let mut lines = Vec::new();
        for clipped in &harness.output().shapes {
            if let Shape::Text(t) = &clipped.shape
                && t.galley.job.text.starts_with("this slide")
            {
                lines.push(t.galley.job.text.clone());
            }
        }
        lines
    };
    let planned = timer_lines(0);
    assert!(
        planned.iter().any(|l| l.contains(" of 1:00")),
        "{planned:?}"
    );
    let optional = timer_lines(1);
    assert!(
        optional
            .iter()
            .any(|l| l.contains("optional: outside the plan")),
        "{optional:?}"
    );
    assert!(
        !optional.iter().any(|l| l.contains("of 0:00")),
        "{optional:?}"
    );
}
