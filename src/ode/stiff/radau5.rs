//! RADAU5: the 3-stage Radau IIA collocation method of order 5 as in E. Hairer & G. Wanner,
//! Solving ODEs II (2nd ed., 1996), IV.8, and their code radau5.f (version of 2002): simplified
//! Newton iterations on the transformed system (one real LU of u₁/h·I − J and one complex LU
//! of (α + iβ)/h·I − J per new matrix), starting values extrapolated from the previous step's
//! collocation polynomial, the Jacobian kept across steps while Newton converges fast
//! (θ ≤ 0.001), the embedded error estimate ESTRAD (with its second, filtered evaluation after
//! a rejection) and Gustafsson's predictive step-size controller (in `ode::adaptive`).
//! Constants to double precision as in radau5.f; c, d, u₁, α, β from their closed forms
//! (evaluated to 50 digits).

use super::{ImplicitWork, jacobian_at};
use crate::ode::System;
use crate::ode::linalg::{Lu, LuComplex, Singular};
use crate::ode::stability::{Complex, cdiv, cmul};

/// c₁ = (4 − √6)/10, c₂ = (4 + √6)/10, c₃ = 1.
pub const C1: f64 = 0.15505102572168219018027159252941086080340525193433;
pub const C2: f64 = 0.64494897427831780981972840747058913919659474806567;
const C1M1: f64 = C1 - 1.0;
const C2M1: f64 = C2 - 1.0;
const C1MC2: f64 = C1 - C2;
/// The error estimate's weights: −(13 + 7√6)/3, (−13 + 7√6)/3, −1/3.
const DD1: f64 = -10.048809399827415562460329507647079914587210788199;
const DD2: f64 = 1.3821427331607488957936628409804132479205441215323;
const DD3: f64 = -1.0 / 3.0;
/// The eigenvalues of A⁻¹: the real u₁ and the pair α ± iβ.
pub const U1: f64 = 3.6378342527444957322084185135777757979459360868739;
pub const ALPHA: f64 = 2.6810828736277521338957907432111121010270319565630;
pub const BETA: f64 = 3.0504301992474105694263776247875679044407041991795;
/// T (A⁻¹'s eigenvectors, T⁻¹A⁻¹T = diag(u₁, [α −β; β α])) and T⁻¹, from radau5.f.
pub const T: [[f64; 3]; 3] = [
    [
        9.1232394870892942792e-02,
        -0.14125529502095420843,
        -3.0029194105147424492e-02,
    ],
    [
        0.24171793270710701896,
        0.20412935229379993199,
        0.38294211275726193779,
    ],
    [0.96604818261509293619, 1.0, 0.0],
];
pub const TI: [[f64; 3]; 3] = [
    [
        4.3255798900631553510,
        0.33919925181580986954,
        0.54177053993587487119,
    ],
    [
        -4.1787185915519047273,
        -0.32768282076106238708,
        0.47662355450055045196,
    ],
    [
        -0.50287263494578687595,
        2.5719269498556054292,
        -0.59603920482822492497,
    ],
];

/// Newton iterations before a step is given up (radau5.f's default NIT).
pub const NIT: usize = 7;
/// θ above which the Jacobian is re-evaluated after a step (radau5.f's THET).
pub const THET: f64 = 0.001;

/// RADAU5's tolerances: it runs at rtol' = 0.1·rtol^(2/3), atol' = rtol'·atol/rtol, with the
/// Newton stopping threshold max(10ε/rtol', min(0.03, √rtol')).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RadauTol {
    pub rtol: f64,
    pub atol: f64,
    pub fnewt: f64,
}

impl RadauTol {
    pub fn from_user(rtol: f64, atol: f64) -> Self {
        let r = 0.1 * rtol.powf(2.0 / 3.0);
        Self {
            rtol: r,
            atol: r * (atol / rtol),
            fnewt: (10.0 * f64::EPSILON / r).max(0.03f64.min(r.sqrt())),
        }
    }
}

