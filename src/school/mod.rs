//! The school of fish: a particle system with boids steering and orientation by a discrete
//! parallel-transport frame. Fish are oriented particles, not rigid bodies.
//!
//! Data is structure-of-arrays (f32) and re-sorted by grid cell every step, so the neighbour
//! loops and the integration pass stream through memory. One step is three passes:
//! [`School::rebuild_grid`] (bin and sort, O(N)), [`School::compute_steering`] (boids sums over
//! the 27 cells around each fish) and [`School::integrate`] (velocity, position, orientation,
//! tail phase).

pub mod frames;
pub mod grid;
mod integrate;
pub mod rng;
mod simd;
mod steer;

pub use integrate::transport;

use crate::waves::WaveSum;
use glam::{Mat3, Quat, Vec3};
use grid::NeighbourGrid;
use rng::SplitMix64;
use serde::{Deserialize, Serialize};

/// The fish's own axes: it swims along +x with its back towards +y.
pub const FISH_FORWARD: Vec3 = Vec3::X;
pub const FISH_UP: Vec3 = Vec3::Y;

/// The longest step the school takes at once; a longer `dt_secs` is clamped to it.
pub const MAX_DT_SECS: f32 = 0.1;

/// What the renderer needs of one fish, per frame (the per-instance buffer's source).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FishInstance {
    pub position: Vec3,
    /// world_from_fish: maps [`FISH_FORWARD`] to the swimming direction
    pub orientation: Quat,
    pub scale: f32,
    /// Phase of the tail beat / body wave, radians; the vertex shader animates with it.
    pub tail_phase: f32,
}

/// The school's parameters as written in a scene file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct SchoolParams {
    pub count: usize,
    pub seed: u64,
    pub min_speed: f32,
    pub max_speed: f32,
    pub separation_radius: f32,
    pub neighbour_radius: f32,
    pub separation_weight: f32,
    pub alignment_weight: f32,
    pub cohesion_weight: f32,
    pub bounds_weight: f32,
    pub flee_radius: f32,
    pub flee_weight: f32,
    pub fish_scale: f32,
    /// m/s², the most steering a fish can do
    pub max_accel: f32,
    /// metres: how far from a wall, the seabed or the lowest trough a fish starts turning
    pub bounds_margin: f32,
    /// tail beats per second at max speed (half of it at rest)
    pub tail_beat_hz: f32,
    /// how many schools the fish form (fish `id` joins school `id % schools`, 1..=16): a fish
    /// sees only its own school's fish for alignment, cohesion and separation
    pub schools: u32,
    /// 1/s²: pull of each school towards its own centre, which wanders through the swim box
    /// on a slow closed path (0: no centre, the classic boids)
    pub goal_weight: f32,
    /// metres: fish spawn within this of their school's centre, heading along its path
    /// (0: scattered through the whole swim box, random headings)
    pub spawn_radius: f32,
}

/// The most schools ([`SchoolParams::schools`]).
pub const MAX_SCHOOLS: u32 = 16;

impl Default for SchoolParams {
    fn default() -> Self {
        Self {
            count: 2000,
            seed: 7,
            min_speed: 0.6,
            max_speed: 2.0,
            separation_radius: 0.35,
            neighbour_radius: 1.2,
            separation_weight: 1.5,
            alignment_weight: 1.0,
            cohesion_weight: 0.8,
            bounds_weight: 2.0,
            flee_radius: 3.0,
            flee_weight: 4.0,
            fish_scale: 0.25,
            max_accel: 6.0,
            bounds_margin: 1.0,
            tail_beat_hz: 2.5,
            schools: 1,
            goal_weight: 0.0,
            spawn_radius: 0.0,
        }
    }
}

impl SchoolParams {
    /// The school count, clamped to 1..=[`MAX_SCHOOLS`].
    pub fn school_count(&self) -> u32 {
        self.schools.clamp(1, MAX_SCHOOLS)
    }

    /// The school fish `id` belongs to.
    pub fn school_of(&self, id: u32) -> u32 {
        id % self.school_count()
    }

