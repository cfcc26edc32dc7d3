//! Snapshot tests of every plot widget in a few parameter states, rendered headless with
//! egui_kittest on the wgpu software adapter and compared with `tests/snapshots/widget-*.png`.
//!
//! Regenerate after an intended change (then LOOK at the PNGs before committing):
//!     UPDATE_SNAPSHOTS=1 cargo test --test suite widgets::

use std::sync::atomic::Ordering;

use egui_kittest::{Harness, SnapshotOptions, SnapshotResults};
use lectern::deck::parse_deck;
use lectern::widgets::{SlideWidget, WidgetSpec, params, work_precision};

const SIZE: egui::Vec2 = egui::vec2(1100.0, 620.0);

/// Per-pixel colour tolerance: absorbs GL vs Vulkan rasterisation differences (1/255), not a
/// moved line (see `a_different_h_does_not_match_its_snapshot`).
fn options() -> SnapshotOptions {
    SnapshotOptions::new().threshold(0.6).max_failed_pixels(8)
}

/// The bundled deck: widget specs name their problem and tableau files relative to it.
fn deck_path() -> &'static std::path::Path {
    std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/slides/lecture.ron"))
}

/// A widget spec from RON, as a deck file would write it (`Option` fields without `Some`).
fn spec_of(ron_spec: &str) -> WidgetSpec {
    ron::Options::default()
        .with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME)
        .from_str(ron_spec)
        .unwrap_or_else(|e| panic!("{ron_spec}: {e}"))
}

/// A widget from a RON spec, its files resolved as in the bundled deck.
fn widget(ron_spec: &str) -> Box<dyn SlideWidget> {
    spec_of(ron_spec).instantiate_in(Some(deck_path()))
}

fn harness(mut w: Box<dyn SlideWidget>) -> Harness<'static> {
    work_precision::DETERMINISTIC.store(true, Ordering::Relaxed);
    let mut h = Harness::builder()
        .with_size(SIZE)
        .with_theme(egui::Theme::Light)
        .with_context_setup(|ctx| lectern::math::install_egui_fallback_fonts(ctx))
        .wgpu()
        .build_ui(move |ui| {
            egui::Frame::new()
                .fill(egui::Color32::WHITE)
                .inner_margin(12.0)
                .show(ui, |ui| {
                    ui.set_min_size(ui.available_size());
                    w.ui(ui);
                });
        });
    h.run_steps(3);
    h
}

fn render(ron_spec: &str) -> image::RgbaImage {
    harness(widget(ron_spec)).render().expect("render")
}

/// Renders `ron_spec` and compares it with `tests/snapshots/{name}.png`; all of a test's
/// comparisons are collected so one run updates (or reports) every picture.
fn check(results: &mut SnapshotResults, name: &str, ron_spec: &str) {
    let mut h = harness(widget(ron_spec));
    results.add(h.try_snapshot_options(name, &options()));
}

const SLOPE_1D: &str = "SlopeField((ode: File(\"problems/forced.ron\"), start: (0.0, 1.5), h: 0.5, t_end: 8.0, view: (0.0, 8.0, -1.5, 2.0)))";

/// A drag across the slope field moves its start point, and the paths on screen are solved
/// from where the pointer is in the frame that sees it move, not one frame late (in the
/// browser's software WebGL2 that frame is ~70 ms: docs/benchmarks/web.md).
#[test]
fn a_dragged_start_point_is_solved_from_in_the_frame_that_moves_it() {
    use egui::{Event, PointerButton, Pos2};
    use lectern::widgets::slope_field::SlopeField;
    let WidgetSpec::SlopeField(spec) = spec_of(SLOPE_1D) else {
        unreachable!()
    };
    let w = SlopeField::new(spec, lectern::widgets::MadeIn::deck(Some(deck_path())));
    let mut h = Harness::builder()
        .with_size(SIZE)
        .with_context_setup(|ctx| lectern::math::install_egui_fallback_fonts(ctx))
        .build_ui_state(|ui, w: &mut SlopeField| w.ui(ui), w);
    h.run_steps(3);
    let first = h.state().spec.start;
    assert_eq!(h.state().solved_start(), first);
    // inside the plot, which fills the widget below its controls
    let at = |x: f32| Pos2::new(x, 0.6 * SIZE.y);
    h.event(Event::PointerMoved(at(400.0)));
    h.step();
    h.event(Event::PointerButton {
        pos: at(400.0),
        button: PointerButton::Primary,
        pressed: true,
        modifiers: Default::default(),
    });
    h.step();
    let mut starts = Vec::new();
    for x in [440.0, 480.0, 520.0, 560.0] {
        h.event(Event::PointerMoved(at(x)));
        h.step();
        let w = h.state();
        starts.push(w.spec.start);
        // (the frame that starts the drag learns of it from the plot, after drawing)
        if x > 440.0 {
            assert_eq!(
                w.solved_start(),
                w.spec.start,
                "at x = {x}: drawn a frame late"
            );
        }
    }
    h.event(Event::PointerButton {
        pos: at(560.0),
        button: PointerButton::Primary,
        pressed: false,
        modifiers: Default::default(),
    });
    h.step();
    let moved: Vec<f64> = starts.iter().map(|s| s.unwrap().0).collect();
    assert!(
        moved.windows(2).all(|p| p[1] > p[0]) && moved[0] > first.unwrap().0,
        "the start did not follow the drag: {first:?} then {moved:?}"
    );
}

