//! Butcher tableaux of explicit Runge–Kutta methods.

use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::diag::Diagnostic;

/// An explicit Runge–Kutta method: `k_i = f(x + h Σ_j<i a_ij k_j, t + c_i h)`,
/// `x(t+h) = x + h Σ b_i k_i`. `a` is stored as full rows; entries on or above the diagonal
/// must be zero (explicit).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Tableau {
    pub name: String,
    pub a: Vec<Vec<f64>>,
    pub b: Vec<f64>,
    pub c: Vec<f64>,
}

impl Tableau {
    pub fn stages(&self) -> usize {
        self.b.len()
    }

    /// Forward Euler: one stage, order 1.
    pub fn euler() -> Self {
        Self {
            name: "Euler".into(),
            a: vec![vec![0.0]],
            b: vec![1.0],
            c: vec![0.0],
        }
    }

    /// The midpoint method, x + h f(x + h/2 f(x), t + h/2) (ERRATA 3): order 2.
    pub fn midpoint() -> Self {
        Self {
            name: "Midpoint".into(),
            a: vec![vec![0.0, 0.0], vec![0.5, 0.0]],
            b: vec![0.0, 1.0],
            c: vec![0.0, 0.5],
        }
    }

    /// Heun's method (explicit trapezoid): order 2.
    pub fn heun() -> Self {
        Self {
            name: "Heun".into(),
            a: vec![vec![0.0, 0.0], vec![1.0, 0.0]],
            b: vec![0.5, 0.5],
            c: vec![0.0, 1.0],
        }
    }

    /// Classical RK4 (ERRATA 1: the last stage samples at x + k3, t + h).
    pub fn rk4() -> Self {
        Self {
            name: "RK4".into(),
            a: vec![
                vec![0.0, 0.0, 0.0, 0.0],
                vec![0.5, 0.0, 0.0, 0.0],
                vec![0.0, 0.5, 0.0, 0.0],
                vec![0.0, 0.0, 1.0, 0.0],
            ],
            b: vec![1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0],
            c: vec![0.0, 0.5, 0.5, 1.0],
        }
    }
}

impl Tableau {
    /// Dormand–Prince 5(4): the six stages and fifth-order weights that propagate the solution
    /// (the seventh, FSAL stage only feeds the error estimate; see `pairs/dopri5.rs`).
    pub fn dopri5() -> Self {
        Self {
            name: "Dormand–Prince 5".into(),
            ..super::pairs::dopri5::DOPRI5.tableau()
        }
    }

    /// The notes' "RK4" with its typo (ERRATA 1): `k4 = h f(x0 + k3/2)`. The stage samples at
    /// t + h/2 so that c stays the row sum of a. Only first order; shipped to show the drop.
    pub fn rk4_typo() -> Self {
        Self {
            name: "RK4 as printed (typo)".into(),
            a: vec![
                vec![0.0, 0.0, 0.0, 0.0],
                vec![0.5, 0.0, 0.0, 0.0],
                vec![0.0, 0.5, 0.0, 0.0],
                vec![0.0, 0.0, 0.5, 0.0],
            ],
            b: vec![1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0],
            c: vec![0.0, 0.5, 0.5, 0.5],
        }
    }

    /// Ralston's second-order method (minimum error bound among 2-stage methods).
    pub fn ralston() -> Self {
        Self {
            name: "Ralston".into(),
            a: vec![vec![0.0, 0.0], vec![2.0 / 3.0, 0.0]],
            b: vec![0.25, 0.75],
            c: vec![0.0, 2.0 / 3.0],
        }
    }

    /// Reads and validates a tableau file (RON, fields `name, a, b, c`).
    pub fn load(path: impl AsRef<Path>) -> Result<Self, Diagnostic> {
        let path = path.as_ref();
        let text = crate::project_files::read_to_string(path)
            .map_err(|e| Diagnostic::whole_file(path, format!("cannot read tableau: {e}")))?;
        Self::parse(&text, path)
    }

