//! The whole stability region {z : |R(z)| ≤ 1} of a method, not a window onto it: a box that
//! grows until it holds the region, then the |R| = 1 contour on a grid over that box (marching
//! squares), its crossings refined by bisection on R itself and linked into closed polylines.
//! RK4's region reaches −2.785 on the real axis and ±2√2 i; the notes' RK4 typo reaches −4.0,
//! which a fixed box cut at −3.5 used to hide.

use super::stability::{Complex, cabs};

/// Boxes grow up to this half-width; a region still touching the edge there is unbounded
/// (an implicit method) and is drawn up to it.
pub const MAX_HALF_WIDTH: f64 = 24.0;

/// Grid points per axis of the coarse search for a region's extent.
const COARSE: usize = 121;

/// A rectangle of the complex plane: (re_min, re_max, im_min, im_max).
pub type Bounds = (f64, f64, f64, f64);

/// Where |R(z)| ≤ 1 (with the same tolerance as the stable-h search: 1e-12).
fn stable(abs_r: &impl Fn(Complex) -> f64, z: Complex) -> bool {
    abs_r(z) <= 1.0 + 1e-12
}

/// The smallest box (grid-accurate, one coarse cell of margin) holding every stable point of
/// the method, and whether the region is unbounded (still at the edge of the largest box).
/// `None` when no point of the plane tried is stable.
pub fn region_extent(abs_r: impl Fn(Complex) -> f64) -> Option<(Bounds, bool)> {
    let mut half = 2.0_f64;
    loop {
        let cell = 2.0 * half / (COARSE - 1) as f64;
        let at = |i: usize| -half + cell * i as f64;
        let (mut lo_re, mut hi_re, mut lo_im, mut hi_im) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
        let mut at_edge = false;
        for j in 0..COARSE {
            for i in 0..COARSE {
                let z = (at(i), at(j));
                if !stable(&abs_r, z) {
                    continue;
                }
                lo_re = lo_re.min(z.0);
                hi_re = hi_re.max(z.0);
                lo_im = lo_im.min(z.1);
                hi_im = hi_im.max(z.1);
                at_edge |= i == 0 || j == 0 || i == COARSE - 1 || j == COARSE - 1;
            }
        }
        if lo_re > hi_re {
            return None;
        }
        if !at_edge || half >= MAX_HALF_WIDTH {
            let clip = |v: f64| v.clamp(-half, half);
            let b = (
                clip(lo_re - cell),
                clip(hi_re + cell),
                clip(lo_im - cell),
                clip(hi_im + cell),
            );
            return Some((b, at_edge));
        }
        half = (half * 2.0).min(MAX_HALF_WIDTH);
    }
}

/// A grid over a box: `nx` × `ny` points, row 0 at `im_max` (image order), with one row on the
/// real axis when the box is symmetric about it and `ny` is odd.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grid {
    pub bounds: Bounds,
    pub nx: usize,
    pub ny: usize,
}

impl Grid {
    pub fn at(&self, i: usize, j: usize) -> Complex {
        let (x0, x1, y0, y1) = self.bounds;
        (
            x0 + (x1 - x0) * i as f64 / (self.nx - 1) as f64,
            y1 - (y1 - y0) * j as f64 / (self.ny - 1) as f64,
        )
    }

    /// |R| − 1 at every grid point, row-major (≤ 0 inside the region).
    pub fn values(&self, abs_r: impl Fn(Complex) -> f64) -> Vec<f64> {
        (0..self.nx * self.ny)
            .map(|k| abs_r(self.at(k % self.nx, k / self.nx)) - 1.0)
            .collect()
    }
}

