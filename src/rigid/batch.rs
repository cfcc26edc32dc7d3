//! Many rigid bodies stepped together: structure of arrays over bodies in chunks of four
//! ([`F4`] lanes), every integrator of [`Integrator`], the wrench per body per stage through
//! [`BatchForces`].
//!
//! Layout: chunk `c` holds bodies `4c … 4c+3`; its state is `[F4; 13]` in
//! [`RigidState::to_array`] order (x, q as xyzw, P, L), component-major, so each of the 13
//! numbers of four bodies is one 32-byte row. The kernel is straight-line lane arithmetic
//! without branches per lane (the NaN reset is a bit-select), which LLVM vectorises. It is
//! compiled twice: portable, and under `avx2,fma` chosen at run time
//! (`is_x86_feature_detected!`). Rust never contracts `a * b + c` into an FMA on its own, so
//! both give identical bits.
//!
//! The maths is `RigidBody::step`'s (tested per body to 1e-12, bit-identical for symplectic
//! Euler, which shares [`free_rotation::drift`]); only ω is computed without the square root:
//! `R(q̂) = M(q) / |q|²` with `M` the homogeneous quadratic form, so one division per stage.

use super::free_rotation;
use super::lanes::{F4, Real};
use super::state::{BodyConstants, Integrator, RigidState};

/// Four bodies' states, component-major in [`RigidState::to_array`] order.
pub type State4 = [F4; 13];

/// The wrench on four bodies at once, evaluated at every stage of the integrator.
pub trait BatchForces {
    /// True when the wrench is identically zero: the kernel then skips the momentum updates
    /// (at compile time), which is exact for finite states.
    const ZERO: bool = false;
    /// Force and torque (world, about the centre of mass) on bodies `first … first + 3` in the
    /// stage state `s` at time `t`, as `[F_x, F_y, F_z, τ_x, τ_y, τ_z]`. Lanes past the
    /// batch's length are padding (a body at rest): give them any finite wrench.
    fn wrench(&self, first: usize, t: f64, mass: F4, s: &State4) -> [F4; 6];
}

/// Free bodies: the zero wrench, which compiles away.
#[derive(Debug, Clone, Copy, Default)]
pub struct FreeBodies;

impl BatchForces for FreeBodies {
    const ZERO: bool = true;
    #[inline(always)]
    fn wrench(&self, _: usize, _: f64, _: F4, _: &State4) -> [F4; 6] {
        [F4::ZERO; 6]
    }
}

/// Lane `j` of a chunk as a [`RigidState`] (for wrenches written per body).
pub fn lane_state(s: &State4, j: usize) -> RigidState {
    let a: [f64; 13] = std::array::from_fn(|i| s[i].0[j]);
    RigidState::from_slice(&a)
}

/// Four bodies' constants; the fields each integrator reads sit together.
#[derive(Debug, Clone, Copy)]
#[repr(C)]
pub(crate) struct Consts4 {
    /// I_body⁻¹ (symmetric): xx, yy, zz, xy, yz, zx
    inv_i: [F4; 6],
    inv_mass: F4,
    mass: F4,
    /// body_from_principal, xyzw
    principal: [F4; 4],
    inv_moments: [F4; 3],
}

impl Consts4 {
    /// Padding lanes: unit mass and inertia, at rest.
    fn padding() -> Self {
        let one = F4::splat(1.0);
        Self {
            inv_i: [one, one, one, F4::ZERO, F4::ZERO, F4::ZERO],
            inv_mass: one,
            mass: one,
            principal: [F4::ZERO, F4::ZERO, F4::ZERO, one],
            inv_moments: [one; 3],
        }
    }
}

#[inline(always)]
fn padding_state() -> State4 {
    let mut s = [F4::ZERO; 13];
    s[6] = F4::splat(1.0);
    s
}

/// Many bodies, one clock, one integrator.
#[derive(Clone)]
pub struct BodyBatch {
    len: usize,
    states: Vec<State4>,
    consts: Vec<Consts4>,
    /// seconds
    pub time: f64,
    pub integrator: Integrator,
}

