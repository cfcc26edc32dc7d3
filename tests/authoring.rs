//! A lecturer's own lecture, as a new user makes it: `lectern new`, then `check`, `export`
//! (PNG, PDF, `--data`) and presenting, each from a different working directory; the deck's
//! path spelt four ways gives one result; the scene works in a project without `shaders/`
//! (the built-in ones) and a project whose `shaders/` lacks one fails `check` at the widget;
//! one unparsable slide leaves the others presenting and exporting; the presenter's controls and
//! its typed-equation preview fit 1280×720; a phase plane in a column shows the view it asks for.

use crate::common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use egui_kittest::Harness;
use lectern::app::LecternApp;
use lectern::deck::DeckSession;

const TITLE: &str = "Damped oscillators and \"chaos\"";

/// `lectern ARGS` run in `cwd`, without a session folder (as on a server or in CI).
fn lectern(cwd: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_lectern"))
        .current_dir(cwd)
        .args(args)
        .env_remove("XDG_RUNTIME_DIR")
        .output()
        .unwrap()
}

fn text(o: &Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

/// A new project `chaos` in a fresh temp folder: (the temp folder, the project folder).
fn new_project() -> (tempfile::TempDir, PathBuf) {
    let tmp = tempfile::tempdir().unwrap();
    let out = lectern(tmp.path(), &["new", "chaos", "--title", TITLE]);
    assert!(out.status.success(), "{}", text(&out));
    let project = tmp_path(&tmp).join("chaos");
    (tmp, project)
}

fn tmp_path(tmp: &tempfile::TempDir) -> PathBuf {
    tmp.path().canonicalize().unwrap()
}

fn pngs(dir: &Path) -> usize {
    std::fs::read_dir(dir)
        .unwrap()
        .filter(|e| {
            e.as_ref()
                .unwrap()
                .path()
                .extension()
                .is_some_and(|x| x == "png")
        })
        .count()
}

#[test]
fn a_new_project_checks_exports_and_presents_from_any_folder() {
    let (tmp, project) = new_project();
    let deck = project.join("slides/talk.ron");
    for f in [
        "slides/talk.ron",
        "slides/problems/oscillator.ron",
        "slides/tableaux/heun3.ron",
        "slides/figures/placeholder.png",
        "scenes/water.ron",
        "README.md",
    ] {
        assert!(project.join(f).is_file(), "{f}");
    }
    let written = std::fs::read_to_string(&deck).unwrap();
    assert!(
        written.contains(r#"title: "Damped oscillators and \"chaos\"""#),
        "{written}"
    );
    // a second `new` never overwrites a lecture
    let again = lectern(tmp.path(), &["new", "chaos"]);
    assert!(
        !again.status.success() && text(&again).contains("not empty"),
        "{}",
        text(&again)
    );

    // check from inside slides/, the deck named bare
    let check = lectern(&project.join("slides"), &["check", "talk.ron"]);
    let said = text(&check);
    assert!(check.status.success(), "{said}");
    assert!(said.contains("talk.ron: 7 slides"), "{said}");
    assert!(said.contains("all good"), "{said}");
    assert!(said.contains("shaders built into lectern"), "{said}");
    assert!(!said.contains("XDG_RUNTIME_DIR"), "{said}");

    // export from somewhere else entirely, by absolute paths
    let elsewhere = tempfile::tempdir().unwrap();
    let out_dir = tmp_path(&tmp).join("export");
    let pdf = tmp_path(&tmp).join("talk.pdf");
    let export = lectern(
        elsewhere.path(),
        &[
            "export",
            deck.to_str().unwrap(),
            "--out",
            out_dir.to_str().unwrap(),
            "--pdf",
            pdf.to_str().unwrap(),
            "--data",
            "--size",
            "960x540",
        ],
    );
    let said = text(&export);
    assert!(export.status.success(), "{said}");
    assert!(!said.contains("XDG_RUNTIME_DIR"), "{said}");
    // the adapter is named in export's own summary: egui-wgpu's warning would say it twice
    assert!(!said.contains("Software rasterizer"), "{said}");
    assert_eq!(pngs(&out_dir), 7, "{said}");
    assert!(std::fs::read(&pdf).unwrap().starts_with(b"%PDF"));
    // the live oscillator's points: x' = v, v' = -2ζωv - ω²x from (1, 0) with h = 0.1
    let csv = std::fs::read_to_string(out_dir.join("slide-03-w1.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(lines.next(), Some("series,t,x,v"));
    assert_eq!(lines.next(), Some("euler,0.0,1.0,0.0"));
    assert_eq!(lines.next(), Some("euler,0.1,1.0,-0.4"));
    // `exact: false`: no reference series
    assert!(!csv.contains("\nreference,") && !csv.contains("\nexact,"));
    assert!(out_dir.join("slide-05-w1.csv").is_file());

    // present it, paging through every slide
    let rs = egui_kittest::wgpu::create_render_state(
        egui_kittest::wgpu::default_wgpu_setup(),
        egui_wgpu::RendererOptions::PREDICTABLE,
    );
    let gpu = rs.clone();
    let app = LecternApp::new(DeckSession::open(&deck).unwrap());
    let mut h = Harness::builder()
        .with_size([1280.0, 720.0])
        .renderer(egui_kittest::wgpu::WgpuTestRenderer::from_render_state(rs))
        .with_context_setup(move |ctx| {
            lectern::widgets::scene::SceneGpu::install(ctx, gpu, 1.0, false)
        })
        .build_ui_state(|ui, app: &mut LecternApp| app.frame_ui(ui), app);
    h.run_steps(3);
    let titles: Vec<String> = (h.state().session().deck().slides.iter())
        .map(|s| s.title.clone())
        .collect();
    assert_eq!(titles.len(), 7);
    assert_eq!(titles[0], TITLE);
    for i in 1..7 {
        h.key_press(egui::Key::ArrowRight);
        h.run_steps(3);
        assert_eq!(h.state().nav().index(), i);
        let state = h.state_mut().slide_state(i).unwrap();
        assert!(
            state.problems().is_empty(),
            "slide {}: {:?}",
            i + 1,
            state.problems()
        );
    }
}

/// The problem lines of `check`'s output without the deck's path as typed (`L:C: message`).
fn problems_without_path(out: &Output) -> Vec<String> {
    text(out)
        .lines()
        .filter_map(|l| {
            let at = l.find("talk.ron:")?;
            let rest = &l[at + "talk.ron:".len()..];
            rest.starts_with(|c: char| c.is_ascii_digit())
                .then(|| rest.to_owned())
        })
        .collect()
}

#[test]
fn the_deck_path_spelt_four_ways_gives_the_same_check() {
    let (tmp, project) = new_project();
    let deck = project.join("slides/talk.ron");
    // one problem, so there is something to compare: a picture that is not there
    let text_now = std::fs::read_to_string(&deck).unwrap();
    std::fs::write(
        &deck,
        text_now.replace("figures/placeholder.png", "figures/missing.png"),
    )
    .unwrap();
    let runs = [
        (PathBuf::from("/"), deck.to_str().unwrap().to_owned()),
        (tmp_path(&tmp), "chaos/slides/talk.ron".to_owned()),
        (project.clone(), "./slides/talk.ron".to_owned()),
        (project.join("slides"), "talk.ron".to_owned()),
    ];
    let mut seen = Vec::new();
    for (cwd, path) in &runs {
        let out = lectern(cwd, &["check", path]);
        assert!(!out.status.success(), "{path}: {}", text(&out));
        assert!(
            !text(&out).contains("outside the project"),
            "{path}: {}",
            text(&out)
        );
        let problems = problems_without_path(&out);
        assert_eq!(problems.len(), 1, "{path}: {}", text(&out));
        assert!(problems[0].contains("figures/missing.png"), "{problems:?}");
        seen.push(problems);
    }
    assert!(seen.windows(2).all(|w| w[0] == w[1]), "{seen:?}");
}

#[test]
fn a_shaders_folder_missing_a_shader_fails_check_at_the_scene_widget() {
    let (_tmp, project) = new_project();
    let out = lectern(&project, &["new", "with-shaders", "--with-shaders"]);
    assert!(out.status.success(), "{}", text(&out));
    let shaders = project.join("with-shaders/shaders");
    assert!(shaders.join("water.wgsl").is_file());
    // this project's own shaders/, without the sky
    std::fs::rename(&shaders, project.join("shaders")).unwrap();
    std::fs::remove_file(project.join("shaders/sky.wgsl")).unwrap();
    let out = lectern(&project, &["check", "slides/talk.ron"]);
    let said = text(&out);
    assert!(!out.status.success(), "{said}");
    let deck_text = std::fs::read_to_string(project.join("slides/talk.ron")).unwrap();
    let line = deck_text
        .lines()
        .position(|l| l.contains("scene: \"../scenes/water.ron\""))
        .unwrap()
        + 1;
    assert!(
        said.contains(&format!("talk.ron:{line}:")) && said.contains("sky.wgsl is missing"),
        "{said}"
    );
    assert!(!said.contains("shaders built into lectern"), "{said}");
}

/// A project with a Scene widget but no scene file: the water scene built into lectern is
/// drawn (and `check` says so), as with the shaders; `check` and `export` agree.
#[test]
fn a_project_without_its_scene_file_uses_the_bundled_scene() {
    let (tmp, project) = new_project();
    std::fs::remove_dir_all(project.join("scenes")).unwrap();
    let out = lectern(&project, &["check", "slides/talk.ron"]);
    let said = text(&out);
    assert!(out.status.success(), "{said}");
    assert!(said.contains("water scene built into lectern"), "{said}");
    assert_eq!(
        said.matches("water scene built into lectern").count(),
        1,
        "one note, not one per widget: {said}"
    );
    let out_dir = tmp_path(&tmp).join("export");
    let export = lectern(
        &project,
        &[
            "export",
            "slides/talk.ron",
            "--out",
            out_dir.to_str().unwrap(),
            "--size",
            "480x270",
        ],
    );
    assert!(export.status.success(), "{}", text(&export));
    assert_eq!(pngs(&out_dir), 7);
    // a scene named by hand must exist: a typo is reported, not replaced
    let deck = project.join("slides/talk.ron");
    let written = std::fs::read_to_string(&deck).unwrap();
    std::fs::write(
        &deck,
        written.replace("../scenes/water.ron", "../scenes/watr.ron"),
    )
    .unwrap();
    let out = lectern(&project, &["check", "slides/talk.ron"]);
    assert!(
        !out.status.success() && text(&out).contains("watr.ron"),
        "{}",
        text(&out)
    );
}

#[test]
fn one_unparsable_slide_leaves_the_others_presenting_and_exporting() {
    let (_tmp, project) = new_project();
    let deck = project.join("slides/talk.ron");
    let good = std::fs::read_to_string(&deck).unwrap();
    let bad = good.replacen("Widget(Convergence((", "Widget(Convergense((", 1);
    std::fs::write(&deck, &bad).unwrap();
    let line = bad.lines().position(|l| l.contains("Convergense")).unwrap() + 1;

    let check = lectern(&project, &["check", "slides/talk.ron"]);
    let said = text(&check);
    assert!(!check.status.success(), "{said}");
    assert!(said.contains(&format!("talk.ron:{line}:")), "{said}");
    assert!(said.contains("did you mean `Convergence`?"), "{said}");

    let out_dir = project.join("export");
    let args = |keep: bool| {
        let mut v = vec![
            "export",
            "slides/talk.ron",
            "--out",
            "export",
            "--size",
            "640x360",
        ];
        if keep {
            v.push("--keep-going");
        }
        v
    };
    let strict = lectern(&project, &args(false));
    assert!(!strict.status.success(), "{}", text(&strict));
    assert!(text(&strict).contains("did you mean `Convergence`?"));
    assert_eq!(pngs(&out_dir), 7, "the files are written anyway");
    std::fs::remove_dir_all(&out_dir).unwrap();
    let keep_going = lectern(&project, &args(true));
    assert!(keep_going.status.success(), "{}", text(&keep_going));
    assert_eq!(pngs(&out_dir), 7);

    // presented: the other slides as written, the broken one as an error slide
    let app = LecternApp::new(DeckSession::open(&deck).unwrap());
    let mut h = Harness::builder()
        .with_size([1280.0, 720.0])
        .wgpu()
        .build_ui_state(|ui, app: &mut LecternApp| app.frame_ui(ui), app);
    h.run_steps(2);
    let slides = &h.state().session().deck().slides;
    assert_eq!(slides.len(), 7);
    assert_eq!(slides[4].title, "⚠ Convergence: the order you can see");
    assert_eq!(slides[5].title, "Where a method is stable");
    for _ in 0..4 {
        h.key_press(egui::Key::ArrowRight);
        h.run_steps(2);
    }
    assert_eq!(h.state().nav().index(), 4);
    let body = format!("{:?}", h.state().session().deck().slides[4].body);
    assert!(
        body.contains(&format!("talk.ron:{line}:")) && body.contains("did you mean `Convergence`?"),
        "{body}"
    );
    h.key_press(egui::Key::ArrowRight);
    h.run_steps(2);
    assert_eq!(
        h.state().nav().index(),
        5,
        "paging goes on past the error slide"
    );
}

#[test]
fn the_presenter_overlay_shows_every_control_of_the_live_slide_at_720_px() {
    use egui_kittest::kittest::Queryable;
    let (_tmp, project) = new_project();
    let deck = project.join("slides/talk.ron");
    let app = LecternApp::new(DeckSession::open(&deck).unwrap());
    let mut h = Harness::builder()
        .with_size([1280.0, 720.0])
        .wgpu()
        .build_ui_state(|ui, app: &mut LecternApp| app.frame_ui(ui), app);
    h.run_steps(2);
    // the oscillator: h, two method switches, exact, then ζ and ω
    for _ in 0..2 {
        h.key_press(egui::Key::ArrowRight);
        h.run_steps(2);
    }
    h.key_press(egui::Key::P);
    h.run_steps(4);
    for name in ["zeta", "omega"] {
        let rects: Vec<egui::Rect> = h.query_all_by_label(name).map(|n| n.rect()).collect();
        assert!(!rects.is_empty(), "no {name} slider");
        for r in rects {
            assert!(
                r.bottom() <= 720.0 && r.top() >= 0.0,
                "{name} at {r:?}: below the window"
            );
        }
    }
    // the equation's fields too
    let fields: Vec<egui::Rect> = h
        .query_all_by_role(egui::accesskit::Role::TextInput)
        .map(|n| n.rect())
        .collect();
    assert_eq!(fields.len(), 2, "{fields:?}");
    assert!(fields.iter().all(|r| r.bottom() <= 720.0), "{fields:?}");

    // typing v' without ζ: the preview is large enough to read (its plot a quarter of the
    // controls' area at least: it was ~60 points of 318 before the slide gave way to it), and
    // after Enter ζ's slider stays, greyed and marked unused
    let v_field = h
        .get_all_by_role(egui::accesskit::Role::TextInput)
        .nth(1)
        .unwrap();
    v_field.focus();
    h.run_steps(2);
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::A);
    h.run_steps(1);
    h.get_all_by_role(egui::accesskit::Role::TextInput)
        .nth(1)
        .unwrap()
        .type_text("-omega^2*x");
    h.run_steps(4);
    let preview = h.get_by_label("equation preview").rect();
    let area_top = h
        .get_by_label("Live controls (R resets, Ctrl+S writes back)")
        .rect()
        .top();
    let area_h = 720.0 - area_top;
    // the plot: from under its y axis's name (a label, the only one of the preview's below
    // its values) to the preview's bottom, less the x axis and its name (at most 45 points
    // at the presenter's size)
    let y_name_bottom = (h.query_all_by_label("v").map(|n| n.rect()))
        .filter(|r| preview.contains_rect(*r))
        .map(|r| r.bottom())
        .fold(f32::NAN, f32::max);
    let plot_h = preview.bottom() - y_name_bottom - 45.0;
    assert!(
        plot_h >= area_h / 4.0 && preview.bottom() <= 721.0,
        "preview {preview:?}: its plot {plot_h} tall in a control area {area_h} tall"
    );
    h.key_press(egui::Key::Enter);
    h.run_steps(4);
    use egui_kittest::kittest::NodeT;
    let unused: Vec<_> = h
        .query_all_by_label("zeta (unused by the equation)")
        .map(|n| n.accesskit_node().is_disabled())
        .collect();
    assert!(
        !unused.is_empty() && unused.iter().all(|d| *d),
        "{unused:?}"
    );
    assert!(
        (h.query_all_by_label("omega")).all(|n| !n.accesskit_node().is_disabled()),
        "ω still moves the plot"
    );
}

/// The pain that started the issue: a phase plane inside `Columns` shows the `view` it asks for
/// (v in ±2.5, not squeezed to equal axes), and its header line (equation and readout) and
/// plot stay inside its column; beside it, a Lorenz (x, z) plane shows its whole butterfly.
#[test]
fn a_phase_plane_in_a_column_shows_its_view_and_stays_in_the_column() {
    use std::sync::Arc;
    let oscillator = r#"Widget(SlopeField((ode: Inline((vars: ["x", "v"], rhs: ["v", "-2*zeta*omega*v - omega^2*x"], params: {"zeta": 0.15, "omega": 2.0}, initial: [1.0, 0.0])), h: 0.1, t_end: 10.0, view: (-1.2, 1.2, -2.5, 2.5), aspect: Free, methods: [Euler, Rk4], exact: false)))"#;
    let lorenz = r#"Widget(SlopeField((ode: Inline((vars: ["x", "y", "z"], rhs: ["sigma*(y - x)", "x*(rho - z) - y", "x*y - beta*z"], params: {"sigma": 10.0, "rho": 28.0, "beta": 2.6666666666666665}, initial: [1.0, 1.0, 1.0])), h: 0.01, t_end: 30.0, plot: ("x", "z"), view: (-25.0, 25.0, 0.0, 55.0), methods: [Rk4], exact: false)))"#;
    let text = format!(
        "(title: \"t\", slides: [(title: \"Two planes\", body: [Columns([[{oscillator}], [{lorenz}]])])])"
    );
    let deck = Arc::new(lectern::deck::parse_deck(&text, Path::new("d.ron")).unwrap());
    let mut state = lectern::app::SlideState::default();
    let mut h = Harness::builder()
        .with_size([1280.0, 720.0])
        .build_ui(move |ui| {
            lectern::app::slide_ui(ui, &deck, 0, &mut state);
        });
    h.run_steps(3);
    let mut widgets = lectern::app::drawn_widgets(&h.ctx);
    widgets.sort_by(|a, b| a.slot.left().total_cmp(&b.slot.left()));
    assert_eq!(widgets.len(), 2, "{widgets:?}");
    let (left, right) = (&widgets[0], &widgets[1]);
    assert!(left.slot.right() <= right.slot.left(), "{left:?} {right:?}");
    for w in [left, right] {
        assert!(
            w.slot.width() <= w.content.width() / 2.0,
            "a column's share: {w:?}"
        );
        assert!(w.slot.expand(0.5).contains_rect(w.drawn), "{w:?}");
    }
    // every text in a column (header, readout, tick labels) is inside it and not clipped
    let boxes = common::text_boxes(h.output());
    let in_slot = |slot: egui::Rect| -> Vec<(String, egui::Rect)> {
        (boxes.iter())
            .filter(|(_, r, _)| slot.contains(r.center()))
            .map(|(t, r, _)| (t.replace('\u{2212}', "-").trim().to_owned(), *r))
            .collect()
    };
    for w in [left, right] {
        for (t, r) in in_slot(w.slot) {
            assert!(
                w.slot.expand(0.5).contains_rect(r),
                "{t:?} at {r:?} leaves {w:?}"
            );
        }
    }
    for (t, r, clip) in &boxes {
        assert!(clip.expand(0.5).contains_rect(*r), "{t:?} cut by its clip");
    }
    // the views: ticks at ±2 on v (an equal-aspect plot of x in ±1.2 would show v in about
    // ±0.6 at this size), and z up to 50, x from -20 to 20 on the Lorenz plane
    let ticks = |w: &lectern::app::DrawnWidget| -> Vec<String> {
        in_slot(w.slot).into_iter().map(|(t, _)| t).collect()
    };
    let osc = ticks(left);
    for want in ["2", "-2", "1", "-1"] {
        assert!(
            osc.iter().any(|t| t == want),
            "no tick {want} on v: {osc:?}"
        );
    }
    let lor = ticks(right);
    for want in ["50", "-20", "20"] {
        assert!(lor.iter().any(|t| t == want), "no tick {want}: {lor:?}");
    }
}