#[test]
fn slope_field_states() {
    let mut r = SnapshotResults::new();
    check(&mut r, "widget-slope-field-1d-h0.5", SLOPE_1D);
    check(
        &mut r,
        "widget-slope-field-1d-h1-rk4-only",
        "SlopeField((ode: File(\"problems/forced.ron\"), start: (1.0, -1.0), h: 1.0, t_end: 8.0, view: (0.0, 8.0, -1.5, 2.0), methods: [Rk4]))",
    );
    check(
        &mut r,
        "widget-slope-field-phase-circle",
        "SlopeField((ode: File(\"problems/circle.ron\"), start: (1.0, 0.0), h: 0.3, t_end: 6.2832, view: (-2.0, 2.0, -2.0, 2.0)))",
    );
    check(
        &mut r,
        "widget-slope-field-phase-vdp",
        "SlopeField((ode: File(\"problems/limit-cycle.ron\"), start: (0.5, 0.0), h: 0.2, t_end: 12.0, view: (-3.0, 3.0, -3.0, 3.0), grid: 17))",
    );
    r.unwrap();
}

#[test]
fn step_construction_states() {
    let mut r = SnapshotResults::new();
    check(
        &mut r,
        "widget-step-euler",
        "StepConstruction((ode: File(\"problems/forced.ron\"), method: Euler, h: 1.5, stage: 2))",
    );
    check(
        &mut r,
        "widget-step-midpoint-half",
        "StepConstruction((ode: File(\"problems/forced.ron\"), method: Midpoint, h: 1.5, stage: 2))",
    );
    check(
        &mut r,
        "widget-step-rk4-k2",
        "StepConstruction((ode: File(\"problems/forced.ron\"), method: Rk4, h: 1.5, stage: 2))",
    );
    check(
        &mut r,
        "widget-step-rk4-full",
        "StepConstruction((ode: File(\"problems/forced.ron\"), method: Rk4, h: 1.5, stage: 5))",
    );
    r.unwrap();
}

#[test]
fn spiral_states() {
    let mut r = SnapshotResults::new();
    check(
        &mut r,
        "widget-spiral-h0.1",
        "Spiral((ode: File(\"problems/circle.ron\"), h: 0.1, turns: 3.0))",
    );
    check(
        &mut r,
        "widget-spiral-h0.5-euler-only",
        "Spiral((ode: File(\"problems/circle.ron\"), h: 0.5, turns: 2.0, compare: false))",
    );
    r.unwrap();
}

#[test]
fn neptune_states() {
    let mut r = SnapshotResults::new();
    check(
        &mut r,
        "widget-neptune-stable",
        "Neptune((ode: File(\"problems/decay.ron\"), h: 0.3, t_end: 4.0, methods: [Euler, Rk4]))",
    );
    check(
        &mut r,
        "widget-neptune-diverged",
        "Neptune((ode: File(\"problems/decay.ron\"), h: 0.45, t_end: 4.0, methods: [Euler, Rk4]))",
    );
    check(
        &mut r,
        "widget-neptune-oscillator",
        "Neptune((ode: File(\"problems/circle.ron\"), h: 0.5, t_end: 20.0, methods: [Euler, Midpoint, Rk4]))",
    );
    // h = 1e9 is clamped, never a panic or NaN
    check(
        &mut r,
        "widget-neptune-huge-h",
        "Neptune((ode: File(\"problems/decay.ron\"), h: 1e9, t_end: 4.0))",
    );
    r.unwrap();
}

#[test]
fn taylor_states() {
    let mut r = SnapshotResults::new();
    check(
        &mut r,
        "widget-taylor-sin-4",
        "Taylor((function: Sin, a: 0.0, order: 4))",
    );
    check(
        &mut r,
        "widget-taylor-log1p-6",
        "Taylor((function: Log1p, a: 0.0, order: 6, range: (-0.95, 3.0)))",
    );
    r.unwrap();
}

