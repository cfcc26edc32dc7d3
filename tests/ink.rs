//! Drawing on slides, driven as a lecturer drives it (egui_kittest): `D` and a drag leave a
//! stroke that the snapshot shows, the drag reaches neither the plot nor "click to advance",
//! `Ctrl+Z` takes it away, `L` shows the laser and saves nothing; ink survives slide changes,
//! restarts and edits on disk; the presenter's view draws in the same canvas units; and
//! `lectern export` draws the ink unless `--no-ink`.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

use egui::{Event, Key, Modifiers, PointerButton, Pos2, pos2};
use egui_kittest::{Harness, SnapshotOptions};
use lectern::app::LecternApp;
use lectern::app::ink::InkTool;
use lectern::app::theme::fit_canvas;
use lectern::deck::DeckSession;
use lectern::deck::ink::{CanvasFrame, Ink, Stroke, Tool, ink_file_path};
use lectern::widgets::ParamSnapshot;

const SIZE: [f32; 2] = [960.0, 540.0];

/// What the harness gives the app: the window less egui_kittest's 8-point outer margin.
fn window() -> egui::Rect {
    egui::Rect::from_min_size(Pos2::ZERO, egui::vec2(SIZE[0], SIZE[1])).shrink(8.0)
}

/// Where the audience view puts the 16:9 canvas in the window, as the slide renderer fits it.
fn canvas() -> CanvasFrame {
    let (rect, scale) = fit_canvas(window(), 16.0 / 9.0);
    CanvasFrame {
        min_points: rect.min.into(),
        points_per_unit: scale,
    }
}

/// A fixed deck: a title slide, a slide whose plot takes drags (the slope field's start point),
/// and a plain one.
const DECK: &str = r#"(
    title: "Ink deck",
    slides: [
        (id: "t", title: "Drawing on slides", layout: Title, body: [Text("Pen, highlighter, laser")]),
        (id: "field", title: "A plot that takes drags", body: [
            Widget(SlopeField((ode: Inline((vars: ["x"], rhs: ["cos(t) - x"], initial: [1.5],
                exact: Some(["(cos(t) + sin(t))/2 + (x - (cos(t0) + sin(t0))/2)*exp(-(t - t0))"]))),
                start: (0.0, 1.5), h: 0.5, t_end: 8.0,
                view: (0.0, 8.0, -1.5, 2.0), exact: true))),
        ]),
        (id: "plain", title: "Plain", body: [Text("Nothing to drag here.")]),
    ],
)"#;

fn deck_dir() -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("ink.ron");
    std::fs::write(&path, DECK).unwrap();
    (dir, path)
}

fn harness(path: &Path) -> Harness<'static, LecternApp> {
    let app = LecternApp::new(DeckSession::open(path).unwrap());
    let mut h = Harness::builder()
        .with_size(SIZE)
        .with_render_cursor(false)
        .wgpu()
        .build_ui_state(|ui, app: &mut LecternApp| app.frame_ui(ui), app);
    h.run_steps(3);
    h
}

fn press(h: &mut Harness<'static, LecternApp>, key: Key) {
    h.key_press(key);
    h.run_steps(2);
}

/// A drag along `path`, one frame per point, as a mouse gives it.
fn drag(h: &mut Harness<'static, LecternApp>, path: &[Pos2]) {
    let button = |pos, pressed| Event::PointerButton {
        pos,
        button: PointerButton::Primary,
        pressed,
        modifiers: Modifiers::NONE,
    };
    h.event(Event::PointerMoved(path[0]));
    h.event(button(path[0], true));
    h.run_steps(1);
    for p in &path[1..] {
        h.event(Event::PointerMoved(*p));
        h.run_steps(1);
    }
    h.event(button(path[path.len() - 1], false));
    h.run_steps(1);
    h.event(Event::PointerGone);
    h.run_steps(2);
}

/// A click (press and release in one frame) at `pos`.
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

/// A circle of radius `r` points around `c`, as a drag path.
fn circle(c: Pos2, r: f32) -> Vec<Pos2> {
    (0..=40)
        .map(|i| {
            let a = i as f32 / 40.0 * std::f32::consts::TAU;
            c + egui::vec2(a.cos(), a.sin()) * r
        })
        .collect()
}

