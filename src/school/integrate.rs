//! Pass 3: velocity, speed limits, position, parallel-transported orientation and tail phase.
//!
//! Written as one branch-free loop over plain `f32` slices (selects, not `if`s; no glam calls
//! with branches inside) so LLVM vectorises it; the same per-fish arithmetic is exposed as
//! [`transport`] so the tests check exactly what ships.

use super::simd::simd_dispatch;
use super::{Environment, School};
use glam::{Quat, Vec3};
use std::f32::consts::TAU;

/// Rotates the unit quaternion `q` by the smallest rotation taking its heading (`q · x̂`) to
/// the unit `h`, then renormalises (ERRATA 5): one discrete parallel-transport step.
///
/// The rotation is (c, 1 + d) with c = f × h and d = f · h, left unnormalised because the
/// product is renormalised anyway. When f and h are opposite (1 + d ≈ 0, no unique smallest
/// rotation) it is a half turn about the fish's own up axis, which keeps the back on the
/// same side. A non-finite result becomes the identity rather than poisoning later steps.
#[inline(always)]
pub(super) fn transport_xyzw(q: [f32; 4], h: [f32; 3]) -> [f32; 4] {
    let [x, y, z, w] = q;
    // the heading f = q x̂ and the up u = q ŷ, from the rotation matrix's first two columns
    let f = [
        1.0 - 2.0 * (y * y + z * z),
        2.0 * (x * y + w * z),
        2.0 * (x * z - w * y),
    ];
    let u = [
        2.0 * (x * y - w * z),
        1.0 - 2.0 * (x * x + z * z),
        2.0 * (y * z + w * x),
    ];
    let d = f[0] * h[0] + f[1] * h[1] + f[2] * h[2];
    let c = [
        f[1] * h[2] - f[2] * h[1],
        f[2] * h[0] - f[0] * h[2],
        f[0] * h[1] - f[1] * h[0],
    ];
    let opposite = 1.0 + d < 1e-6;
    let r = if opposite {
        [u[0], u[1], u[2], 0.0]
    } else {
        [c[0], c[1], c[2], 1.0 + d]
    };
    // r ⊗ q
    let n = [
        r[3] * x + r[0] * w + r[1] * z - r[2] * y,
        r[3] * y - r[0] * z + r[1] * w + r[2] * x,
        r[3] * z + r[0] * y - r[1] * x + r[2] * w,
        r[3] * w - r[0] * x - r[1] * y - r[2] * z,
    ];
    let n2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2] + n[3] * n[3];
    let ok = n2 > 1e-30 && n2 < f32::INFINITY;
    let inv = 1.0 / n2.sqrt();
    if ok {
        [n[0] * inv, n[1] * inv, n[2] * inv, n[3] * inv]
    } else {
        [0.0, 0.0, 0.0, 1.0]
    }
}

/// [`transport_xyzw`] on glam types: the parallel-transport step the school ships.
pub fn transport(q: Quat, new_heading: Vec3) -> Quat {
    Quat::from_array(transport_xyzw(q.to_array(), new_heading.to_array()))
}

/// Per-step constants of the pass.
#[derive(Debug, Clone, Copy)]
struct Consts {
    dt: f32,
    lo: [f32; 3],
    hi: [f32; 3],
    min_speed: f32,
    max_speed: f32,
    /// tail phase advance at max speed
    beat: f32,
    inv_max: f32,
}

pub(super) fn integrate(s: &mut School, dt: f32, env: &Environment) {
    let p = &s.params;
    let (lo, hi) = env.swim_box();
    let min_speed = p.min_speed.max(0.0);
    let max_speed = p.max_speed.max(min_speed).max(1e-6);
    let c = Consts {
        dt,
        lo: lo.to_array(),
        hi: hi.to_array(),
        min_speed,
        max_speed,
        beat: TAU * p.tail_beat_hz.max(0.0) * dt,
        inv_max: 1.0 / max_speed,
    };
    integrate_all(&c, s)
}

simd_dispatch!(fn integrate_all(c: &Consts, s: &mut School) => integrate_lanes);

#[inline(always)]
fn integrate_lanes(c: &Consts, s: &mut School) {
    let n = s.len();
    let (ax, ay, az) = (&s.ax[..n], &s.ay[..n], &s.az[..n]);
    let (px, py, pz) = (&mut s.px[..n], &mut s.py[..n], &mut s.pz[..n]);
    let (vx, vy, vz) = (&mut s.vx[..n], &mut s.vy[..n], &mut s.vz[..n]);
    let (qx, qy, qz, qw) = (
        &mut s.qx[..n],
        &mut s.qy[..n],
        &mut s.qz[..n],
        &mut s.qw[..n],
    );
    let phase = &mut s.phase[..n];
    for i in 0..n {
        let q = [qx[i], qy[i], qz[i], qw[i]];
        let v = [
            vx[i] + ax[i] * c.dt,
            vy[i] + ay[i] * c.dt,
            vz[i] + az[i] * c.dt,
        ];
        let speed = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        let moving = speed > 1e-6 && speed < f32::INFINITY;
        let inv = 1.0 / speed;
        // no usable velocity: keep swimming along the current heading
        let heading = if moving {
            [v[0] * inv, v[1] * inv, v[2] * inv]
        } else {
            [
                1.0 - 2.0 * (q[1] * q[1] + q[2] * q[2]),
                2.0 * (q[0] * q[1] + q[3] * q[2]),
                2.0 * (q[0] * q[2] - q[3] * q[1]),
            ]
        };
        let speed = if speed < f32::INFINITY {
            speed.max(c.min_speed).min(c.max_speed)
        } else {
            c.min_speed
        };
        let v = [heading[0] * speed, heading[1] * speed, heading[2] * speed];
        vx[i] = v[0];
        vy[i] = v[1];
        vz[i] = v[2];
        px[i] = (px[i] + v[0] * c.dt).max(c.lo[0]).min(c.hi[0]);
        py[i] = (py[i] + v[1] * c.dt).max(c.lo[1]).min(c.hi[1]);
        pz[i] = (pz[i] + v[2] * c.dt).max(c.lo[2]).min(c.hi[2]);
        let [x, y, z, w] = transport_xyzw(q, heading);
        qx[i] = x;
        qy[i] = y;
        qz[i] = z;
        qw[i] = w;
        let ph = phase[i] + c.beat * (0.5 + 0.5 * speed * c.inv_max);
        phase[i] = if ph >= TAU { ph - TAU } else { ph };
    }
}