/// The |R| = 1 contour of `abs_r` on `grid` (with `vals` = [`Grid::values`]) as polylines:
/// closed ones end on their first point; one that runs off the grid (an unbounded region) is
/// left open. Every vertex lies on a grid edge and is refined there by bisection on `abs_r`, so
/// it is on the true contour to ~1e-12 whatever the grid's resolution. Longest first.
pub fn contour(abs_r: impl Fn(Complex) -> f64, grid: &Grid, vals: &[f64]) -> Vec<Vec<Complex>> {
    let (nx, ny) = (grid.nx, grid.ny);
    let inside = |i: usize, j: usize| vals[j * nx + i] <= 1e-12;
    // An edge by its lower-left grid point and direction: (i, j, 0) runs to (i+1, j),
    // (i, j, 1) to (i, j+1).
    type Edge = (usize, usize, u8);
    let ends = |e: Edge| {
        let (i, j, d) = e;
        if d == 0 {
            ((i, j), (i + 1, j))
        } else {
            ((i, j), (i, j + 1))
        }
    };
    let crosses = |e: Edge| {
        let ((a, b), (c, d)) = ends(e);
        inside(a, b) != inside(c, d)
    };
    // segments between edges, cell by cell; a saddle (all four edges cut) is resolved by the
    // value at the cell's centre
    let mut segs: Vec<(Edge, Edge)> = Vec::new();
    for j in 0..ny - 1 {
        for i in 0..nx - 1 {
            let sides: [Edge; 4] = [(i, j, 0), (i + 1, j, 1), (i, j + 1, 0), (i, j, 1)];
            let cut: Vec<Edge> = sides.iter().copied().filter(|&e| crosses(e)).collect();
            match cut.len() {
                2 => segs.push((cut[0], cut[1])),
                4 => {
                    let (a, b) = (grid.at(i, j), grid.at(i + 1, j + 1));
                    let centre_in = stable(&abs_r, ((a.0 + b.0) / 2.0, (a.1 + b.1) / 2.0));
                    // pair each cut edge with the neighbour that keeps the centre's side joined
                    if centre_in == inside(i, j) {
                        segs.push((sides[0], sides[1]));
                        segs.push((sides[2], sides[3]));
                    } else {
                        segs.push((sides[0], sides[3]));
                        segs.push((sides[1], sides[2]));
                    }
                }
                _ => {}
            }
        }
    }
    // link segments sharing an edge into chains
    let mut by_edge: std::collections::HashMap<Edge, Vec<usize>> = Default::default();
    for (k, (a, b)) in segs.iter().enumerate() {
        by_edge.entry(*a).or_default().push(k);
        by_edge.entry(*b).or_default().push(k);
    }
    let mut used = vec![false; segs.len()];
    let mut chains: Vec<Vec<Edge>> = Vec::new();
    let next_from = |e: Edge, used: &[bool]| -> Option<usize> {
        by_edge.get(&e)?.iter().copied().find(|&k| !used[k])
    };
    for start in 0..segs.len() {
        if used[start] {
            continue;
        }
        used[start] = true;
        let (a, b) = segs[start];
        let mut chain = vec![a, b];
        // forwards from b, then backwards from a (an open chain runs edge to edge of the grid)
        while let Some(k) = next_from(*chain.last().expect("two edges"), &used) {
            used[k] = true;
            let (p, q) = segs[k];
            chain.push(if p == *chain.last().expect("non-empty") {
                q
            } else {
                p
            });
        }
        if chain.first() != chain.last() {
            let mut back = Vec::new();
            let mut at = a;
            while let Some(k) = next_from(at, &used) {
                used[k] = true;
                let (p, q) = segs[k];
                at = if p == at { q } else { p };
                back.push(at);
            }
            back.reverse();
            back.extend(chain);
            chain = back;
        }
        chains.push(chain);
    }
    let point = |e: Edge| {
        let ((a, b), (c, d)) = ends(e);
        let (mut pin, mut pout) = (grid.at(a, b), grid.at(c, d));
        if !inside(a, b) {
            std::mem::swap(&mut pin, &mut pout);
        }
        for _ in 0..48 {
            let mid = ((pin.0 + pout.0) / 2.0, (pin.1 + pout.1) / 2.0);
            if stable(&abs_r, mid) {
                pin = mid
            } else {
                pout = mid
            }
        }
        pin
    };
    let mut lines: Vec<Vec<Complex>> = chains
        .into_iter()
        .map(|c| c.into_iter().map(point).collect())
        .collect();
    lines.sort_by_key(|l| std::cmp::Reverse(l.len()));
    lines
}

/// Points per axis of the fine grid the contour is traced on.
pub const FINE: usize = 301;

/// A method's region: the box it fits in, whether it is unbounded, and its boundary.
#[derive(Debug, Clone, PartialEq)]
pub struct Region {
    pub bounds: Bounds,
    pub unbounded: bool,
    /// Closed polylines of |R| = 1, longest (the main region's edge) first.
    pub boundary: Vec<Vec<Complex>>,
}

/// The region of `r` (a stability function): its extent, then the contour on a grid over a
/// box padded by a tenth around it and symmetric about the real axis, with a row on it. An
/// unbounded region (an implicit method: implicit Euler is stable outside the disc
/// |z − 1| ≤ 1) is traced over the extent of where it is *not* stable when that is bounded,
/// so its boundary is as fine as a bounded region's; else over the largest box.
pub fn region(r: impl Fn(Complex) -> Complex) -> Option<Region> {
    let abs_r = |z: Complex| cabs(r(z));
    let (b, unbounded) = region_extent(abs_r)?;
    let traced = if unbounded {
        // |R| ≥ 1 where 1/|R| ≤ 1: the unstable set with its edge
        match region_extent(|z| 1.0 / abs_r(z)) {
            Some((u, false)) => u,
            _ => b,
        }
    } else {
        b
    };
    let grid = Grid {
        bounds: pad_symmetric(traced, 0.1),
        nx: FINE,
        ny: FINE,
    };
    let vals = grid.values(abs_r);
    Some(Region {
        bounds: b,
        unbounded,
        boundary: contour(abs_r, &grid, &vals),
    })
}