#[test]
fn convergence_states() {
    let mut r = SnapshotResults::new();
    check(
        &mut r,
        "widget-convergence",
        "Convergence((ode: File(\"problems/forced.ron\"), levels: 8))",
    );
    check(
        &mut r,
        "widget-convergence-typo",
        "Convergence((ode: File(\"problems/forced.ron\"), levels: 8, methods: [Euler, Midpoint, Rk4, Tableau(\"tableaux/rk4-typo.ron\")]))",
    );
    // adaptive pairs at fixed h: their formulas' orders, labelled as such
    check(
        &mut r,
        "widget-convergence-pairs",
        "Convergence((ode: File(\"problems/forced.ron\"), h_max: 1.0, levels: 8, methods: [Euler, Midpoint, Rk4, Tableau(\"tableaux/rk4-typo.ron\"), Dop853, Vern9]))",
    );
    r.unwrap();
}

#[test]
fn work_precision_states() {
    let mut r = SnapshotResults::new();
    check(
        &mut r,
        "widget-work-precision",
        "WorkPrecision((ode: File(\"problems/circle.ron\"), t_end: 10.0, levels: 10, rk5: true))",
    );
    // the adaptive pairs as squares (tolerance sweep) beside the h sweeps
    check(
        &mut r,
        "widget-work-precision-pairs",
        "WorkPrecision((ode: File(\"problems/circle.ron\"), t_end: 10.0, levels: 10, methods: [Euler, Midpoint, Rk4, Tsit5, Dop853, Vern9]))",
    );
    // every pair at once, with RK4, on the forced decay (exact solution)
    check(
        &mut r,
        "widget-work-precision-all-pairs",
        "WorkPrecision((ode: File(\"problems/forced.ron\"), t_end: 10.0, levels: 9, methods: [Rk4, Dopri5, Tsit5, Vern6, Vern7, Vern8, Dop853, Vern9], rk5: false))",
    );
    r.unwrap();
}

/// The work-precision slide of the bundled deck, computed on its own spec (no pixels): the
/// class must see DOP853 and Vern9 overtake RK4 at tight errors, and RK4 hold its own at
/// loose ones.
#[test]
fn work_precision_slide_shows_high_order_pairs_overtake_rk4_at_tight_errors() {
    use lectern::ode::study::cost_at_error;
    use lectern::widgets::work_precision::{Curve, WorkPrecision};
    let deck = lectern::deck::load_deck(deck_path()).unwrap();
    let slide = deck
        .slides
        .iter()
        .find(|s| s.id.as_deref() == Some("work-precision"))
        .expect("the work-precision slide");
    let spec = slide
        .widgets()
        .into_iter()
        .find_map(|(_, w)| match w {
            WidgetSpec::WorkPrecision(s) => Some(s.clone()),
            _ => None,
        })
        .expect("its widget");
    let curves =
        WorkPrecision::new(spec, lectern::widgets::MadeIn::deck(Some(deck_path()))).compute();
    let curve = |k: &str| -> &Curve {
        curves
            .iter()
            .find(|c| c.key == k)
            .unwrap_or_else(|| panic!("the slide shows {k}"))
    };
    let rk4 = curve("rk4");
    assert!(!rk4.adaptive && curve("dop853").adaptive && curve("vern9").adaptive);
    // (error, f-evaluations) of a curve, for interpolation
    let work = |c: &Curve| -> Vec<(f64, f64)> {
        c.samples
            .iter()
            .map(|s| (s.error, s.f_evals as f64))
            .collect()
    };
    let tight: Vec<_> = rk4.samples.iter().filter(|s| s.error < 1e-8).collect();
    assert!(tight.len() >= 3, "{:?}", rk4.samples);
    for pair in ["dop853", "vern9"] {
        let c = curve(pair);
        for s in &tight {
            // at no more f-evaluations than RK4 spent, the pair's error is smaller
            let best = c
                .samples
                .iter()
                .filter(|p| p.f_evals <= s.f_evals)
                .map(|p| p.error)
                .fold(f64::INFINITY, f64::min);
            assert!(
                best < s.error,
                "{pair} at ≤ {} f-evals: {best:e}, RK4 {:e}",
                s.f_evals,
                s.error
            );
        }
        // and by a wide margin: RK4 needs many times the work for 1e-10
        let (mine, rk4s) = (
            cost_at_error(&work(c), 1e-10).unwrap(),
            cost_at_error(&work(rk4), 1e-10).unwrap(),
        );
        println!(
            "f-evaluations for 1e-10: {pair} {mine:.0}, RK4 {rk4s:.0} ({:.1}×)",
            rk4s / mine
        );
        assert!(rk4s > 5.0 * mine, "{pair}: {mine} vs RK4 {rk4s}");
        let at_rk4_best = cost_at_error(&work(c), rk4.best_error()).unwrap();
        println!(
            "  for RK4's best error {:e} ({} f-evals): {pair} {at_rk4_best:.0}",
            rk4.best_error(),
            rk4.samples.last().unwrap().f_evals
        );
    }
    // At the loose end an extra order is not worth its stages: RK4's cheapest run is cheaper
    // than any pair's, and Vern9 (16 evaluations a step) spends more at its loosest tolerance
    // than RK4 needs for an error of 1e-2.
    let cheapest = |c: &Curve| c.samples.iter().map(|s| s.f_evals).min().unwrap();
    let rk4_at_loose = cost_at_error(&work(rk4), 1e-2).unwrap();
    println!("RK4 reaches 1e-2 with {rk4_at_loose:.0} f-evaluations");
    for c in curves.iter().filter(|c| c.adaptive) {
        println!("  {} cheapest run {}", c.key, cheapest(c));
        assert!(cheapest(c) > cheapest(rk4), "{}", c.key);
    }
    assert!(cheapest(curve("vern9")) as f64 > rk4_at_loose);
}