fn start_point(h: &mut Harness<'static, LecternApp>) -> (ParamSnapshot, ParamSnapshot) {
    let state = h.state_mut().slide_state(1).unwrap();
    (
        state.param(&[0], "start.0").unwrap(),
        state.param(&[0], "start.1").unwrap(),
    )
}

/// The toasts ("pen 1: drag on the slide", "stroke undone") sit in a band at the top.
const TOAST_BAND_PX: u32 = 60;

/// The box (min x, min y, max x, max y) of the pixels where two same-sized images differ by
/// more than `tol` in some channel, and how many there are; the toast band is left out.
fn diff_box(a: &image::RgbaImage, b: &image::RgbaImage, tol: u8) -> (Option<[u32; 4]>, usize) {
    diff_box_from(a, b, tol, TOAST_BAND_PX)
}

fn diff_box_from(
    a: &image::RgbaImage,
    b: &image::RgbaImage,
    tol: u8,
    first_row: u32,
) -> (Option<[u32; 4]>, usize) {
    assert_eq!(a.dimensions(), b.dimensions());
    let mut bx: Option<[u32; 4]> = None;
    let mut n = 0;
    for (x, y, p) in a.enumerate_pixels().filter(|(_, y, _)| *y >= first_row) {
        let q = b.get_pixel(x, y);
        if p.0.iter().zip(q.0).any(|(u, v)| u.abs_diff(v) > tol) {
            n += 1;
            bx = Some(match bx {
                None => [x, y, x, y],
                Some([x0, y0, x1, y1]) => [x0.min(x), y0.min(y), x1.max(x), y1.max(y)],
            });
        }
    }
    (bx, n)
}

fn snapshot_options() -> SnapshotOptions {
    SnapshotOptions::new().threshold(2.0).max_failed_pixels(40)
}

#[test]
fn d_and_a_drag_draw_a_stroke_the_plot_never_sees_and_ctrl_z_removes_it() {
    let (_dir, path) = deck_dir();
    let mut h = harness(&path);
    press(&mut h, Key::ArrowRight);
    assert_eq!(h.state().nav().index(), 1);
    let start_before = start_point(&mut h);
    let before = h.render().unwrap();

    press(&mut h, Key::D);
    assert_eq!(h.state().ink().tool(), Some(InkTool::Pen));
    // Around the middle of the plot, where a drag would move the slope field's start point.
    let centre = pos2(480.0, 330.0);
    drag(&mut h, &circle(centre, 80.0));
    assert_eq!(
        h.state().nav().index(),
        1,
        "drawing does not change the slide"
    );
    assert_eq!(
        start_point(&mut h),
        start_before,
        "the plot did not get the drag"
    );
    let strokes = h.state().ink().file().ink().strokes("field").to_vec();
    assert_eq!(strokes.len(), 1);
    let s = &strokes[0];
    assert_eq!((s.tool, s.color), (Tool::Pen, 0));
    // In canvas units, as the window's canvas maps them.
    let frame = canvas();
    let c = frame.canvas_from_screen(centre.into());
    let radius = 80.0 / frame.points_per_unit;
    for p in &s.points {
        let r = (p[0] - c[0]).hypot(p[1] - c[1]);
        assert!(
            (r - radius).abs() < 1.0,
            "point {p:?} at r = {r}, not {radius}"
        );
    }
    assert!(s.points.len() >= 20, "{} points", s.points.len());
    // Saved at once, beside the deck.
    let saved = std::fs::read_to_string(ink_file_path(&path)).unwrap();
    let saved = Ink::parse(&saved, &path).unwrap();
    assert_eq!(saved.strokes("field"), strokes.as_slice());

    // The stroke is on screen, and only around the circle.
    h.run_steps(1);
    let after = h.render().unwrap();
    let (bx, n) = diff_box(&before, &after, 24);
    let [x0, y0, x1, y1] = bx.expect("the stroke shows");
    assert!(n > 300, "only {n} pixels changed");
    let reach = 80.0 + 6.0;
    assert!(
        x0 as f32 >= centre.x - reach
            && x1 as f32 <= centre.x + reach
            && y0 as f32 >= centre.y - reach
            && y1 as f32 <= centre.y + reach,
        "changed pixels {bx:?} outside the circle"
    );
    h.snapshot_options("ink-pen-circle", &snapshot_options());

    // A click while drawing is a dot, not "next slide".
    let dot = pos2(100.0, 480.0);
    click(&mut h, dot);
    assert_eq!(h.state().nav().index(), 1, "a click while drawing stays");
    assert_eq!(h.state().ink().file().ink().strokes("field").len(), 2);

    // Ctrl+Z twice: both gone, on screen and in the file.
    for _ in 0..2 {
        h.key_press_modifiers(Modifiers::CTRL, Key::Z);
        h.run_steps(2);
    }
    assert!(h.state().ink().file().ink().strokes("field").is_empty());
    let saved = std::fs::read_to_string(ink_file_path(&path)).unwrap();
    assert!(Ink::parse(&saved, &path).unwrap().is_empty());
    h.event(Event::PointerGone);
    h.run_steps(2);
    let undone = h.render().unwrap();
    let (bx, n) = diff_box(&before, &undone, 24);
    assert!(n == 0, "{n} pixels still differ in {bx:?}");

    // D again leaves drawing: a click on the background advances again.
    press(&mut h, Key::D);
    assert_eq!(h.state().ink().tool(), None);
    click(&mut h, pos2(20.0, 20.0));
    assert_eq!(h.state().nav().index(), 2);
}

