//! Arithmetic written once for a scalar `f64` and for four bodies side by side ([`F4`]), so the
//! free-rotation map in [`super::free_rotation`] is the same code in `RigidBody::step` and in
//! [`super::batch`] (bit-identical results), and the batch kernel is straight-line `[f64; 4]`
//! arithmetic that LLVM turns into SIMD.
//!
//! Quaternions here are `[x, y, z, w]` arrays (glam's order).

use std::ops::{Add, Div, Mul, Neg, Sub};

/// A real number, or four of them.
pub trait Real:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    fn splat(v: f64) -> Self;
    fn sqrt(self) -> Self;
}

impl Real for f64 {
    #[inline(always)]
    fn splat(v: f64) -> Self {
        v
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        f64::sqrt(self)
    }
}

/// Four f64 lanes, one per body; every operation is lane-wise and branch-free. Aligned to 32
/// bytes so a lane group is one AVX register load.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[repr(C, align(32))]
pub struct F4(pub [f64; 4]);

// No closures below: a closure is compiled without the caller's `#[target_feature]`s, and
// one LLVM declines to inline would drop the AVX2 build back to SSE2.
impl F4 {
    pub const ZERO: F4 = F4([0.0; 4]);

    /// All-ones bits in the lanes where `v` is finite, zero elsewhere.
    #[inline(always)]
    pub fn finite_mask(self) -> [u64; 4] {
        let a = self.0;
        [m(a[0]), m(a[1]), m(a[2]), m(a[3])]
    }

    /// `if mask { self } else { other }` per lane, by bits: no branch.
    #[inline(always)]
    pub fn select(self, mask: [u64; 4], other: F4) -> F4 {
        let (a, b) = (self.0, other.0);
        F4([
            pick(a[0], b[0], mask[0]),
            pick(a[1], b[1], mask[1]),
            pick(a[2], b[2], mask[2]),
            pick(a[3], b[3], mask[3]),
        ])
    }
}

impl Real for F4 {
    #[inline(always)]
    fn splat(v: f64) -> Self {
        F4([v; 4])
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        let a = self.0;
        F4([a[0].sqrt(), a[1].sqrt(), a[2].sqrt(), a[3].sqrt()])
    }
}

/// All-ones bits if `v` is finite, else zero.
#[inline(always)]
fn m(v: f64) -> u64 {
    (v.is_finite() as u64).wrapping_neg()
}

/// `x` where `m` is all ones, `y` where it is zero.
#[inline(always)]
fn pick(x: f64, y: f64, m: u64) -> f64 {
    f64::from_bits((x.to_bits() & m) | (y.to_bits() & !m))
}

macro_rules! lane_op {
    ($tr:ident, $f:ident, $op:tt) => {
        impl $tr for F4 {
            type Output = F4;
            #[inline(always)]
            fn $f(self, o: F4) -> F4 {
                let (a, b) = (self.0, o.0);
                F4([a[0] $op b[0], a[1] $op b[1], a[2] $op b[2], a[3] $op b[3]])
            }
        }
    };
}
lane_op!(Add, add, +);
lane_op!(Sub, sub, -);
lane_op!(Mul, mul, *);
lane_op!(Div, div, /);

impl Neg for F4 {
    type Output = F4;
    #[inline(always)]
    fn neg(self) -> F4 {
        let a = self.0;
        F4([-a[0], -a[1], -a[2], -a[3]])
    }
}

/// Hamilton product `a b`.
#[inline(always)]
pub fn qmul<T: Real>(a: [T; 4], b: [T; 4]) -> [T; 4] {
    let [ax, ay, az, aw] = a;
    let [bx, by, bz, bw] = b;
    [
        aw * bx + ax * bw + ay * bz - az * by,
        aw * by - ax * bz + ay * bw + az * bx,
        aw * bz + ax * by - ay * bx + az * bw,
        aw * bw - ax * bx - ay * by - az * bz,
    ]
}

/// The conjugate (the inverse of a unit quaternion).
#[inline(always)]
pub fn qconj<T: Real>(q: [T; 4]) -> [T; 4] {
    [-q[0], -q[1], -q[2], q[3]]
}

/// `R(q)ᵀ v` for a unit quaternion q: the world vector `v` in the rotated frame's axes.
#[inline(always)]
pub fn rotate_inverse<T: Real>(q: [T; 4], v: [T; 3]) -> [T; 3] {
    // v' = v + 2 u × (u × v − w v) with u = −q.xyz (the conjugate's vector part)
    let (ux, uy, uz, w) = (-q[0], -q[1], -q[2], q[3]);
    let two = T::splat(2.0);
    let tx = two * (uy * v[2] - uz * v[1]);
    let ty = two * (uz * v[0] - ux * v[2]);
    let tz = two * (ux * v[1] - uy * v[0]);
    [
        v[0] + w * tx + (uy * tz - uz * ty),
        v[1] + w * ty + (uz * tx - ux * tz),
        v[2] + w * tz + (ux * ty - uy * tx),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{DQuat, DVec3};

    #[test]
    fn product_and_inverse_rotation_agree_with_glam() {
        let a = DQuat::from_euler(glam::EulerRot::XYZ, 0.3, -1.2, 2.1);
        let b = DQuat::from_euler(glam::EulerRot::ZYX, -0.7, 0.4, 1.9);
        let ab = qmul(a.to_array(), b.to_array());
        assert!((DQuat::from_array(ab) - a * b).length() < 1e-15);
        let v = DVec3::new(0.3, -2.0, 1.5);
        let r = DVec3::from_array(rotate_inverse(a.to_array(), v.to_array()));
        assert!((r - a.inverse() * v).length() < 1e-14);
        let back = DQuat::from_array(qmul(qconj(a.to_array()), a.to_array()));
        assert!((back - DQuat::IDENTITY).length() < 1e-15);
    }

    #[test]
    fn lanes_select_and_detect_non_finite_values() {
        let v = F4([1.0, f64::NAN, f64::INFINITY, -3.0]);
        let m = v.finite_mask();
        assert_eq!(m, [u64::MAX, 0, 0, u64::MAX]);
        assert_eq!(v.select(m, F4::splat(7.0)).0, [1.0, 7.0, 7.0, -3.0]);
        let s = F4([4.0, 9.0, 16.0, 25.0]).sqrt() * F4::splat(2.0) - F4::splat(1.0);
        assert_eq!((s / F4::splat(2.0)).0, [1.5, 2.5, 3.5, 4.5]);
    }
}