#[test]
fn stability_states() {
    let mut r = SnapshotResults::new();
    check(&mut r, "widget-stability", "Stability(())");
    check(
        &mut r,
        "widget-stability-deck-tableau",
        r#"Stability((methods: [Euler, Rk4], tableaux: [(name: "Ralston", a: [[0.0, 0.0], [0.6666666666666666, 0.0]], b: [0.25, 0.75], c: [0.0, 0.6666666666666666])], lambda: Some((0.0, 1.0)), h: 2.5))"#,
    );
    r.unwrap();
}

#[test]
fn rigid_body_states() {
    let mut r = SnapshotResults::new();
    check(
        &mut r,
        "widget-rigid-body-t0",
        "RigidBody((t: 0.0, playing: false))",
    );
    check(
        &mut r,
        "widget-rigid-body-t12",
        "RigidBody((t: 12.0, playing: false, n: 8))",
    );
    r.unwrap();
}

/// Slide 16's boxes read as solids at a glance: in every panel of the slide's own widget (its
/// spec from the bundled deck) the painted faces cover at least 30 % of the panel, and at least
/// three faces show, each in its own shade (Lambert shading by a fixed light; flat, edge-on
/// boxes covering ~15 % of their panels with one or two faces failed this). Read from the
/// shapes the widget paints.
#[test]
fn rigid_body_boxes_fill_their_panels_and_show_three_shaded_faces() {
    use egui::epaint::Shape;
    let deck = parse_deck(include_str!("../slides/lecture.ron"), deck_path()).unwrap();
    let spec = deck
        .slides
        .iter()
        .flat_map(|s| s.widgets())
        .find(|(_, w)| w.kind() == "rigid-body")
        .map(|(_, w)| w.clone())
        .expect("the lecture has a rigid-body slide");
    let h = harness(spec.instantiate_in(Some(deck_path())));
    fn walk(
        shape: &Shape,
        faces: &mut Vec<(Vec<egui::Pos2>, egui::Color32)>,
        panels: &mut Vec<egui::Rect>,
    ) {
        match shape {
            Shape::Vec(v) => v.iter().for_each(|s| walk(s, faces, panels)),
            Shape::Path(p) if p.closed && p.fill != egui::Color32::TRANSPARENT => {
                faces.push((p.points.clone(), p.fill));
            }
            Shape::Rect(r)
                if r.fill == egui::Color32::TRANSPARENT
                    && r.stroke.width > 0.0
                    && r.rect.width() > 100.0
                    && r.rect.height() > 100.0 =>
            {
                panels.push(r.rect);
            }
            _ => {}
        }
    }
    let (mut faces, mut panels) = (Vec::new(), Vec::new());
    for c in &h.output().shapes {
        walk(&c.shape, &mut faces, &mut panels);
    }
    assert_eq!(panels.len(), 4, "one panel per method: {panels:?}");
    let area = |pts: &[egui::Pos2]| {
        let n = pts.len();
        0.5 * (0..n)
            .map(|i| pts[i].x * pts[(i + 1) % n].y - pts[(i + 1) % n].x * pts[i].y)
            .sum::<f32>()
            .abs()
    };
    for panel in &panels {
        let mine: Vec<_> = faces
            .iter()
            .filter(|(pts, _)| {
                let c =
                    pts.iter().fold(egui::Vec2::ZERO, |a, p| a + p.to_vec2()) / pts.len() as f32;
                panel.contains(c.to_pos2())
            })
            .collect();
        let covered: f32 = mine.iter().map(|(pts, _)| area(pts)).sum();
        let share = covered / panel.area();
        let mut shades: Vec<egui::Color32> = mine.iter().map(|(_, c)| *c).collect();
        shades.sort_by_key(|c| c.to_array());
        shades.dedup();
        assert!(
            share >= 0.30,
            "panel {panel:?}: the box covers {:.0} %",
            100.0 * share
        );
        assert!(
            mine.len() >= 3 && shades.len() == mine.len(),
            "panel {panel:?}: {} faces in {} shades",
            mine.len(),
            shades.len()
        );
        println!(
            "panel {panel:?}: {:.1} % covered, {} faces",
            100.0 * share,
            mine.len()
        );
    }
}

