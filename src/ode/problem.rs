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
//! One definition, [`ProblemDef`], is read from problem files and written inline in a deck
//! (`ode: Inline((vars: …, rhs: …))`); [`ProblemDef::compile`] checks it and says where a fault
//! is ([`DefError`], a field, item and character), so each reader reports it at its own file's
//! line and column. Errors in a problem file are reported at their line and column in the file.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::System;
use super::expr::{self, Program};
use crate::diag::Diagnostic;
use crate::ron_tree;

/// An ODE problem as written: every field of a problem file. Inline in a deck, `name` may be
/// left out.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ProblemDef {
    #[serde(default)]
    pub name: String,
    pub vars: Vec<String>,
    /// One expression per variable: ẋᵢ = rhs[i](t, vars…, params…).
    pub rhs: Vec<String>,
    #[serde(default)]
    pub params: BTreeMap<String, f64>,
    /// Slider range of a parameter on the presenter's screen, e.g. `{"k": (0.0, 5.0)}`;
    /// parameters not listed get a range around their value.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub ranges: BTreeMap<String, (f64, f64)>,
    pub initial: Vec<f64>,
    #[serde(default)]
    pub t0: f64,
    /// The exact solution, one expression per variable, of `t`, the parameters, `t0` and the
    /// variables (which read the initial values).
    #[serde(default)]
    pub exact: Option<Vec<String>>,
}

