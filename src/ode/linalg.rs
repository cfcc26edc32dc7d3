//! Dense LU with partial pivoting, real and complex, for the Newton matrices of the implicit
//! methods (I − θhJ, I/(γh) − J, RADAU5's (α + iβ)/h·I − J). Row-major, factored in place,
//! allocation-free after construction.
//!
//! Dense is the right choice for the systems a lecture meets (n up to a few dozen: one LU is
//! n³/3 multiply-adds, 3·10⁵ at n = 100); beyond n ≈ 200 a factorisation costs milliseconds and
//! a banded or sparse solver would be the tool, which lectern does not have.

/// The matrix had a zero (or non-finite) pivot: it is singular to working precision.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Singular;

/// A real n×n LU factorisation, PA = LU, stored in place.
#[derive(Debug, Clone)]
pub struct Lu {
    n: usize,
    /// row-major: the matrix to factor, then L (unit diagonal, below) and U (on and above)
    pub m: Vec<f64>,
    piv: Vec<usize>,
    /// 1/U_kk: a solve multiplies (the Newton iterations solve many times per factorisation)
    inv_diag: Vec<f64>,
}

impl Lu {
    pub fn new(n: usize) -> Self {
        Self {
            n,
            m: vec![0.0; n * n],
            piv: vec![0; n],
            inv_diag: vec![0.0; n],
        }
    }

    /// Factors `self.m` in place.
    pub fn factor(&mut self) -> Result<(), Singular> {
        let (n, m) = (self.n, &mut self.m);
        for k in 0..n {
            let mut p = k;
            for i in k + 1..n {
                if m[i * n + k].abs() > m[p * n + k].abs() {
                    p = i;
                }
            }
            self.piv[k] = p;
            let d = m[p * n + k];
            if d == 0.0 || !d.is_finite() {
                return Err(Singular);
            }
            if p != k {
                for j in 0..n {
                    m.swap(k * n + j, p * n + j);
                }
            }
            self.inv_diag[k] = 1.0 / d;
            for i in k + 1..n {
                let f = m[i * n + k] / d;
                m[i * n + k] = f;
                if f != 0.0 {
                    for j in k + 1..n {
                        m[i * n + j] -= f * m[k * n + j];
                    }
                }
            }
        }
        Ok(())
    }

    /// Solves A x = r in place (r becomes x) with the factors of A.
    pub fn solve(&self, r: &mut [f64]) {
        let (n, m) = (self.n, &self.m);
        for k in 0..n {
            r.swap(k, self.piv[k]);
        }
        // rows as slices, zipped: no bounds checks in the inner loops (the Newton iterations
        // and Rosenbrock's stages spend most of their time here)
        for i in 0..n {
            let (done, rest) = r.split_at_mut(i);
            let mut acc = rest[0];
            for (l, x) in m[i * n..i * n + i].iter().zip(done.iter()) {
                acc -= l * x;
            }
            rest[0] = acc;
        }
        for i in (0..n).rev() {
            let (head, done) = r.split_at_mut(i + 1);
            let mut acc = head[i];
            for (u, x) in m[i * n + i + 1..(i + 1) * n].iter().zip(done.iter()) {
                acc -= u * x;
            }
            head[i] = acc * self.inv_diag[i];
        }
    }
}

/// A complex n×n LU factorisation with real and imaginary parts in separate arrays (RADAU5's
/// DECC/SOLC layout).
#[derive(Debug, Clone)]
pub struct LuComplex {
    n: usize,
    pub re: Vec<f64>,
    pub im: Vec<f64>,
    piv: Vec<usize>,
    /// 1/U_kk (real and imaginary parts), as [`Lu`]'s
    inv_diag: Vec<(f64, f64)>,
}

impl LuComplex {
    pub fn new(n: usize) -> Self {
        Self {
            n,
            re: vec![0.0; n * n],
            im: vec![0.0; n * n],
            piv: vec![0; n],
            inv_diag: vec![(0.0, 0.0); n],
        }
    }