/// Proves the snapshots bite: the committed slope-field picture for h = 0.5 must not match a
/// rendering with h = 0.45, with the same tolerance the snapshot tests use; and, as a control,
/// the same h must match (so the comparison is not simply always failing).
#[test]
fn a_different_h_does_not_match_its_snapshot() {
    let committed = image::open(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/snapshots/widget-slope-field-1d-h0.5.png"
    ))
    .expect("run the snapshot tests first")
    .to_rgba8();
    let same = render(SLOPE_1D);
    let other = render(&SLOPE_1D.replace("h: 0.5", "h: 0.45"));
    let differing = |img: &image::RgbaImage| {
        assert_eq!(img.dimensions(), committed.dimensions());
        img.pixels()
            .zip(committed.pixels())
            .filter(|(a, b)| a.0.iter().zip(b.0.iter()).any(|(x, y)| x.abs_diff(*y) > 16))
            .count()
    };
    assert!(
        differing(&same) <= 8,
        "control: same h should match ({} px differ)",
        differing(&same)
    );
    assert!(
        differing(&other) > 200,
        "h = 0.45 matched the h = 0.5 snapshot: the tests would not bite"
    );
}

/// Every widget exposes its tweakable values by stable id; they survive a "reload" (a fresh
/// instance) through snapshot/restore, are written back through `spec()`, and `reset` undoes
/// them.
#[test]
fn params_round_trip_through_reload_and_reset() {
    let deck = parse_deck(include_str!("../slides/lecture.ron"), deck_path()).unwrap();
    let specs: Vec<WidgetSpec> = deck
        .slides
        .iter()
        .flat_map(|s| s.body.iter())
        .flat_map(|b| match b {
            lectern::deck::Block::Widget(w) => vec![w.clone()],
            lectern::deck::Block::Columns(cols) => cols
                .iter()
                .flatten()
                .filter_map(|b| match b {
                    lectern::deck::Block::Widget(w) => Some(w.clone()),
                    _ => None,
                })
                .collect(),
            _ => vec![],
        })
        .collect();
    let kinds: std::collections::BTreeSet<_> = specs.iter().map(|s| s.kind()).collect();
    assert_eq!(
        kinds.len(),
        13,
        "the deck shows all thirteen widgets: {kinds:?}"
    );
    for spec in specs {
        let mut w = spec.instantiate_in(Some(deck_path()));
        let ids: Vec<String> = w.params().iter().map(|p| p.id.clone()).collect();
        assert!(!ids.is_empty(), "{} has no params", spec.kind());
        let mut uniq = ids.clone();
        uniq.dedup();
        assert_eq!(ids.len(), uniq.len());
        // tweak every value
        for mut p in w.params() {
            let v = match p.get() {
                params::ParamSnapshot::F64(x) => params::ParamSnapshot::F64(x * 0.9 + 0.01),
                params::ParamSnapshot::Bool(b) => params::ParamSnapshot::Bool(!b),
                params::ParamSnapshot::Usize(n) => params::ParamSnapshot::Usize(n + 1),
            };
            p.set(v).unwrap();
            assert!(p.set(params::ParamSnapshot::F64(f64::NAN)).is_err());
        }
        let saved = params::snapshot(w.as_mut());
        let tweaked_spec = w.spec();
        // as the widget starts: the file's values with the defaults it filled in
        let fresh = spec.instantiate_in(Some(deck_path())).spec();
        assert_ne!(
            tweaked_spec,
            fresh,
            "{}: tweaks must reach spec()",
            spec.kind()
        );
        let mut reloaded = spec.instantiate_in(Some(deck_path()));
        params::restore(reloaded.as_mut(), &saved);
        assert_eq!(reloaded.spec(), tweaked_spec, "{}", spec.kind());
        // and written back to RON, it parses to the same spec
        let ron_text = ron::to_string(&tweaked_spec).unwrap();
        assert_eq!(
            ron::from_str::<WidgetSpec>(&ron_text).unwrap(),
            tweaked_spec
        );
        reloaded.reset();
        assert_eq!(reloaded.spec(), fresh, "{}: reset", spec.kind());
        assert_eq!(
            params::snapshot(reloaded.as_mut()),
            params::snapshot(spec.instantiate_in(Some(deck_path())).as_mut()),
            "{}: reset",
            spec.kind()
        );
    }
}

