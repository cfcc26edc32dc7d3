//! The two per-fish passes after binning: boids steering over grid neighbours, and the
//! integration with parallel-transported orientation.

use super::{Environment, FISH_FORWARD, School, transport};
use glam::Vec3;
use std::f32::consts::TAU;

/// Boids acceleration for every fish; arrays must be in the grid's cell order.
pub(super) fn compute(s: &mut School, env: &Environment) {
    let n = s.len();
    s.ax.resize(n, 0.0);
    s.ay.resize(n, 0.0);
    s.az.resize(n, 0.0);
    let p = &s.params;
    let r2 = p.neighbour_radius * p.neighbour_radius;
    let s2 = p.separation_radius * p.separation_radius;
    let (lo, hi) = env.swim_box();
    let margin = p.bounds_margin.max(1e-3);
    let wall = p.bounds_weight * p.max_speed;
    let max_accel = p.max_accel.max(0.0);
    let flee = env
        .flee_point
        .filter(|f| f.is_finite() && p.flee_radius > 0.0);
    let (px, py, pz) = (&s.px[..], &s.py[..], &s.pz[..]);
    let (vx, vy, vz) = (&s.vx[..], &s.vy[..], &s.vz[..]);
    for i in 0..n {
        let (xi, yi, zi) = (px[i], py[i], pz[i]);
        // neighbour sums: count, velocity, offset; separation push
        let (mut cnt, mut svx, mut svy, mut svz) = (0.0f32, 0.0f32, 0.0f32, 0.0f32);
        let (mut sdx, mut sdy, mut sdz) = (0.0f32, 0.0f32, 0.0f32);
        let (mut sepx, mut sepy, mut sepz) = (0.0f32, 0.0f32, 0.0f32);
        s.grid
            .for_each_run(s.grid.cell_coords(Vec3::new(xi, yi, zi)), |a, b| {
                // branch-free body so the compiler can vectorise the run
                for j in a..b {
                    let dx = px[j] - xi;
                    let dy = py[j] - yi;
                    let dz = pz[j] - zi;
                    let d2 = dx * dx + dy * dy + dz * dz;
                    let near = if d2 < r2 && d2 > 0.0 { 1.0 } else { 0.0 };
                    let push = if d2 < s2 && d2 > 0.0 {
                        1.0 / d2.max(1e-12)
                    } else {
                        0.0
                    };
                    cnt += near;
                    svx += near * vx[j];
                    svy += near * vy[j];
                    svz += near * vz[j];
                    sdx += near * dx;
                    sdy += near * dy;
                    sdz += near * dz;
                    sepx -= push * dx;
                    sepy -= push * dy;
                    sepz -= push * dz;
                }
            });
        let mut a = Vec3::new(sepx, sepy, sepz) * p.separation_weight;
        if cnt > 0.0 {
            let inv = 1.0 / cnt;
            let vi = Vec3::new(vx[i], vy[i], vz[i]);
            a += (Vec3::new(svx, svy, svz) * inv - vi) * p.alignment_weight;
            a += Vec3::new(sdx, sdy, sdz) * inv * p.cohesion_weight;
        }
        // walls, seabed and the lowest trough: a push growing across the margin
        let pos = Vec3::new(xi, yi, zi);
        let into_lo = ((lo + Vec3::splat(margin) - pos) / margin).max(Vec3::ZERO);
        let into_hi = ((pos - (hi - Vec3::splat(margin))) / margin).max(Vec3::ZERO);
        a += (into_lo - into_hi) * wall;
        if let Some(f) = flee {
            let d = pos - f;
            let dist = d.length();
            if dist < p.flee_radius && dist > 1e-6 {
                a += d / dist * (p.flee_weight * p.max_speed * (1.0 - dist / p.flee_radius));
            }
        }
        let a = a.clamp_length_max(max_accel);
        let a = if a.is_finite() { a } else { Vec3::ZERO };
        s.ax[i] = a.x;
        s.ay[i] = a.y;
        s.az[i] = a.z;
    }
}

/// Velocity (speed kept in [min, max]), position (kept in the swim box), orientation by
/// parallel transport, and tail phase.
pub(super) fn integrate(s: &mut School, dt: f32, env: &Environment) {
    let n = s.len();
    let p = &s.params;
    let (lo, hi) = env.swim_box();
    let min_speed = p.min_speed.max(0.0);
    let max_speed = p.max_speed.max(min_speed).max(1e-6);
    let beat = TAU * p.tail_beat_hz.max(0.0) * dt;
    let inv_max = 1.0 / max_speed;
    for i in 0..n {
        let q = s.orientation[i];
        let v = Vec3::new(s.vx[i], s.vy[i], s.vz[i]) + Vec3::new(s.ax[i], s.ay[i], s.az[i]) * dt;
        let speed = v.length();
        let heading = if speed > 1e-6 && speed.is_finite() {
            v / speed
        } else {
            q * FISH_FORWARD
        };
        let speed = if speed.is_finite() {
            speed.clamp(min_speed, max_speed)
        } else {
            min_speed
        };
        let v = heading * speed;
        let pos = (Vec3::new(s.px[i], s.py[i], s.pz[i]) + v * dt).clamp(lo, hi);
        s.vx[i] = v.x;
        s.vy[i] = v.y;
        s.vz[i] = v.z;
        s.px[i] = pos.x;
        s.py[i] = pos.y;
        s.pz[i] = pos.z;
        s.orientation[i] = transport(q, heading);
        let ph = s.phase[i] + beat * (0.5 + 0.5 * speed * inv_max);
        s.phase[i] = if ph >= TAU { ph - TAU } else { ph };
    }
}
