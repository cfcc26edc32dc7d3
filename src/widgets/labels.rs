//! In-plot labels that never overlap each other, the points they sit beside or the drawn lines
//! (labels avoid segments, not only points): each label is
//! placed at its preferred side of its anchor if that is free, else at the first free spot of a
//! fixed list (the other sides, then further out, then nudged up and down), joined to its anchor
//! by a leader line when it had to move away; a label that finds no free spot inside the plot
//! is dropped (its value is in the widget's readout row as well). egui_plot knows nothing of
//! collisions, so the labels are drawn here from the plot's transform, after the plot.

use egui::{Align2, Color32, Pos2, Rect, Vec2, vec2};
use egui_plot::{PlotPoint, PlotTransform};

use super::style;

/// A label to place beside the data point `at`.
#[derive(Debug, Clone)]
pub struct PlotLabel {
    pub text: String,
    /// The label's colour (made readable on the plot with [`style::text_color_in`]).
    pub color: Color32,
    pub at: PlotPoint,
    /// Where the label would like to be, seen from the point: `RIGHT_CENTER` puts it to the
    /// point's left (the label's right edge at the point), `LEFT_BOTTOM` above and to the right.
    pub anchor: Align2,
}

/// Where a label ended up.
#[derive(Debug, Clone, PartialEq)]
pub struct Placed {
    pub index: usize,
    pub rect: Rect,
    /// From the anchor to the label, when it was moved away from its preferred spot.
    pub leader: Option<[Pos2; 2]>,
}

/// The rect of a `size` label at `anchor` (its `align` corner) with a `gap` to the anchor.
fn rect_at(anchor: Pos2, align: Align2, size: Vec2, gap: f32) -> Rect {
    // push the rect away from the point on the side(s) it is aligned to
    let dx = match align.x() {
        egui::Align::Min => gap,
        egui::Align::Center => 0.0,
        egui::Align::Max => -gap,
    };
    let dy = match align.y() {
        egui::Align::Min => gap,
        egui::Align::Center => 0.0,
        egui::Align::Max => -gap,
    };
    align.anchor_size(anchor + vec2(dx, dy), size)
}

/// Whether the segment `a`–`b` crosses or touches `rect` (Liang–Barsky clipping).
pub fn segment_hits_rect([a, b]: [Pos2; 2], rect: Rect) -> bool {
    let d = b - a;
    let (mut t0, mut t1) = (0.0_f32, 1.0_f32);
    for (p, q) in [
        (-d.x, a.x - rect.min.x),
        (d.x, rect.max.x - a.x),
        (-d.y, a.y - rect.min.y),
        (d.y, rect.max.y - a.y),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return false; // parallel to this edge and outside it
            }
        } else {
            let r = q / p;
            if p < 0.0 {
                t0 = t0.max(r);
            } else {
                t1 = t1.min(r);
            }
            if t0 > t1 {
                return false;
            }
        }
    }
    true
}

/// Places labels of the given screen `sizes` at screen `anchors` (in order; earlier labels
/// win), inside `frame`, clear of each other, of `obstacles` and of the drawn `segments` (a
/// label never sits on a line, its own included), by `gap / 4` at least. `gap`: the distance
/// kept from an anchor, in points. Pure geometry, so it is tested without a window.
pub fn place(
    anchors: &[(Pos2, Align2)],
    sizes: &[Vec2],
    frame: Rect,
    obstacles: &[Rect],
    segments: &[[Pos2; 2]],
    gap: f32,
) -> Vec<Placed> {
    let mut taken: Vec<Rect> = obstacles.to_vec();
    let mut out = Vec::new();
    let sides = [
        Align2::RIGHT_CENTER,
        Align2::LEFT_CENTER,
        Align2::LEFT_BOTTOM,
        Align2::RIGHT_BOTTOM,
        Align2::LEFT_TOP,
        Align2::RIGHT_TOP,
        Align2::CENTER_BOTTOM,
        Align2::CENTER_TOP,
    ];
    let clearance = 0.25 * gap;
    for (index, (&(anchor, preferred), &size)) in anchors.iter().zip(sizes).enumerate() {
        let fits = |r: &Rect| {
            let padded = r.expand(clearance);
            frame.contains_rect(*r)
                && taken.iter().all(|t| !t.shrink(0.5).intersects(*r))
                && !segments.iter().any(|s| segment_hits_rect(*s, padded))
        };
        let first = rect_at(anchor, preferred, size, gap);
        let mut candidates = vec![(first, false)];
        // nudged up and down from the preferred spot, a line at a time (a short nudge keeps
        // the label on the side its author chose), then the other sides, further out, and
        // longer nudges
        let nudge = |k: i32| first.translate(vec2(0.0, k as f32 * (size.y + 0.25 * gap)));
        for k in 1..=2 {
            candidates.push((nudge(k), true));
            candidates.push((nudge(-k), true));
        }
        for far in [1.0, 3.0, 6.0, 10.0] {
            for side in sides {
                candidates.push((
                    rect_at(anchor, side, size, gap * far),
                    far > 1.0 || side != preferred,
                ));
            }
        }
        for k in 3..=8 {
            candidates.push((nudge(k), true));
            candidates.push((nudge(-k), true));
        }
        if let Some((rect, moved)) = candidates.into_iter().find(|(r, _)| fits(r)) {
            let leader = moved.then(|| [anchor, rect.clamp(anchor)]);
            // a leader shorter than the gap is no help
            let leader = leader.filter(|[a, b]| a.distance(*b) > 1.5 * gap);
            taken.push(rect);
            out.push(Placed {
                index,
                rect,
                leader,
            });
        }
    }
    out
}