#[test]
fn without_drawing_the_same_drag_moves_the_plot() {
    // The counterpart of the test above: proves the drag there would have reached the plot.
    let (_dir, path) = deck_dir();
    let mut h = harness(&path);
    press(&mut h, Key::ArrowRight);
    let start_before = start_point(&mut h);
    drag(&mut h, &circle(pos2(480.0, 330.0), 80.0));
    assert_ne!(start_point(&mut h), start_before);
    assert!(!ink_file_path(&path).exists());
}

#[test]
fn laser_shows_a_dot_and_saves_nothing() {
    let (_dir, path) = deck_dir();
    let mut h = harness(&path);
    let before = h.render().unwrap();
    press(&mut h, Key::L);
    assert_eq!(h.state().ink().tool(), Some(InkTool::Laser));
    for x in [300.0, 340.0, 380.0, 420.0] {
        h.event(Event::PointerMoved(pos2(x, 200.0)));
        h.run_steps(1);
    }
    let lit = h.render().unwrap();
    // White centre, red ring, at the pointer.
    let dot = lit.get_pixel(420, 200).0;
    let ring = lit.get_pixel(420 + 3, 200).0;
    assert!(
        dot.iter().take(3).all(|&c| c > 200),
        "white at the pointer: {dot:?}"
    );
    assert!(
        ring[0] > 200 && ring[1] < 80,
        "laser red around it: {ring:?}"
    );
    let (bx, _) = diff_box(&before, &lit, 24);
    let [x0, y0, x1, y1] = bx.unwrap();
    assert!(x0 >= 280 && x1 <= 440 && y0 >= 180 && y1 <= 220, "{bx:?}");
    h.snapshot_options("ink-laser", &snapshot_options());
    // The trail fades; the dot stays where the pointer rests.
    h.run_steps(60);
    let rested = h.render().unwrap();
    let (bx, _) = diff_box(&before, &rested, 24);
    let [x0, _, x1, _] = bx.unwrap();
    assert!(x0 >= 400 && x1 <= 440, "trail gone, dot left: {bx:?}");
    // Nothing drawn, nothing saved; a click with the laser stays on the slide.
    click(&mut h, pos2(420.0, 200.0));
    assert_eq!(h.state().nav().index(), 0);
    assert!(h.state().ink().file().ink().is_empty());
    assert!(!ink_file_path(&path).exists(), "the laser writes no file");
    // Esc leaves the laser; the dot goes.
    press(&mut h, Key::Escape);
    assert_eq!(h.state().ink().tool(), None);
    let off = h.render().unwrap();
    assert_eq!(diff_box(&before, &off, 24).1, 0);
}