/// Wall time of the work-precision slide's whole study (what its background thread runs, with
/// live timing: each run repeated until 2 ms or 50 times), the slide before the adaptive pairs
/// and now. A measurement, not a test (run with `cargo test --test suite widgets::study_time --
/// --ignored --nocapture`); the figures are in docs/benchmarks/work-precision-slide.md.
#[test]
#[ignore]
fn work_precision_study_time() {
    use lectern::widgets::work_precision::WorkPrecision;
    use std::time::Instant;
    work_precision::DETERMINISTIC.store(false, Ordering::Relaxed);
    let before =
        "WorkPrecision((ode: File(\"problems/circle.ron\"), t_end: 10.0, levels: 10, rk5: true))";
    let now = "WorkPrecision((ode: File(\"problems/circle.ron\"), t_end: 10.0, levels: 10, methods: [Euler, Midpoint, Rk4, Tsit5, Dop853, Vern9], rk5: true))";
    for (name, ron_spec) in [
        ("before (Euler, Midpoint, RK4, RK5)", before),
        ("now (+ Tsit5, DOP853, Vern9)", now),
    ] {
        let WidgetSpec::WorkPrecision(spec) = spec_of(ron_spec) else {
            unreachable!()
        };
        let mut secs: Vec<f64> = (0..7)
            .map(|_| {
                let mut w = WorkPrecision::new(
                    spec.clone(),
                    lectern::widgets::MadeIn::deck(Some(deck_path())),
                );
                let t = Instant::now();
                let curves = w.compute();
                assert!(!curves.is_empty());
                t.elapsed().as_secs_f64()
            })
            .collect();
        secs.sort_by(f64::total_cmp);
        println!(
            "{name}: median {:.0} ms (min {:.0}, max {:.0}) over 7 studies",
            secs[3] * 1e3,
            secs[0] * 1e3,
            secs[6] * 1e3
        );
    }
    // The convergence slide computes on the UI thread within a per-frame budget: its slowest
    // frame at the sliders' heaviest setting (12 halvings from h = 1), with the pairs ticked.
    for (name, methods) in [
        (
            "without pairs",
            "[Euler, Midpoint, Rk4, Tableau(\"tableaux/rk4-typo.ron\")]",
        ),
        (
            "with DOP853, Vern9",
            "[Euler, Midpoint, Rk4, Tableau(\"tableaux/rk4-typo.ron\"), Dop853, Vern9]",
        ),
    ] {
        let spec = format!(
            "Convergence((ode: File(\"problems/forced.ron\"), t_end: 4.0, h_max: 1.0, levels: 12, methods: {methods}))"
        );
        let mut w = widget(&spec);
        let mut h = Harness::builder()
            .with_size(SIZE)
            .with_context_setup(|ctx| lectern::math::install_egui_fallback_fonts(ctx))
            .build_ui(move |ui| w.ui(ui));
        let mut frames: Vec<f64> = (0..40)
            .map(|_| {
                let t = Instant::now();
                h.step();
                t.elapsed().as_secs_f64()
            })
            .collect();
        let slowest = frames.iter().copied().fold(0.0, f64::max);
        frames.sort_by(f64::total_cmp);
        println!(
            "convergence {name}, 12 halvings: slowest frame {:.1} ms, median {:.2} ms over 40",
            slowest * 1e3,
            frames[20] * 1e3
        );
    }
}

