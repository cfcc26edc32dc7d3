//! In-plot labels that never overlap each other or the points they sit beside: each label is
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

/// Places labels of the given screen `sizes` at screen `anchors` (in order; earlier labels
/// win), inside `frame`, clear of each other and of `obstacles`. `gap`: the distance kept from
/// an anchor, in points. Pure geometry, so it is tested without a window.
pub fn place(
    anchors: &[(Pos2, Align2)],
    sizes: &[Vec2],
    frame: Rect,
    obstacles: &[Rect],
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
    for (index, (&(anchor, preferred), &size)) in anchors.iter().zip(sizes).enumerate() {
        let fits = |r: &Rect| {
            frame.contains_rect(*r) && taken.iter().all(|t| !t.shrink(0.5).intersects(*r))
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
        for far in [1.0, 3.0] {
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

/// The screen rect a marker of `radius` at data point `at` covers (an obstacle for labels).
pub fn marker_rect(transform: &PlotTransform, at: PlotPoint, radius: f32) -> Rect {
    Rect::from_center_size(
        transform.position_from_point(&at),
        Vec2::splat(2.0 * radius),
    )
}

/// Draws `labels` over the plot whose transform is `transform`, placed by [`place`], in the
/// widgets' body text; `obstacles` are screen rects to keep clear (markers at curves' ends).
pub fn draw(ui: &egui::Ui, transform: &PlotTransform, labels: &[PlotLabel], obstacles: &[Rect]) {
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
    for p in place(&anchors, &sizes, frame, obstacles, 8.0 * u) {
        let color = style::text_color_in(&visuals, labels[p.index].color);
        if let Some([a, b]) = p.leader {
            painter.line_segment([a, b], egui::Stroke::new(1.5 * u, color));
        }
        painter.galley(p.rect.min, galleys[p.index].clone(), color);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_at_one_point_are_stacked_not_overlapped() {
        let frame = Rect::from_min_size(Pos2::ZERO, vec2(800.0, 600.0));
        let at = (Pos2::new(400.0, 300.0), Align2::RIGHT_CENTER);
        let sizes = vec![vec2(200.0, 30.0); 4];
        let placed = place(&[at; 4], &sizes, frame, &[], 8.0);
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
        let placed = place(&[at], &[vec2(100.0, 20.0)], frame, &[marker], 8.0);
        assert_eq!(placed.len(), 1);
        assert!(frame.contains_rect(placed[0].rect));
        assert!(!placed[0].rect.intersects(marker));
        // wider than the frame: dropped
        assert!(place(&[at], &[vec2(400.0, 20.0)], frame, &[], 8.0).is_empty());
    }
}
