//! The five cases of the stiff benchmark, each with its right-hand side and its exact Jacobian
//! written by hand (the same functions are handed to every solver), its tolerance ratio and the
//! reference final state it is measured against.

/// One benchmark case. All five systems are autonomous (∂f/∂t = 0).
pub struct Case {
    /// file-name stem of the plots
    pub key: &'static str,
    pub title: &'static str,
    pub t_end: f64,
    pub y0: &'static [f64],
    /// atol = this · rtol
    pub atol_over_rtol: f64,
    /// the reference y(t_end) and where it comes from
    pub reference: Vec<f64>,
    pub reference_source: &'static str,
    pub f: fn(&[f64], &mut [f64]),
    /// ∂f/∂y, row-major
    pub jac: fn(&[f64], &mut [f64]),
}

impl Case {
    pub fn dim(&self) -> usize {
        self.y0.len()
    }

    /// The error of a final state: the largest relative error over the components (the measure
    /// of `scripts/scipy_stiff_reference.py`); ∞ for a failed run.
    pub fn error(&self, y: Option<&[f64]>) -> f64 {
        let Some(y) = y else {
            return f64::INFINITY;
        };
        let mut e: f64 = 0.0;
        for (a, r) in y.iter().zip(&self.reference) {
            let d = ((a - r) / r).abs();
            if !d.is_finite() {
                return f64::INFINITY;
            }
            e = e.max(d);
        }
        e
    }
}

const MU: f64 = 1000.0;

fn vdp(y: &[f64], f: &mut [f64]) {
    f[0] = y[1];
    f[1] = MU * (1.0 - y[0] * y[0]) * y[1] - y[0];
}

fn vdp_jac(y: &[f64], j: &mut [f64]) {
    j[0] = 0.0;
    j[1] = 1.0;
    j[2] = -2.0 * MU * y[0] * y[1] - 1.0;
    j[3] = MU * (1.0 - y[0] * y[0]);
}

const K1: f64 = 0.04;
const K2: f64 = 3e7;
const K3: f64 = 1e4;

fn rober(y: &[f64], f: &mut [f64]) {
    f[0] = -K1 * y[0] + K3 * y[1] * y[2];
    f[1] = K1 * y[0] - K3 * y[1] * y[2] - K2 * y[1] * y[1];
    f[2] = K2 * y[1] * y[1];
}

fn rober_jac(y: &[f64], j: &mut [f64]) {
    j.copy_from_slice(&[
        -K1,
        K3 * y[2],
        K3 * y[1],
        K1,
        -K3 * y[2] - 2.0 * K2 * y[1],
        -K3 * y[1],
        0.0,
        2.0 * K2 * y[1],
        0.0,
    ]);
}

fn hires(y: &[f64], f: &mut [f64]) {
    f[0] = -1.71 * y[0] + 0.43 * y[1] + 8.32 * y[2] + 0.0007;
    f[1] = 1.71 * y[0] - 8.75 * y[1];
    f[2] = -10.03 * y[2] + 0.43 * y[3] + 0.035 * y[4];
    f[3] = 8.32 * y[1] + 1.71 * y[2] - 1.12 * y[3];
    f[4] = -1.745 * y[4] + 0.43 * y[5] + 0.43 * y[6];
    f[5] = -280.0 * y[5] * y[7] + 0.69 * y[3] + 1.71 * y[4] - 0.43 * y[5] + 0.69 * y[6];
    f[6] = 280.0 * y[5] * y[7] - 1.81 * y[6];
    f[7] = -280.0 * y[5] * y[7] + 1.81 * y[6];
}

fn hires_jac(y: &[f64], j: &mut [f64]) {
    j.fill(0.0);
    let mut set = |r: usize, c: usize, v: f64| j[r * 8 + c] = v;
    set(0, 0, -1.71);
    set(0, 1, 0.43);
    set(0, 2, 8.32);
    set(1, 0, 1.71);
    set(1, 1, -8.75);
    set(2, 2, -10.03);
    set(2, 3, 0.43);
    set(2, 4, 0.035);
    set(3, 1, 8.32);
    set(3, 2, 1.71);
    set(3, 3, -1.12);
    set(4, 4, -1.745);
    set(4, 5, 0.43);
    set(4, 6, 0.43);
    set(5, 3, 0.69);
    set(5, 4, 1.71);
    set(5, 5, -280.0 * y[7] - 0.43);
    set(5, 6, 0.69);
    set(5, 7, -280.0 * y[5]);
    set(6, 5, 280.0 * y[7]);
    set(6, 6, -1.81);
    set(6, 7, 280.0 * y[5]);
    set(7, 5, -280.0 * y[7]);
    set(7, 6, 1.81);
    set(7, 7, -280.0 * y[5]);
}

fn orego(y: &[f64], f: &mut [f64]) {
    f[0] = 77.27 * (y[1] + y[0] * (1.0 - 8.375e-6 * y[0] - y[1]));
    f[1] = (y[2] - (1.0 + y[0]) * y[1]) / 77.27;
    f[2] = 0.161 * (y[0] - y[2]);
}