/// The box of a region's closed boundary curves (an unbounded region's open ones, such as
/// implicit midpoint's imaginary axis, have no extent to fit), or `None` if it has none.
pub fn closed_boundary_bounds(r: &Region) -> Option<Bounds> {
    r.boundary
        .iter()
        .filter(|l| l.len() > 2 && l.first() == l.last())
        .flatten()
        .fold(None, |acc: Option<Bounds>, z| {
            Some(match acc {
                None => (z.0, z.0, z.1, z.1),
                Some(b) => (b.0.min(z.0), b.1.max(z.0), b.2.min(z.1), b.3.max(z.1)),
            })
        })
}

/// `b` widened by `frac` of its size on each side and made symmetric about the real axis.
pub fn pad_symmetric(b: Bounds, frac: f64) -> Bounds {
    let (x0, x1, y0, y1) = b;
    let px = frac * (x1 - x0).max(0.5);
    let y = y0.abs().max(y1.abs());
    let y = y + frac * (2.0 * y).max(0.5);
    (x0 - px, x1 + px, -y, y)
}

/// Where a polyline crosses the line Im z = 0 (`axis` 0) or Re z = 0 (`axis` 1): the other
/// coordinate at each crossing, by linear interpolation between its vertices.
pub fn crossings(line: &[Complex], axis: u8) -> Vec<f64> {
    // (coordinate along the axis, signed distance from it)
    let split = |z: Complex| if axis == 0 { (z.0, z.1) } else { (z.1, z.0) };
    let mut out = Vec::new();
    for w in line.windows(2) {
        let ((pa, a), (pb, b)) = (split(w[0]), split(w[1]));
        if (a <= 0.0) != (b <= 0.0) {
            let t = a / (a - b);
            out.push(pa + t * (pb - pa));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ode::Tableau;

    fn region_of(t: &Tableau) -> Region {
        region(|z| t.stability(z)).expect("explicit methods are stable near 0")
    }

    #[test]
    fn euler_is_the_unit_disc_around_minus_one() {
        let r = region_of(&Tableau::euler());
        assert!(!r.unbounded);
        let main = &r.boundary[0];
        assert_eq!(main.first(), main.last(), "closed");
        for z in main {
            let d = (z.0 + 1.0).hypot(z.1);
            assert!((d - 1.0).abs() < 1e-9, "{z:?} is {d} from −1");
        }
        // the whole disc fits: −2 … 0 and ±1
        let (x0, x1, y0, y1) = r.bounds;
        assert!(
            x0 <= -2.0 && x1 >= 0.0 && y0 <= -1.0 && y1 >= 1.0,
            "{:?}",
            r.bounds
        );
        assert!(x0 > -2.1 && x1 < 0.1, "{:?} fits the disc", r.bounds);
    }

    #[test]
    fn rk4_and_the_typo_reach_their_true_edges() {
        let rk4 = region_of(&Tableau::rk4());
        let re = crossings(&rk4.boundary[0], 0);
        let left = re.iter().copied().fold(f64::MAX, f64::min);
        assert!((left + 2.785_293_563).abs() < 1e-6, "{left}");
        let im = crossings(&rk4.boundary[0], 1);
        let top = im.iter().copied().fold(f64::MIN, f64::max);
        assert!((top - 8f64.sqrt()).abs() < 1e-3, "{top}");
        // R(−4) = 1 − 4 + 20/3 − 8 + 16/3 = 1: the typo's region reaches −4.0, past a box at −3.5
        let typo = region_of(&Tableau::rk4_typo());
        let left = crossings(&typo.boundary[0], 0)
            .into_iter()
            .fold(f64::MAX, f64::min);
        assert!((left + 4.0).abs() < 1e-6, "{left}");
        assert!(
            typo.bounds.0 < -4.0 && typo.bounds.0 > -4.2,
            "{:?}",
            typo.bounds
        );
    }

    #[test]
    fn an_implicit_methods_region_is_unbounded_and_drawn_to_the_cap() {
        // implicit Euler: stable outside the disc |z − 1| < 1
        let t = Tableau {
            name: "implicit Euler".into(),
            a: vec![vec![1.0]],
            b: vec![1.0],
            c: vec![1.0],
        };
        let r = region_of(&t);
        assert!(r.unbounded);
        assert!(r.bounds.0 <= -MAX_HALF_WIDTH + 1.0, "{:?}", r.bounds);
    }
}