/// How an attempt ended.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Attempt {
    /// Newton converged: the scaled error estimate (≥ 1e-10) and the iterations it took
    Converged {
        err: f64,
        newton_iterations: usize,
    },
    /// Newton diverged or converged too slowly: retry with h times this factor
    Retry {
        factor: f64,
    },
    Singular,
    /// the Jacobian at the state has a NaN or ∞
    JacobianNotFinite,
}

/// State of one RADAU5 integration besides the solution itself.
#[derive(Debug, Clone)]
pub struct Radau5 {
    n: usize,
    jac: Vec<f64>,
    e1: Lu,
    e2: LuComplex,
    /// stage increments Z_i = Y_i − x, and their transforms W = T⁻¹Z
    z: [Vec<f64>; 3],
    w: [Vec<f64>; 3],
    /// the last step's collocation polynomial (divided differences), for starting values
    cont: [Vec<f64>; 3],
    /// f at the accepted state
    pub fx: Vec<f64>,
    inv_weight: Vec<f64>,
    tmp: Vec<f64>,
    tmp2: Vec<f64>,
    fp: Vec<f64>,
    /// the Jacobian was evaluated at the current state
    jac_here: bool,
    /// a new Jacobian is wanted before the next factorisation
    need_jac: bool,
    /// step size of the current factorisations (NaN: none)
    lu_h: f64,
    faccon: f64,
    theta: f64,
    first: bool,
    h_old: f64,
    pub work: ImplicitWork,
}

impl Radau5 {
    pub fn new(n: usize) -> Self {
        let v = || vec![0.0; n];
        Self {
            n,
            jac: vec![0.0; n * n],
            e1: Lu::new(n),
            e2: LuComplex::new(n),
            z: std::array::from_fn(|_| v()),
            w: std::array::from_fn(|_| v()),
            cont: std::array::from_fn(|_| v()),
            fx: v(),
            inv_weight: v(),
            tmp: v(),
            tmp2: v(),
            fp: v(),
            jac_here: false,
            need_jac: true,
            lu_h: f64::NAN,
            faccon: 1.0,
            theta: THET,
            first: true,
            h_old: 0.0,
            work: ImplicitWork::default(),
        }
    }

    /// Starts from (t, x): f there, and a Jacobian before the first factorisation.
    pub fn start<S: System + ?Sized>(&mut self, sys: &S, t: f64, x: &[f64]) {
        sys.rhs(t, x, &mut self.fx);
        self.jac_here = false;
        self.need_jac = true;
        self.lu_h = f64::NAN;
        self.first = true;
    }

    fn factor(&mut self, h: f64) -> Result<(), Singular> {
        let n = self.n;
        let (fac1, alphn, betan) = (U1 / h, ALPHA / h, BETA / h);
        for (k, &j) in self.jac.iter().enumerate() {
            self.e1.m[k] = -j;
            self.e2.re[k] = -j;
            self.e2.im[k] = 0.0;
        }
        for i in 0..n {
            self.e1.m[i * n + i] += fac1;
            self.e2.re[i * n + i] += alphn;
            self.e2.im[i * n + i] = betan;
        }
        self.work.lu_decomps += 1;
        self.lu_h = f64::NAN;
        self.e1.factor()?;
        self.e2.factor()?;
        self.lu_h = h;
        Ok(())
    }