impl BodyBatch {
    pub fn new(integrator: Integrator) -> Self {
        Self {
            len: 0,
            states: Vec::new(),
            consts: Vec::new(),
            time: 0.0,
            integrator,
        }
    }

    pub fn len(&self) -> usize {
        self.len
    }

    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Appends a body (constants from [`BodyConstants::new`]).
    pub fn push(&mut self, c: &BodyConstants, state: RigidState) {
        if self.len.is_multiple_of(4) {
            self.states.push(padding_state());
            self.consts.push(Consts4::padding());
        }
        let (ci, j) = (self.len / 4, self.len % 4);
        let k = &mut self.consts[ci];
        let m = c.inv_inertia_body;
        let sym = |r: usize, s: usize| 0.5 * (m.col(s)[r] + m.col(r)[s]);
        let inv_i = [
            sym(0, 0),
            sym(1, 1),
            sym(2, 2),
            sym(0, 1),
            sym(1, 2),
            sym(2, 0),
        ];
        for (dst, v) in k.inv_i.iter_mut().zip(inv_i) {
            dst.0[j] = v;
        }
        k.inv_mass.0[j] = c.inv_mass;
        k.mass.0[j] = c.mass;
        for (dst, v) in k.principal.iter_mut().zip(c.principal.to_array()) {
            dst.0[j] = v;
        }
        for (dst, v) in k
            .inv_moments
            .iter_mut()
            .zip(c.inv_principal_moments.to_array())
        {
            dst.0[j] = v;
        }
        self.len += 1;
        self.set_state(self.len - 1, state);
    }

    /// Body `i`'s state. Panics if `i >= len()`.
    pub fn state(&self, i: usize) -> RigidState {
        assert!(i < self.len, "body {i} of {}", self.len);
        lane_state(&self.states[i / 4], i % 4)
    }

    /// Sets body `i`'s state; q is normalised here (the step keeps it unit after that), as
    /// `RigidBody::step` does for a state it did not produce.
    pub fn set_state(&mut self, i: usize, mut state: RigidState) {
        assert!(i < self.len, "body {i} of {}", self.len);
        if (state.q.length_squared() - 1.0).abs() > 1e-14 {
            state.q = state.q.normalize();
        }
        for (dst, v) in self.states[i / 4].iter_mut().zip(state.to_array()) {
            dst.0[i % 4] = v;
        }
    }

    /// Advances every body by `h` (ignored unless finite and positive) with the batch's
    /// integrator: the AVX2 + FMA build of the kernel where the CPU has it, else the portable.
    pub fn step<F: BatchForces>(&mut self, h: f64, forces: &F) {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("fma")
        {
            // SAFETY: the CPU supports the features step_avx2 is compiled for (checked above).
            unsafe { self.step_avx2(h, forces) };
            return;
        }
        self.step_portable(h, forces);
    }