/// Frame cost of the long-path widgets while the lecturer drags `h` (a new h every frame) and
/// while nothing changes, in this build on this adapter. A measurement, not a test: it prints
/// and asserts nothing about time (run with `cargo test --test suite widgets::frame_cost -- --ignored
/// --nocapture`).
#[test]
#[ignore]
fn frame_cost_while_dragging_h() {
    use std::time::Instant;
    let cases = [
        (
            "slope field, 20 000 steps",
            "SlopeField((ode: File(\"problems/forced.ron\"), start: (0.0, 1.5), h: 0.01, t_end: 200.0, view: (0.0, 200.0, -1.5, 2.0)))",
            0.01,
        ),
        (
            "slope field phase (VdP), 6 000 steps",
            "SlopeField((ode: File(\"problems/limit-cycle.ron\"), start: (0.5, 0.0), h: 0.01, t_end: 60.0, view: (-3.0, 3.0, -3.0, 3.0)))",
            0.01,
        ),
        (
            "spiral, 3 × 20 000 steps",
            "Spiral((ode: File(\"problems/circle.ron\"), h: 0.005, turns: 20.0))",
            0.005,
        ),
    ];
    for (name, spec, h0) in cases {
        let mut w = widget(spec);
        let frames = 20;
        let drag = |w: &mut Box<dyn SlideWidget>, k: usize| {
            for mut p in w.params() {
                if p.id == "h" {
                    p.set(params::ParamSnapshot::F64(h0 * (1.0 + 0.002 * k as f64)))
                        .unwrap();
                }
            }
        };
        drag(&mut w, 0);
        let first = Instant::now();
        let mut h = harness(w);
        let first = first.elapsed();
        // steady frames: same parameters
        let t = Instant::now();
        for _ in 0..frames {
            h.step();
        }
        let steady = t.elapsed() / frames as u32;
        let t = Instant::now();
        h.render().unwrap();
        let render = t.elapsed();
        drop(h);
        // dragging: h changes before every frame
        let k = std::cell::Cell::new(0usize);
        let mut w = widget(spec);
        drag(&mut w, 0);
        let mut hd = Harness::builder()
            .with_size(SIZE)
            .with_context_setup(|ctx| lectern::math::install_egui_fallback_fonts(ctx))
            .wgpu()
            .build_ui(move |ui| {
                k.set(k.get() + 1);
                drag(&mut w, k.get());
                w.ui(ui);
            });
        let t = Instant::now();
        for _ in 0..frames {
            hd.step();
        }
        let dragging = t.elapsed() / frames as u32;
        println!(
            "{name}: first 3 frames {first:.1?}, steady frame {steady:.2?}, dragging h {dragging:.2?}/frame, one wgpu render {render:.1?}"
        );
    }
}

#[test]
fn parallel_transport_states() {
    let mut r = SnapshotResults::new();
    check(
        &mut r,
        "widget-parallel-transport-s-curve",
        "ParallelTransport((path: StraightThenS, step: 14))",
    );
    check(
        &mut r,
        "widget-parallel-transport-loop",
        "ParallelTransport((path: Loop, fish: 30, yaw_deg: -60.0, pitch_deg: 15.0))",
    );
    r.unwrap();
}

/// The exercise slide's point, from the widget's own data: on the S-curve the Frenet fish's up
/// flips (once per inflection) and the transported fish's never does; on the straight part the
/// Frenet frame is undefined.
#[test]
fn parallel_transport_widget_data_flips_only_for_frenet() {
    use lectern::deck::widgets::ParallelTransportSpec;
    use lectern::widgets::parallel_transport::ParallelTransport;
    let mut w = ParallelTransport::new(ParallelTransportSpec::default());
    assert_eq!(w.frenet_flips().len(), 2, "{:?}", w.frenet_flips());
    let frames = w.frames().to_vec();
    assert!(frames[1].frenet.is_none(), "straight: N undefined");
    for pair in frames.windows(2) {
        let (a, b) = (pair[0].transported_up(), pair[1].transported_up());
        assert!(a.dot(b) > 0.9, "transported up turned: {a} -> {b}");
    }
    // the spelled-out step is the one the fish took
    w.spec.step = 10;
    let s = w.shown_step();
    assert!(s.q_new.dot(w.frames()[11].transported).abs() > 1.0 - 1e-6);
    assert!(
        s.angle_rad > 0.05,
        "a visible turn at step 10: {}",
        s.angle_rad
    );
}

fn simulation_loop() -> lectern::widgets::simulation_loop::SimulationLoop {
    let spec: WidgetSpec =
        ron::from_str("SimulationLoop((scene: \"../scenes/water.ron\", body: 0, playing: false))")
            .unwrap();
    let WidgetSpec::SimulationLoop(spec) = spec else {
        unreachable!()
    };
    let slides = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("slides");
    lectern::widgets::simulation_loop::SimulationLoop::new_in(spec, Some(&slides))
}

