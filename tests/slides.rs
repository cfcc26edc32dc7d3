//! The bundled lecture: its structure (budgets, notes, every formula renders, every widget
//! instantiates) and a snapshot of every slide, rendered headless on the software adapter.
//!
//! Slides are drawn by the app's public slide renderer, the same code as the window and
//! `lectern export`.
//!
//! Regenerate after an intended change (then LOOK at the PNGs before committing):
//!     UPDATE_SNAPSHOTS=1 cargo test --test slides

use std::path::Path;
use std::sync::Arc;
use std::sync::atomic::Ordering;

use egui_kittest::{Harness, SnapshotOptions};
use lectern::app::{SlideState, slide_ui};
use lectern::deck::{Block, Deck, Slide, load_deck};
use lectern::math::{MathSyntax, render_formula};
use lectern::widgets::scene::SceneGpu;
use lectern::widgets::work_precision;

fn deck() -> Deck {
    load_deck(&Path::new(env!("CARGO_MANIFEST_DIR")).join("slides/lecture.ron")).unwrap()
}

#[test]
fn budgets_add_up_to_fifteen_minutes_and_every_slide_has_notes() {
    let d = deck();
    for s in &d.slides {
        assert!(s.seconds.is_some(), "{}: a budget", s.title);
    }
    // optional (`skip: true`) slides are not part of the plan
    assert_eq!(d.planned_secs(), 900.0);
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
        "exercise",
        "scene",
        "summary",
        "project-draw-call",
        "project-env-map",
        "project-normal-map",
        "project-shadow-map",
        "project-brdf",
        "project-particles",
        "project-caustics",
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

/// One optional slide per technique the students' project asks for, each showing the live
/// scene (a `Scene` widget), in an appendix after the closing slide (so paging ends there).
#[test]
fn the_project_slides_are_optional_and_show_the_live_scene() {
    let d = deck();
    let project: Vec<&Slide> = d
        .slides
        .iter()
        .filter(|s| s.id.as_deref().is_some_and(|i| i.starts_with("project-")))
        .collect();
    assert_eq!(
        project.len(),
        7,
        "draw call, env map, normal map, shadows, BRDF, particles, the GPU Gems article (caustics)"
    );
    let last_main = d.slides.iter().rposition(|s| !s.skip).unwrap();
    assert_eq!(d.slides[last_main].key(), "summary", "the talk ends on its summary");
    for s in project {
        assert!(d.find(s.key()).unwrap() > last_main, "{}: after the summary", s.title);
        assert!(
            s.skip,
            "{}: optional (skip: true), outside the 15:00 plan",
            s.title
        );
        let scenes = blocks(s)
            .into_iter()
            .filter(|b| {
                matches!(
                    b,
                    Block::Widget(lectern::deck::widgets::WidgetSpec::Scene(_))
                )
            })
            .count();
        assert!(scenes >= 1, "{}: shows the live scene", s.title);
    }
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

/// Every slide through the app's own slide renderer (`lectern::app::slide_ui`, the one the
/// window and `lectern export` use), so the snapshot is what the audience sees.
#[test]
fn every_slide_matches_its_snapshot() {
    work_precision::DETERMINISTIC.store(true, Ordering::Relaxed);
    let options = SnapshotOptions::new().threshold(0.6).max_failed_pixels(8);
    let mut results = egui_kittest::SnapshotResults::new();
    let deck = Arc::new(deck());
    for (n, slide) in deck.slides.iter().enumerate() {
        let name = format!(
            "slide-{:02}-{}",
            n + 1,
            slide.id.clone().unwrap_or_default()
        );
        let deck = deck.clone();
        let mut state = SlideState::default();
        // Scene widgets render on the harness's own device, at the deck's `time_s`.
        let rs = egui_kittest::wgpu::create_render_state(
            egui_kittest::wgpu::default_wgpu_setup(),
            egui_wgpu::RendererOptions::PREDICTABLE,
        );
        let gpu = rs.clone();
        let mut h = Harness::builder()
            .with_size(SIZE)
            .renderer(egui_kittest::wgpu::WgpuTestRenderer::from_render_state(rs))
            .with_context_setup(move |ctx| SceneGpu::install(ctx, gpu, 1.0, false))
            .build_ui(move |ui| {
                slide_ui(ui, &deck, n, &mut state);
            });
        h.run_steps(3);
        results.add(h.try_snapshot_options(&name, &options));
    }
    results.unwrap();
}

/// Every piece of text a slide draws in a colour of its own (control labels in a method's
/// colour, slope labels, legends, the footer) reaches WCAG's 4.5:1 against the slide's
/// background and the plots' background, on both themes. Text egui fades on purpose (alpha
/// below 255: grid labels fading out as they get dense) is left out.
#[test]
fn every_coloured_text_is_readable_on_both_themes() {
    use egui::epaint::Shape;
    use lectern::widgets::style::{MIN_TEXT_CONTRAST, contrast_ratio};
    fn texts(shape: &Shape, out: &mut Vec<(String, egui::Color32)>) {
        match shape {
            Shape::Vec(v) => v.iter().for_each(|s| texts(s, out)),
            Shape::Text(t) => {
                for section in &t.galley.job.sections {
                    let color = t.override_text_color.unwrap_or(section.format.color);
                    let color = if color == egui::Color32::PLACEHOLDER {
                        t.fallback_color
                    } else {
                        color
                    };
                    let r = &section.byte_range;
                    let text = t.galley.job.text[r.start.0..r.end.0].to_string();
                    if color.a() == 255 && !text.trim().is_empty() {
                        out.push((text, color));
                    }
                }
            }
            _ => {}
        }
    }
    work_precision::DETERMINISTIC.store(true, Ordering::Relaxed);
    let mut failures = Vec::new();
    for theme in [lectern::deck::Theme::Dark, lectern::deck::Theme::Light] {
        let mut d = deck();
        d.theme = theme;
        let palette = lectern::app::theme::Palette::of(theme);
        let deck = Arc::new(d);
        for n in 0..deck.slides.len() {
            let shown = deck.clone();
            let mut state = SlideState::default();
            let mut h = Harness::builder().with_size(SIZE).build_ui(move |ui| {
                slide_ui(ui, &shown, n, &mut state);
            });
            h.run_steps(3);
            let mut found = Vec::new();
            for clipped in &h.output().shapes {
                texts(&clipped.shape, &mut found);
            }
            for (text, color) in found {
                let ratio = contrast_ratio(color, palette.background)
                    .min(contrast_ratio(color, palette.panel));
                if ratio < MIN_TEXT_CONTRAST {
                    failures.push(format!(
                        "{theme:?} slide {}: {text:?} in {color:?}: {ratio:.2}:1",
                        n + 1
                    ));
                }
            }
        }
    }
    failures.dedup();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