fn orego_jac(y: &[f64], j: &mut [f64]) {
    j.copy_from_slice(&[
        77.27 * (1.0 - 2.0 * 8.375e-6 * y[0] - y[1]),
        77.27 * (1.0 - y[0]),
        0.0,
        -y[1] / 77.27,
        -(1.0 + y[0]) / 77.27,
        1.0 / 77.27,
        0.161,
        0.0,
        -0.161,
    ]);
}

/// Robertson at t = 1e5 has no test-set reference: scipy's Radau at rtol 1e-13, committed in
/// `tests/data/stiff_reference.json` (cross-checked against LSODA at 1e-12 there).
fn robertson_1e5_reference(json: &serde_json::Value) -> Vec<f64> {
    json["problems"]["robertson-1e5"]["reference"]
        .as_array()
        .expect("robertson-1e5 reference")
        .iter()
        .map(|v| v.as_f64().expect("a number"))
        .collect()
}

pub fn cases(json: &serde_json::Value) -> Vec<Case> {
    vec![
        Case {
            key: "robertson-1e5",
            title: "Robertson, t ∈ [0, 1e5], atol = 1e-8·rtol",
            t_end: 1e5,
            y0: &[1.0, 0.0, 0.0],
            atol_over_rtol: 1e-8,
            reference: robertson_1e5_reference(json),
            reference_source: "scipy Radau at rtol 1e-13 (tests/data/stiff_reference.json; the test set has none at 1e5)",
            f: rober,
            jac: rober_jac,
        },
        Case {
            key: "robertson-1e11",
            title: "Robertson, t ∈ [0, 1e11], atol = 1e-10·rtol",
            t_end: 1e11,
            y0: &[1.0, 0.0, 0.0],
            atol_over_rtol: 1e-10,
            reference: vec![
                2.083340149701255e-8,
                8.333360770334713e-14,
                0.9999999791665050,
            ],
            reference_source: "Test Set for IVP Solvers (Bari), ROBER",
            f: rober,
            jac: rober_jac,
        },
        Case {
            key: "vanderpol-1000",
            title: "Van der Pol μ = 1000, t ∈ [0, 2000], atol = rtol",
            t_end: 2000.0,
            y0: &[2.0, 0.0],
            atol_over_rtol: 1.0,
            reference: vec![1.706167732170469, -8.928097010248125e-4],
            reference_source: "Test Set for IVP Solvers (Bari), VDPOL",
            f: vdp,
            jac: vdp_jac,
        },
        Case {
            key: "hires",
            title: "HIRES, t ∈ [0, 321.8122], atol = rtol",
            t_end: 321.8122,
            y0: &[1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0057],
            atol_over_rtol: 1.0,
            reference: vec![
                0.7371312573325668e-3,
                0.1442485726316185e-3,
                0.5888729740967575e-4,
                0.1175651343283149e-2,
                0.2386356198831331e-2,
                0.6238968252742796e-2,
                0.2849998395185769e-2,
                0.2850001604814231e-2,
            ],
            reference_source: "Test Set for IVP Solvers (Bari), HIRES",
            f: hires,
            jac: hires_jac,
        },
        Case {
            key: "orego",
            title: "OREGO, t ∈ [0, 360], atol = rtol",
            t_end: 360.0,
            y0: &[1.0, 2.0, 3.0],
            atol_over_rtol: 1.0,
            reference: vec![
                0.1000814870318523e1,
                0.1228178521549917e4,
                0.1320554942846706e3,
            ],
            reference_source: "Test Set for IVP Solvers (Bari), OREGO",
            f: orego,
            jac: orego_jac,
        },
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each hand-written Jacobian against central differences of its right-hand side (exact
    /// up to rounding for these polynomials of degree ≤ 2, Van der Pol's cubic term aside).
    /// Run with `cargo test --release problems::` here: the other tests this crate compiles
    /// are lectern's own (by `#[path]`) and look for its files beside this manifest.
    #[test]
    fn jacobians_match_differences() {
        let json =
            serde_json::json!({"problems": {"robertson-1e5": {"reference": [1.0, 1.0, 1.0]}}});
        for c in cases(&json) {
            let n = c.dim();
            let y: Vec<f64> = (0..n).map(|i| 0.03 + 0.01 * i as f64).collect();
            let mut j = vec![0.0; n * n];
            (c.jac)(&y, &mut j);
            for col in 0..n {
                let h = 1e-4;
                let (mut yp, mut ym) = (y.clone(), y.clone());
                yp[col] += h;
                ym[col] -= h;
                let (mut fp, mut fm) = (vec![0.0; n], vec![0.0; n]);
                (c.f)(&yp, &mut fp);
                (c.f)(&ym, &mut fm);
                for row in 0..n {
                    let d = (fp[row] - fm[row]) / (2.0 * h);
                    let e = j[row * n + col];
                    assert!(
                        (d - e).abs() <= 1e-6 * (1.0 + e.abs()),
                        "{} J[{row}][{col}] = {e}, differences {d}",
                        c.key
                    );
                }
            }
        }
    }
}
