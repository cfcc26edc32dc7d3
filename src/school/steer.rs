//! Pass 2: boids steering over grid neighbours.
//!
//! The 3×3×3 cells around a fish are 9 runs of contiguous sorted slots. Each run is summed
//! [`LANES`] slots at a time with one accumulator per lane, branch-free (slots past the run's
//! end are masked, not skipped), so the compiler turns the lanes into SIMD registers.
//!
//! Alignment and cohesion are both linear in the neighbour sums, so they share one sum:
//! Σ (w_a v_j + w_c x_j) over neighbours, divided by the count, minus (w_a v_i + w_c x_i), is
//! exactly w_a (v̄ − v_i) + w_c (x̄ − x_i). The per-fish term w_a v_j + w_c x_j is computed once
//! per fish into a padded buffer, which also lets a chunk near the end never read past it.
//! Separation (1/d² pushes) is rare at boids densities, so a chunk computes it only when one of
//! its lanes is that close.

use super::simd::simd_dispatch;
use super::{Environment, School};
use glam::Vec3;

/// Slots summed at once: one AVX register of f32, or two SSE ones.
pub const LANES: usize = 8;
const _: () = assert!(LANES == 8, "lane_sum adds 8 lanes as a tree");

/// Each lane's index, as f32, for the end-of-run mask.
const LANE_INDEX: [f32; LANES] = [0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0];

/// Where padding slots sit: never anyone's neighbour, and their squared distance stays finite.
const FAR: f32 = 1e18;

/// The sorted positions and each fish's w_a v + w_c x, padded with [`LANES`] far-away slots.
#[derive(Debug, Clone, Default)]
pub(super) struct Padded {
    x: [Vec<f32>; 3],
    w: [Vec<f32>; 3],
}

/// How far apart the schools are put in the padded x coordinate: the swim box's width plus
/// twice the largest radius, so a fish's neighbour sums see only its own school with no
/// per-pair test (and no farther, to keep f32 precision in the offset coordinates).
fn school_spacing_m(s: &School, env: &Environment) -> f32 {
    let (lo, hi) = env.bounds.sanitised();
    let r = s.params.neighbour_radius.max(s.params.separation_radius);
    let r = if r.is_finite() { r.max(0.0) } else { 0.0 };
    ((hi.x - lo.x) + 2.0 * r + 1.0).ceil()
}

impl Padded {
    fn fill(&mut self, s: &School, alignment: f32, cohesion: f32, spacing: f32) {
        let n = s.len();
        let (p, v) = ([&s.px, &s.py, &s.pz], [&s.vx, &s.vy, &s.vz]);
        for d in 0..3 {
            let x = &mut self.x[d];
            x.clear();
            if d == 0 && s.params.school_count() > 1 {
                x.extend(
                    p[0].iter()
                        .zip(&s.id)
                        .map(|(&px, &id)| px + s.params.school_of(id) as f32 * spacing),
                );
            } else {
                x.extend_from_slice(p[d]);
            }
            x.resize(n + LANES, FAR);
            let w = &mut self.w[d];
            w.clear();
            w.extend(
                self.x[d][..n]
                    .iter()
                    .zip(v[d])
                    .map(|(&x, &v)| alignment * v + cohesion * x),
            );
            w.resize(n + LANES, 0.0);
        }
    }
}

/// The neighbour sums of one fish.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
struct Sums {
    /// neighbours within the neighbour radius
    count: f32,
    /// Σ (w_a v_j + w_c x_j) over them
    weighted: [f32; 3],
    /// Σ −d/|d|² over fish within the separation radius
    separation: [f32; 3],
}

/// Per-lane partial sums, added up once per fish.
#[derive(Debug, Clone, Copy, Default)]
struct Lanes {
    count: [f32; LANES],
    weighted: [[f32; LANES]; 3],
    separation: [[f32; LANES]; 3],
}

impl Lanes {
    #[inline(always)]
    fn sums(&self) -> Sums {
        Sums {
            count: lane_sum(&self.count),
            weighted: [
                lane_sum(&self.weighted[0]),
                lane_sum(&self.weighted[1]),
                lane_sum(&self.weighted[2]),
            ],
            separation: [
                lane_sum(&self.separation[0]),
                lane_sum(&self.separation[1]),
                lane_sum(&self.separation[2]),
            ],
        }
    }
}

