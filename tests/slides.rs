//! The bundled lecture: its structure (budgets, notes, every formula renders, every widget
//! instantiates) and a snapshot of every slide, rendered headless on the software adapter.
//!
//! Until the app's public slide renderer lands, slides are laid out here by `slide_ui`, a
//! minimal stand-in that shows the same blocks.
//!
//! Regenerate after an intended change (then LOOK at the PNGs before committing):
//!     UPDATE_SNAPSHOTS=1 cargo test --test slides

use std::path::Path;
use std::sync::atomic::Ordering;

use egui_kittest::{Harness, SnapshotOptions};
use lectern::deck::{Block, Deck, Slide, load_deck};
use lectern::math::{MathSyntax, math_ui, render_formula};
use lectern::widgets::{SlideWidget, work_precision};

fn deck() -> Deck {
    load_deck(&Path::new(env!("CARGO_MANIFEST_DIR")).join("slides/lecture.ron")).unwrap()
}

#[test]
fn budgets_add_up_to_fifteen_minutes_and_every_slide_has_notes() {
    let d = deck();
    let total: f32 = d
        .slides
        .iter()
        .map(|s| s.seconds.expect("every slide has a budget"))
        .sum();
    assert_eq!(total, 900.0);
    for s in &d.slides {
        assert!(s.notes.len() > 10, "{}: speaker notes", s.title);
        assert!(s.id.is_some(), "{}: id", s.title);
    }
    let ids: Vec<_> = d.slides.iter().map(|s| s.id.clone().unwrap()).collect();
    // the notes' order
    let order = [
        "title",
        "state",
        "ode",
        "slope-field",
        "euler",
        "inaccuracy",
        "instability",
        "taylor",
        "derive",
        "rk4",
        "convergence",
        "work-precision",
        "rotation",
        "inertia",
        "simulation",
        "scene",
    ];
    let pos: Vec<usize> = order
        .iter()
        .map(|o| {
            ids.iter()
                .position(|i| i == o)
                .unwrap_or_else(|| panic!("missing slide {o}"))
        })
        .collect();
    assert!(
        pos.windows(2).all(|w| w[0] < w[1]),
        "slides out of the notes' order: {ids:?}"
    );
}

fn blocks(slide: &Slide) -> Vec<&Block> {
    fn walk<'a>(b: &'a Block, out: &mut Vec<&'a Block>) {
        out.push(b);
        if let Block::Columns(cols) = b {
            cols.iter().flatten().for_each(|b| walk(b, out));
        }
    }
    let mut out = Vec::new();
    slide.body.iter().for_each(|b| walk(b, &mut out));
    out
}

#[test]
fn every_formula_in_the_deck_renders() {
    for s in deck().slides {
        for b in blocks(&s) {
            if let Block::Math { src, latex } = b {
                let syntax = if *latex {
                    MathSyntax::Latex
                } else {
                    MathSyntax::Typst
                };
                render_formula(src, syntax, 40.0, [0, 0, 0, 255])
                    .unwrap_or_else(|e| panic!("slide {}: {src}: {e}", s.title));
            }
        }
    }
}

const SIZE: egui::Vec2 = egui::vec2(1280.0, 720.0);

/// A minimal slide layout (title, then blocks top to bottom, columns side by side).
fn slide_ui(ui: &mut egui::Ui, slide: &Slide, widgets: &mut [Box<dyn SlideWidget>]) {
    ui.label(
        egui::RichText::new(&slide.title)
            .size(40.0)
            .strong()
            .color(egui::Color32::from_gray(20)),
    );
    ui.add_space(8.0);
    let mut next = 0;
    let id = slide.id.clone().unwrap_or_default();
    for (i, b) in slide.body.iter().enumerate() {
        block_ui(ui, &format!("{id}/{i}"), b, widgets, &mut next);
    }
}

fn block_ui(
    ui: &mut egui::Ui,
    slot: &str,
    b: &Block,
    widgets: &mut [Box<dyn SlideWidget>],
    next: &mut usize,
) {
    match b {
        Block::Text(t) => {
            ui.label(egui::RichText::new(t).size(26.0));
        }
        Block::Bullets(items) => {
            for t in items {
                ui.label(egui::RichText::new(format!("•  {t}")).size(24.0));
            }
        }
        Block::Math { src, latex } => {
            let syntax = if *latex {
                MathSyntax::Latex
            } else {
                MathSyntax::Typst
            };
            if let Some(e) = math_ui(ui, slot, src, syntax, 30.0, egui::Color32::from_gray(10)) {
                panic!("{slot}: {e}");
            }
        }
        Block::Image { path, .. } => {
            ui.label(path);
        }
        Block::Widget(_) => {
            let w = &mut widgets[*next];
            *next += 1;
            ui.push_id(slot, |ui| w.ui(ui));
        }
        Block::Columns(cols) => {
            ui.columns(cols.len(), |uis| {
                for (c, (ui, col)) in uis.iter_mut().zip(cols).enumerate() {
                    for (i, b) in col.iter().enumerate() {
                        block_ui(ui, &format!("{slot}/{c}/{i}"), b, widgets, next);
                    }
                }
            });
        }
    }
}

#[test]
fn every_slide_matches_its_snapshot() {
    work_precision::DETERMINISTIC.store(true, Ordering::Relaxed);
    let options = SnapshotOptions::new().threshold(0.6).max_failed_pixels(8);
    let mut results = egui_kittest::SnapshotResults::new();
    for (n, slide) in deck().slides.into_iter().enumerate() {
        let mut widgets: Vec<Box<dyn SlideWidget>> = blocks(&slide)
            .into_iter()
            .filter_map(|b| match b {
                Block::Widget(w) => Some(w.instantiate()),
                _ => None,
            })
            .collect();
        let name = format!(
            "slide-{:02}-{}",
            n + 1,
            slide.id.clone().unwrap_or_default()
        );
        let mut h = Harness::builder()
            .with_size(SIZE)
            .with_theme(egui::Theme::Light)
            .wgpu()
            .build_ui(move |ui| {
                egui::Frame::new()
                    .fill(egui::Color32::WHITE)
                    .inner_margin(24.0)
                    .show(ui, |ui| {
                        ui.set_min_size(ui.available_size());
                        slide_ui(ui, &slide, &mut widgets);
                    });
            });
        h.run_steps(3);
        results.add(h.try_snapshot_options(&name, &options));
    }
    results.unwrap();
}