#[test]
fn ink_stays_on_its_slide_across_slide_changes_and_restarts() {
    let (_dir, path) = deck_dir();
    let mut h = harness(&path);
    press(&mut h, Key::ArrowRight);
    press(&mut h, Key::H);
    press(&mut h, Key::Num2);
    drag(
        &mut h,
        &[pos2(200.0, 150.0), pos2(400.0, 150.0), pos2(600.0, 152.0)],
    );
    press(&mut h, Key::ArrowRight);
    press(&mut h, Key::ArrowLeft);
    let strokes = h.state().ink().file().ink().strokes("field").to_vec();
    assert_eq!(strokes.len(), 1, "still there after next and back");
    assert_eq!((strokes[0].tool, strokes[0].color), (Tool::Highlighter, 1));
    assert!(h.state().ink().file().ink().strokes("plain").is_empty());
    h.run_steps(1);
    let shown = h.render().unwrap();
    drop(h);

    let mut h = harness(&path);
    press(&mut h, Key::ArrowRight);
    assert_eq!(h.state().ink().file().ink().strokes("field"), strokes);
    h.run_steps(1);
    let again = h.render().unwrap();
    assert_eq!(
        diff_box(&shown, &again, 24).1,
        0,
        "drawn the same after a restart"
    );
}

#[test]
fn ink_reloads_when_the_file_changes_and_a_damaged_file_is_ignored() {
    let (_dir, path) = deck_dir();
    let mut h = harness(&path);
    let ctx = h.ctx.clone();
    h.state_mut().watch(&ctx);
    std::thread::sleep(Duration::from_millis(100));
    let mut ink = Ink::default();
    ink.add(
        "t",
        Stroke {
            tool: Tool::Pen,
            color: 3,
            width: 6.0,
            points: vec![[100.0, 100.0], [900.0, 500.0]],
        },
    );
    std::fs::write(ink_file_path(&path), ink.to_ron()).unwrap();
    let wait_until = |h: &mut Harness<'static, LecternApp>, done: &dyn Fn(&LecternApp) -> bool| {
        let deadline = Instant::now() + Duration::from_secs(10);
        while !done(h.state()) && Instant::now() < deadline {
            std::thread::sleep(Duration::from_millis(50));
            h.run_steps(1);
        }
    };
    wait_until(&mut h, &|app| !app.ink().file().ink().is_empty());
    assert_eq!(*h.state().ink().file().ink(), ink);

    std::fs::write(ink_file_path(&path), "(slides: {\"t\": [(tool: Pen, col").unwrap();
    wait_until(&mut h, &|app| app.ink().problem().is_some());
    let problem = h.state().ink().problem().expect("reported").to_string();
    assert!(problem.contains("ink.ink.ron"), "{problem}");
    assert_eq!(
        *h.state().ink().file().ink(),
        ink,
        "the last good ink stays"
    );
}

#[test]
fn the_presenter_view_draws_in_the_same_canvas_units() {
    let (_dir, path) = deck_dir();
    let mut h = harness(&path);
    press(&mut h, Key::ArrowRight);
    press(&mut h, Key::P);
    press(&mut h, Key::D);
    // The presenter's current slide sits top left; find its canvas from a click-free probe:
    // draw a short line through its middle and check it lands mid-canvas.
    let now_rect = presenter_now_rect();
    let mid = now_rect.center();
    drag(
        &mut h,
        &[
            mid - egui::vec2(40.0, 0.0),
            mid,
            mid + egui::vec2(40.0, 0.0),
        ],
    );
    let strokes = h.state().ink().file().ink().strokes("field").to_vec();
    assert_eq!(strokes.len(), 1, "drawn on the presenter's current slide");
    let s = &strokes[0];
    let ys: Vec<f32> = s.points.iter().map(|p| p[1]).collect();
    let xs: Vec<f32> = s.points.iter().map(|p| p[0]).collect();
    let mid_x = (xs[0] + xs[xs.len() - 1]) / 2.0;
    assert!((mid_x - 960.0).abs() < 2.0, "centre x {mid_x}");
    assert!(ys.iter().all(|y| (y - 540.0).abs() < 2.0), "{ys:?}");
    // And the audience view (P again) shows it in the same place of its canvas.
    press(&mut h, Key::P);
    press(&mut h, Key::D);
    h.run_steps(2);
    let img = h.render().unwrap();
    let centre = canvas().screen_from_canvas([960.0, 540.0]);
    let p = img.get_pixel(centre[0] as u32, centre[1] as u32).0;
    assert!(
        p[0] > 180 && p[1] > 120,
        "accent ink at the audience's centre: {p:?}"
    );
    h.snapshot_options("ink-audience-after-presenter", &snapshot_options());
}