    /// Parses and validates tableau text; `path` only names the file in errors, which point
    /// at the value at fault (`a[3][3]`, `c`, …).
    pub fn parse(text: &str, path: impl AsRef<Path>) -> Result<Self, Diagnostic> {
        let path = path.as_ref();
        let tab: Tableau = ron::from_str(text).map_err(|e| Diagnostic::from_ron(path, &e))?;
        tab.validate_at().map_err(|(at, m)| {
            let tree = crate::ron_tree::parse(text).ok();
            Diagnostic::at_value(tree.as_ref(), text, path, &at, m)
        })?;
        Ok(tab)
    }

    /// Checks sizes, finiteness and explicitness (`a` strictly lower triangular).
    pub fn validate(&self) -> Result<(), String> {
        self.validate_at().map_err(|(_, m)| m)
    }

    /// Like [`validate`](Self::validate), with the path of the value at fault (`a[2][3]`,
    /// `b`, `c[1]`; 0-based like [`crate::ron_tree`] paths, 1-based in the message).
    pub fn validate_at(&self) -> Result<(), (String, String)> {
        let s = self.b.len();
        if s == 0 {
            return Err(("b".into(), "tableau has no stages (b is empty)".into()));
        }
        if self.c.len() != s {
            return Err((
                "c".into(),
                format!("c has {} entries but b has {s}", self.c.len()),
            ));
        }
        if self.a.len() != s {
            return Err((
                "a".into(),
                format!("a has {} rows but b has {s} entries", self.a.len()),
            ));
        }
        for (i, row) in self.a.iter().enumerate() {
            if row.len() != s {
                return Err((
                    format!("a[{i}]"),
                    format!("row {} of a has {} entries, expected {s}", i + 1, row.len()),
                ));
            }
            for (j, &v) in row.iter().enumerate() {
                if !v.is_finite() {
                    return Err((
                        format!("a[{i}][{j}]"),
                        format!("a[{}][{}] is not finite", i + 1, j + 1),
                    ));
                }
                if j >= i && v != 0.0 {
                    return Err((
                        format!("a[{i}][{j}]"),
                        format!(
                            "a[{}][{}] = {v} is on or above the diagonal: only explicit methods are supported",
                            i + 1,
                            j + 1
                        ),
                    ));
                }
            }
        }
        for (name, values) in [("b", &self.b), ("c", &self.c)] {
            if let Some(k) = values.iter().position(|v| !v.is_finite()) {
                return Err((
                    format!("{name}[{k}]"),
                    format!("{name}[{}] = {} is not finite", k + 1, values[k]),
                ));
            }
        }
        Ok(())
    }

    /// Residuals of the order conditions up to order 4, each with its name (for display; see
    /// [`Tableau::order`] for any order). A method has order p when every condition of order
    /// ≤ p holds (and c is the row sum of a).
    pub fn order_conditions(&self) -> Vec<OrderCondition> {
        let s = self.stages();
        let (a, b, c) = (&self.a, &self.b, &self.c);
        let ac: Vec<f64> = (0..s)
            .map(|i| (0..s).map(|j| a[i][j] * c[j]).sum())
            .collect();
        let ac2: Vec<f64> = (0..s)
            .map(|i| (0..s).map(|j| a[i][j] * c[j] * c[j]).sum())
            .collect();
        let aac: Vec<f64> = (0..s)
            .map(|i| (0..s).map(|j| a[i][j] * ac[j]).sum())
            .collect();
        let dot = |f: &dyn Fn(usize) -> f64| (0..s).map(|i| b[i] * f(i)).sum::<f64>();
        let mut out = Vec::new();
        let mut push = |order, name: &'static str, value: f64, target: f64| {
            out.push(OrderCondition {
                order,
                name,
                residual: value - target,
            })
        };
        push(1, "Σ b = 1", dot(&|_| 1.0), 1.0);
        push(2, "Σ b c = 1/2", dot(&|i| c[i]), 0.5);
        push(3, "Σ b c² = 1/3", dot(&|i| c[i] * c[i]), 1.0 / 3.0);
        push(3, "Σ b A c = 1/6", dot(&|i| ac[i]), 1.0 / 6.0);
        push(4, "Σ b c³ = 1/4", dot(&|i| c[i].powi(3)), 0.25);
        push(4, "Σ b c A c = 1/8", dot(&|i| c[i] * ac[i]), 0.125);
        push(4, "Σ b A c² = 1/12", dot(&|i| ac2[i]), 1.0 / 12.0);
        push(4, "Σ b A A c = 1/24", dot(&|i| aac[i]), 1.0 / 24.0);
        out
    }

    /// Whether `c_i = Σ_j a_ij` for every stage (assumed by the order conditions above).
    pub fn row_sums_consistent(&self) -> bool {
        self.a
            .iter()
            .zip(&self.c)
            .all(|(row, &c)| (row.iter().sum::<f64>() - c).abs() < 1e-12)
    }

    /// The highest order p ≤ 10 whose conditions (all rooted trees with up to p nodes, see
    /// [`super::trees`]) hold to 1e-12 relative to the size of their terms.
    pub fn order(&self) -> u32 {
        let residuals = super::trees::order_residuals(self, 10);
        residuals.iter().take_while(|&&r| r < 1e-12).count() as u32
    }
}

