//! The live window never waits for a formula: driven frame by frame through egui_kittest, the
//! app draws a slide whose formula is still being typeset at once (with a placeholder), and the
//! formula appears in a later frame; formulas of the next slides are typeset ahead.

use std::path::Path;
use std::time::{Duration, Instant};

use egui::epaint::{ClippedShape, Shape};
use egui::{Key, TextureId};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use lectern::app::LecternApp;
use lectern::deck::DeckSession;

/// Slide 6 is beyond what slide 1 typesets ahead; slide 2 is within it.
const DECK: &str = r#"(
    title: "Live maths",
    slides: [
        (id: "a", title: "Start", body: [Text("no maths here")]),
        (id: "b", title: "Next", body: [Math(src: "a^2 + b^2 = c^2")]),
        (id: "c", title: "C", body: [Text("c")]),
        (id: "d", title: "D", body: [Text("d")]),
        (id: "e", title: "E", body: [Text("e")]),
        (id: "m", title: "Maths far ahead", body: [
            Math(src: "x(t + h) = x(t) + h f(x(t), t) + h^2/2 dot.double(x)(t)"),
            Text("after the formula"),
        ]),
    ],
)"#;

fn harness(path: &Path) -> Harness<'static, LecternApp> {
    lectern::math::set_worker_program(Some(env!("CARGO_BIN_EXE_lectern").into()));
    let app = LecternApp::new(DeckSession::open(path).unwrap());
    Harness::builder()
        .with_size([960.0, 540.0])
        .wgpu()
        .with_context_setup(lectern::math::never_wait)
        .build_ui_state(|ui, app: &mut LecternApp| app.frame_ui(ui), app)
}

/// (texts drawn, number of textured meshes: formulas, as nothing else on these slides is
/// an image).
fn drawn(shapes: &[ClippedShape]) -> (Vec<String>, usize) {
    fn walk(shape: &Shape, texts: &mut Vec<String>, images: &mut usize) {
        match shape {
            Shape::Vec(v) => v.iter().for_each(|s| walk(s, texts, images)),
            Shape::Text(t) => texts.push(t.galley.text().to_owned()),
            Shape::Mesh(m) if m.texture_id != TextureId::default() => *images += 1,
            Shape::Rect(r) if r.fill_texture_id() != TextureId::default() => *images += 1,
            _ => {}
        }
    }
    let (mut texts, mut images) = (Vec::new(), 0);
    for s in shapes {
        walk(&s.shape, &mut texts, &mut images);
    }
    (texts, images)
}

fn wait_for_formula(h: &mut Harness<'static, LecternApp>) -> usize {
    let start = Instant::now();
    loop {
        std::thread::sleep(Duration::from_millis(20));
        h.step();
        let (_, images) = drawn(&h.output().shapes);
        if images > 0 {
            return images;
        }
        assert!(
            start.elapsed() < Duration::from_secs(30),
            "the formula never appeared"
        );
    }
}

#[test]
fn a_slide_whose_formula_is_typesetting_is_drawn_at_once_and_the_formula_follows() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("live.ron");
    std::fs::write(&path, DECK).unwrap();
    let mut h = harness(&path);
    h.step();
    h.step();
    // Slide 1 shown: slide 2's formula is typeset ahead, in the background.
    let start = Instant::now();
    while lectern::math::pool().busy() > 0 {
        assert!(
            start.elapsed() < Duration::from_secs(30),
            "nothing typeset ahead"
        );
        std::thread::sleep(Duration::from_millis(20));
    }

    // Keep both workers busy for their whole time budget (two formulas that compute too
    // much), so that the next formula certainly cannot be ready within a frame.
    let busy: Vec<_> = (0..2)
        .map(|i| {
            let req = lectern::math::wire::Request {
                src: format!("#range({}).map(i => i).len()", 100_000_000 + i),
                syntax: lectern::math::MathSyntax::Typst,
                style: Default::default(),
                size_px: 20.0,
                rgba: [0, 0, 0, 255],
            };
            lectern::math::pool().submit(req, true, true, None)
        })
        .collect();
    std::thread::sleep(Duration::from_millis(200)); // both picked up by the workers

    // Jump past what was typeset ahead: the very frame that handles the key draws the slide.
    h.key_press(Key::End);
    h.step();
    assert_eq!(h.state().session().nav().index(), 5);
    let (texts, images) = drawn(&h.output().shapes);
    assert!(
        texts.iter().any(|t| t == "Maths far ahead"),
        "the slide is drawn in the same frame: {texts:?}"
    );
    assert!(
        texts.iter().any(|t| t.contains("after the formula")),
        "with the blocks after the formula: {texts:?}"
    );
    assert_eq!(
        images, 0,
        "the formula is not ready in that frame: no waiting"
    );

    // It arrives without a key press: the pool asks for a repaint when it is done.
    assert_eq!(wait_for_formula(&mut h), 1);
    for job in busy {
        let err = job.wait().unwrap_err();
        // the time bound, or on a fast machine the memory bound first
        let stopped = ["stopped after", "more than 512 MB"];
        assert!(stopped.iter().any(|w| err.message.contains(w)), "{err}");
    }

    // Slide 2's formula was typeset ahead while slide 1 was shown: going there draws it at once.
    h.key_press(Key::Home);
    h.step();
    h.key_press(Key::ArrowRight);
    h.step();
    assert_eq!(h.state().session().nav().index(), 1);
    let (_, images) = drawn(&h.output().shapes);
    assert_eq!(
        images, 1,
        "typeset ahead: no placeholder when paging forward"
    );
}

/// Tried as a lecturer would: a formula that computes far too much, saved while presenting.
/// The slide stays (with the formula's last good picture), a notice names the formula's line
/// and column, and the work was stopped at the budget in a worker, not in this process.
#[test]
fn a_heavy_formula_saved_while_presenting_is_stopped_and_named_at_its_line() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("talk.ron");
    let good = r#"(
    title: "Talk",
    slides: [
        (id: "a", title: "Growth", body: [
            Text("before"),
            Math(src: "x^2 + 1"),
        ]),
    ],
)"#;
    std::fs::write(&path, good).unwrap();
    let mut h = harness(&path);
    let ctx = h.ctx.clone();
    h.state_mut().watch(&ctx);
    h.step();
    assert_eq!(wait_for_formula(&mut h), 1);

    let heavy = good.replace("x^2 + 1", "#range(100000000).map(i => i).len()");
    let byte = heavy.find("#range").unwrap();
    let line = heavy[..byte].matches('\n').count() + 1;
    let col = byte - heavy[..byte].rfind('\n').unwrap();
    std::fs::write(&path, &heavy).unwrap();
    let saved = Instant::now();
    // which bound stops it first depends on the machine's speed
    let notices = ["stopped after 2 s", "used more than 512 MB"]
        .map(|why| format!("talk.ron:{line}:{col}: formula {why}"));
    loop {
        std::thread::sleep(Duration::from_millis(20));
        h.step();
        let (texts, images) = drawn(&h.output().shapes);
        assert!(
            texts.iter().any(|t| t == "Growth"),
            "the slide stays on screen"
        );
        assert_eq!(images, 1, "the last good formula stays on screen");
        if notices
            .iter()
            .any(|n| h.query_by_label_contains(n).is_some())
        {
            break;
        }
        assert!(
            saved.elapsed() < Duration::from_secs(20),
            "no notice {notices:?}; drawn: {texts:?}"
        );
    }
    assert_eq!(
        h.state().session().deck().slides[0].body.len(),
        2,
        "the new deck is on screen"
    );
}
