//! What one slide frame asks of the rasteriser, measured (not asserted): for every slide of
//! the bundled lecture, the frame as the window paints it (cleared to the slide's background)
//! and as a painted background would cost, plus a slide under 200 ink strokes. On the software
//! adapter the numbers are the CPU time llvmpipe spends on the frame; see
//! docs/benchmarks/slides.md. Run:
//!
//! `cargo test --release --test suite slide_frame_cost:: -- --ignored --nocapture`

use std::cell::Cell;
use std::time::Instant;

use lectern::app::ink_draw::InkView;
use lectern::app::{OffscreenRenderer, SlideOptions, SlideState, slide_ui_with};
use lectern::deck::ink::{Stroke, StrokeBuilder, Tool};
use lectern::deck::load_deck;

const SIZE: [u32; 2] = [1280, 720];
const REPEATS: usize = 5;

/// This process's CPU seconds (all threads: llvmpipe rasterises on its own threads).
fn cpu_secs() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    let fields: Vec<&str> = stat
        .rsplit_once(')')
        .map_or("", |(_, rest)| rest)
        .split_whitespace()
        .collect();
    let ticks = |i: usize| {
        fields
            .get(i)
            .and_then(|v| v.parse::<f64>().ok())
            .unwrap_or(0.0)
    };
    (ticks(11) + ticks(12)) / 100.0
}

/// 200 strokes over the whole canvas: a quarter highlighter, circles of 30-150 units drawn
/// with a slightly shaky hand, thinned as the pen thins them.
fn strokes_200() -> Vec<Stroke> {
    let mut seed = 12345u64;
    let mut rnd = move || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (seed >> 33) as f32 / (1u64 << 31) as f32
    };
    (0..200)
        .map(|i| {
            let tool = if i % 4 == 0 {
                Tool::Highlighter
            } else {
                Tool::Pen
            };
            let (cx, cy) = (100.0 + rnd() * 1720.0, 100.0 + rnd() * 880.0);
            let r = 30.0 + rnd() * 120.0;
            let mut b = StrokeBuilder::new(tool, (i % 5) as u8, [cx + r, cy]);
            for k in 1..=400 {
                let a = k as f32 / 400.0 * 6.2;
                b.push([cx + r * a.cos() + rnd(), cy + r * a.sin() + rnd()]);
            }
            b.finish()
        })
        .collect()
}

/// Mean wall and CPU milliseconds per frame of `options` on slide `index` (after a warm-up,
/// so typesetting and widget set-up are not counted).
fn frame_ms(
    r: &mut OffscreenRenderer,
    deck: &lectern::deck::Deck,
    index: usize,
    options: SlideOptions,
) -> (f64, f64) {
    let mut state = SlideState::default();
    let clear = Cell::new(lectern::app::theme::Palette::of(deck.theme).background);
    let mut draw = |r: &mut OffscreenRenderer| {
        r.render_cleared(
            SIZE,
            1.0,
            |ui| {
                slide_ui_with(ui, deck, index, &mut state, options);
            },
            &clear,
        )
        .unwrap()
    };
    draw(r);
    let (t0, c0) = (Instant::now(), cpu_secs());
    for _ in 0..REPEATS {
        draw(r);
    }
    let n = REPEATS as f64;
    (
        t0.elapsed().as_secs_f64() * 1e3 / n,
        (cpu_secs() - c0) * 1e3 / n,
    )
}

#[test]
#[ignore = "a measurement, minutes on a software adapter: run with --ignored --nocapture"]
fn slide_frame_cost() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("slides/lecture.ron");
    let deck = load_deck(&path).unwrap();
    let mut r = OffscreenRenderer::new().unwrap();
    println!(
        "{} at {}x{}, {REPEATS} frames each (3 egui passes + paint + read-back)",
        r.adapter_name(),
        SIZE[0],
        SIZE[1]
    );
    println!(
        "slide                      cleared: wall / CPU ms   painted background: wall / CPU ms"
    );
    let cleared = SlideOptions {
        background: false,
        ..SlideOptions::default()
    };
    for (i, slide) in deck.slides.iter().enumerate() {
        let (w0, c0) = frame_ms(&mut r, &deck, i, cleared);
        let (w1, c1) = frame_ms(&mut r, &deck, i, SlideOptions::default());
        println!(
            "{:2} {:24} {w0:7.1} / {c0:6.1}          {w1:7.1} / {c1:6.1}",
            i + 1,
            slide.key()
        );
    }
    let strokes = strokes_200();
    let points: usize = strokes.iter().map(|s| s.points.len()).sum();
    for (name, plain_edges) in [("anti-aliased", false), ("plain edges", true)] {
        let options = SlideOptions {
            ink: InkView {
                strokes: &strokes,
                plain_edges,
                ..InkView::default()
            },
            ..cleared
        };
        let (w, c) = frame_ms(&mut r, &deck, 0, options);
        let (w0, c0) = frame_ms(&mut r, &deck, 0, cleared);
        println!(
            "slide 1 with 200 strokes ({points} points), {name}: {w:.1} / {c:.1} ms (without: {w0:.1} / {c0:.1})"
        );
    }
}
