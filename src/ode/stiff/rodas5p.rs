//! Rodas5P, a stiffly accurate, L-stable Rosenbrock–Wanner method of order 5 with an embedded
//! method of order 4: S. Steinebach, "Construction of Rosenbrock–Wanner method Rodas5P and
//! numerical benchmarks within the Julia Differential Equations package", BIT Numer. Math. 63
//! (2023) 27. Coefficients in the transformed form of Hairer & Wanner (Solving ODEs II, IV.7,
//! (7.25)), to double precision as published in OrdinaryDiffEq.jl's `Rodas5PTableau`
//! (Steinebach's own listing).
//!
//! One step with W = I/(γh) − J, J = ∂f/∂x and f_t = ∂f/∂t at (t, x):
//! `W k_i = f(t + c_i h, x + Σ_{j<i} a_ij k_j) + Σ_{j<i} (C_ij/h) k_j + h d_i f_t`, i = 1…8;
//! stages 6, 7, 8 are taken at t + h and each adds its k to the state (stiff accuracy):
//! x_new = x + Σ_{j<6} a_6j k_j + k_6 + k_7 + k_8, and k_8 is the error estimate.

use super::{ImplicitWork, jacobian_at, time_derivative_at};
use crate::ode::System;
use crate::ode::linalg::{Lu, Singular};
use crate::ode::stability::{Complex, cdiv, cmul};

pub const GAMMA: f64 = 0.21193756319429014;

/// a_ij (rows 2…6; stages 7 and 8 add to the 6th stage's state).
const A: [[f64; 5]; 5] = [
    [3.0, 0.0, 0.0, 0.0, 0.0],
    [2.849394379747939, 0.45842242204463923, 0.0, 0.0, 0.0],
    [
        -6.954028509809101,
        2.489845061869568,
        -10.358996098473584,
        0.0,
        0.0,
    ],
    [
        2.8029986275628964,
        0.5072464736228206,
        -0.3988312541770524,
        -0.04721187230404641,
        0.0,
    ],
    [
        -7.502846399306121,
        2.561846144803919,
        -11.627539656261098,
        -0.18268767659942256,
        0.030198172008377946,
    ],
];

