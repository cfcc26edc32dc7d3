//! Linear stability: the stability function R(z) of a method, with z = hλ for y' = λy.
//! One step multiplies y by R(z); the method is stable where |R(z)| ≤ 1.

use super::Tableau;

/// A complex number as (re, im): enough arithmetic for stability functions, no extra crate.
pub type Complex = (f64, f64);

pub(crate) fn cmul(a: Complex, b: Complex) -> Complex {
    (a.0 * b.0 - a.1 * b.1, a.0 * b.1 + a.1 * b.0)
}

pub(crate) fn cdiv(a: Complex, b: Complex) -> Complex {
    let d = b.0 * b.0 + b.1 * b.1;
    ((a.0 * b.0 + a.1 * b.1) / d, (a.1 * b.0 - a.0 * b.1) / d)
}

pub fn cabs(a: Complex) -> f64 {
    a.0.hypot(a.1)
}

impl Tableau {
    /// R(z) = 1 + z bᵀ (I − zA)⁻¹ 1. For an explicit tableau (I − zA) is unit lower
    /// triangular, so this is forward substitution and R is a polynomial of degree ≤ stages.
    /// A general (implicit) `a` is solved by Gaussian elimination.
    pub fn stability(&self, z: Complex) -> Complex {
        let s = self.stages();
        // m = I − zA, solve m g = 1
        let mut m: Vec<Complex> = vec![(0.0, 0.0); s * s];
        for i in 0..s {
            for j in 0..s {
                let za = (z.0 * self.a[i][j], z.1 * self.a[i][j]);
                let id = if i == j { 1.0 } else { 0.0 };
                m[i * s + j] = (id - za.0, -za.1);
            }
        }
        let mut g: Vec<Complex> = vec![(1.0, 0.0); s];
        // Gaussian elimination with partial pivoting
        for col in 0..s {
            let piv = (col..s)
                .max_by(|&p, &q| cabs(m[p * s + col]).total_cmp(&cabs(m[q * s + col])))
                .unwrap_or(col);
            if piv != col {
                for j in 0..s {
                    m.swap(col * s + j, piv * s + j);
                }
                g.swap(col, piv);
            }
            let d = m[col * s + col];
            for r in col + 1..s {
                let f = cdiv(m[r * s + col], d);
                if f == (0.0, 0.0) {
                    continue;
                }
                for j in col..s {
                    let p = cmul(f, m[col * s + j]);
                    m[r * s + j].0 -= p.0;
                    m[r * s + j].1 -= p.1;
                }
                let p = cmul(f, g[col]);
                g[r].0 -= p.0;
                g[r].1 -= p.1;
            }
        }
        for r in (0..s).rev() {
            let mut acc = g[r];
            for j in r + 1..s {
                let p = cmul(m[r * s + j], g[j]);
                acc.0 -= p.0;
                acc.1 -= p.1;
            }
            g[r] = cdiv(acc, m[r * s + r]);
        }
        let btg = self.b.iter().zip(&g).fold((0.0, 0.0), |acc, (&b, gi)| {
            (acc.0 + b * gi.0, acc.1 + b * gi.1)
        });
        let zb = cmul(z, btg);
        (1.0 + zb.0, zb.1)
    }

    /// Where the stability region meets the negative real axis: the most negative x with
    /// |R(y)| ≤ 1 for every y in [x, 0]. Euler −2, RK4 −2.7853.
    pub fn real_axis_limit(&self) -> f64 {
        real_axis_limit(|z| self.stability(z))
    }
}

/// The negative-real-axis stability limit of any stability function (see
/// [`Tableau::real_axis_limit`]); returns −∞ when the whole scanned range (to −1e4) is stable.
pub fn real_axis_limit(r: impl Fn(Complex) -> Complex) -> f64 {
    let stable = |x: f64| cabs(r((x, 0.0))) <= 1.0 + 1e-12;
    // march out in small steps to find the first unstable point, then bisect
    let dx = 1e-3;
    let mut x: f64 = 0.0;
    while x > -1e4 {
        let next = x - dx * (1.0 + x.abs() * 0.01);
        if !stable(next) {
            let (mut lo, mut hi) = (next, x);
            for _ in 0..100 {
                let mid = 0.5 * (lo + hi);
                if stable(mid) {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            return hi;
        }
        x = next;
    }
    f64::NEG_INFINITY
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rk4_stability_is_the_degree_four_taylor_polynomial() {
        let z = (-0.7, 1.3);
        let mut want = (1.0, 0.0);
        let mut term = (1.0, 0.0);
        for k in 1..=4 {
            term = cmul(term, z);
            want.0 += term.0 / (1..=k).product::<u32>() as f64;
            want.1 += term.1 / (1..=k).product::<u32>() as f64;
        }
        let got = Tableau::rk4().stability(z);
        assert!((got.0 - want.0).abs() < 1e-14 && (got.1 - want.1).abs() < 1e-14);
    }

    #[test]
    fn real_axis_limits() {
        assert!((Tableau::euler().real_axis_limit() + 2.0).abs() < 1e-9);
        assert!((Tableau::heun().real_axis_limit() + 2.0).abs() < 1e-9);
        assert!((Tableau::rk4().real_axis_limit() + 2.785293563).abs() < 1e-6);
    }

    #[test]
    fn implicit_tableau_gives_rational_function() {
        // implicit midpoint as a one-stage tableau: R = (1 + z/2) / (1 − z/2)
        let t = Tableau {
            name: "imp mid".into(),
            a: vec![vec![0.5]],
            b: vec![1.0],
            c: vec![0.5],
        };
        let z = (-3.0, 2.0);
        let want = cdiv((1.0 + z.0 / 2.0, z.1 / 2.0), (1.0 - z.0 / 2.0, -z.1 / 2.0));
        let got = t.stability(z);
        assert!((got.0 - want.0).abs() < 1e-14 && (got.1 - want.1).abs() < 1e-14);
    }
}