/// Where in a [`ProblemDef`] a fault is.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum DefPos {
    /// The definition as a whole.
    Whole,
    /// A field (`vars`, `rhs`, `initial`, `exact`, `t0`, `params`, `ranges`).
    Field(&'static str),
    /// Item `i` of a list field (`vars[1]`).
    Item(&'static str, usize),
    /// Character `char` (0-based) of expression `i` of `rhs` or `exact`.
    InExpr(&'static str, usize, usize),
    /// The value of parameter (or range) `name`.
    Entry(&'static str, String),
    /// The key `name` itself of the map field (a bad parameter name).
    Key(&'static str, String),
}

impl DefPos {
    /// The path of the value inside the definition, for [`ron_tree::Node::at`], and the
    /// character inside that string (0 if not a string).
    pub fn tree_path(&self) -> (String, usize) {
        match self {
            DefPos::Whole => (String::new(), 0),
            DefPos::Field(f) => (f.to_string(), 0),
            DefPos::Item(f, i) => (format!("{f}[{i}]"), 0),
            DefPos::InExpr(f, i, c) => (format!("{f}[{i}]"), *c),
            // resolved through the map itself (a name may hold dots or brackets)
            DefPos::Entry(f, _) | DefPos::Key(f, _) => (f.to_string(), 0),
        }
    }
}

/// A fault in a definition: where, and what.
#[derive(Debug, Clone, PartialEq)]
pub struct DefError {
    pub pos: DefPos,
    pub message: String,
}

impl std::fmt::Display for DefError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

/// The longest expression accepted: a lecture's right-hand side is a line, and the parser and
/// compiler recurse on nesting, so a pasted novel must come back as a message, not a crash.
pub const MAX_EXPR_CHARS: usize = 2000;
/// The deepest nesting of parentheses, powers and prefix signs accepted.
pub const MAX_EXPR_DEPTH: usize = 48;

/// Refuses expressions too long or too deeply nested to parse safely (the parser recurses).
pub fn check_expr_size(src: &str) -> Result<(), expr::ExprError> {
    let n = src.chars().count();
    if n > MAX_EXPR_CHARS {
        return Err(expr::ExprError {
            offset: MAX_EXPR_CHARS,
            token: format!("{n} characters"),
            message: format!(
                "the expression is {n} characters long; at most {MAX_EXPR_CHARS} are accepted"
            ),
        });
    }
    // Nesting: open parentheses, plus every `^` and prefix sign (each recurses once).
    let mut depth = 0usize;
    let mut deepest = (0usize, 0usize);
    let mut prev_operand_end = false;
    for (i, c) in src.chars().enumerate() {
        match c {
            '(' => depth += 1,
            ')' => depth = depth.saturating_sub(1),
            _ => {}
        }
        let prefix = matches!(c, '-' | '+') && !prev_operand_end;
        let extra = usize::from(c == '^' || prefix);
        if c == '(' || extra > 0 {
            // powers and prefix signs count towards the depth of what follows
            depth += extra;
            if depth > deepest.0 {
                deepest = (depth, i);
            }
        }
        if !c.is_whitespace() {
            prev_operand_end = c.is_alphanumeric() || c == '_' || c == ')' || c == '.';
        }
    }
    if deepest.0 > MAX_EXPR_DEPTH {
        return Err(expr::ExprError {
            offset: deepest.1,
            token: src
                .chars()
                .nth(deepest.1)
                .map(String::from)
                .unwrap_or_default(),
            message: format!(
                "the expression nests {} levels deep; at most {MAX_EXPR_DEPTH} are accepted",
                deepest.0
            ),
        });
    }
    Ok(())
}

/// Parses, size-checks and compiles the expressions of one list field.
fn compile_exprs(
    field: &'static str,
    exprs: &[String],
    inputs: &[String],
    params: &[(String, f64)],
) -> Result<Program, DefError> {
    let fail = |i: usize, e: expr::ExprError| DefError {
        pos: DefPos::InExpr(field, i, e.offset),
        message: format!("in {field}[{i}]: {}: `{}`", e.message, e.token),
    };
    for (i, e) in exprs.iter().enumerate() {
        check_expr_size(e).map_err(|err| fail(i, err))?;
    }
    expr::compile(exprs, inputs, params).map_err(|(i, e)| fail(i, e))
}

impl ProblemDef {
    /// Checks the definition and compiles its expressions; `path` is kept for messages.
    pub fn compile(&self, path: impl AsRef<Path>) -> Result<Problem, DefError> {
        let err = |pos: DefPos, message: String| DefError { pos, message };
        let n = self.vars.len();
        if n == 0 {
            return Err(err(
                DefPos::Field("vars"),
                "`vars` is empty: a problem needs at least one variable".into(),
            ));
        }
        if self.rhs.len() != n {
            return Err(err(
                DefPos::Field("rhs"),
                format!(
                    "`rhs` has {} expressions but `vars` names {n} variables",
                    self.rhs.len()
                ),
            ));
        }
        if self.initial.len() != n {
            return Err(err(
                DefPos::Field("initial"),
                format!(
                    "`initial` has {} values but `vars` names {n} variables",
                    self.initial.len()
                ),
            ));
        }
        if let Some(ex) = &self.exact
            && ex.len() != n
        {
            return Err(err(
                DefPos::Field("exact"),
                format!(
                    "`exact` has {} expressions but `vars` names {n} variables",
                    ex.len()
                ),
            ));
        }
        let mut names: Vec<&str> = vec!["t"];
        let vars = self
            .vars
            .iter()
            .enumerate()
            .map(|(i, v)| (DefPos::Item("vars", i), v));
        let params = self
            .params
            .keys()
            .map(|k| (DefPos::Key("params", k.clone()), k));
        for (pos, name) in vars.chain(params) {
            let ok = name
                .chars()
                .next()
                .is_some_and(|c| c.is_alphabetic() || c == '_')
                && name.chars().all(|c| c.is_alphanumeric() || c == '_');
            if !ok {
                return Err(err(
                    pos,
                    format!("`{name}` is not a valid name (letters, digits, _)"),
                ));
            }
            if expr::is_reserved(name) || name == "t0" {
                return Err(err(
                    pos,
                    format!(
                        "`{name}` names a function or constant (or the start time t0) and cannot be a variable or parameter"
                    ),
                ));
            }
            if names.contains(&name.as_str()) {
                return Err(err(
                    pos,
                    format!(
                        "the name `{name}` is used twice (variables, parameters and t share one namespace)"
                    ),
                ));
            }
            names.push(name);
        }
        if !self.t0.is_finite() {
            return Err(err(
                DefPos::Field("t0"),
                format!("t0 = {} must be finite", self.t0),
            ));
        }
        for (i, v) in self.initial.iter().enumerate() {
            if !v.is_finite() {
                return Err(err(
                    DefPos::Item("initial", i),
                    format!("initial[{i}] = {v} must be a finite number"),
                ));
            }
        }
        for (k, v) in &self.params {
            if !v.is_finite() {
                return Err(err(
                    DefPos::Entry("params", k.clone()),
                    format!("parameter `{k}` = {v} must be a finite number"),
                ));
            }
        }
        for (k, (lo, hi)) in &self.ranges {
            if !self.params.contains_key(k) {
                return Err(err(
                    DefPos::Key("ranges", k.clone()),
                    format!("`ranges` names `{k}`, which is not a parameter"),
                ));
            }
            if !(lo.is_finite() && hi.is_finite() && lo < hi) {
                return Err(err(
                    DefPos::Entry("ranges", k.clone()),
                    format!("the range of `{k}` must be two finite numbers, low < high"),
                ));
            }
            // the slider could not show it, and would clamp it on the first touch
            if let Some(v) = self.params.get(k)
                && !(lo..=hi).contains(&v)
            {
                return Err(err(
                    DefPos::Entry("params", k.clone()),
                    format!("parameter `{k}` = {v} is outside its range ({lo}, {hi})"),
                ));
            }
        }
        let params: Vec<(String, f64)> = self.params.clone().into_iter().collect();
        let mut inputs = self.vars.clone();
        let rhs = compile_exprs("rhs", &self.rhs, &inputs, &params)?;
        inputs.push("t0".into());
        let exact = match &self.exact {
            Some(ex) => Some(compile_exprs("exact", ex, &inputs, &params)?),
            None => None,
        };
        Ok(Problem {
            name: self.name.clone(),
            path: path.as_ref().to_path_buf(),
            vars: self.vars.clone(),
            rhs_src: self.rhs.clone(),
            params,
            initial: self.initial.clone(),
            t0: self.t0,
            exact_src: self.exact.clone(),
            jac: Derivatives::of(&rhs, n),
            rhs,
            exact,
        })
    }

    /// The slider range of parameter `name`: from `ranges`, else twice its size either side of
    /// its value (±1 around zero).
    pub fn range_of(&self, name: &str) -> (f64, f64) {
        if let Some(r) = self.ranges.get(name) {
            return *r;
        }
        let v = self.params.get(name).copied().unwrap_or(0.0);
        let half = if v == 0.0 { 1.0 } else { 2.0 * v.abs() };
        (v - half, v + half)
    }
}

/// A compiled problem: it is a [`System`] (the compiled right-hand side) with its initial value.
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
    jac: Derivatives,
    exact: Option<Program>,
}

/// The right-hand side's exact derivatives, differentiated from its compiled program.
#[derive(Debug, Clone)]
struct Derivatives {
    /// ∂f_i/∂x_j, row-major
    dfdx: Program,
    /// ∂f/∂t; `None` when it is identically zero (an autonomous system)
    dfdt: Option<Program>,
}

impl Derivatives {
    fn of(rhs: &Program, n: usize) -> Self {
        let vars: Vec<usize> = (1..=n).collect();
        let dfdt = expr::derivatives(rhs, &[0]);
        Self {
            dfdx: expr::derivatives(rhs, &vars),
            dfdt: (!dfdt.is_zero()).then_some(dfdt),
        }
    }
}

/// A problem file's definition, or the file's own diagnostic (unreadable, not RON).
pub fn read_def(path: &Path) -> Result<(String, ProblemDef), Diagnostic> {
    let text = crate::project_files::read_to_string(path)
        .map_err(|e| Diagnostic::whole_file(path, format!("cannot read problem: {e}")))?;
    let def = parse_def(&text, path)?;
    Ok((text, def))
}

/// A problem file's text as its definition (named after the file when it gives no name) and
/// compiled; a fault at its line and column in the file.
pub fn parse_file(text: &str, path: &Path) -> Result<(ProblemDef, Problem), Diagnostic> {
    let mut def = parse_def(text, path)?;
    if def.name.is_empty() {
        def.name = path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
    }
    let problem = def
        .compile(path)
        .map_err(|e| diagnostic_at(text, "", path, &e))?;
    Ok((def, problem))
}

fn parse_def(text: &str, path: &Path) -> Result<ProblemDef, Diagnostic> {
    if text.trim().is_empty() {
        return Err(Diagnostic::whole_file(path, "problem file is empty"));
    }
    ron::from_str(text).map_err(|e| Diagnostic::from_ron(path, &e))
}

/// A [`DefError`] at its line and column in `text`, whose value at `base` (a
/// [`ron_tree`] path, empty for the whole file) is the definition.
pub fn diagnostic_at(text: &str, base: &str, path: &Path, e: &DefError) -> Diagnostic {
    let (sub, ch) = e.pos.tree_path();
    let full = match (base.is_empty(), sub.is_empty()) {
        (true, _) => sub,
        (false, true) => base.to_string(),
        (false, false) => format!("{base}.{sub}"),
    };
    let (line, col) = ron_tree::parse(text)
        .ok()
        .and_then(|tree| {
            let node = if full.is_empty() {
                Some(&tree)
            } else {
                tree.at(&full)
            }?;
            let node = match &e.pos {
                DefPos::Entry(_, name) | DefPos::Key(_, name) => {
                    let ron_tree::Value::Map(entries) = &node.value else {
                        return node.str_offset(text, 0);
                    };
                    let Some((key, value)) = entries
                        .iter()
                        .find(|(k, _)| k.as_str() == Some(name.as_str()))
                    else {
                        return node.str_offset(text, 0);
                    };
                    if matches!(e.pos, DefPos::Key(..)) {
                        key
                    } else {
                        value
                    }
                }
                _ => node,
            };
            node.str_offset(text, ch)
        })
        .map_or((0, 0), |at| ron_tree::line_col(text, at));
    Diagnostic::new(path, line, col, e.message.clone())
}

impl Problem {
    pub fn load(path: impl AsRef<Path>) -> Result<Self, Diagnostic> {
        let path = path.as_ref();
        let text = crate::project_files::read_to_string(path)
            .map_err(|e| Diagnostic::whole_file(path, format!("cannot read problem: {e}")))?;
        Self::parse(&text, path)
    }

    /// Parses problem text; `path` names the file in errors.
    pub fn parse(text: &str, path: impl AsRef<Path>) -> Result<Self, Diagnostic> {
        parse_file(text, path.as_ref()).map(|(_, problem)| problem)
    }

    /// The exact solution at time t, when the file gives one. Its expressions may use t and
    /// the parameters (the variables read the initial values).
    pub fn exact(&self, t: f64) -> Option<Vec<f64>> {
        self.exact_from(self.t0, &self.initial, t)
    }

    /// The exact solution through `(t0, x0)` at time `t`: the expressions read `x0` for the
    /// variables and `t0` for the start time.
    pub fn exact_from(&self, t0: f64, x0: &[f64], t: f64) -> Option<Vec<f64>> {
        let p = self.exact.as_ref()?;
        let mut input = Vec::with_capacity(x0.len() + 1);
        input.extend_from_slice(x0);
        input.push(t0);
        let mut out = vec![0.0; self.vars.len()];
        p.eval(t, &input, &mut out);
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
        self.jac = Derivatives::of(&self.rhs, self.vars.len());
        if let Some(src) = &self.exact_src {
            let mut inputs = self.vars.clone();
            inputs.push("t0".into());
            self.exact =
                Some(expr::compile(src, &inputs, &self.params).map_err(|(_, e)| e.to_string())?);
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
    /// Exact, from the symbolic derivative of the compiled right-hand side.
    fn jacobian(&self, t: f64, x: &[f64], jac: &mut [f64]) -> bool {
        self.jac.dfdx.eval(t, x, jac);
        true
    }
    fn time_derivative(&self, t: f64, x: &[f64], dfdt: &mut [f64]) -> bool {
        match &self.jac.dfdt {
            Some(p) => p.eval(t, x, dfdt),
            None => dfdt.fill(0.0),
        }
        true
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
    fn a_parameter_outside_its_declared_range_at_its_value() {
        let text = OSC.replace("params: {", "ranges: {\"w\": (0.0, 1.0)},\n    params: {");
        let d = Problem::parse(&text, "p.ron").unwrap_err();
        assert!(d.message.contains("outside its range (0, 1)"), "{d}");
        let value_at = text.find("\"w\": 2").unwrap() + "\"w\": ".len();
        assert_eq!((d.line, d.col), ron_tree::line_col(&text, value_at), "{d}");
    }

    #[test]
    fn semantic_errors_point_at_the_value() {
        let at = |text: String| {
            let d = Problem::parse(&text, "p.ron").unwrap_err();
            (d.line, d.col)
        };
        // `vars: ["x", "v"]` on line 3: the second name's first character is at column 18
        assert_eq!(at(OSC.replace("\"v\"]", "\"x\"]")), (3, 18));
        assert_eq!(
            at(OSC.replace("[\"x\", \"v\"]", "[\"x\", \"2v\"]")),
            (3, 18)
        );
        // the params key `"sin"` on line 5: its first character at column 15
        assert_eq!(at(OSC.replace("\"w\":", "\"sin\":")), (5, 15));
        assert_eq!(at(OSC.replace("[1.0, 0.0]", "[1.0]")), (6, 14));
        assert_eq!(at(OSC.replace("t0: 0.0", "t0: NaN")), (7, 9));
        assert_eq!(
            at(OSC.replace("rhs: [\"v\", \"-w*w*x\"]", "rhs: [\"v\"]")),
            (4, 10)
        );
    }
}