/// One order condition of a tableau and how far it is from holding.
#[derive(Debug, Clone, PartialEq)]
pub struct OrderCondition {
    pub order: u32,
    pub name: &'static str,
    pub residual: f64,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn orders_of_the_builtin_tableaux() {
        assert_eq!(Tableau::euler().order(), 1);
        assert_eq!(Tableau::midpoint().order(), 2);
        assert_eq!(Tableau::heun().order(), 2);
        assert_eq!(Tableau::ralston().order(), 2);
        assert_eq!(Tableau::rk4().order(), 4);
        assert_eq!(Tableau::dopri5().order(), 5);
        assert!(Tableau::dopri5().row_sums_consistent());
        // the typo breaks Σ b c = 1/2: first order only
        assert_eq!(Tableau::rk4_typo().order(), 1);
        for t in [Tableau::rk4(), Tableau::rk4_typo(), Tableau::heun()] {
            assert!(t.row_sums_consistent());
            t.validate().unwrap();
        }
    }

    #[test]
    fn implicit_and_misshapen_tableaux_are_rejected() {
        let mut t = Tableau::heun();
        t.a[0][0] = 0.5;
        assert!(t.validate().unwrap_err().contains("explicit"));
        let mut t = Tableau::heun();
        t.c.pop();
        assert!(t.validate().is_err());
    }

    #[test]
    fn errors_in_a_file_point_at_the_value() {
        let text = "(\n  name: \"x\",\n  a: [[0.0, 0.0],\n      [1.0, 0.5]],\n  b: [0.5, 0.5],\n  c: [0.0, NaN],\n)";
        let d = Tableau::parse(text, "t.ron").unwrap_err();
        assert_eq!((d.line, d.col), (4, 13), "{d}");
        assert!(d.message.contains("a[2][2]"), "{d}");
        let d = Tableau::parse(&text.replace("0.5]],", "0.0]],"), "t.ron").unwrap_err();
        assert_eq!(
            (d.line, d.col, d.message.as_str()),
            (6, 12, "c[2] = NaN is not finite")
        );
        let d = Tableau::parse(&text.replace("[0.0, NaN]", "[0.0]"), "t.ron").unwrap_err();
        assert_eq!((d.line, d.col), (6, 6), "{d}");
        let d = Tableau::parse(
            "(name: \"x\", a: [[0.0]], b: [1.0], c: [0.0, 1.0])",
            "t.ron",
        )
        .unwrap_err();
        assert!(d.message.contains("c has 2"), "{d}");
        let d = Tableau::parse("(name: \"x\",\n a: [[0.0]] b: [1.0])", "t.ron").unwrap_err();
        assert_eq!(d.line, 2, "{d}");
    }
}