#[test]
fn simulation_loop_numbers_are_the_bodys_derivative() {
    let mut w = simulation_loop();
    let n = w
        .advance(3.0)
        .expect("the bundled scene has a floating body");
    // 3 s at h = 1/60 s (an f32 in the scene file)
    assert!((n.time_secs - 3.0).abs() < 1e-6, "{}", n.time_secs);
    assert!(
        (n.q.length() - 1.0).abs() < 1e-9,
        "q is renormalised each step"
    );
    // ω = I⁻¹(t) L, and I⁻¹(t) is symmetric positive definite like I_body⁻¹
    assert!((n.inv_inertia_world * n.l - n.omega).length() < 1e-12);
    let i = n.inv_inertia_world;
    assert!((i - i.transpose()).abs_diff_eq(glam::DMat3::ZERO, 1e-12));
    assert!(i.determinant() > 0.0 && i.x_axis.x > 0.0);
    // a box of density 500 in water floats: it stays near the surface, with buoyancy
    // roughly carrying its weight after it has settled
    let after = w.advance(20.0).unwrap();
    assert!(
        after.x.y.abs() < 1.0,
        "floating near the surface: {}",
        after.x
    );
    assert!(after.wrench.force.is_finite());
    // the drift one unnormalised Euler step of q would add is second order in h|ω|
    let h_omega = after.h_secs * after.omega.length();
    assert!(
        after.q_drift <= 0.5 * h_omega * h_omega + 1e-12,
        "{} vs {}",
        after.q_drift,
        h_omega
    );
}

#[test]
fn simulation_loop_reports_a_missing_scene_or_body() {
    let slides = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("slides");
    let mut spec = lectern::deck::widgets::SimulationLoopSpec {
        body: 7,
        ..Default::default()
    };
    let mut w =
        lectern::widgets::simulation_loop::SimulationLoop::new_in(spec.clone(), Some(&slides));
    assert!(w.advance(0.1).is_none());
    assert!(w.error().unwrap().contains("no floating body number 7"));
    spec.body = 0;
    spec.scene = "../../../etc/passwd".into();
    let mut w = lectern::widgets::simulation_loop::SimulationLoop::new_in(spec, Some(&slides));
    assert!(
        w.error().unwrap().contains("outside the project"),
        "{:?}",
        w.error()
    );
}

#[test]
fn simulation_loop_snapshot() {
    let mut r = SnapshotResults::new();
    let mut w = simulation_loop();
    w.advance(2.0).unwrap();
    let mut h = harness(Box::new(w));
    r.add(h.try_snapshot_options("widget-simulation-loop", &options()));
    r.unwrap();
}

/// The deck's colour map as the audience meets it: every method's colour, gathered from every
/// widget of the bundled lecture, is the same wherever that method appears, reads as a line on
/// both themes (3:1), and the colours that share a slide stay apart in CIEDE2000 for normal,
/// protanope and deuteranope vision (bounds justified in `widgets::colors`).
#[test]
fn one_colour_per_method_across_the_deck_distinct_on_every_slide() {
    use lectern::widgets::colors::{self, Vision};
    use lectern::widgets::style::contrast_ratio;
    let deck = parse_deck(include_str!("../slides/lecture.ron"), deck_path()).unwrap();
    let mut seen: std::collections::BTreeMap<String, (egui::Color32, usize)> = Default::default();
    let mut slides_checked = 0;
    for (i, slide) in deck.slides.iter().enumerate() {
        let mut on_slide: Vec<(String, egui::Color32)> = Vec::new();
        for (_, spec) in slide.widgets() {
            on_slide.extend(spec.instantiate_in(Some(deck_path())).colours());
        }
        on_slide.sort_by(|a, b| a.0.cmp(&b.0));
        on_slide.dedup();
        for (name, c) in &on_slide {
            let (first, at) = *seen.entry(name.clone()).or_insert((*c, i + 1));
            assert_eq!(
                first,
                *c,
                "{name} is {first:?} on slide {at} but {c:?} on {}",
                i + 1
            );
            for theme in [lectern::deck::Theme::Dark, lectern::deck::Theme::Light] {
                let p = lectern::app::theme::Palette::of(theme);
                for bg in [p.background, p.panel] {
                    let r = contrast_ratio(*c, bg);
                    assert!(r >= colors::MIN_LINE_CONTRAST, "{name} on {bg:?}: {r:.2}");
                }
            }
        }
        for (k, (a, ca)) in on_slide.iter().enumerate() {
            for (b, cb) in &on_slide[k + 1..] {
                for v in [Vision::Normal, Vision::Protanopia, Vision::Deuteranopia] {
                    let d = colors::delta_e(*ca, *cb, v);
                    assert!(
                        d >= colors::min_delta_e_on_a_slide(v),
                        "slide {}: {a} and {b} are ΔE {d:.1} apart for {v:?}",
                        i + 1
                    );
                }
            }
        }
        slides_checked += usize::from(on_slide.len() > 1);
    }
    assert!(
        slides_checked >= 8,
        "{slides_checked} slides compare methods"
    );
    // the names slides use for them
    assert_eq!(
        colors::name_of(colors::Role::Method(lectern::ode::Method::Euler)),
        "vermillion"
    );
    assert_eq!(colors::name_of(colors::Role::Rk4Typo), "pink");
}
