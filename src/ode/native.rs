//! Native fixed-size right-hand sides of the shipped benchmark problems (oscillator, Kepler,
//! pendulum), written as their problem files write them, so `lectern bench` can time the
//! fast path on the same equations as the expression files (the test below proves they agree);
//! and the stiff ones (Robertson, Van der Pol) as [`System`]s with their hand-written Jacobians.

use super::System;
use super::fixed::FixedSystem;
use super::problem::Problem;

/// x'' = −w² x as (x, v).
#[derive(Debug, Clone, Copy)]
pub struct Harmonic {
    pub w: f64,
}

impl FixedSystem<2> for Harmonic {
    #[inline(always)]
    fn rhs(&self, _t: f64, x: &[f64; 2]) -> [f64; 2] {
        // "-w*w*x": the file's constant −w·w folds first
        [x[1], -self.w * self.w * x[0]]
    }
}

/// The Kepler problem with GM = 1, state (x, y, vx, vy).
#[derive(Debug, Clone, Copy)]
pub struct Kepler;

impl FixedSystem<4> for Kepler {
    #[inline(always)]
    fn rhs(&self, _t: f64, x: &[f64; 4]) -> [f64; 4] {
        let r2 = x[0] * x[0] + x[1] * x[1];
        let r3 = r2 * r2.sqrt();
        [x[2], x[3], -x[0] / r3, -x[1] / r3]
    }
}

/// θ'' = −(g/L) sin θ as (θ, ω).
#[derive(Debug, Clone, Copy)]
pub struct Pendulum {
    pub g: f64,
    pub l: f64,
}

impl FixedSystem<2> for Pendulum {
    #[inline(always)]
    fn rhs(&self, _t: f64, x: &[f64; 2]) -> [f64; 2] {
        [x[1], -self.g / self.l * x[0].sin()]
    }
}

/// Robertson's kinetics with rate constants k1, k2, k3 (`robertson.ron`).
#[derive(Debug, Clone, Copy)]
pub struct Robertson {
    pub k1: f64,
    pub k2: f64,
    pub k3: f64,
}

impl Default for Robertson {
    fn default() -> Self {
        Self {
            k1: 0.04,
            k2: 3e7,
            k3: 1e4,
        }
    }
}

impl System for Robertson {
    fn dim(&self) -> usize {
        3
    }
    fn rhs(&self, _t: f64, y: &[f64], d: &mut [f64]) {
        let (a, b) = (self.k1 * y[0], self.k3 * y[1] * y[2]);
        let c = self.k2 * y[1] * y[1];
        d[0] = -a + b;
        d[1] = a - b - c;
        d[2] = c;
    }
    fn jacobian(&self, _t: f64, y: &[f64], j: &mut [f64]) -> bool {
        let (k1, k2, k3) = (self.k1, self.k2, self.k3);
        j.copy_from_slice(&[
            -k1,
            k3 * y[2],
            k3 * y[1],
            k1,
            -k3 * y[2] - 2.0 * k2 * y[1],
            -k3 * y[1],
            0.0,
            2.0 * k2 * y[1],
            0.0,
        ]);
        true
    }
    fn time_derivative(&self, _t: f64, _y: &[f64], d: &mut [f64]) -> bool {
        d.fill(0.0);
        true
    }
}

/// Van der Pol in the classic form y1' = y2, y2' = μ(1 − y1²)y2 − y1 (`vanderpol-1000.ron`).
#[derive(Debug, Clone, Copy)]
pub struct VanDerPol {
    pub mu: f64,
}

impl System for VanDerPol {
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&self, _t: f64, y: &[f64], d: &mut [f64]) {
        d[0] = y[1];
        d[1] = self.mu * (1.0 - y[0] * y[0]) * y[1] - y[0];
    }
    fn jacobian(&self, _t: f64, y: &[f64], j: &mut [f64]) -> bool {
        let mu = self.mu;
        j.copy_from_slice(&[
            0.0,
            1.0,
            -2.0 * mu * y[0] * y[1] - 1.0,
            mu * (1.0 - y[0] * y[0]),
        ]);
        true
    }
    fn time_derivative(&self, _t: f64, _y: &[f64], d: &mut [f64]) -> bool {
        d.fill(0.0);
        true
    }
}

/// A problem's parameter, or `default` when the file does not set it.
fn param(p: &Problem, name: &str, default: f64) -> f64 {
    p.params
        .iter()
        .find(|(n, _)| n == name)
        .map_or(default, |(_, v)| *v)
}

impl Harmonic {
    pub fn from_problem(p: &Problem) -> Self {
        Self {
            w: param(p, "w", 1.0),
        }
    }
}

impl Pendulum {
    pub fn from_problem(p: &Problem) -> Self {
        Self {
            g: param(p, "g", 1.0),
            l: param(p, "L", 1.0),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ode::System;

    /// The native RHS equals the file's expression RHS on many states (a small LCG, so the
    /// test is deterministic).
    fn agrees<const N: usize>(file: &str, native: impl FixedSystem<N>) {
        let p = Problem::load(format!("slides/problems/{file}.ron")).unwrap();
        let mut seed = 12345u64;
        let mut rand = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 * 4.0 - 2.0
        };
        for _ in 0..1000 {
            let x: [f64; N] = std::array::from_fn(|_| rand());
            let t = rand();
            let mut d = [0.0; N];
            p.rhs(t, &x, &mut d);
            let n = native.rhs(t, &x);
            for i in 0..N {
                assert!(
                    (d[i] - n[i]).abs() <= 1e-15 * (1.0 + d[i].abs()),
                    "{file}: {d:?} vs {n:?} at {x:?}"
                );
            }
        }
    }

    /// The stiff natives' f and hand-written Jacobians equal the files' f and the Jacobians
    /// differentiated from their programs.
    #[test]
    fn stiff_natives_equal_the_shipped_problem_files() {
        let cases: [(&str, &dyn System); 2] = [
            ("robertson", &Robertson::default()),
            ("vanderpol-1000", &VanDerPol { mu: 1000.0 }),
        ];
        for (file, native) in cases {
            let p = Problem::load(format!("slides/problems/{file}.ron")).unwrap();
            let n = p.dim();
            for x in [[0.9, 1e-5, 0.1], [-1.5, 0.7, 0.3], [2.0, -3.0, 0.5]] {
                let x = &x[..n];
                let (mut a, mut b) = (vec![0.0; n], vec![0.0; n]);
                p.rhs(0.0, x, &mut a);
                native.rhs(0.0, x, &mut b);
                for (u, v) in a.iter().zip(&b) {
                    assert!(
                        (u - v).abs() <= 1e-15 * u.abs().max(1.0),
                        "{file}: {a:?} vs {b:?}"
                    );
                }
                let (mut ja, mut jb) = (vec![0.0; n * n], vec![0.0; n * n]);
                assert!(p.jacobian(0.0, x, &mut ja) && native.jacobian(0.0, x, &mut jb));
                for (u, v) in ja.iter().zip(&jb) {
                    assert!(
                        (u - v).abs() <= 1e-15 * u.abs().max(1.0),
                        "{file}: {ja:?} vs {jb:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn natives_equal_the_shipped_problem_files() {
        let h = Problem::load("slides/problems/harmonic.ron").unwrap();
        agrees("harmonic", Harmonic::from_problem(&h));
        agrees("kepler", Kepler);
        let p = Problem::load("slides/problems/pendulum.ron").unwrap();
        agrees("pendulum", Pendulum::from_problem(&p));
    }
}