/// The lanes added as a fixed tree (halves first, so it stays in SIMD registers); the order
/// is fixed, so the result is deterministic.
#[inline(always)]
fn lane_sum(a: &[f32; LANES]) -> f32 {
    let q = [a[0] + a[4], a[1] + a[5], a[2] + a[6], a[3] + a[7]];
    (q[0] + q[2]) + (q[1] + q[3])
}

/// Per-step constants of the pass.
#[derive(Debug, Clone, Copy)]
struct Consts {
    r2: f32,
    s2: f32,
    lo: Vec3,
    hi: Vec3,
    margin: f32,
    wall: f32,
    max_accel: f32,
    flee: Option<Vec3>,
    flee_radius: f32,
    flee_push: f32,
    separation_weight: f32,
    /// each school's centre, and the pull towards it
    centres: [Vec3; super::MAX_SCHOOLS as usize],
    goal_weight: f32,
    /// the first [`MAX_OBSTACLES`] obstacles (centre, radius), the rest unused (radius 0)
    obstacles: [(Vec3, f32); MAX_OBSTACLES],
}

/// Obstacles the steering turns away from (more are still kept out by the step's projection).
const MAX_OBSTACLES: usize = 8;

/// Boids acceleration for every fish; arrays must be in the grid's cell order (pass 1).
pub(super) fn compute(s: &mut School, env: &Environment) {
    let n = s.len();
    for a in [&mut s.ax, &mut s.ay, &mut s.az] {
        a.resize(n, 0.0);
    }
    let p = &s.params;
    let mut padded = std::mem::take(&mut s.padded);
    padded.fill(
        s,
        p.alignment_weight,
        p.cohesion_weight,
        school_spacing_m(s, env),
    );
    let (lo, hi) = env.swim_box();
    let c = Consts {
        r2: p.neighbour_radius * p.neighbour_radius,
        s2: p.separation_radius * p.separation_radius,
        lo,
        hi,
        margin: p.bounds_margin.max(1e-3),
        wall: p.bounds_weight * p.max_speed,
        max_accel: p.max_accel.max(0.0),
        flee: env
            .flee_point
            .filter(|f| f.is_finite() && p.flee_radius > 0.0),
        flee_radius: p.flee_radius,
        flee_push: p.flee_weight * p.max_speed,
        separation_weight: p.separation_weight,
        centres: std::array::from_fn(|k| p.school_centre(k as u32, s.time_secs, (lo, hi)).0),
        goal_weight: if p.goal_weight.is_finite() {
            p.goal_weight.max(0.0)
        } else {
            0.0
        },
        obstacles: std::array::from_fn(|k| {
            env.obstacles.get(k).copied().unwrap_or((Vec3::ZERO, 0.0))
        }),
    };
    steer_all(&c, s, &padded);
    s.padded = padded;
}

simd_dispatch!(fn steer_all(c: &Consts, s: &mut School, b: &Padded) => steer_lanes);

#[inline(always)]
fn steer_lanes(c: &Consts, s: &mut School, b: &Padded) {
    let (mut last_cell, mut runs, mut count) = ([usize::MAX; 3], [(0, 0); 9], 0);
    for i in 0..s.len() {
        // in the padded buffers, x carries the school's offset
        let pos = Vec3::new(b.x[0][i], b.x[1][i], b.x[2][i]);
        let world = Vec3::new(s.px[i], s.py[i], s.pz[i]);
        // fish are sorted by cell: consecutive fish mostly share their 27-cell block
        let cell = s.grid.cell_coords(world);
        if cell != last_cell {
            (runs, count) = s.grid.runs(cell);
            last_cell = cell;
        }
        let mut lanes = Lanes::default();
        for &(lo, hi) in &runs[..count] {
            lanes = add_run(c, b, pos, lo as usize, hi as usize, lanes);
        }
        let own = Vec3::new(b.w[0][i], b.w[1][i], b.w[2][i]);
        let centre = c.centres[s.params.school_of(s.id[i]) as usize];
        let a = acceleration(c, world, own, &lanes.sums(), centre);
        s.ax[i] = a.x;
        s.ay[i] = a.y;
        s.az[i] = a.z;
    }
}