    /// The kernel compiled for the baseline target (SSE2 on x86-64).
    pub fn step_portable<F: BatchForces>(&mut self, h: f64, forces: &F) {
        self.kernel(h, forces);
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,fma")]
    fn step_avx2<F: BatchForces>(&mut self, h: f64, forces: &F) {
        self.kernel(h, forces);
    }

    #[inline(always)]
    fn kernel<F: BatchForces>(&mut self, h: f64, forces: &F) {
        if !(h.is_finite() && h > 0.0) {
            return;
        }
        let t = self.time;
        let chunks = self.states.iter_mut().zip(&self.consts).enumerate();
        // one loop per method, each over a straight-line chunk kernel; plain loops, no
        // closures, so everything inlines into (and is compiled with) the caller's features
        match self.integrator {
            Integrator::Euler => {
                for (i, (s, c)) in chunks {
                    euler(c, forces, 4 * i, t, s, h);
                }
            }
            Integrator::Midpoint => {
                for (i, (s, c)) in chunks {
                    midpoint(c, forces, 4 * i, t, s, h);
                }
            }
            Integrator::Rk4 => {
                for (i, (s, c)) in chunks {
                    rk4(c, forces, 4 * i, t, s, h);
                }
            }
            Integrator::SymplecticEuler => {
                for (i, (s, c)) in chunks {
                    symplectic_euler(c, forces, 4 * i, t, s, h);
                    finish(s);
                }
            }
        }
        self.time += h;
    }
}

#[inline(always)]
fn euler<F: BatchForces>(c: &Consts4, forces: &F, first: usize, t: f64, s: &mut State4, h: f64) {
    let k1 = rhs(c, forces, first, t + 0.0 * h, s);
    accumulate::<F>(s, h * 1.0, &k1);
    finish(s);
}

#[inline(always)]
fn midpoint<F: BatchForces>(c: &Consts4, forces: &F, first: usize, t: f64, s: &mut State4, h: f64) {
    let k1 = rhs(c, forces, first, t + 0.0 * h, s);
    let k2 = rhs(c, forces, first, t + 0.5 * h, &stage::<F>(s, h * 0.5, &k1));
    accumulate::<F>(s, h * 1.0, &k2);
    finish(s);
}

#[inline(always)]
fn rk4<F: BatchForces>(c: &Consts4, forces: &F, first: usize, t: f64, s: &mut State4, h: f64) {
    let k1 = rhs(c, forces, first, t + 0.0 * h, s);
    let k2 = rhs(c, forces, first, t + 0.5 * h, &stage::<F>(s, h * 0.5, &k1));
    let k3 = rhs(c, forces, first, t + 0.5 * h, &stage::<F>(s, h * 0.5, &k2));
    let k4 = rhs(c, forces, first, t + 1.0 * h, &stage::<F>(s, h * 1.0, &k3));
    accumulate::<F>(s, h * (1.0 / 6.0), &k1);
    accumulate::<F>(s, h * (1.0 / 3.0), &k2);
    accumulate::<F>(s, h * (1.0 / 3.0), &k3);
    accumulate::<F>(s, h * (1.0 / 6.0), &k4);
    finish(s);
}

/// How many leading components a stage changes: x and q only when the wrench is zero.
#[inline(always)]
const fn moving<F: BatchForces>() -> usize {
    if F::ZERO { 7 } else { 13 }
}

#[inline(always)]
fn stage<F: BatchForces>(x: &State4, ha: f64, k: &State4) -> State4 {
    let mut out = *x;
    for i in 0..moving::<F>() {
        out[i] = x[i] + F4::splat(ha) * k[i];
    }
    out
}

#[inline(always)]
fn accumulate<F: BatchForces>(x: &mut State4, hb: f64, k: &State4) {
    for i in 0..moving::<F>() {
        x[i] = x[i] + F4::splat(hb) * k[i];
    }
}

/// `Ẋ = (P/M, ½ ω q, F, τ)` for four bodies, `ω = R I_body⁻¹ Rᵀ L` with `R = M(q) / |q|²`.
#[inline(always)]
fn rhs<F: BatchForces>(c: &Consts4, forces: &F, first: usize, t: f64, s: &State4) -> State4 {
    let [qx, qy, qz, qw] = [s[3], s[4], s[5], s[6]];
    let (xx, yy, zz, ww) = (qx * qx, qy * qy, qz * qz, qw * qw);
    let (xy, xz, yz) = (qx * qy, qx * qz, qy * qz);
    let (wx, wy, wz) = (qw * qx, qw * qy, qw * qz);
    let two = F4::splat(2.0);
    // M(q) = |q|² R(q̂), row-major
    let m = [
        [ww + xx - yy - zz, two * (xy - wz), two * (xz + wy)],
        [two * (xy + wz), ww - xx + yy - zz, two * (yz - wx)],
        [two * (xz - wy), two * (yz + wx), ww - xx - yy + zz],
    ];
    let l = [s[10], s[11], s[12]];
    // body-axes momentum (times |q|²): Mᵀ L
    let a = [
        m[0][0] * l[0] + m[1][0] * l[1] + m[2][0] * l[2],
        m[0][1] * l[0] + m[1][1] * l[1] + m[2][1] * l[2],
        m[0][2] * l[0] + m[1][2] * l[1] + m[2][2] * l[2],
    ];
    let ii = &c.inv_i;
    let b = [
        ii[0] * a[0] + ii[3] * a[1] + ii[5] * a[2],
        ii[3] * a[0] + ii[1] * a[1] + ii[4] * a[2],
        ii[5] * a[0] + ii[4] * a[1] + ii[2] * a[2],
    ];
    let inv_n2 = F4::splat(1.0) / (xx + yy + zz + ww);
    let half_scale = F4::splat(0.5) * inv_n2 * inv_n2;
    // ½ ω
    let w = [
        (m[0][0] * b[0] + m[0][1] * b[1] + m[0][2] * b[2]) * half_scale,
        (m[1][0] * b[0] + m[1][1] * b[1] + m[1][2] * b[2]) * half_scale,
        (m[2][0] * b[0] + m[2][1] * b[1] + m[2][2] * b[2]) * half_scale,
    ];
    let mut d = [F4::ZERO; 13];
    for i in 0..3 {
        d[i] = s[7 + i] * c.inv_mass;
    }
    // (0, ½ω) q
    d[3] = w[0] * qw + w[1] * qz - w[2] * qy;
    d[4] = w[1] * qw + w[2] * qx - w[0] * qz;
    d[5] = w[2] * qw + w[0] * qy - w[1] * qx;
    d[6] = -(w[0] * qx + w[1] * qy + w[2] * qz);
    if !F::ZERO {
        d[7..13].copy_from_slice(&forces.wrench(first, t, c.mass, s));
    }
    d
}

/// Kick P, L with the old wrench, drift x, then the free-rotation splitting (as
/// `step::symplectic_euler`, operation for operation).
#[inline(always)]
fn symplectic_euler<F: BatchForces>(
    c: &Consts4,
    forces: &F,
    first: usize,
    t: f64,
    s: &mut State4,
    h: f64,
) {
    let hv = F4::splat(h);
    if !F::ZERO {
        let wr = forces.wrench(first, t, c.mass, s);
        for i in 0..6 {
            s[7 + i] = s[7 + i] + hv * wr[i];
        }
    }
    for i in 0..3 {
        s[i] = s[i] + hv * (s[7 + i] * c.inv_mass);
    }
    let q = free_rotation::drift(
        [s[3], s[4], s[5], s[6]],
        [s[10], s[11], s[12]],
        c.principal,
        c.inv_moments,
        hv,
    );
    s[3..7].copy_from_slice(&q);
}

#[inline(always)]
fn and_assign(a: &mut [u64; 4], b: [u64; 4]) {
    for j in 0..4 {
        a[j] &= b[j];
    }
}

#[allow(clippy::needless_range_loop)]
/// Renormalise q; a lane that blew up (non-finite q, x or P) is reset to rest at the origin
/// if x is lost, else where it is: `RigidBody::step`'s rule, by bit-select.
#[inline(always)]
fn finish(s: &mut State4) {
    let n2 = s[3] * s[3] + s[4] * s[4] + s[5] * s[5] + s[6] * s[6];
    let inv = F4::splat(1.0) / n2.sqrt();
    let mut x_ok = [u64::MAX; 4];
    for i in 0..3 {
        and_assign(&mut x_ok, s[i].finite_mask());
    }
    for i in 3..7 {
        s[i] = s[i] * inv;
    }
    let mut ok = x_ok;
    for i in 3..10 {
        and_assign(&mut ok, s[i].finite_mask());
    }
    // index loops over constant ranges: fully unrolled, nothing left to inline
    for i in 0..3 {
        s[i] = s[i].select(x_ok, F4::ZERO);
    }
    for i in 3..13 {
        let rest = if i == 6 { F4::splat(1.0) } else { F4::ZERO };
        s[i] = s[i].select(ok, rest);
    }
}

#[cfg(test)]
#[path = "batch_tests.rs"]
mod tests;
