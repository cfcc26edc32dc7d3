//! The bundled lecture: its structure (budgets, notes, every formula renders, every widget
//! instantiates) and a snapshot of every slide, rendered headless on the software adapter.
//!
//! Slides are drawn by the app's public slide renderer, the same code as the window and
//! `lectern export`.
//!
//! Regenerate after an intended change (then LOOK at the PNGs before committing):
//!     UPDATE_SNAPSHOTS=1 cargo test --test suite slides::

use crate::common;

use std::path::Path;
use std::sync::Arc;
use std::sync::atomic::Ordering;

use egui_kittest::{Harness, SnapshotOptions};
use lectern::app::{SlideState, slide_ui};
use lectern::deck::{Block, Deck, Slide, load_deck};
use lectern::math::{MathSyntax, render_formula};
use lectern::widgets::scene::SceneGpu;
use lectern::widgets::work_precision;

use common::text_boxes;

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
    assert_eq!(
        d.slides[last_main].key(),
        "summary",
        "the talk ends on its summary"
    );
    for s in project {
        assert!(
            d.find(s.key()).unwrap() > last_main,
            "{}: after the summary",
            s.title
        );
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

/// Every straight piece of every line a slide paints wider than a grid line (one point), in
/// screen points: paths' segments (closed ones closed) and single segments.
fn drawn_segments(output: &egui::FullOutput) -> Vec<[egui::Pos2; 2]> {
    use egui::epaint::Shape;
    const GRID_WIDTH: f32 = 1.05;
    fn walk(shape: &Shape, out: &mut Vec<[egui::Pos2; 2]>) {
        match shape {
            Shape::Vec(v) => v.iter().for_each(|s| walk(s, out)),
            Shape::LineSegment { points, stroke } if stroke.width > GRID_WIDTH => {
                out.push(*points);
            }
            Shape::Path(p) if p.stroke.width > GRID_WIDTH => {
                out.extend(p.points.windows(2).map(|w| [w[0], w[1]]));
                if p.closed && p.points.len() > 2 {
                    out.push([p.points[p.points.len() - 1], p.points[0]]);
                }
            }
            _ => {}
        }
    }
    let mut out = Vec::new();
    for c in &output.shapes {
        walk(&c.shape, &mut out);
    }
    out
}

/// The audience reads every word: on every bundled slide, at 1280×720 and 1920×1080, in both
/// themes, no two texts overlap (labels, readouts, tick labels, legends, captions, footer),
/// no text is cut by its clip rect (a readout past a column's edge, a line under the footer),
/// and every widget stays inside the slot the slide gave it, and the slot inside the slide's
/// content area (above the footer). In-plot labels (slopes, step labels, "off to Neptune")
/// keep off every drawn line, not only off points: labels avoid segments.
#[test]
fn no_text_overlaps_and_every_widget_stays_in_its_slot() {
    work_precision::DETERMINISTIC.store(true, Ordering::Relaxed);
    let mut failures = Vec::new();
    let mut texts_checked = 0;
    let mut widgets_checked = 0;
    let mut labels_checked = 0;
    for size in [egui::vec2(1280.0, 720.0), egui::vec2(1920.0, 1080.0)] {
        for theme in [lectern::deck::Theme::Dark, lectern::deck::Theme::Light] {
            let mut d = deck();
            d.theme = theme;
            let deck = Arc::new(d);
            for n in 0..deck.slides.len() {
                let shown = deck.clone();
                let mut state = SlideState::default();
                let mut h = Harness::builder().with_size(size).build_ui(move |ui| {
                    slide_ui(ui, &shown, n, &mut state);
                });
                h.run_steps(3);
                let at = format!("{}×{} {theme:?} slide {}", size.x, size.y, n + 1);
                let boxes = text_boxes(h.output());
                texts_checked += boxes.len();
                for (i, (a, ra, clip)) in boxes.iter().enumerate() {
                    // half a point of slack: rects of adjacent rows may touch
                    if !clip.expand(0.5).contains_rect(*ra) {
                        failures.push(format!("{at}: {a:?} at {ra:?} is cut by its clip {clip:?}"));
                    }
                    for (b, rb, _) in &boxes[i + 1..] {
                        let overlap = ra.intersect(*rb);
                        if overlap.width() > 1.0 && overlap.height() > 1.0 {
                            failures.push(format!("{at}: {a:?} overlaps {b:?} ({ra:?} / {rb:?})"));
                        }
                    }
                }
                // in-plot labels never sit on a drawn line (curves, arrows, reference
                // curves; grid lines, one point wide, are left out)
                let segments = drawn_segments(h.output());
                for label in lectern::widgets::labels::placed_labels(&h.ctx) {
                    labels_checked += 1;
                    // a leader ends on its label's edge: only the inside counts
                    let inside = label.shrink(1.0);
                    if let Some(s) = segments
                        .iter()
                        .find(|s| lectern::widgets::labels::segment_hits_rect(**s, inside))
                    {
                        failures.push(format!(
                            "{at}: the label at {label:?} sits on the line {s:?}"
                        ));
                    }
                }
                for w in lectern::app::drawn_widgets(&h.ctx) {
                    if w.slide != n {
                        continue;
                    }
                    widgets_checked += 1;
                    if !w.slot.expand(0.5).contains_rect(w.drawn) {
                        failures.push(format!(
                            "{at}: {} {:?} drew {:?} outside its slot {:?}",
                            w.kind, w.path, w.drawn, w.slot
                        ));
                    }
                    if !w.content.expand(0.5).contains_rect(w.slot) {
                        failures.push(format!(
                            "{at}: {} {:?} has a slot {:?} outside the content area {:?}",
                            w.kind, w.path, w.slot, w.content
                        ));
                    }
                }
            }
        }
    }
    assert!(
        texts_checked > 1000 && widgets_checked >= 4 * 20 && labels_checked >= 4 * 8,
        "{texts_checked} {widgets_checked} {labels_checked}"
    );
    failures.dedup();
    assert!(
        failures.is_empty(),
        "{} problems:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// A thumbnail (the overview's, the presenter's "next") is the slide scaled down: the slide
/// drawn into a 480×270 rect equals its 1920×1080 rendering box-filtered to that size, within
/// a tolerance that small text's hinting passes and that unscaled markers, lines and in-plot
/// labels (giant dots, a blob of labels) fail: over the whole slide and in its worst
/// 16×16 window ([`worst_window`], where one giant dot shows). The scene slides are left out (their 3-D views
/// render at the view's own resolution).
#[test]
fn thumbnails_are_the_slide_scaled_down() {
    work_precision::DETERMINISTIC.store(true, Ordering::Relaxed);
    let deck = deck();
    let mut gpu = lectern::app::OffscreenRenderer::software_first().unwrap();
    // one point per pixel at both sizes, as the overview draws a thumbnail into a small rect
    // of the window: only the slide's own scale differs
    let mut render = |n: usize, size: egui::Vec2| {
        let mut state = SlideState::default();
        gpu.render([size.x as u32, size.y as u32], 1.0, |ui| {
            slide_ui(ui, &deck, n, &mut state);
        })
        .unwrap()
    };
    const K: u32 = 4;
    let mut report = Vec::new();
    let mut failures = Vec::new();
    for (n, slide) in deck.slides.iter().enumerate() {
        if slide.widgets().iter().any(|(_, w)| w.kind() == "scene") {
            continue;
        }
        let full = render(n, egui::vec2(1920.0, 1080.0));
        let small = render(n, egui::vec2(480.0, 270.0));
        let (w, h) = small.dimensions();
        assert_eq!(full.dimensions(), (w * K, h * K));
        // per pixel of the thumbnail: the largest channel difference to the full rendering
        // box-filtered K × K
        let mut diff = vec![0.0f64; (w * h) as usize];
        for y in 0..h {
            for x in 0..w {
                let mut acc = [0.0f64; 3];
                for dy in 0..K {
                    for dx in 0..K {
                        let p = full.get_pixel(x * K + dx, y * K + dy);
                        for c in 0..3 {
                            acc[c] += f64::from(p[c]);
                        }
                    }
                }
                let q = small.get_pixel(x, y);
                diff[(y * w + x) as usize] = (0..3)
                    .map(|c| (acc[c] / f64::from(K * K) - f64::from(q[c])).abs())
                    .fold(0.0, f64::max);
            }
        }
        let sum: f64 = diff.iter().sum();
        let far = diff.iter().filter(|&&d| d > 96.0).count();
        let (window, at) = worst_window(&full, &small);
        if let Ok(dir) = std::env::var("THUMBNAIL_DUMP") {
            small.save(format!("{dir}/small-{:02}.png", n + 1)).unwrap();
            full.save(format!("{dir}/full-{:02}.png", n + 1)).unwrap();
        }
        let mean = sum / f64::from(w * h);
        let far_frac = far as f64 / f64::from(w * h);
        report.push(format!(
            "slide {}: mean {mean:.2}, far {:.3} %, worst window {window:.1} at {at:?}",
            n + 1,
            100.0 * far_frac,
        ));
        if mean > MEAN_MAX || far_frac > FAR_MAX || window > WINDOW_MAX {
            failures.push(n + 1);
        }
    }
    println!("{}", report.join("\n"));
    assert!(
        failures.is_empty(),
        "slides {failures:?}:\n{}",
        report.join("\n")
    );
}
/// Bounds of [`thumbnails_are_the_slide_scaled_down`] (channel levels 0…255): measured on the
/// bundled deck, see docs/slides.md. The whole-slide mean and the share of far-off pixels
/// catch a slide drawn differently all over; they cannot catch one giant dot (a marker of 5 px
/// where 1.25 px belong is under 0.1 % of a thumbnail), and a per-pixel bound cannot be tight:
/// egui lays a small slide out a pixel or two off the large one (spacing, tick-label widths).
const MEAN_MAX: f64 = 8.5;
const FAR_MAX: f64 = 0.025;
/// So the worst window is compared too: the mean of the signed difference over a
/// `WINDOW`² window (every `WINDOW_STRIDE` px), per channel. Ink moved by a pixel stays inside
/// a window, so misregistration and text hinting cancel (≤ 23.1 today, slide 18), while ink
/// that is not scaled down (a marker, a line width, an in-plot label) adds up: with marker radii
/// in fixed points 45.6 … 121.6 on 4–9, 11, 13, 14, with every size fixed 63 … 129 on 4–9,
/// 11, 13, 14, 17, 18.
const WINDOW: u32 = 16;
const WINDOW_STRIDE: u32 = 4;
const WINDOW_MAX: f64 = 36.0;

/// The largest |mean(full box-filtered − small)| over `WINDOW`² windows of the thumbnail, any
/// channel, and where (its top-left pixel).
fn worst_window(full: &image::RgbaImage, small: &image::RgbaImage) -> (f64, (u32, u32)) {
    let (w, h) = small.dimensions();
    let k = full.width() / w;
    // summed-area table of the signed difference per channel: sat[c][y][x] sums the
    // differences of the pixels above and left of (x, y)
    let stride = (w + 1) as usize;
    let mut sat = vec![vec![0.0f64; stride * (h + 1) as usize]; 3];
    for y in 0..h {
        let mut row = [0.0f64; 3];
        for x in 0..w {
            let q = small.get_pixel(x, y);
            for c in 0..3 {
                let mut acc = 0.0;
                for dy in 0..k {
                    for dx in 0..k {
                        acc += f64::from(full.get_pixel(x * k + dx, y * k + dy)[c]);
                    }
                }
                row[c] += acc / f64::from(k * k) - f64::from(q[c]);
                let i = (y as usize + 1) * stride + x as usize + 1;
                sat[c][i] = sat[c][i - stride] + row[c];
            }
        }
    }
    let mut worst = (0.0, (0, 0));
    let area = f64::from(WINDOW * WINDOW);
    for y in (0..=h - WINDOW).step_by(WINDOW_STRIDE as usize) {
        for x in (0..=w - WINDOW).step_by(WINDOW_STRIDE as usize) {
            let at = |xx: u32, yy: u32| yy as usize * stride + xx as usize;
            for t in &sat {
                let s = t[at(x + WINDOW, y + WINDOW)] - t[at(x, y + WINDOW)] - t[at(x + WINDOW, y)]
                    + t[at(x, y)];
                if (s / area).abs() > worst.0 {
                    worst = ((s / area).abs(), (x, y));
                }
            }
        }
    }
    worst
}

/// `controls: Presenter`: the slide (projector, export) shows the plot and its values, not the
/// sliders and checkboxes; the default deck shows them; `ShowControls::Always` (the `C` key) brings
/// them back.
#[test]
fn controls_presenter_shows_values_not_sliders() {
    use egui::accesskit::Role;
    use egui_kittest::kittest::Queryable;
    use lectern::app::{SlideOptions, slide_ui_with};
    let slope_field = 3; // slide 4: h slider, three method checkboxes, "exact"
    let run = |controls: lectern::deck::Controls, force: bool| {
        let mut d = deck();
        d.controls = controls;
        let mut state = SlideState::default();
        let mut h = Harness::builder().with_size(SIZE).build_ui(move |ui| {
            let options = SlideOptions {
                controls: match force {
                    true => lectern::app::ShowControls::Always,
                    false => lectern::app::ShowControls::AsDeck,
                },
                ..SlideOptions::default()
            };
            slide_ui_with(ui, &d, slope_field, &mut state, options);
        });
        h.run_steps(3);
        let sliders = h.query_all_by_role(Role::Slider).count();
        let boxes = h.query_all_by_role(Role::CheckBox).count();
        let texts: Vec<String> = text_boxes(h.output()).into_iter().map(|t| t.0).collect();
        (sliders, boxes, texts)
    };
    let (sliders, boxes, _) = run(lectern::deck::Controls::Slide, false);
    assert!(
        sliders >= 1 && boxes >= 4,
        "{sliders} sliders, {boxes} checkboxes"
    );
    let (sliders, boxes, texts) = run(lectern::deck::Controls::Presenter, false);
    assert_eq!((sliders, boxes), (0, 0), "the projector shows no controls");
    assert!(texts.iter().any(|t| t.contains("h = 0.500")), "{texts:?}");
    for legend in ["Euler", "Midpoint", "RK4", "exact"] {
        assert!(
            texts.iter().any(|t| t.trim() == legend),
            "{legend} in {texts:?}"
        );
    }
    let (sliders, _, _) = run(lectern::deck::Controls::Presenter, true);
    assert!(sliders >= 1, "C brings the controls back");
}

/// The smallest share of the slide's height a picture of the scene may take. Two pictures side
/// by side on a 16:9 slide are each ~45 % of its width; at 40 % of its height a pair still
/// reads from the back row (at 1080p: 430 px, where the techniques' details, a shadow, sand
/// ripples, a fish, are several pixels), and a slide with a title, one line of text or a
/// formula and one-line captions leaves about 50 %: 40 % is what such a slide can always keep.
/// On 27 as it was (three lines of text, a formula, two-line captions) they got 23 %.
const MIN_PICTURE_SHARE: f32 = 0.4;

/// The scene slides show their pictures large and lined up: every `Scene` widget takes at
/// least [`MIN_PICTURE_SHARE`] of the slide's height and ends above the footer, the pictures of
/// one `Columns` block start and end at the same height, and every caption in a picture's
/// column is laid out on one line (no caption wraps, at 1280×720 and 1920×1080).
#[test]
fn scene_pictures_are_large_lined_up_and_captioned_on_one_line() {
    let mut failures = Vec::new();
    let mut pictures = 0;
    let deck = Arc::new(deck());
    for size in [egui::vec2(1280.0, 720.0), egui::vec2(1920.0, 1080.0)] {
        for (n, slide) in deck.slides.iter().enumerate() {
            let scene_columns: Vec<&Vec<Block>> = slide
                .body
                .iter()
                .filter_map(|b| match b {
                    Block::Columns(cols) => Some(cols),
                    _ => None,
                })
                .flatten()
                .filter(|col| col.iter().any(is_scene))
                .collect();
            if !blocks(slide).into_iter().any(is_scene) {
                continue;
            }
            let shown = deck.clone();
            let mut state = SlideState::default();
            let mut h = Harness::builder().with_size(size).build_ui(move |ui| {
                slide_ui(ui, &shown, n, &mut state);
            });
            h.run_steps(3);
            let at = format!("{}×{} slide {} {:?}", size.x, size.y, n + 1, slide.title);
            let scenes: Vec<_> = lectern::app::drawn_widgets(&h.ctx)
                .into_iter()
                .filter(|w| w.slide == n && w.kind == "scene")
                .collect();
            if scenes.is_empty() {
                failures.push(format!("{at}: no scene drawn"));
            }
            for w in &scenes {
                pictures += 1;
                let share = w.drawn.height() / size.y;
                if share < MIN_PICTURE_SHARE {
                    failures.push(format!(
                        "{at}: picture {:?} is {:.0} % of the slide's height (< {:.0} %)",
                        w.path,
                        100.0 * share,
                        100.0 * MIN_PICTURE_SHARE
                    ));
                }
                if w.drawn.bottom() > w.content.bottom() + 0.5 {
                    failures.push(format!("{at}: picture {:?} reaches the footer", w.path));
                }
                // the pictures of one `Columns` block (path: block, column, index)
                for o in &scenes {
                    let pair = w.path.len() == 3 && o.path.len() == 3 && w.path[0] == o.path[0];
                    if pair
                        && ((w.drawn.top() - o.drawn.top()).abs() > 1.0
                            || (w.drawn.bottom() - o.drawn.bottom()).abs() > 1.0)
                    {
                        failures.push(format!(
                            "{at}: pictures {:?} {:?} and {:?} {:?} do not line up",
                            w.path, w.drawn, o.path, o.drawn
                        ));
                    }
                }
            }
            // a caption on one line is one row of text holding the whole caption
            let rows: Vec<String> = text_boxes(h.output())
                .into_iter()
                .map(|(t, _, _)| t.trim().to_owned())
                .collect();
            for caption in scene_columns.iter().flat_map(|col| col.iter()) {
                if let Block::Text(t) = caption
                    && !rows.iter().any(|r| r == t.src.trim())
                {
                    failures.push(format!("{at}: caption {t:?} wraps"));
                }
            }
        }
    }
    failures.dedup();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    // slide 19 and the seven project slides, at two sizes
    assert!(pictures >= 2 * 14, "{pictures} pictures");
}

fn is_scene(b: &Block) -> bool {
    matches!(
        b,
        Block::Widget(lectern::deck::widgets::WidgetSpec::Scene(_))
    )
}
