//! The box of the complex plane a stability plot shows: fitted to the methods' regions, and
//! fitted to the plot's shape with one unit the same length on both axes. Pure geometry, no
//! drawing.

use super::stability_region::{Bounds, Region};

/// The box the regions need: the union of the bounded regions' boxes and of the unbounded
/// ones' closed boundary curves (implicit Euler's circle |z − 1| = 1, radau5's island in
/// Re z > 0), with the origin; when an unbounded region is drawn the box reaches as far left
/// of the origin as right of it, so the shaded left half-plane shows. Widened by a tenth on
/// each side and symmetric about the real axis.
pub fn fitted_bounds(all: &[&Region]) -> Bounds {
    let boxes = all.iter().filter_map(|r| {
        if r.unbounded {
            super::stability_region::closed_boundary_bounds(r)
        } else {
            Some(r.bounds)
        }
    });
    let (mut x0, x1, y0, y1) = boxes.fold((0.0_f64, 0.0_f64, 0.0_f64, 0.0_f64), |a, b| {
        (a.0.min(b.0), a.1.max(b.1), a.2.min(b.2), a.3.max(b.3))
    });
    if all.iter().any(|r| r.unbounded) {
        // the shaded left half-plane shows: at least a unit, and half as far as the right
        x0 = x0.min(-0.5 * x1).min(-1.0);
    }
    let y = y0
        .abs()
        .max(y1.abs())
        .max(if x0 < -0.5 { 1.0 } else { 0.0 });
    super::stability_region::pad_symmetric((x0, x1.max(0.0), -y, y), 0.1)
}

/// `b` widened (about its centre) to the shape `shape` (width over height): never cropped.
pub fn expand_to_shape(b: Bounds, shape: f64) -> Bounds {
    let (x0, x1, y0, y1) = b;
    let (w, h) = ((x1 - x0).max(1e-9), (y1 - y0).max(1e-9));
    let (cx, cy) = ((x0 + x1) / 2.0, (y0 + y1) / 2.0);
    let (w, h) = if w / h < shape {
        (h * shape, h)
    } else {
        (w, w / shape.max(1e-9))
    };
    (cx - w / 2.0, cx + w / 2.0, cy - h / 2.0, cy + h / 2.0)
}

/// `b` (re_min, re_max, im_min, im_max) made to fit a plot `shape` (width over height, in
/// points) with one unit the same length on both axes: the box's short side is padded (about
/// its centre) towards the plot's shape, but never beyond the long side — a wide, low slot
/// gets a square box and blank space beside the plot, not a complex plane three times as
/// wide as the regions. Returns the box and the fraction (width, height) of the slot the plot
/// then takes.
pub fn equal_aspect_box(b: Bounds, shape: f64) -> (Bounds, (f32, f32)) {
    let (x0, x1, y0, y1) = b;
    let (w, h) = ((x1 - x0).max(1e-9), (y1 - y0).max(1e-9));
    let long = w.max(h);
    let (cx, cy) = ((x0 + x1) / 2.0, (y0 + y1) / 2.0);
    let (w2, h2) = if shape > w / h {
        // the slot is wider than the box: widen the box, up to square
        ((h * shape).min(long), h)
    } else {
        (w, (w / shape).min(long))
    };
    let bounds = (cx - w2 / 2.0, cx + w2 / 2.0, cy - h2 / 2.0, cy + h2 / 2.0);
    // the plot's share of the slot at that box's aspect
    let frac = if shape > w2 / h2 {
        ((w2 / h2 / shape) as f32, 1.0)
    } else {
        (1.0, (shape / (w2 / h2)) as f32)
    };
    (bounds, frac)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// With `Equal` a wide, low slot pads the box's short side only up to its long side: slide
    /// 8's regions at 1280×720 used to be shown on −16 … 12.
    #[test]
    fn equal_aspect_pads_the_short_side_only_up_to_the_long_one() {
        let slide_8 = (-4.4, 0.4, -3.3, 3.3);
        let ((x0, x1, y0, y1), frac) = equal_aspect_box(slide_8, 4.3);
        assert!((x1 - x0 - 6.6).abs() < 1e-9 && (y1 - y0 - 6.6).abs() < 1e-9);
        assert!((x0 + x1 - (-4.0)).abs() < 1e-9, "about the box's centre");
        assert!(
            (frac.0 - 1.0 / 4.3).abs() < 1e-6 && frac.1 == 1.0,
            "{frac:?}"
        );
        // a wide box in a wide slot keeps its long side; a tall slot pads the height
        let ((a, b, _, _), _) = equal_aspect_box((-10.0, 10.0, -1.0, 1.0), 3.0);
        assert_eq!((a, b), (-10.0, 10.0));
        let ((_, _, c, d), frac) = equal_aspect_box((-1.0, 1.0, -1.0, 1.0), 0.5);
        assert_eq!((c, d), (-1.0, 1.0), "a square box stays square");
        assert!((frac.1 - 0.5).abs() < 1e-6);
        // never cropped
        let e = expand_to_shape((0.0, 1.0, 0.0, 4.0), 2.0);
        assert!(
            e.0 <= 0.0 && e.1 >= 1.0 && e.2 <= 0.0 && e.3 >= 4.0,
            "{e:?}"
        );
        assert!(((e.1 - e.0) / (e.3 - e.2) - 2.0).abs() < 1e-12);
    }
}