/// The screen segments of `polylines` (data coordinates) under `transform`: what labels keep
/// clear of.
pub fn screen_segments(transform: &PlotTransform, polylines: &[Vec<[f64; 2]>]) -> Vec<[Pos2; 2]> {
    polylines
        .iter()
        .flat_map(|line| {
            line.windows(2).map(|w| {
                [w[0], w[1]].map(|p| transform.position_from_point(&PlotPoint::new(p[0], p[1])))
            })
        })
        .collect()
}

/// The screen rect a marker of `radius` at data point `at` covers (an obstacle for labels).
pub fn marker_rect(transform: &PlotTransform, at: PlotPoint, radius: f32) -> Rect {
    Rect::from_center_size(
        transform.position_from_point(&at),
        Vec2::splat(2.0 * radius),
    )
}

/// Draws `labels` over the plot whose transform is `transform`, placed by [`place`], in the
/// widgets' body text; `obstacles` are screen rects to keep clear (markers at curves' ends),
/// `lines` the plot's drawn polylines in data coordinates (labels never sit on one). Where each
/// label went is noted for [`placed_labels`].
pub fn draw(
    ui: &egui::Ui,
    transform: &PlotTransform,
    labels: &[PlotLabel],
    obstacles: &[Rect],
    lines: &[Vec<[f64; 2]>],
) {
    let u = style::unit(ui);
    let font = egui::TextStyle::Body.resolve(ui.style());
    let visuals = ui.visuals().clone();
    let painter = ui.painter().with_clip_rect(*transform.frame());
    let galleys: Vec<_> = labels
        .iter()
        .map(|l| {
            let color = style::text_color_in(&visuals, l.color);
            painter.layout_no_wrap(l.text.clone(), font.clone(), color)
        })
        .collect();
    let anchors: Vec<(Pos2, Align2)> = labels
        .iter()
        .map(|l| (transform.position_from_point(&l.at), l.anchor))
        .collect();
    let sizes: Vec<Vec2> = galleys.iter().map(|g| g.size()).collect();
    let frame = transform.frame().shrink(2.0 * u);
    let segments = screen_segments(transform, lines);
    let placed = place(&anchors, &sizes, frame, obstacles, &segments, 8.0 * u);
    for p in &placed {
        let color = style::text_color_in(&visuals, labels[p.index].color);
        if let Some([a, b]) = p.leader {
            painter.line_segment([a, b], egui::Stroke::new(1.5 * u, color));
        }
        painter.galley(p.rect.min, galleys[p.index].clone(), color);
    }
    record(ui.ctx(), placed.iter().map(|p| p.rect));
}

fn placed_labels_id() -> egui::Id {
    egui::Id::unique("lectern-placed-plot-labels")
}

/// Notes this pass's placed label rects, dropping those of passes before the last.
fn record(ctx: &egui::Context, rects: impl Iterator<Item = Rect>) {
    let pass = ctx.cumulative_pass_nr();
    ctx.data_mut(|d| {
        let v = d.get_temp_mut_or_default::<Vec<(u64, Rect)>>(placed_labels_id());
        v.retain(|(p, _)| *p + 1 >= pass);
        v.extend(rects.map(|r| (pass, r)));
    });
}