/// C_ij (rows 2…8).
const C: [[f64; 7]; 7] = [
    [-14.155112264123755, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [
        -17.97296035885952,
        -2.859693295451294,
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
    ],
    [
        147.12150275711716,
        -1.41221402718213,
        71.68940251302358,
        0.0,
        0.0,
        0.0,
        0.0,
    ],
    [
        165.43517024871676,
        -0.4592823456491126,
        42.90938336958603,
        -5.961986721573306,
        0.0,
        0.0,
        0.0,
    ],
    [
        24.854864614690072,
        -3.0009227002832186,
        47.4931110020768,
        5.5814197821558125,
        -0.6610691825249471,
        0.0,
        0.0,
    ],
    [
        30.91273214028599,
        -3.1208243349937974,
        77.79954646070892,
        34.28646028294783,
        -19.097331116725623,
        -28.087943162872662,
        0.0,
    ],
    [
        37.80277123390563,
        -3.2571969029072276,
        112.26918849496327,
        66.9347231244047,
        -40.06618937091002,
        -54.66780262877968,
        -9.48861652309627,
    ],
];

/// Stage times c_1 … c_8.
pub const NODES: [f64; 8] = [
    0.0,
    0.6358126895828704,
    0.4095798393397535,
    0.9769306725060716,
    0.4288403609558664,
    1.0,
    1.0,
    1.0,
];

/// d_i = Σ_j γ_ij, the weights of h·f_t (zero for stages 6…8).
const D: [f64; 8] = [
    0.21193756319429014,
    -0.42387512638858027,
    -0.3384627126235924,
    1.8046452872882734,
    2.325825639765069,
    0.0,
    0.0,
    0.0,
];

/// Scratch and the Jacobian of one Rodas5P integration.
#[derive(Debug, Clone)]
pub struct Rodas5p {
    n: usize,
    jac: Vec<f64>,
    dfdt: Vec<f64>,
    lu: Lu,
    k: [Vec<f64>; 8],
    u: Vec<f64>,
    du: Vec<f64>,
    fp: Vec<f64>,
    pub work: ImplicitWork,
}

impl Rodas5p {
    pub fn new(n: usize) -> Self {
        Self {
            n,
            jac: vec![0.0; n * n],
            dfdt: vec![0.0; n],
            lu: Lu::new(n),
            k: std::array::from_fn(|_| vec![0.0; n]),
            u: vec![0.0; n],
            du: vec![0.0; n],
            fp: vec![0.0; n],
            work: ImplicitWork::default(),
        }
    }

    /// Evaluates J and ∂f/∂t at (t, x), where `fx` = f(t, x); every attempt from this state
    /// reuses them. False when either has a NaN or ∞.
    pub fn prepare<S: System + ?Sized>(&mut self, sys: &S, t: f64, x: &[f64], fx: &[f64]) -> bool {
        self.u.copy_from_slice(x);
        jacobian_at(sys, t, &mut self.u, fx, &mut self.fp, &mut self.jac);
        time_derivative_at(sys, t, x, fx, &mut self.dfdt);
        self.work.jac_evals += 1;
        self.jac.iter().chain(&self.dfdt).all(|v| v.is_finite())
    }

    /// One step of h from (t, x) with f(t, x) = `fx` into `x_new`; returns the error
    /// estimate k_8 (x_new minus the embedded solution). 7 f-evaluations, one LU.
    pub fn attempt<S: System + ?Sized>(
        &mut self,
        sys: &S,
        t: f64,
        x: &[f64],
        fx: &[f64],
        h: f64,
        x_new: &mut [f64],
    ) -> Result<&[f64], Singular> {
        let n = self.n;
        let inv_gh = 1.0 / (GAMMA * h);
        for (m, j) in self.lu.m.iter_mut().zip(&self.jac) {
            *m = -j;
        }
        for i in 0..n {
            self.lu.m[i * n + i] += inv_gh;
        }
        self.work.lu_decomps += 1;
        self.lu.factor()?;
        let inv_h = 1.0 / h;
        for s in 0..8 {
            // the stage's f: at x for the first, else at x + Σ a_sj k_j (stages 6…8: at the
            // running state u, which the previous stage advanced by its k)
            if s == 0 {
                self.du.copy_from_slice(fx);
            } else {
                if s <= 5 {
                    let a = &A[s - 1];
                    for m in 0..n {
                        let mut acc = x[m];
                        for j in 0..s {
                            acc += a[j] * self.k[j][m];
                        }
                        self.u[m] = acc;
                    }
                } else {
                    for m in 0..n {
                        self.u[m] += self.k[s - 1][m];
                    }
                }
                sys.rhs(t + NODES[s] * h, &self.u, &mut self.du);
            }
            let (done, rest) = self.k.split_at_mut(s);
            let ks = &mut rest[0];
            for m in 0..n {
                let mut acc = self.du[m] + h * D[s] * self.dfdt[m];
                if s > 0 {
                    let c = &C[s - 1];
                    let mut sum = 0.0;
                    for j in 0..s {
                        sum += c[j] * done[j][m];
                    }
                    acc += inv_h * sum;
                }
                ks[m] = acc;
            }
            self.lu.solve(ks);
        }
        for m in 0..n {
            x_new[m] = self.u[m] + self.k[7][m];
        }
        Ok(&self.k[7])
    }
}

/// Rodas5P with a fixed step (the order tests, slides with an h slider): J and f_t at every
/// step's start.
#[derive(Debug, Clone)]
pub struct FixedRodas5p {
    core: Rodas5p,
    fx: Vec<f64>,
    x_new: Vec<f64>,
}

impl FixedRodas5p {
    pub fn new(n: usize) -> Self {
        Self {
            core: Rodas5p::new(n),
            fx: vec![0.0; n],
            x_new: vec![0.0; n],
        }
    }

    pub fn step<S: System + ?Sized>(
        &mut self,
        sys: &S,
        t: f64,
        x: &mut [f64],
        h: f64,
    ) -> Result<(), &'static str> {
        sys.rhs(t, x, &mut self.fx);
        if !self.core.prepare(sys, t, x, &self.fx) {
            return Err("the Jacobian or ∂f/∂t has NaN or ∞");
        }
        self.core
            .attempt(sys, t, x, &self.fx, h, &mut self.x_new)
            .map_err(|_| "the matrix I/(γh) − J is singular")?;
        x.copy_from_slice(&self.x_new);
        Ok(())
    }
}

/// R(z): one step on y' = λy, z = hλ, y₀ = 1, by the stage recurrence in complex arithmetic
/// (J = λ, f_t = 0): k_i = (z·u_i + Σ_j C_ij k_j) / (1/γ − z) with k scaled by 1/h.
pub fn stability(z: Complex) -> Complex {
    let w = (1.0 / GAMMA - z.0, -z.1);
    let mut k = [(0.0, 0.0); 8];
    let mut u = (1.0, 0.0);
    for s in 0..8 {
        if (1..=5).contains(&s) {
            u = (1.0, 0.0);
            for j in 0..s {
                u.0 += A[s - 1][j] * k[j].0;
                u.1 += A[s - 1][j] * k[j].1;
            }
        } else if s > 5 {
            u.0 += k[s - 1].0;
            u.1 += k[s - 1].1;
        }
        let mut r = cmul(z, u);
        if s > 0 {
            for j in 0..s {
                r.0 += C[s - 1][j] * k[j].0;
                r.1 += C[s - 1][j] * k[j].1;
            }
        }
        k[s] = cdiv(r, w);
    }
    (u.0 + k[7].0, u.1 + k[7].1)
}