    /// Tries a step of h from (t, x) into `x_new`. `rejected_before`: the last attempt from
    /// this state was rejected (ESTRAD then filters its estimate once more).
    #[allow(clippy::too_many_arguments)]
    pub fn attempt<S: System + ?Sized>(
        &mut self,
        sys: &S,
        t: f64,
        x: &[f64],
        h: f64,
        tol: RadauTol,
        rejected_before: bool,
        x_new: &mut [f64],
    ) -> Attempt {
        let n = self.n;
        if self.need_jac && !self.jac_here {
            self.tmp.copy_from_slice(x);
            jacobian_at(sys, t, &mut self.tmp, &self.fx, &mut self.fp, &mut self.jac);
            self.work.jac_evals += 1;
            self.jac_here = true;
            self.lu_h = f64::NAN;
            if !self.jac.iter().all(|v| v.is_finite()) {
                return Attempt::JacobianNotFinite;
            }
        }
        self.need_jac = false;
        if self.lu_h != h && self.factor(h).is_err() {
            return Attempt::Singular;
        }
        // the reciprocal weights: the Newton and error norms multiply
        for i in 0..n {
            self.inv_weight[i] = 1.0 / (tol.atol + tol.rtol * x[i].abs());
        }
        // starting values: zero, or the last collocation polynomial extrapolated
        if self.first {
            for k in 0..3 {
                self.z[k].fill(0.0);
                self.w[k].fill(0.0);
            }
        } else {
            let c3q = h / self.h_old;
            let cq = [C1 * c3q, C2 * c3q, c3q];
            for i in 0..n {
                let (a1, a2, a3) = (self.cont[0][i], self.cont[1][i], self.cont[2][i]);
                for k in 0..3 {
                    self.z[k][i] = cq[k] * (a1 + (cq[k] - C2M1) * (a2 + (cq[k] - C1M1) * a3));
                }
                for k in 0..3 {
                    self.w[k][i] =
                        TI[k][0] * self.z[0][i] + TI[k][1] * self.z[1][i] + TI[k][2] * self.z[2][i];
                }
            }
        }
        // simplified Newton
        let (fac1, alphn, betan) = (U1 / h, ALPHA / h, BETA / h);
        self.faccon = self.faccon.max(f64::EPSILON).powf(0.8);
        self.theta = THET;
        let (mut dynold, mut thqold) = (0.0f64, 0.0f64);
        let mut newt = 0;
        let c = [C1, C2, 1.0];
        loop {
            if newt >= NIT {
                self.need_jac = true;
                return Attempt::Retry { factor: 0.5 };
            }
            // F(x + Z_k) into z_k, then T⁻¹F
            let mut finite = true;
            for k in 0..3 {
                for i in 0..n {
                    self.tmp[i] = x[i] + self.z[k][i];
                }
                sys.rhs(t + c[k] * h, &self.tmp, &mut self.z[k]);
                finite &= self.z[k].iter().all(|v| v.is_finite());
            }
            if !finite {
                self.need_jac = true;
                return Attempt::Retry { factor: 0.5 };
            }
            for i in 0..n {
                let (a1, a2, a3) = (self.z[0][i], self.z[1][i], self.z[2][i]);
                let t1 = TI[0][0] * a1 + TI[0][1] * a2 + TI[0][2] * a3;
                let t2 = TI[1][0] * a1 + TI[1][1] * a2 + TI[1][2] * a3;
                let t3 = TI[2][0] * a1 + TI[2][1] * a2 + TI[2][2] * a3;
                // the right-hand sides of the two systems (SLVRAD)
                let (s2, s3) = (-self.w[1][i], -self.w[2][i]);
                self.z[0][i] = t1 - self.w[0][i] * fac1;
                self.z[1][i] = t2 + s2 * alphn - s3 * betan;
                self.z[2][i] = t3 + s3 * alphn + s2 * betan;
            }
            self.e1.solve(&mut self.z[0]);
            {
                let (a, b) = self.z.split_at_mut(2);
                self.e2.solve(&mut a[1], &mut b[0]);
            }
            newt += 1;
            let mut dyno = 0.0;
            for i in 0..n {
                let s = self.inv_weight[i];
                dyno += (self.z[0][i] * s).powi(2)
                    + (self.z[1][i] * s).powi(2)
                    + (self.z[2][i] * s).powi(2);
            }
            let dyno = (dyno / (3 * n) as f64).sqrt();
            if !dyno.is_finite() {
                self.need_jac = true;
                return Attempt::Retry { factor: 0.5 };
            }
            if newt > 1 && newt < NIT {
                let thq = dyno / dynold;
                self.theta = if newt == 2 {
                    thq
                } else {
                    (thq * thqold).sqrt()
                };
                thqold = thq;
                if self.theta < 0.99 {
                    self.faccon = self.theta / (1.0 - self.theta);
                    let left = (NIT - 1 - newt) as i32;
                    let dyth = self.faccon * dyno * self.theta.powi(left) / tol.fnewt;
                    if dyth >= 1.0 {
                        let qnewt = dyth.clamp(1e-4, 20.0);
                        self.need_jac = true;
                        return Attempt::Retry {
                            factor: 0.8 * qnewt.powf(-1.0 / (4.0 + left as f64)),
                        };
                    }
                } else {
                    self.need_jac = true;
                    return Attempt::Retry { factor: 0.5 };
                }
            }
            dynold = dyno.max(f64::EPSILON);
            for i in 0..n {
                let w1 = self.w[0][i] + self.z[0][i];
                let w2 = self.w[1][i] + self.z[1][i];
                let w3 = self.w[2][i] + self.z[2][i];
                self.w[0][i] = w1;
                self.w[1][i] = w2;
                self.w[2][i] = w3;
                self.z[0][i] = T[0][0] * w1 + T[0][1] * w2 + T[0][2] * w3;
                self.z[1][i] = T[1][0] * w1 + T[1][1] * w2 + T[1][2] * w3;
                self.z[2][i] = T[2][0] * w1 + w2;
            }
            if self.faccon * dyno <= tol.fnewt {
                break;
            }
        }
        let err = self.estimate(sys, t, x, h, rejected_before);
        for i in 0..n {
            x_new[i] = x[i] + self.z[2][i];
        }
        Attempt::Converged {
            err,
            newton_iterations: newt,
        }
    }