/// The screen rects of the in-plot labels drawn in the latest pass of `ctx` (for the test that
/// labels never sit on a drawn line).
pub fn placed_labels(ctx: &egui::Context) -> Vec<Rect> {
    let v: Vec<(u64, Rect)> = ctx.data(|d| d.get_temp(placed_labels_id()).unwrap_or_default());
    let last = v.iter().map(|(p, _)| *p).max().unwrap_or(0);
    v.into_iter()
        .filter(|(p, _)| *p == last)
        .map(|(_, r)| r)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_at_one_point_are_stacked_not_overlapped() {
        let frame = Rect::from_min_size(Pos2::ZERO, vec2(800.0, 600.0));
        let at = (Pos2::new(400.0, 300.0), Align2::RIGHT_CENTER);
        let sizes = vec![vec2(200.0, 30.0); 4];
        let placed = place(&[at; 4], &sizes, frame, &[], &[], 8.0);
        assert_eq!(placed.len(), 4);
        for (i, a) in placed.iter().enumerate() {
            assert!(frame.contains_rect(a.rect));
            for b in &placed[i + 1..] {
                assert!(!a.rect.shrink(0.5).intersects(b.rect), "{a:?} {b:?}");
            }
        }
        // the first keeps its preferred spot: left of the point, no leader
        assert!(placed[0].rect.right() <= 400.0 && placed[0].leader.is_none());
    }

    #[test]
    fn a_label_keeps_clear_of_markers_and_the_frame_and_drops_when_nothing_fits() {
        let frame = Rect::from_min_size(Pos2::ZERO, vec2(300.0, 100.0));
        // at the left edge, preferring the left: it must move right, inside the frame
        let at = (Pos2::new(5.0, 50.0), Align2::RIGHT_CENTER);
        let marker = Rect::from_center_size(Pos2::new(60.0, 50.0), Vec2::splat(10.0));
        let placed = place(&[at], &[vec2(100.0, 20.0)], frame, &[marker], &[], 8.0);
        assert_eq!(placed.len(), 1);
        assert!(frame.contains_rect(placed[0].rect));
        assert!(!placed[0].rect.intersects(marker));
        // wider than the frame: dropped
        assert!(place(&[at], &[vec2(400.0, 20.0)], frame, &[], &[], 8.0).is_empty());
    }

    #[test]
    fn labels_avoid_segments_not_only_points() {
        let frame = Rect::from_min_size(Pos2::ZERO, vec2(400.0, 300.0));
        // a line through the preferred spot (left of the point) and one through the spot above
        let anchor = Pos2::new(200.0, 150.0);
        let segments = [
            [Pos2::new(0.0, 150.0), Pos2::new(190.0, 150.0)],
            [Pos2::new(200.0, 0.0), Pos2::new(260.0, 140.0)],
        ];
        let size = vec2(80.0, 20.0);
        let placed = place(
            &[(anchor, Align2::RIGHT_CENTER)],
            &[size],
            frame,
            &[],
            &segments,
            8.0,
        );
        assert_eq!(placed.len(), 1);
        let r = placed[0].rect;
        assert!(frame.contains_rect(r));
        for s in segments {
            assert!(!segment_hits_rect(s, r.expand(2.0)), "{r:?} on {s:?}");
        }
        // without the segments it keeps its preferred spot, which the first line crosses
        let free = place(
            &[(anchor, Align2::RIGHT_CENTER)],
            &[size],
            frame,
            &[],
            &[],
            8.0,
        );
        assert!(segment_hits_rect(segments[0], free[0].rect));
    }

    #[test]
    fn segment_rect_intersection() {
        let r = Rect::from_min_max(Pos2::new(0.0, 0.0), Pos2::new(10.0, 10.0));
        let hit = |a: (f32, f32), b: (f32, f32)| {
            segment_hits_rect([Pos2::new(a.0, a.1), Pos2::new(b.0, b.1)], r)
        };
        assert!(hit((-5.0, 5.0), (15.0, 5.0))); // straight through
        assert!(hit((2.0, 2.0), (3.0, 3.0))); // inside
        assert!(hit((-5.0, -5.0), (15.0, 15.0))); // diagonal
        assert!(!hit((-5.0, 11.0), (15.0, 11.0))); // above
        assert!(!hit((11.0, -5.0), (20.0, 5.0))); // right of it
        assert!(!hit((-3.0, 8.0), (1.0, 13.0))); // passes outside a corner
    }
}
