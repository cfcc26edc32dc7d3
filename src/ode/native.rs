//! Native fixed-size right-hand sides of the shipped benchmark problems (oscillator, Kepler,
//! pendulum), written as their problem files write them, so `lectern bench` can time the
//! fast path on the same equations as the expression files (the test below proves they agree).

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

    #[test]
    fn natives_equal_the_shipped_problem_files() {
        let h = Problem::load("slides/problems/harmonic.ron").unwrap();
        agrees("harmonic", Harmonic::from_problem(&h));
        agrees("kepler", Kepler);
        let p = Problem::load("slides/problems/pendulum.ron").unwrap();
        agrees("pendulum", Pendulum::from_problem(&p));
    }
}