    /// Where school `k`'s centre is at `t_secs` in the swim box `(lo, hi)`, and its velocity:
    /// a Lissajous loop (frequencies 1 : 0.8 : 1.3 across x, z, y) through the middle of the
    /// box, each school a golden-angle phase apart, moving at about half the top speed.
    pub fn school_centre(&self, k: u32, t_secs: f64, (lo, hi): (Vec3, Vec3)) -> (Vec3, Vec3) {
        let mid = 0.5 * (lo + hi);
        let half = (0.5 * (hi - lo)).max(Vec3::ZERO);
        let reach = Vec3::new(0.6 * half.x, 0.3 * half.y, 0.6 * half.z);
        let omega = (0.5 * self.max_speed.max(0.1) / reach.x.max(reach.z).max(0.5)) as f64;
        let phi = k as f64 * 2.399_963; // the golden angle, radians
        let arg = |f: f64, k_phi: f64| f * omega * t_secs + k_phi * phi;
        let (sx, cx) = arg(1.0, 1.0).sin_cos();
        let (sz, cz) = arg(0.8, 2.0).sin_cos();
        let (sy, cy) = arg(1.3, 3.0).sin_cos();
        let pos = mid + reach * Vec3::new(sx as f32, sy as f32, sz as f32);
        let vel = reach * Vec3::new(cx as f32, (1.3 * cy) as f32, (0.8 * cz) as f32) * omega as f32;
        (pos, vel)
    }
}

/// An axis-aligned box, world metres.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Aabb {
    pub min: Vec3,
    pub max: Vec3,
}

impl Aabb {
    pub fn new(min: Vec3, max: Vec3) -> Self {
        Self { min, max }
    }

    /// (min, max) made finite and ordered, so a bad scene cannot break the grid.
    pub fn sanitised(&self) -> (Vec3, Vec3) {
        let fix = |v: Vec3, d: f32| {
            Vec3::new(
                if v.x.is_finite() { v.x } else { d },
                if v.y.is_finite() { v.y } else { d },
                if v.z.is_finite() { v.z } else { d },
            )
        };
        let (a, b) = (fix(self.min, -10.0), fix(self.max, 10.0));
        (a.min(b), a.max(b))
    }
}

/// Where the school swims: everything outside it that it reacts to.
#[derive(Debug, Clone, Copy)]
pub struct Environment<'a> {
    pub bounds: Aabb,
    /// The water surface. Fish stay below its lowest possible trough
    /// ([`WaveSum::lowest_level`]), so they are under water everywhere at all times and the
    /// step needs no per-fish wave evaluation.
    pub surface: Option<&'a WaveSum>,
    /// world y of the seabed (flat)
    pub seabed_height: f32,
    /// a point the fish flee from (the lecturer's pointer), if any
    pub flee_point: Option<Vec3>,
    /// spheres (centre, radius) the fish keep out of: the rocks
    pub obstacles: &'a [(Vec3, f32)],
}

impl<'a> Environment<'a> {
    pub fn new(bounds: Aabb) -> Self {
        Self {
            bounds,
            surface: None,
            seabed_height: f32::NEG_INFINITY,
            flee_point: None,
            obstacles: &[],
        }
    }

    /// The box fish may occupy: bounds cut below the lowest trough and above the seabed.
    pub fn swim_box(&self) -> (Vec3, Vec3) {
        let (mut lo, mut hi) = self.bounds.sanitised();
        if let Some(s) = self.surface {
            let top = s.lowest_level() as f32;
            if top.is_finite() {
                hi.y = hi.y.min(top);
            }
        }
        if self.seabed_height.is_finite() {
            lo.y = lo.y.max(self.seabed_height);
        }
        if hi.y < lo.y {
            let mid = 0.5 * (lo.y + hi.y);
            (lo.y, hi.y) = (mid, mid);
        }
        (lo, hi)
    }
}

/// The school: per-fish state as structure-of-arrays, kept sorted by grid cell.
#[derive(Debug, Clone, Default)]
pub struct School {
    params: SchoolParams,
    px: Vec<f32>,
    py: Vec<f32>,
    pz: Vec<f32>,
    vx: Vec<f32>,
    vy: Vec<f32>,
    vz: Vec<f32>,
    /// world_from_fish orientation, unit quaternion (x, y, z, w)
    qx: Vec<f32>,
    qy: Vec<f32>,
    qz: Vec<f32>,
    qw: Vec<f32>,
    phase: Vec<f32>,
    /// stable identity: fish `id` always spawns the same way and is the one removed first
    /// when the count drops (largest ids go first)
    id: Vec<u32>,
    ax: Vec<f32>,
    ay: Vec<f32>,
    az: Vec<f32>,
    grid: NeighbourGrid,
    padded: steer::Padded,
    scratch_f: Vec<f32>,
    scratch_u: Vec<u32>,
    time_secs: f64,
}

impl School {
    /// A school of `params.count` fish scattered through the swim box, from `params.seed`.
    pub fn new(params: &SchoolParams, env: &Environment) -> Self {
        let mut s = Self {
            params: params.clone(),
            ..Default::default()
        };
        s.resize(params.count, env);
        s
    }

