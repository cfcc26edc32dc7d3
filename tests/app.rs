//! The presenting app driven frame by frame (egui_kittest), as a lecturer's keys and clicks
//! drive it: navigation, overlays, click-forward, a reload error notice; with snapshots of what
//! the audience sees.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use egui::{Event, Key, Modifiers, PointerButton, Pos2};
use egui_kittest::kittest::Queryable;
use egui_kittest::{Harness, SnapshotOptions};
use lectern::app::{LecternApp, Mode, Overlay};
use lectern::deck::DeckSession;

const SIZE: [f32; 2] = [960.0, 540.0];

use crate::common;
use common::lecture_copy;

/// A small deck that stays fixed (the bundled lecture changes), for snapshots: a title slide,
/// bullets with inline markup, maths, and a live plot.
const FIXTURE: &str = concat!(
    r#"(
    title: "Fixture deck",
    slides: [
        (id: "t", title: "Integrating motion", layout: Title,
         body: [Text("From *one particle* to a tumbling rigid body")]),
        (id: "b", title: "Bullets and maths", body: [
            Bullets(["Euler: follow the slope", "Midpoint: look *half a step* ahead", "RK4: four slopes, `h^4` error"]),
            Math(src: "x(t + h) = x(t) + h dot(x)(t)"),
        ]),
        (id: "p", title: "A live plot", body: [Widget(Spiral(("#,
    r#"ode: Inline((vars: ["x", "y"], rhs: ["-y", "x"], initial: [1.0, 0.0], "#,
    r#"exact: Some(["x*cos(t - t0) - y*sin(t - t0)", "x*sin(t - t0) + y*cos(t - t0)"]))), "#,
    r#"h: 0.2, turns: 2.0)))]),
    ],
)"#
);

fn fixture() -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("fixture.ron");
    std::fs::write(&path, FIXTURE).unwrap();
    (dir, path)
}

fn harness(path: &Path) -> Harness<'static, LecternApp> {
    let app = LecternApp::new(DeckSession::open(path).unwrap());
    Harness::builder()
        .with_size(SIZE)
        .wgpu()
        .build_ui_state(|ui, app: &mut LecternApp| app.frame_ui(ui), app)
}

fn press(h: &mut Harness<'static, LecternApp>, key: Key) {
    h.key_press(key);
    h.run_steps(2);
}

fn index(h: &Harness<'static, LecternApp>) -> usize {
    h.state().nav().index()
}

fn click(h: &mut Harness<'static, LecternApp>, pos: Pos2) {
    h.event(Event::PointerMoved(pos));
    for pressed in [true, false] {
        h.event(Event::PointerButton {
            pos,
            button: PointerButton::Primary,
            pressed,
            modifiers: Modifiers::NONE,
        });
    }
    h.run_steps(2);
}

fn snapshot_options() -> SnapshotOptions {
    SnapshotOptions::new().threshold(2.0).max_failed_pixels(40)
}

#[test]
fn keys_move_through_the_deck() {
    let (_dir, path) = lecture_copy();
    let mut h = harness(&path);
    h.run_steps(2);
    let n = h.state().session().deck().slides.len();
    // End and paging stop at the last planned slide: the optional appendix follows it
    let last_planned = h
        .state()
        .session()
        .deck()
        .slides
        .iter()
        .rposition(|s| !s.skip)
        .unwrap_or(n - 1);
    assert_eq!(index(&h), 0);
    for key in [Key::ArrowRight, Key::Space, Key::PageDown] {
        press(&mut h, key);
    }
    assert_eq!(index(&h), 3.min(n - 1));
    for key in [Key::ArrowLeft, Key::PageUp, Key::ArrowUp] {
        press(&mut h, key);
    }
    assert_eq!(index(&h), 0);
    press(&mut h, Key::ArrowUp);
    assert_eq!(index(&h), 0, "no wrap before the first slide");
    press(&mut h, Key::End);
    assert_eq!(index(&h), last_planned);
    press(&mut h, Key::ArrowDown);
    assert_eq!(
        index(&h),
        last_planned,
        "no wrap after the last planned slide"
    );
    press(&mut h, Key::Home);
    assert_eq!(index(&h), 0);

    // G 2 Enter jumps; G 9 9 Enter is refused and leaves the place alone.
    for key in [Key::G, Key::Num2, Key::Enter] {
        press(&mut h, key);
    }
    assert_eq!(index(&h), 1);
    for key in [Key::G, Key::Num9, Key::Num9, Key::Enter] {
        press(&mut h, key);
    }
    assert_eq!(index(&h), 1);
    assert_eq!(*h.state().overlay(), Overlay::None);
    // G then Esc cancels without moving.
    for key in [Key::G, Key::Num1, Key::Escape] {
        press(&mut h, key);
    }
    assert_eq!(index(&h), 1);
    assert_eq!(*h.state().overlay(), Overlay::None);
}

#[test]
fn overlays_black_screen_and_scene_mode_toggle_and_escape() {
    let (_dir, path) = lecture_copy();
    let mut h = harness(&path);
    h.run_steps(2);
    press(&mut h, Key::O);
    assert_eq!(*h.state().overlay(), Overlay::Overview);
    press(&mut h, Key::Escape);
    assert_eq!(*h.state().overlay(), Overlay::None);
    h.event(Event::Text("?".into()));
    h.run_steps(2);
    assert_eq!(*h.state().overlay(), Overlay::Help);
    press(&mut h, Key::Escape);
    assert_eq!(*h.state().overlay(), Overlay::None);
    press(&mut h, Key::B);
    assert!(h.state().is_black());
    press(&mut h, Key::Escape);
    assert!(!h.state().is_black());
    press(&mut h, Key::Tab);
    assert_eq!(h.state().mode(), Mode::Scene);
    press(&mut h, Key::Tab);
    assert_eq!(h.state().mode(), Mode::Slides);
}

#[test]
fn overview_click_jumps_to_that_slide() {
    let (_dir, path) = lecture_copy();
    let mut h = harness(&path);
    h.run_steps(2);
    press(&mut h, Key::O);
    let n = h.state().session().deck().slides.len();
    let screen = egui::Rect::from_min_size(Pos2::ZERO, SIZE.into());
    let cells = lectern::app::overlays::overview_cells(n, 16.0 / 9.0, screen);
    click(&mut h, cells[n - 1].center());
    assert_eq!(*h.state().overlay(), Overlay::None);
    assert_eq!(index(&h), n - 1, "clicked the last thumbnail");
}

#[test]
fn click_on_the_slide_goes_forward_but_not_on_a_widget() {
    let (_dir, path) = lecture_copy();
    let mut h = harness(&path);
    h.run_steps(2);
    // Top-left margin of the title slide: background.
    click(&mut h, Pos2::new(20.0, 20.0));
    assert_eq!(index(&h), 1);
    // Go to the first slide with a live widget and click in its middle (the plot).
    let with_widget = h
        .state()
        .session()
        .deck()
        .slides
        .iter()
        .position(|s| {
            s.body
                .iter()
                .any(|b| matches!(b, lectern::deck::Block::Widget(_)))
        })
        .expect("the lecture has a widget slide");
    let n = with_widget + 1;
    for key in [Key::G]
        .into_iter()
        .chain(n.to_string().chars().map(digit_key))
        .chain([Key::Enter])
    {
        press(&mut h, key);
    }
    assert_eq!(index(&h), with_widget);
    click(&mut h, Pos2::new(SIZE[0] * 0.5, SIZE[1] * 0.62));
    assert_eq!(
        index(&h),
        with_widget,
        "a click on a widget does not advance"
    );
}

fn digit_key(c: char) -> Key {
    [
        Key::Num0,
        Key::Num1,
        Key::Num2,
        Key::Num3,
        Key::Num4,
        Key::Num5,
        Key::Num6,
        Key::Num7,
        Key::Num8,
        Key::Num9,
    ][c.to_digit(10).unwrap() as usize]
}

#[test]
fn broken_save_shows_the_notice_and_keeps_the_slide() {
    let (_dir, path) = lecture_copy();
    let mut h = harness(&path);
    let ctx = h.ctx.clone();
    h.state_mut().watch(&ctx);
    std::thread::sleep(Duration::from_millis(100));
    press(&mut h, Key::ArrowRight);
    let good = std::fs::read_to_string(&path).unwrap();
    let broken = good.replacen("slides: [", "slides: [[", 1);
    std::fs::write(&path, &broken).unwrap();
    let deadline = Instant::now() + Duration::from_secs(10);
    while h.state().session().error().is_none() && Instant::now() < deadline {
        std::thread::sleep(Duration::from_millis(50));
        h.run_steps(1);
    }
    let err = h
        .state()
        .session()
        .error()
        .expect("the broken save is reported")
        .clone();
    assert!(err.line > 0 && err.col > 0, "{err}");
    assert_eq!(index(&h), 1, "still on the same slide");
    h.run_steps(2);
    // The notice names file:line:col (its path is a temp folder, so no snapshot here).
    let notice = format!("lecture.ron:{}:{}:", err.line, err.col);
    assert!(
        h.query_by_label_contains(&notice).is_some(),
        "no notice with {notice}"
    );

    std::fs::write(&path, &good).unwrap();
    let deadline = Instant::now() + Duration::from_secs(10);
    while h.state().session().error().is_some() && Instant::now() < deadline {
        std::thread::sleep(Duration::from_millis(50));
        h.run_steps(1);
    }
    assert!(
        h.state().session().error().is_none(),
        "the notice goes when fixed"
    );
    h.run_steps(2);
    assert!(h.query_by_label_contains("lecture.ron:").is_none());
    assert_eq!(index(&h), 1);
}

#[test]
fn snapshots_of_slides_overview_and_help() {
    let (_dir, path) = fixture();
    let mut h = harness(&path);
    h.run_steps(3);
    h.snapshot_options("app-title", &snapshot_options());
    press(&mut h, Key::ArrowRight);
    h.run_steps(2);
    h.snapshot_options("app-bullets-math", &snapshot_options());
    press(&mut h, Key::ArrowRight);
    h.run_steps(2);
    h.snapshot_options("app-plot", &snapshot_options());
    press(&mut h, Key::O);
    h.run_steps(2);
    h.snapshot_options("app-overview", &snapshot_options());
    press(&mut h, Key::O);
    h.event(Event::Text("?".into()));
    h.run_steps(3);
    h.snapshot_options("app-help", &snapshot_options());
}

#[test]
fn frame_stats_append_one_line_per_drawn_frame_with_the_mode() {
    let (dir, path) = fixture();
    let stats = dir.path().join("frames.csv");
    let mut app = LecternApp::new(DeckSession::open(&path).unwrap());
    app.set_frame_stats(&stats).unwrap();
    let mut h = Harness::builder()
        .with_size(SIZE)
        .wgpu()
        .build_ui_state(|ui, app: &mut LecternApp| app.frame_ui(ui), app);
    h.run_steps(4);
    press(&mut h, Key::Tab);
    assert_eq!(h.state().mode(), Mode::Scene);
    h.run_steps(3);
    let text = std::fs::read_to_string(&stats).unwrap();
    let lines: Vec<(&str, f64)> = text
        .lines()
        .map(|l| {
            let (mode, ms) = l.split_once(',').unwrap();
            (mode, ms.parse().unwrap())
        })
        .collect();
    // One line per frame drawn, but the first (no interval yet).
    let frames = h.ctx.cumulative_frame_nr();
    assert_eq!(lines.len() as u64 + 1, frames, "{text}");
    assert!(lines.iter().all(|(_, ms)| *ms >= 0.0));
    let modes: Vec<&str> = lines.iter().map(|(m, _)| *m).collect();
    let first_scene = modes.iter().position(|m| *m == "scene").unwrap();
    assert!(modes[..first_scene].iter().all(|m| *m == "slides"));
    assert!(modes[first_scene..].iter().all(|m| *m == "scene"));
    assert!(modes.len() - first_scene >= 3, "{modes:?}");
}

/// The window clears to the slide's background (or the letterbox colour, or black) and then
/// does not paint those window-sized rectangles again: a frame must look the same as one that
/// paints them. Rendered headless as the window renders: cleared to the app's clear colour.
#[test]
fn window_clear_colour_shows_the_same_pixels_as_painting_the_background() {
    use std::cell::Cell;
    let (_dir, path) = fixture();
    let mut r = lectern::app::OffscreenRenderer::software_first().unwrap();
    // 16:9 (no letterbox) and 4:3 (bars above and below).
    for size in [[960, 540], [800, 600]] {
        for keys in [
            &[][..],
            &[Key::ArrowRight],
            &[Key::ArrowRight, Key::ArrowRight],
            &[Key::O],
            &[Key::B],
            &[Key::P],
        ] {
            let mut render = |window_clear: bool| {
                let mut app = LecternApp::new(DeckSession::open(&path).unwrap());
                app.set_window_clear(window_clear);
                let events: Vec<Event> = keys
                    .iter()
                    .map(|k| lectern::app::keys::press(*k, Modifiers::NONE))
                    .collect();
                let mut sent = false;
                let clear = Cell::new(egui::Color32::from_rgb(255, 0, 255));
                let img = r
                    .render_cleared(
                        size,
                        1.0,
                        |ui| {
                            // The keys once, in the first pass; the slide settles in the others.
                            if !sent {
                                ui.ctx()
                                    .input_mut(|i| i.events.extend(events.iter().cloned()));
                                sent = true;
                            }
                            app.frame_ui(ui);
                            if window_clear {
                                clear.set(app.clear_color32());
                            }
                        },
                        &clear,
                    )
                    .unwrap();
                (img, app.nav().index())
            };
            let (painted, at) = render(false);
            let (cleared, at_too) = render(true);
            assert_eq!(at, at_too);
            let mut differ = 0;
            let mut worst = 0;
            for (p, q) in painted.pixels().zip(cleared.pixels()) {
                for i in 0..3 {
                    let d = p.0[i].abs_diff(q.0[i]);
                    worst = worst.max(d);
                    differ += usize::from(d > 2);
                }
            }
            assert!(
                differ <= 20,
                "{size:?} after {keys:?}: {differ} channel values differ, worst by {worst}"
            );
        }
    }
}

/// The window drops the release of slide keys (each event egui sees costs frames): a press
/// alone must work, twice, and leave no key held in egui's input state.
#[test]
fn slide_keys_work_without_their_release_and_are_not_left_held() {
    let (_dir, path) = fixture();
    let mut h = harness(&path);
    h.run_steps(2);
    for want in [1, 2] {
        h.key_down(Key::ArrowRight);
        h.run_steps(2);
        assert_eq!(index(&h), want);
        assert!(!h.ctx.input(|i| i.key_down(Key::ArrowRight)));
    }
}

/// Every text the frame painted, rows joined.
fn painted_text(h: &Harness<'static, LecternApp>) -> String {
    use egui::epaint::Shape;
    fn walk(shape: &Shape, out: &mut String) {
        match shape {
            Shape::Vec(v) => v.iter().for_each(|s| walk(s, out)),
            Shape::Text(t) => {
                out.push_str(t.galley.text());
                out.push('\n');
            }
            _ => {}
        }
    }
    let mut out = String::new();
    for c in &h.output().shapes {
        walk(&c.shape, &mut out);
    }
    out
}

/// Live, on the lecture's slope field (slide 4, h = 0.5): `+`/`−` walk round values of h,
/// never 0.7071, and every path still ends at t_end (the readout's "error at the end"); the
/// `?` list names the widget keys; hovering the plot draws nothing more than the slide did
/// (no crosshair's unlabelled grid lines).
#[test]
fn widget_keys_walk_round_h_paths_end_at_t_end_help_names_them_no_crosshair() {
    use lectern::widgets::{ParamSnapshot, params};
    let (_dir, path) = lecture_copy();
    let mut h = harness(&path);
    h.run_steps(2);
    for _ in 0..3 {
        press(&mut h, Key::ArrowRight);
    }
    assert_eq!(index(&h), 3);
    let slide = h.state().session().deck().slides[3].clone();
    let (widget_path, spec) = slide.widgets().into_iter().next().unwrap();
    assert_eq!(spec.kind(), "slope-field");
    let state = |h: &mut Harness<'static, LecternApp>| {
        let w = h
            .state_mut()
            .slide_state(3)
            .unwrap()
            .widget_at(&widget_path)
            .unwrap();
        let hv = params::snapshot(w)
            .into_iter()
            .find_map(|(id, v)| match (id.as_str(), v) {
                ("h", ParamSnapshot::F64(x)) => Some(x),
                _ => None,
            })
            .unwrap();
        (hv, w.data().unwrap(), w.readouts())
    };
    let mut seen = Vec::new();
    for key in [Key::Plus, Key::Plus, Key::Minus, Key::Minus, Key::Minus] {
        press(&mut h, key);
        let (hv, data, readouts) = state(&mut h);
        seen.push(hv);
        let t_end = readouts
            .iter()
            .find(|r| r.name == "t_end")
            .map(|r| r.value)
            .unwrap();
        for (series, p) in &data.series {
            assert_eq!(
                p.ts.last(),
                Some(&t_end),
                "{series} at h = {hv} ends at t_end"
            );
        }
    }
    assert_eq!(seen, [1.0, 2.0, 1.0, 0.5, 0.2]);

    // hovering the plot adds no shapes (egui_plot's crosshair drew two lines)
    let plot = lectern::app::drawn_widgets(&h.ctx)
        .into_iter()
        .find(|w| w.slide == 3)
        .unwrap()
        .drawn;
    h.event(Event::PointerMoved(Pos2::new(2000.0, 2000.0)));
    h.run_steps(2);
    let away = h.output().shapes.len();
    h.event(Event::PointerMoved(plot.center()));
    h.run_steps(2);
    assert_eq!(h.output().shapes.len(), away, "hovering adds shapes");

    h.event(Event::Text("?".into()));
    h.run_steps(2);
    let help = painted_text(&h);
    for (keys, what) in [
        ("- +", "step size h"),
        ("[ ]", "step back / forward"),
        ("drag", "move the start"),
    ] {
        assert!(
            help.contains(keys) && help.contains(what),
            "{keys} {what} in the ? list"
        );
    }
}