/// Adds the slots `lo..hi` of the padded buffers to the lanes. The lanes go in and come back
/// by value, and masks multiply rather than select, so they stay in registers.
#[inline(always)]
fn add_run(c: &Consts, b: &Padded, p: Vec3, lo: usize, hi: usize, acc: Lanes) -> Lanes {
    let len = hi - lo;
    // one bounds check per run; the chunks below stay inside these slices
    // (no closures in here: they would not inherit the caller's AVX2)
    let (x, y, z) = (
        &b.x[0][lo..hi + LANES],
        &b.x[1][lo..hi + LANES],
        &b.x[2][lo..hi + LANES],
    );
    let (wx, wy, wz) = (
        &b.w[0][lo..hi + LANES],
        &b.w[1][lo..hi + LANES],
        &b.w[2][lo..hi + LANES],
    );
    let Lanes {
        mut count,
        weighted: [mut w0, mut w1, mut w2],
        separation: [mut s0, mut s1, mut s2],
    } = acc;
    let mut k = 0;
    while k < len {
        // lanes at or past the run's end are masked; an f32 compare keeps the mask in the
        // same register width as the data
        let valid = (len - k).min(LANES) as f32;
        let (cx, cy, cz) = (chunk(x, k), chunk(y, k), chunk(z, k));
        let (cwx, cwy, cwz) = (chunk(wx, k), chunk(wy, k), chunk(wz, k));
        for l in 0..LANES {
            let dx = cx[l] - p.x;
            let dy = cy[l] - p.y;
            let dz = cz[l] - p.z;
            let d2 = dx * dx + dy * dy + dz * dz;
            // d2 > 0 leaves out the fish itself
            let inside = LANE_INDEX[l] < valid && d2 > 0.0;
            let near = if inside && d2 < c.r2 { 1.0f32 } else { 0.0 };
            count[l] += near;
            w0[l] += near * cwx[l];
            w1[l] += near * cwy[l];
            w2[l] += near * cwz[l];
            let push = if inside && d2 < c.s2 {
                1.0 / d2.max(1e-12)
            } else {
                0.0
            };
            s0[l] -= push * dx;
            s1[l] -= push * dy;
            s2[l] -= push * dz;
        }
        k += LANES;
    }
    Lanes {
        count,
        weighted: [w0, w1, w2],
        separation: [s0, s1, s2],
    }
}

#[inline(always)]
fn chunk(v: &[f32], k: usize) -> [f32; LANES] {
    v[k..k + LANES].try_into().expect("padded")
}

/// Separation, alignment, cohesion, walls and fleeing, capped at `max_accel`.
#[inline(always)]
fn acceleration(c: &Consts, pos: Vec3, own: Vec3, s: &Sums, centre: Vec3) -> Vec3 {
    let mut a = Vec3::from(s.separation) * c.separation_weight;
    if s.count > 0.0 {
        // w_a (v̄ − v) + w_c (x̄ − x): the mean of w_a v_j + w_c x_j minus the fish's own
        a += Vec3::from(s.weighted) / s.count - own;
    }
    // the school's wandering centre: a spring, capped so a straggler does not rocket back
    a += ((centre - pos) * c.goal_weight).clamp_length_max(0.5 * c.max_accel);
    // rocks: a push out growing across the margin around each
    for &(o, r) in &c.obstacles {
        let d = pos - o;
        let dist = d.length();
        let depth = (r + c.margin - dist) / c.margin;
        if r > 0.0 && depth > 0.0 && dist > 1e-6 {
            a += d / dist * (depth.min(1.0) * 2.0 * c.wall);
        }
    }
    // walls, seabed and the lowest trough: a push growing across the margin
    let into_lo = ((c.lo + Vec3::splat(c.margin) - pos) / c.margin).max(Vec3::ZERO);
    let into_hi = ((pos - (c.hi - Vec3::splat(c.margin))) / c.margin).max(Vec3::ZERO);
    a += (into_lo - into_hi) * c.wall;
    if let Some(f) = c.flee {
        let d = pos - f;
        let dist = d.length();
        if dist < c.flee_radius && dist > 1e-6 {
            a += d / dist * (c.flee_push * (1.0 - dist / c.flee_radius));
        }
    }
    let a = a.clamp_length_max(c.max_accel);
    if a.is_finite() { a } else { Vec3::ZERO }
}