    /// ESTRAD: err = ‖E₁⁻¹(f(x) + (dd·Z)/h)‖; on the first step or after a rejection, once
    /// more through f at x + that estimate, which filters out its stiff components.
    fn estimate<S: System + ?Sized>(
        &mut self,
        sys: &S,
        t: f64,
        x: &[f64],
        h: f64,
        rejected_before: bool,
    ) -> f64 {
        let n = self.n;
        let (hee1, hee2, hee3) = (DD1 / h, DD2 / h, DD3 / h);
        for i in 0..n {
            self.tmp2[i] = hee1 * self.z[0][i] + hee2 * self.z[1][i] + hee3 * self.z[2][i];
            self.tmp[i] = self.tmp2[i] + self.fx[i];
        }
        self.e1.solve(&mut self.tmp);
        let norm = |v: &[f64], inv_weight: &[f64]| {
            let s: f64 = v.iter().zip(inv_weight).map(|(e, s)| (e * s).powi(2)).sum();
            (s / n as f64).sqrt().max(1e-10)
        };
        let mut err = norm(&self.tmp, &self.inv_weight);
        if err >= 1.0 && (self.first || rejected_before) {
            for i in 0..n {
                self.tmp[i] += x[i];
            }
            sys.rhs(t, &self.tmp, &mut self.fp);
            for i in 0..n {
                self.tmp[i] = self.fp[i] + self.tmp2[i];
            }
            self.e1.solve(&mut self.tmp);
            err = norm(&self.tmp, &self.inv_weight);
        }
        // NaN (a non-finite f at the filtered point) rejects
        if err.is_nan() { f64::INFINITY } else { err }
    }

    /// The step of h ending at (t_new, x_new) was accepted: keeps its collocation polynomial,
    /// evaluates f at the new state and decides whether the Jacobian is kept (θ ≤ THET).
    pub fn accept<S: System + ?Sized>(&mut self, sys: &S, t_new: f64, x_new: &[f64], h: f64) {
        let n = self.n;
        for i in 0..n {
            let (z1, z2, z3) = (self.z[0][i], self.z[1][i], self.z[2][i]);
            self.cont[0][i] = (z2 - z3) / C2M1;
            let ak = (z1 - z2) / C1MC2;
            let acont3 = (ak - z1 / C1) / C2;
            self.cont[1][i] = (ak - self.cont[0][i]) / C1M1;
            self.cont[2][i] = self.cont[1][i] - acont3;
        }
        self.first = false;
        self.h_old = h;
        sys.rhs(t_new, x_new, &mut self.fx);
        self.jac_here = false;
        self.need_jac = self.theta > THET;
    }

