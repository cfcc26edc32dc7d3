//! ODE problems written in RON, with right-hand sides (and optionally the exact solution) as
//! expressions of the variables, `t` and named parameters:
//!
//! ```ron
//! (
//!     name: "Harmonic oscillator",
//!     vars: ["x", "v"],
//!     rhs: ["v", "-w*w*x"],
//!     params: {"w": 1.0},
//!     initial: [1.0, 0.0],
//!     t0: 0.0,
//!     exact: Some(["cos(w*t)", "-w*sin(w*t)"]),
//! )
//! ```
//! Errors in an expression are reported at their line and column in the file.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::Deserialize;

use super::System;
use super::expr::{self, Program};
use crate::diag::Diagnostic;
use crate::ron_tree;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ProblemFile {
    name: String,
    vars: Vec<String>,
    rhs: Vec<String>,
    #[serde(default)]
    params: BTreeMap<String, f64>,
    initial: Vec<f64>,
    #[serde(default)]
    t0: f64,
    #[serde(default)]
    exact: Option<Vec<String>>,
}

/// A loaded problem: it is a [`System`] (the compiled right-hand side) with its initial value.
#[derive(Debug, Clone)]
pub struct Problem {
    pub name: String,
    pub path: PathBuf,
    pub vars: Vec<String>,
    pub rhs_src: Vec<String>,
    pub params: Vec<(String, f64)>,
    pub initial: Vec<f64>,
    pub t0: f64,
    pub exact_src: Option<Vec<String>>,
    rhs: Program,
    exact: Option<Program>,
}

impl Problem {
    pub fn load(path: impl AsRef<Path>) -> Result<Self, Diagnostic> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path)
            .map_err(|e| Diagnostic::whole_file(path, format!("cannot read problem: {e}")))?;
        Self::parse(&text, path)
    }

    /// Parses problem text; `path` names the file in errors.
    pub fn parse(text: &str, path: impl AsRef<Path>) -> Result<Self, Diagnostic> {
        let path = path.as_ref();
        if text.trim().is_empty() {
            return Err(Diagnostic::whole_file(path, "problem file is empty"));
        }
        let f: ProblemFile = ron::from_str(text).map_err(|e| Diagnostic::from_ron(path, &e))?;
        // Errors found past serde point at the value at fault, found again in the syntax tree.
        let tree = ron_tree::parse(text).ok();
        let at = |value: &str, m: String| Diagnostic::at_value(tree.as_ref(), text, path, value, m);
        let n = f.vars.len();
        if n == 0 {
            return Err(at(
                "vars",
                "`vars` is empty: a problem needs at least one variable".into(),
            ));
        }
        if f.rhs.len() != n {
            return Err(at(
                "rhs",
                format!(
                    "`rhs` has {} expressions but `vars` names {n} variables",
                    f.rhs.len()
                ),
            ));
        }
        if f.initial.len() != n {
            return Err(at(
                "initial",
                format!(
                    "`initial` has {} values but `vars` names {n} variables",
                    f.initial.len()
                ),
            ));
        }
        if let Some(ex) = &f.exact
            && ex.len() != n
        {
            return Err(at(
                "exact",
                format!(
                    "`exact` has {} expressions but `vars` names {n} variables",
                    ex.len()
                ),
            ));
        }
        // A bad name sits in `vars[i]` or is a key of `params`.
        let name_at = |i: usize, name: &str, m: String| {
            if i < n {
                return at(&format!("vars[{i}]"), m);
            }
            let key = tree
                .as_ref()
                .and_then(|t| t.field("params"))
                .and_then(|p| match &p.value {
                    ron_tree::Value::Map(entries) => entries
                        .iter()
                        .find(|(k, _)| k.as_str() == Some(name))
                        .map(|(k, _)| k.span.start),
                    _ => None,
                });
            match key {
                Some(offset) => Diagnostic::at_offset(text, path, offset, m),
                None => at("params", m),
            }
        };
        let mut names: Vec<&str> = vec!["t"];
        for (i, name) in f.vars.iter().chain(f.params.keys()).enumerate() {
            let ok = name
                .chars()
                .next()
                .is_some_and(|c| c.is_alphabetic() || c == '_')
                && name.chars().all(|c| c.is_alphanumeric() || c == '_');
            if !ok {
                return Err(name_at(
                    i,
                    name,
                    format!("`{name}` is not a valid name (letters, digits, _)"),
                ));
            }
            if expr::is_reserved(name) {
                return Err(name_at(
                    i,
                    name,
                    format!(
                        "`{name}` names a function or constant and cannot be a variable or parameter"
                    ),
                ));
            }
            if names.contains(&name.as_str()) {
                return Err(name_at(
                    i,
                    name,
                    format!(
                        "the name `{name}` is used twice (variables, parameters and t share one namespace)"
                    ),
                ));
            }
            names.push(name);
        }
        if !f.t0.is_finite() {
            return Err(at("t0", format!("t0 = {} must be finite", f.t0)));
        }
        let params: Vec<(String, f64)> = f.params.into_iter().collect();
        let locate = |field: &str, i: usize, e: &expr::ExprError| {
            let message = format!("in {field}[{i}]: {}: `{}`", e.message, e.token);
            let node = tree.as_ref().and_then(|t| t.at(&format!("{field}[{i}]")));
            match node.and_then(|s| s.str_offset(text, e.offset)) {
                Some(offset) => Diagnostic::at_offset(text, path, offset, message),
                None => Diagnostic::whole_file(path, message),
            }
        };
        let rhs = expr::compile(&f.rhs, &f.vars, &params).map_err(|(i, e)| locate("rhs", i, &e))?;
        let exact = match &f.exact {
            Some(ex) => {
                Some(expr::compile(ex, &f.vars, &params).map_err(|(i, e)| locate("exact", i, &e))?)
            }
            None => None,
        };
        Ok(Problem {
            name: f.name,
            path: path.to_path_buf(),
            vars: f.vars,
            rhs_src: f.rhs,
            params,
            initial: f.initial,
            t0: f.t0,
            exact_src: f.exact,
            rhs,
            exact,
        })
    }

    /// The exact solution at time t, when the file gives one. Its expressions may use t and
    /// the parameters (the variables read the initial values).
    pub fn exact(&self, t: f64) -> Option<Vec<f64>> {
        let p = self.exact.as_ref()?;
        let mut out = vec![0.0; self.vars.len()];
        p.eval(t, &self.initial, &mut out);
        Some(out)
    }

    pub fn has_exact(&self) -> bool {
        self.exact.is_some()
    }

    /// Changes a parameter and recompiles (parameters are folded into the program).
    pub fn set_param(&mut self, name: &str, value: f64) -> Result<(), String> {
        let slot = self
            .params
            .iter_mut()
            .find(|(n, _)| n == name)
            .ok_or_else(|| format!("`{}` has no parameter `{name}`", self.name))?;
        slot.1 = value;
        // the sources compiled once already, so they compile again
        self.rhs = expr::compile(&self.rhs_src, &self.vars, &self.params)
            .map_err(|(_, e)| e.to_string())?;
        if let Some(src) = &self.exact_src {
            self.exact =
                Some(expr::compile(src, &self.vars, &self.params).map_err(|(_, e)| e.to_string())?);
        }
        Ok(())
    }

    /// The compiled right-hand side (for inspection and benchmarks).
    pub fn program(&self) -> &Program {
        &self.rhs
    }
}