/// Where the presenter view (960x540) puts the current slide: as `presenter_ui` lays it out.
fn presenter_now_rect() -> egui::Rect {
    let full = window();
    let pad = (full.width() / 80.0).max(8.0);
    let area = full.shrink(pad);
    let left_w = area.width() * 0.62;
    let left = egui::Rect::from_min_size(area.min, egui::vec2(left_w - pad * 0.5, area.height()));
    let text = (full.height() / 40.0).clamp(12.0, 26.0);
    let ratio = 16.0 / 9.0;
    // the slide drawn on has live widgets: half the height is left to their controls
    let now_h = (left.width() / ratio).min(left.height() * 0.5);
    egui::Rect::from_min_size(
        left.min + egui::vec2(0.0, text * 1.5),
        egui::vec2(now_h * ratio, now_h),
    )
}

#[test]
fn export_draws_the_ink_exactly_where_it_is_and_no_ink_leaves_it_out() {
    let (dir, path) = deck_dir();
    let stroke = Stroke {
        tool: Tool::Pen,
        color: 1,
        width: 8.0,
        points: vec![[400.0, 300.0], [700.0, 420.0], [1000.0, 300.0]],
    };
    let mut ink = Ink::default();
    ink.add("field", stroke.clone());
    std::fs::write(ink_file_path(&path), ink.to_ron()).unwrap();
    let export = |out: &str, no_ink: bool| {
        let out = dir.path().join(out);
        let mut cmd = Command::new(env!("CARGO_BIN_EXE_lectern"));
        cmd.args([
            "export",
            path.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ]);
        cmd.args(["--size", "960x540"]);
        if no_ink {
            cmd.arg("--no-ink");
        }
        let status = cmd.status().unwrap();
        assert!(status.success());
        out
    };
    let with = export("with", false);
    let without = export("without", true);
    let load = |dir: &Path, n: u32| image::open(dir.join(format!("slide-0{n}.png"))).unwrap();
    // Slides without ink are the same either way.
    for n in [1, 3] {
        let (a, b) = (load(&with, n).to_rgba8(), load(&without, n).to_rgba8());
        assert_eq!(diff_box_from(&a, &b, 0, 0).1, 0, "slide {n}");
    }
    let (a, b) = (load(&with, 2).to_rgba8(), load(&without, 2).to_rgba8());
    let (bx, n) = diff_box_from(&a, &b, 0, 0);
    let [x0, y0, x1, y1] = bx.expect("the ink is in the export");
    // The stroke's box in pixels (960 wide: half a canvas unit each), widened by half the
    // width and a pixel of anti-aliasing.
    let half = stroke.width * 0.5 * 0.5 + 1.5;
    let (sx0, sx1, sy0, sy1) = (400.0 * 0.5, 1000.0 * 0.5, 300.0 * 0.5, 420.0 * 0.5);
    assert!(
        x0 as f32 >= sx0 - half
            && x1 as f32 <= sx1 + half
            && y0 as f32 >= sy0 - half
            && y1 as f32 <= sy1 + half,
        "differences {bx:?} outside the stroke"
    );
    assert!(
        x0 as f32 <= sx0 + 2.0 && x1 as f32 >= sx1 - 2.0 && y1 as f32 >= sy1 - 2.0,
        "the whole stroke is drawn: {bx:?}"
    );
    // A line 600 units (300 px) + 2 x 250 units long, 4 px wide: well over 1000 pixels.
    assert!(n > 1000, "{n} pixels");
    // The stroke's pixels are the theme's second ink colour (red on the dark theme).
    let on = a.get_pixel(350, 210).0;
    assert!(
        on[0] > 200 && on[1] < 120,
        "red ink at the stroke's bottom: {on:?}"
    );
}