    /// A rejected step: the next attempt wants a Jacobian at this state (RADAU5 re-evaluates
    /// it unless it already is from here).
    pub fn reject(&mut self) {
        self.need_jac = true;
    }

    pub fn is_first(&self) -> bool {
        self.first
    }
}

/// RADAU5's collocation step with a fixed h (the order tests, slides with an h slider): a
/// fresh Jacobian at each step, Newton from zero to a tight tolerance.
#[derive(Debug, Clone)]
pub struct FixedRadau5 {
    core: Radau5,
    x_new: Vec<f64>,
}

impl FixedRadau5 {
    pub fn new(n: usize) -> Self {
        Self {
            core: Radau5::new(n),
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
        self.core.start(sys, t, x);
        let tol = RadauTol::from_user(1e-13, 1e-13);
        match self.core.attempt(sys, t, x, h, tol, false, &mut self.x_new) {
            Attempt::Converged { .. } => {
                x.copy_from_slice(&self.x_new);
                Ok(())
            }
            Attempt::Retry { .. } => Err("Newton iteration did not converge"),
            Attempt::Singular => Err("the Newton matrix is singular"),
            Attempt::JacobianNotFinite => Err("the Jacobian has NaN or ∞"),
        }
    }
}

/// R(z) of Radau IIA with 3 stages: the (2, 3) Padé approximation of e^z (Hairer & Wanner
/// II, IV.5, Table 5.13), (1 + 2z/5 + z²/20) / (1 − 3z/5 + 3z²/20 − z³/60).
pub fn stability(z: Complex) -> Complex {
    let z2 = cmul(z, z);
    let z3 = cmul(z2, z);
    let num = (1.0 + 0.4 * z.0 + z2.0 / 20.0, 0.4 * z.1 + z2.1 / 20.0);
    let den = (
        1.0 - 0.6 * z.0 + 0.15 * z2.0 - z3.0 / 60.0,
        -0.6 * z.1 + 0.15 * z2.1 - z3.1 / 60.0,
    );
    cdiv(num, den)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// T⁻¹ is T's inverse, and T⁻¹ A⁻¹ T is block diagonal with u₁ and α ± iβ (A: Radau IIA).
    #[test]
    fn transformation_diagonalises_the_inverse_of_a() {
        let s6 = 6f64.sqrt();
        let a = [
            [
                (88.0 - 7.0 * s6) / 360.0,
                (296.0 - 169.0 * s6) / 1800.0,
                (-2.0 + 3.0 * s6) / 225.0,
            ],
            [
                (296.0 + 169.0 * s6) / 1800.0,
                (88.0 + 7.0 * s6) / 360.0,
                (-2.0 - 3.0 * s6) / 225.0,
            ],
            [(16.0 - s6) / 36.0, (16.0 + s6) / 36.0, 1.0 / 9.0],
        ];
        let mul = |x: &[[f64; 3]; 3], y: &[[f64; 3]; 3]| {
            let mut r = [[0.0; 3]; 3];
            for i in 0..3 {
                for j in 0..3 {
                    for k in 0..3 {
                        r[i][j] += x[i][k] * y[k][j];
                    }
                }
            }
            r
        };
        let id = mul(&TI, &T);
        for i in 0..3 {
            for j in 0..3 {
                let e = if i == j { 1.0 } else { 0.0 };
                assert!((id[i][j] - e).abs() < 1e-14, "{id:?}");
            }
        }
        // T⁻¹A⁻¹T = Λ  ⇔  A T Λ = T
        let lambda = [[U1, 0.0, 0.0], [0.0, ALPHA, -BETA], [0.0, BETA, ALPHA]];
        let atl = mul(&a, &mul(&T, &lambda));
        for i in 0..3 {
            for j in 0..3 {
                assert!((atl[i][j] - T[i][j]).abs() < 1e-14, "{atl:?}");
            }
        }
        assert!((C1 - (4.0 - s6) / 10.0).abs() < 1e-16 && (C2 - (4.0 + s6) / 10.0).abs() < 1e-16);
    }
}