    pub fn params(&self) -> &SchoolParams {
        &self.params
    }

    pub fn len(&self) -> usize {
        self.px.len()
    }

    pub fn is_empty(&self) -> bool {
        self.px.is_empty()
    }

    pub fn time_secs(&self) -> f64 {
        self.time_secs
    }

    /// Live tweak. A new count adds fish (with the ids that follow, each spawning as it would
    /// have from the start) or removes the largest ids; a new seed respawns everything.
    pub fn set_params(&mut self, params: &SchoolParams, env: &Environment) {
        let reseed = params.seed != self.params.seed;
        self.params = params.clone();
        if reseed {
            self.clear();
        }
        self.resize(params.count, env);
    }

    fn clear(&mut self) {
        for v in self.per_fish_f32() {
            v.clear();
        }
        self.id.clear();
    }

    fn resize(&mut self, count: usize, env: &Environment) {
        let n = self.len();
        if count < n {
            let keep: Vec<bool> = self.id.iter().map(|&id| (id as usize) < count).collect();
            for v in self.per_fish_f32() {
                retain_by(v, &keep);
            }
            retain_by(&mut self.id, &keep);
            return;
        }
        let (lo, hi) = env.swim_box();
        let p = &self.params;
        let speed = 0.5 * (p.min_speed + p.max_speed);
        for id in n..count {
            let mut g = SplitMix64::for_item(p.seed, id as u64);
            let mut pos = Vec3::new(
                g.range(lo.x, hi.x),
                g.range(lo.y, hi.y),
                g.range(lo.z, hi.z),
            );
            // mostly horizontal headings, like a real school
            let yaw = g.range(0.0, std::f32::consts::TAU);
            let pitch = g.range(-0.3, 0.3);
            let mut dir = Vec3::new(
                yaw.cos() * pitch.cos(),
                pitch.sin(),
                yaw.sin() * pitch.cos(),
            );
            if p.spawn_radius > 0.0 && p.spawn_radius.is_finite() {
                // a ball around the school's centre, swimming along its path
                let (centre, vel) = p.school_centre(p.school_of(id as u32), 0.0, (lo, hi));
                let offset = Vec3::new(g.range(-1.0, 1.0), g.range(-1.0, 1.0), g.range(-1.0, 1.0));
                pos = (centre + offset * p.spawn_radius).clamp(lo, hi);
                dir = (vel.normalize_or(Vec3::X) + 0.2 * dir).normalize_or(Vec3::X);
            }
            let vel = dir * if speed.is_finite() { speed } else { 1.0 };
            self.px.push(pos.x);
            self.py.push(pos.y);
            self.pz.push(pos.z);
            self.vx.push(vel.x);
            self.vy.push(vel.y);
            self.vz.push(vel.z);
            let q = upright_frame(dir);
            self.qx.push(q.x);
            self.qy.push(q.y);
            self.qz.push(q.z);
            self.qw.push(q.w);
            self.phase.push(g.range(0.0, std::f32::consts::TAU));
            self.id.push(id as u32);
        }
    }

    /// Advances the school by `dt_secs` (clamped to [`MAX_DT_SECS`]; non-finite or negative
    /// steps do nothing).
    pub fn step(&mut self, dt_secs: f32, env: &Environment) {
        if !(dt_secs.is_finite() && dt_secs > 0.0) || self.is_empty() {
            return;
        }
        let dt = dt_secs.min(MAX_DT_SECS);
        self.rebuild_grid(env);
        self.compute_steering(env);
        self.integrate(dt, env);
        self.keep_out_of_obstacles(env);
        self.time_secs += dt as f64;
    }

    /// Moves any fish inside an obstacle's sphere back onto its surface (steering turns them
    /// away first; this makes it certain, whatever the step).
    fn keep_out_of_obstacles(&mut self, env: &Environment) {
        for &(centre, radius) in env.obstacles {
            let r2 = radius * radius;
            for i in 0..self.len() {
                let d = Vec3::new(self.px[i], self.py[i], self.pz[i]) - centre;
                let d2 = d.length_squared();
                if d2 < r2 {
                    let out = centre + d.normalize_or(Vec3::Y) * radius;
                    self.px[i] = out.x;
                    self.py[i] = out.y;
                    self.pz[i] = out.z;
                }
            }
        }
    }