    pub fn factor(&mut self) -> Result<(), Singular> {
        let n = self.n;
        let (re, im) = (&mut self.re, &mut self.im);
        for k in 0..n {
            // pivot on |re| + |im| (as DECC), cheaper than the modulus and as good
            let size = |i: usize| re[i * n + k].abs() + im[i * n + k].abs();
            let mut p = k;
            for i in k + 1..n {
                if size(i) > size(p) {
                    p = i;
                }
            }
            self.piv[k] = p;
            let (dr, di) = (re[p * n + k], im[p * n + k]);
            let den = dr * dr + di * di;
            if den == 0.0 || !den.is_finite() {
                return Err(Singular);
            }
            if p != k {
                for j in 0..n {
                    re.swap(k * n + j, p * n + j);
                    im.swap(k * n + j, p * n + j);
                }
            }
            // 1/d
            let (ir, ii) = (dr / den, -di / den);
            self.inv_diag[k] = (ir, ii);
            for i in k + 1..n {
                let (ar, ai) = (re[i * n + k], im[i * n + k]);
                let (fr, fi) = (ar * ir - ai * ii, ar * ii + ai * ir);
                re[i * n + k] = fr;
                im[i * n + k] = fi;
                if fr != 0.0 || fi != 0.0 {
                    for j in k + 1..n {
                        let (br, bi) = (re[k * n + j], im[k * n + j]);
                        re[i * n + j] -= fr * br - fi * bi;
                        im[i * n + j] -= fr * bi + fi * br;
                    }
                }
            }
        }
        Ok(())
    }

    /// Solves A x = r in place, r = (r_re + i r_im).
    pub fn solve(&self, r_re: &mut [f64], r_im: &mut [f64]) {
        let n = self.n;
        let (re, im) = (&self.re, &self.im);
        for k in 0..n {
            r_re.swap(k, self.piv[k]);
            r_im.swap(k, self.piv[k]);
        }
        // as `Lu::solve`: rows as slices, zipped (no bounds checks)
        for i in 0..n {
            let (mut ar, mut ai) = (r_re[i], r_im[i]);
            let row = i * n..i * n + i;
            for (((lr, li), xr), xi) in re[row.clone()]
                .iter()
                .zip(&im[row])
                .zip(&r_re[..i])
                .zip(&r_im[..i])
            {
                ar -= lr * xr - li * xi;
                ai -= lr * xi + li * xr;
            }
            r_re[i] = ar;
            r_im[i] = ai;
        }
        for i in (0..n).rev() {
            let (mut ar, mut ai) = (r_re[i], r_im[i]);
            let row = i * n + i + 1..(i + 1) * n;
            for (((ur, ui), xr), xi) in re[row.clone()]
                .iter()
                .zip(&im[row])
                .zip(&r_re[i + 1..])
                .zip(&r_im[i + 1..])
            {
                ar -= ur * xr - ui * xi;
                ai -= ur * xi + ui * xr;
            }
            let (ir, ii) = self.inv_diag[i];
            r_re[i] = ar * ir - ai * ii;
            r_im[i] = ar * ii + ai * ir;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn real_lu_solves_a_pivoting_system() {
        let mut lu = Lu::new(3);
        // needs a row swap at the first column
        lu.m = vec![0.0, 2.0, 1.0, 1.0, 1.0, 0.0, 3.0, 0.0, 1.0];
        let a = lu.m.clone();
        lu.factor().unwrap();
        let x = [1.0, -2.0, 0.5];
        let mut r: Vec<f64> = (0..3)
            .map(|i| (0..3).map(|j| a[i * 3 + j] * x[j]).sum())
            .collect();
        lu.solve(&mut r);
        for i in 0..3 {
            assert!((r[i] - x[i]).abs() < 1e-15, "{r:?}");
        }
    }

    #[test]
    fn complex_lu_solves_against_complex_multiplication() {
        let n = 3;
        let mut lu = LuComplex::new(n);
        lu.re = vec![0.0, 1.0, 2.0, 1.0, -1.0, 0.5, 3.0, 0.0, 1.0];
        lu.im = vec![0.5, 0.0, -1.0, 0.0, 2.0, 0.0, 1.0, 1.0, 0.0];
        let (ar, ai) = (lu.re.clone(), lu.im.clone());
        lu.factor().unwrap();
        let (xr, xi) = ([1.0, -2.0, 0.5], [0.25, 1.0, -1.0]);
        let mut br = vec![0.0; n];
        let mut bi = vec![0.0; n];
        for i in 0..n {
            for j in 0..n {
                br[i] += ar[i * n + j] * xr[j] - ai[i * n + j] * xi[j];
                bi[i] += ar[i * n + j] * xi[j] + ai[i * n + j] * xr[j];
            }
        }
        lu.solve(&mut br, &mut bi);
        for i in 0..n {
            assert!((br[i] - xr[i]).abs() < 1e-14 && (bi[i] - xi[i]).abs() < 1e-14);
        }
    }

    #[test]
    fn a_singular_matrix_is_reported() {
        let mut lu = Lu::new(2);
        lu.m = vec![1.0, 2.0, 2.0, 4.0];
        assert_eq!(lu.factor(), Err(Singular));
        let mut lu = Lu::new(1);
        lu.m = vec![f64::NAN];
        assert_eq!(lu.factor(), Err(Singular));
    }
}
