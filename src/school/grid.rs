//! Uniform-grid neighbour search: fish are binned into cubic cells at least as wide as the
//! query radius and counting-sorted by cell (stable, O(N)); a query visits the 3×3×3 block of
//! cells around a point, as 9 runs of 3 x-adjacent cells that are contiguous in sorted order.

use super::Aabb;
use glam::Vec3;

/// Cells are never more than this many; wide bounds get larger cells instead.
pub const MAX_CELLS: usize = 1 << 22;

#[derive(Debug, Clone, Default)]
pub struct NeighbourGrid {
    origin: Vec3,
    cell: f32,
    inv_cell: f32,
    dims: [usize; 3],
    /// `cell_start[c]..cell_start[c + 1]` are the sorted slots of cell `c`
    cell_start: Vec<u32>,
    /// fish index for each sorted slot (stable counting sort by cell)
    order: Vec<u32>,
    cell_of: Vec<u32>,
    cursor: Vec<u32>,
}

impl NeighbourGrid {
    /// Bins the points `(xs[i], ys[i], zs[i])`. Queries are exact for any radius ≤ `radius`.
    /// Points outside `bounds` (or NaN) land in the nearest edge cell, which keeps queries
    /// exact: clamping never separates two points by more than one cell.
    pub fn build(&mut self, xs: &[f32], ys: &[f32], zs: &[f32], bounds: &Aabb, radius: f32) {
        let n = xs.len();
        let (lo, hi) = bounds.sanitised();
        let extent = (hi - lo).max(Vec3::splat(1e-3));
        // a hair wider than the radius, so rounding in the cell coordinates cannot put two
        // points closer than `radius` two cells apart
        let mut cell = if radius.is_finite() && radius > 0.0 {
            radius * 1.0001
        } else {
            1.0
        };
        loop {
            let d = (extent / cell).ceil().max(Vec3::ONE);
            let count = d.x as f64 * d.y as f64 * d.z as f64;
            if count <= MAX_CELLS as f64 {
                self.dims = [d.x as usize, d.y as usize, d.z as usize];
                break;
            }
            cell *= (count / MAX_CELLS as f64).cbrt() as f32 * 1.01;
        }
        self.origin = lo;
        self.cell = cell;
        self.inv_cell = 1.0 / cell;
        let cells = self.dims[0] * self.dims[1] * self.dims[2];
        self.cell_start.clear();
        self.cell_start.resize(cells + 1, 0);
        self.cell_of.resize(n, 0);
        for i in 0..n {
            let c = self.cell_index(self.cell_coords(Vec3::new(xs[i], ys[i], zs[i])));
            self.cell_of[i] = c as u32;
            self.cell_start[c + 1] += 1;
        }
        for c in 0..cells {
            self.cell_start[c + 1] += self.cell_start[c];
        }
        self.order.resize(n, 0);
        // counting sort; `cursor` reuses the prefix sums shifted by one cell
        self.cursor.clear();
        self.cursor.extend_from_slice(&self.cell_start[..cells]);
        for i in 0..n {
            let c = self.cell_of[i] as usize;
            self.order[self.cursor[c] as usize] = i as u32;
            self.cursor[c] += 1;
        }
    }

    /// Fish indices in cell order.
    pub fn order(&self) -> &[u32] {
        &self.order
    }

    pub fn cell_size(&self) -> f32 {
        self.cell
    }

    pub fn dims(&self) -> [usize; 3] {
        self.dims
    }

    #[inline]
    pub fn cell_coords(&self, p: Vec3) -> [usize; 3] {
        let c = (p - self.origin) * self.inv_cell;
        // `as` saturates (NaN → 0); then clamp into the grid
        let clamp = |v: f32, d: usize| (v.floor().max(0.0) as usize).min(d - 1);
        [
            clamp(c.x, self.dims[0]),
            clamp(c.y, self.dims[1]),
            clamp(c.z, self.dims[2]),
        ]
    }

    #[inline]
    pub fn cell_index(&self, c: [usize; 3]) -> usize {
        c[0] + self.dims[0] * (c[1] + self.dims[1] * c[2])
    }

    /// The (up to) 9 non-empty runs of sorted slots `lo..hi` covering the 3×3×3 cells around
    /// cell `c`, as an array (no closure, so SIMD callers keep their target features).
    #[inline]
    pub fn runs(&self, c: [usize; 3]) -> ([(u32, u32); 9], usize) {
        let mut runs = [(0, 0); 9];
        let mut k = 0;
        self.for_each_run(c, |lo, hi| {
            runs[k] = (lo as u32, hi as u32);
            k += 1;
        });
        (runs, k)
    }

    /// Calls `f(lo, hi)` for the 9 runs of sorted slots `lo..hi` covering the 3×3×3 cells
    /// around cell `c`.
    #[inline]
    pub fn for_each_run(&self, c: [usize; 3], mut f: impl FnMut(usize, usize)) {
        let [dx, dy, dz] = self.dims;
        let x0 = c[0].saturating_sub(1);
        let x1 = (c[0] + 1).min(dx - 1);
        for z in c[2].saturating_sub(1)..=(c[2] + 1).min(dz - 1) {
            for y in c[1].saturating_sub(1)..=(c[1] + 1).min(dy - 1) {
                let row = dx * (y + dy * z);
                let lo = self.cell_start[row + x0] as usize;
                let hi = self.cell_start[row + x1 + 1] as usize;
                if hi > lo {
                    f(lo, hi);
                }
            }
        }
    }

    /// Every `j ≠ i` with squared distance `< radius²` from point `i` (radius ≤ the build
    /// radius), appended to `out` in cell order. The distance is computed exactly as a brute
    /// force would, so the sets agree exactly.
    pub fn neighbours(
        &self,
        xs: &[f32],
        ys: &[f32],
        zs: &[f32],
        i: usize,
        radius: f32,
        out: &mut Vec<u32>,
    ) {
        let p = Vec3::new(xs[i], ys[i], zs[i]);
        let r2 = radius * radius;
        self.for_each_run(self.cell_coords(p), |lo, hi| {
            for &j in &self.order[lo..hi] {
                let j = j as usize;
                if j != i && squared_distance(xs, ys, zs, i, j) < r2 {
                    out.push(j as u32);
                }
            }
        });
    }
}

/// The one distance formula both the grid and a brute-force search use.
#[inline]
pub fn squared_distance(xs: &[f32], ys: &[f32], zs: &[f32], i: usize, j: usize) -> f32 {
    let dx = xs[j] - xs[i];
    let dy = ys[j] - ys[i];
    let dz = zs[j] - zs[i];
    dx * dx + dy * dy + dz * dz
}

/// Brute force, O(N²): the reference the grid must match.
pub fn brute_force_neighbours(
    xs: &[f32],
    ys: &[f32],
    zs: &[f32],
    i: usize,
    radius: f32,
    out: &mut Vec<u32>,
) {
    let r2 = radius * radius;
    for j in 0..xs.len() {
        if j != i && squared_distance(xs, ys, zs, i, j) < r2 {
            out.push(j as u32);
        }
    }
}