impl System for Problem {
    fn dim(&self) -> usize {
        self.vars.len()
    }
    #[inline]
    fn rhs(&self, t: f64, x: &[f64], dxdt: &mut [f64]) {
        self.rhs.eval(t, x, dxdt)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const OSC: &str = r#"(
    name: "Harmonic oscillator",
    vars: ["x", "v"],
    rhs: ["v", "-w*w*x"],
    params: {"w": 2.0},
    initial: [1.0, 0.0],
    t0: 0.0,
    exact: Some(["cos(w*t)", "-w*sin(w*t)"]),
)"#;

    #[test]
    fn loads_and_evaluates() {
        let p = Problem::parse(OSC, "osc.ron").unwrap();
        let mut d = [0.0; 2];
        p.rhs(0.0, &[0.5, 3.0], &mut d);
        assert_eq!(d, [3.0, -2.0]);
        let e = p.exact(0.25).unwrap();
        assert_eq!(e, vec![(0.5f64).cos(), -2.0 * (0.5f64).sin()]);
    }

    #[test]
    fn expression_errors_have_file_line_column() {
        let bad = OSC.replace("\"-w*w*x\"", "\"-w*w*q\"");
        let d = Problem::parse(&bad, "osc.ron").unwrap_err();
        // line 4 is `    rhs: ["v", "-w*w*q"],`; `q` sits at column 22
        assert_eq!((d.line, d.col), (4, 22), "{d}");
        assert!(
            d.to_string()
                .starts_with("osc.ron:4:22: in rhs[1]: unknown name"),
            "{d}"
        );
        let bad = OSC.replace("\"-w*sin(w*t)\"", "\"-w*sin(w*t\"");
        let d = Problem::parse(&bad, "osc.ron").unwrap_err();
        assert_eq!((d.line, d.col), (8, 41), "{d}");
        assert!(d.message.contains("exact[1]"), "{d}");
    }

    #[test]
    fn structural_errors() {
        let d = Problem::parse(&OSC.replace("[1.0, 0.0]", "[1.0]"), "p.ron").unwrap_err();
        assert!(d.message.contains("`initial` has 1"), "{d}");
        let d = Problem::parse(&OSC.replace("t0:", "tzero:"), "p.ron").unwrap_err();
        assert_eq!(d.line, 7, "{d}");
        let d = Problem::parse(&OSC.replace("\"w\":", "\"sin\":"), "p.ron").unwrap_err();
        assert!(d.message.contains("`sin`"), "{d}");
        let d = Problem::parse("", "p.ron").unwrap_err();
        assert!(d.message.contains("empty"));
        let d = Problem::parse(&OSC.replace("\"v\"]", "\"x\"]"), "p.ron").unwrap_err();
        assert!(d.message.contains("twice"), "{d}");
    }

    #[test]
    fn semantic_errors_point_at_the_value() {
        let at = |text: String| {
            let d = Problem::parse(&text, "p.ron").unwrap_err();
            (d.line, d.col)
        };
        // `vars: ["x", "v"]` on line 3: the second name is at column 17
        assert_eq!(at(OSC.replace("\"v\"]", "\"x\"]")), (3, 17));
        assert_eq!(
            at(OSC.replace("[\"x\", \"v\"]", "[\"x\", \"2v\"]")),
            (3, 17)
        );
        // the params key `"sin"` on line 5, column 14
        assert_eq!(at(OSC.replace("\"w\":", "\"sin\":")), (5, 14));
        assert_eq!(at(OSC.replace("[1.0, 0.0]", "[1.0]")), (6, 14));
        assert_eq!(at(OSC.replace("t0: 0.0", "t0: NaN")), (7, 9));
        assert_eq!(
            at(OSC.replace("rhs: [\"v\", \"-w*w*x\"]", "rhs: [\"v\"]")),
            (4, 10)
        );
    }
}