    /// Pass 1: bin fish into the grid and reorder all arrays by cell.
    pub fn rebuild_grid(&mut self, env: &Environment) {
        let r = self
            .params
            .neighbour_radius
            .max(self.params.separation_radius);
        let mut grid = std::mem::take(&mut self.grid);
        grid.build(&self.px, &self.py, &self.pz, &env.bounds, r);
        let order = grid.order();
        let n = order.len();
        let mut scratch = std::mem::take(&mut self.scratch_f);
        scratch.resize(n, 0.0);
        for v in self.per_fish_f32() {
            for (dst, &i) in scratch.iter_mut().zip(order) {
                *dst = v[i as usize];
            }
            std::mem::swap(v, &mut scratch);
        }
        self.scratch_f = scratch;
        self.scratch_u.resize(n, 0);
        for (dst, &i) in self.scratch_u.iter_mut().zip(order) {
            *dst = self.id[i as usize];
        }
        self.grid = grid;
        std::mem::swap(&mut self.id, &mut self.scratch_u);
    }

    /// Pass 2: boids steering acceleration of every fish (needs pass 1 this step).
    pub fn compute_steering(&mut self, env: &Environment) {
        steer::compute(self, env);
    }

    /// Pass 3: velocity, position, parallel-transported orientation and tail phase.
    pub fn integrate(&mut self, dt: f32, env: &Environment) {
        integrate::integrate(self, dt, env);
    }

    /// Every per-fish f32 array (all but the ids), for the passes that treat them alike.
    fn per_fish_f32(&mut self) -> [&mut Vec<f32>; 11] {
        [
            &mut self.px,
            &mut self.py,
            &mut self.pz,
            &mut self.vx,
            &mut self.vy,
            &mut self.vz,
            &mut self.qx,
            &mut self.qy,
            &mut self.qz,
            &mut self.qw,
            &mut self.phase,
        ]
    }

    /// One fish's render data.
    pub fn instance(&self, i: usize) -> FishInstance {
        FishInstance {
            position: Vec3::new(self.px[i], self.py[i], self.pz[i]),
            orientation: Quat::from_xyzw(self.qx[i], self.qy[i], self.qz[i], self.qw[i]),
            scale: self.params.fish_scale * size_variation(self.params.seed, self.id[i]),
            tail_phase: self.phase[i],
        }
    }

    pub fn instances(&self) -> impl Iterator<Item = FishInstance> + '_ {
        (0..self.len()).map(|i| self.instance(i))
    }

    /// Replaces `out`'s contents with every fish's instance (no allocation once sized).
    pub fn fill_instances(&self, out: &mut Vec<FishInstance>) {
        out.clear();
        out.extend(self.instances());
    }

    pub fn position(&self, i: usize) -> Vec3 {
        Vec3::new(self.px[i], self.py[i], self.pz[i])
    }

    pub fn velocity(&self, i: usize) -> Vec3 {
        Vec3::new(self.vx[i], self.vy[i], self.vz[i])
    }

    /// The steering acceleration of fish `i` from the last [`School::compute_steering`]
    /// (zero before the first).
    pub fn acceleration(&self, i: usize) -> Vec3 {
        match (self.ax.get(i), self.ay.get(i), self.az.get(i)) {
            (Some(&x), Some(&y), Some(&z)) => Vec3::new(x, y, z),
            _ => Vec3::ZERO,
        }
    }

    pub fn id(&self, i: usize) -> u32 {
        self.id[i]
    }

    /// Bytes the integration pass reads and writes per fish (for the bandwidth report).
    pub const INTEGRATE_BYTES_PER_FISH: usize = 4 * (3 + 3 + 3 + 4 + 1) + 4 * (3 + 3 + 4 + 1);
}

fn retain_by<T>(v: &mut Vec<T>, keep: &[bool]) {
    let mut it = keep.iter();
    v.retain(|_| *it.next().unwrap_or(&false));
}

/// ±10 % size spread, fixed per fish.
fn size_variation(seed: u64, id: u32) -> f32 {
    0.9 + 0.2 * SplitMix64::for_item(seed ^ 0x5157_5A1E, id as u64).next_f32()
}

/// The orientation that points [`FISH_FORWARD`] along `dir` with the back as close to world
/// up as possible (the starting frame; after that the frame is parallel-transported).
pub fn upright_frame(dir: Vec3) -> Quat {
    let f = dir.try_normalize().unwrap_or(FISH_FORWARD);
    let side = f.cross(Vec3::Y);
    let side = if side.length_squared() < 1e-8 {
        f.any_orthonormal_vector()
    } else {
        side.normalize()
    };
    let up = side.cross(f);
    // columns: images of (forward = x, up = y, x × y = z)
    Quat::from_mat3(&Mat3::from_cols(f, up, f.cross(up))).normalize()
}
