//! A widget's equation while presenting: loaded from its [`OdeSource`], compiled, and changed
//! live — parameters by slider ([`LiveOde::params`]), expressions by typing
//! ([`LiveOde::set_expr`]: a text that compiles replaces the equation, one that does not keeps
//! the last good one and records the error with its column). `revision` changes whenever the
//! compiled equation does, so widgets key their caches on it. No egui here: the presenter's
//! editor (`app::ode_editor`) and the widgets draw it.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use super::params::{Param, WriteTo};
use super::problem_files::MadeIn;
use crate::deck::widgets::{OdeError, OdeSource};
use crate::ode::problem::{DefPos, Problem, ProblemDef};

/// Which expression of the equation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ExprSlot {
    Rhs(usize),
    Exact(usize),
}

impl ExprSlot {
    /// Its path inside a problem definition (`rhs[0]`), for write-back.
    pub fn def_path(self) -> String {
        match self {
            ExprSlot::Rhs(k) => format!("rhs[{k}]"),
            ExprSlot::Exact(k) => format!("exact[{k}]"),
        }
    }
}

/// The text of one expression field and, while it does not compile, why (with the 1-based
/// column in the text).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct FieldState {
    pub text: String,
    pub error: Option<(String, usize)>,
}

pub struct LiveOde {
    source: OdeSource,
    file: Option<PathBuf>,
    /// The definition the file (deck or problem file) gives; `None` if it never loaded.
    file_def: Option<ProblemDef>,
    /// The file's definition with the live changes: the last good one.
    def: Option<ProblemDef>,
    problem: Option<Problem>,
    /// The parameter values `problem` was compiled with (sliders write into `def`).
    compiled_params: BTreeMap<String, f64>,
    load_error: Option<String>,
    rhs: Vec<FieldState>,
    exact: Vec<FieldState>,
    revision: u64,
    /// Set when a committed right-hand side left the file's exact solution behind (it solved
    /// the old equation): what the readouts say instead of an error against the wrong curve.
    dropped_exact: Option<String>,
}

impl LiveOde {
    /// The equation of `source`, from its problem file's holder while presenting ([`MadeIn`]):
    /// a file whose newest save is broken gives its last good equation and the error.
    pub fn new(source: &OdeSource, at: MadeIn<'_>) -> Self {
        let mut live = Self {
            source: source.clone(),
            file: None,
            file_def: None,
            def: None,
            problem: None,
            compiled_params: BTreeMap::new(),
            load_error: None,
            rhs: Vec::new(),
            exact: Vec::new(),
            revision: 0,
            dropped_exact: None,
        };
        let (loaded, file_error) = at.load(source);
        live.load_error = file_error;
        match loaded {
            Ok(loaded) => {
                live.file = loaded.file;
                live.compiled_params = loaded.def.params.clone();
                live.file_def = Some(loaded.def.clone());
                live.def = Some(loaded.def);
                live.problem = Some(loaded.problem);
                live.refill_fields();
            }
            Err(e) => live.load_error = Some(load_message(&e)),
        }
        live
    }

    fn refill_fields(&mut self) {
        let Some(def) = &self.def else { return };
        let field = |s: &String| FieldState {
            text: s.clone(),
            error: None,
        };
        self.rhs = def.rhs.iter().map(field).collect();
        self.exact = def.exact.iter().flatten().map(field).collect();
    }

    /// The compiled equation (after applying slider changes), or `None` if it never loaded.
    pub fn problem(&mut self) -> Option<&Problem> {
        self.sync_params();
        self.problem.as_ref()
    }

    /// Changes whenever the compiled equation does.
    pub fn revision(&mut self) -> u64 {
        self.sync_params();
        self.revision
    }

    fn sync_params(&mut self) {
        let Some(def) = &self.def else { return };
        if def.params == self.compiled_params {
            return;
        }
        // Sliders only produce finite values inside their range, so this compiles; if it ever
        // did not, the last good equation stays.
        if let Ok(p) = def.compile(self.named()) {
            self.problem = Some(p);
            self.revision += 1;
        }
        self.compiled_params = def.params.clone();
    }

    fn named(&self) -> PathBuf {
        self.file.clone().unwrap_or_default()
    }

    /// The problem file's newest save is broken (`Some`: its error, shown while the last good
    /// equation stays) or loaded again (`None`).
    pub fn set_file_error(&mut self, error: Option<String>) {
        self.load_error = error;
    }

    /// Why the source did not load (the widget shows it; the last good equation, if any, stays).
    pub fn load_error(&self) -> Option<&str> {
        self.load_error.as_deref()
    }

    pub fn source(&self) -> &OdeSource {
        &self.source
    }

    /// The problem file, for `File` sources.
    pub fn file(&self) -> Option<&Path> {
        self.file.as_deref()
    }

    pub fn def(&self) -> Option<&ProblemDef> {
        self.def.as_ref()
    }

    pub fn file_def(&self) -> Option<&ProblemDef> {
        self.file_def.as_ref()
    }

    /// The expression fields: right-hand sides, then the exact solution's (if any).
    pub fn fields(&self) -> (&[FieldState], &[FieldState]) {
        (&self.rhs, &self.exact)
    }

    /// One slider per parameter of the equation, id = its name, range from the file's `ranges`
    /// or around the file's value; one the shown equation (rhs or exact) no longer names is
    /// marked [`Param::unused`].
    pub fn params(&mut self) -> Vec<Param<'_>> {
        let (Some(def), Some(file_def)) = (self.def.as_mut(), self.file_def.as_ref()) else {
            return Vec::new();
        };
        let mut written = def.rhs.clone();
        written.extend(def.exact.iter().flatten().cloned());
        def.params
            .iter_mut()
            .map(|(name, value)| {
                let (lo, hi) = file_def.range_of(name);
                let unused = !crate::ode::expr::mentions(&written, name);
                Param::f64(name.clone(), name.clone(), value, lo, hi)
                    .writing_to(WriteTo::OdeParam(name.clone()))
                    .unused(unused)
            })
            .collect()
    }

    /// Typing: `text` becomes the expression in `slot` if the whole equation then compiles;
    /// otherwise the last good equation stays and the field keeps the error and its column.
    /// A changed right-hand side drops the file's exact solution, as [`LiveOde::commit`]
    /// does. Returns whether the equation changed.
    pub fn set_expr(&mut self, slot: ExprSlot, text: &str) -> bool {
        self.sync_params();
        let Some(def) = &self.def else { return false };
        let named = self.named();
        let mut candidate = def.clone();
        let (target, field) = match slot {
            ExprSlot::Rhs(k) => (candidate.rhs.get_mut(k), self.rhs.get_mut(k)),
            ExprSlot::Exact(k) => (
                candidate.exact.as_mut().and_then(|e| e.get_mut(k)),
                self.exact.get_mut(k),
            ),
        };
        let (Some(target), Some(field)) = (target, field) else {
            return false;
        };
        field.text = text.to_owned();
        if *target == text {
            field.error = None;
            return false;
        }
        *target = text.to_owned();
        fit_exact(self.file_def.as_ref(), &mut candidate);
        match candidate.compile(named) {
            Ok(p) => {
                field.error = None;
                self.use_committed(candidate, p);
                true
            }
            Err(e) => {
                let col = match e.pos {
                    DefPos::InExpr(_, _, c) => c + 1,
                    _ => 0,
                };
                field.error = Some((e.message, col));
                false
            }
        }
    }

    /// `def` (compiled to `problem`) becomes the equation everyone sees; the readouts say so
    /// when it left the file's exact solution behind.
    fn use_committed(&mut self, def: ProblemDef, problem: Problem) {
        let file_has_exact = self.file_def.as_ref().is_some_and(|f| f.exact.is_some());
        self.dropped_exact = (file_has_exact && def.exact.is_none()).then(|| {
            "the exact solution was dropped: it solved the file's equation, not the typed one"
                .to_owned()
        });
        self.def = Some(def);
        self.problem = Some(problem);
        self.revision += 1;
        self.refill_fields();
    }

    /// Whether the equation shown has no exact solution although its file gives one (the
    /// write-back then removes it from the file: it solved the file's old equation).
    pub fn drops_files_exact(&self) -> bool {
        let file_has_exact = self.file_def.as_ref().is_some_and(|f| f.exact.is_some());
        file_has_exact && self.def.as_ref().is_some_and(|d| d.exact.is_none())
    }

    /// Typing, as the presenter does: `text` becomes the draft of `slot`. Nothing the
    /// audience sees changes until [`LiveOde::commit`] (Enter); [`LiveOde::revert`] (Esc)
    /// drops the drafts. Every field's error is brought up to date; returns whether the
    /// drafts compile together.
    pub fn set_draft(&mut self, slot: ExprSlot, text: &str) -> bool {
        self.sync_params();
        let field = match slot {
            ExprSlot::Rhs(k) => self.rhs.get_mut(k),
            ExprSlot::Exact(k) => self.exact.get_mut(k),
        };
        let Some(field) = field else { return false };
        field.text = text.to_owned();
        let verdict = self.draft();
        for f in self.rhs.iter_mut().chain(self.exact.iter_mut()) {
            f.error = None;
        }
        match verdict {
            Some(Err((at, message, col))) => {
                let field = match at {
                    ExprSlot::Rhs(k) => self.rhs.get_mut(k),
                    ExprSlot::Exact(k) => self.exact.get_mut(k),
                };
                if let Some(f) = field {
                    f.error = Some((message, col));
                }
                false
            }
            _ => true,
        }
    }

    /// Whether a field holds text the audience does not see yet.
    pub fn has_draft(&self) -> bool {
        let Some(def) = &self.def else { return false };
        let exact = def.exact.as_deref().unwrap_or(&[]);
        (self.rhs.iter().map(|f| &f.text)).ne(def.rhs.iter())
            || (self.exact.iter().map(|f| &f.text)).ne(exact.iter())
    }

    /// The equation the drafts make, compiled (`None` without drafts or a loaded equation;
    /// the error with its field and 1-based column when they do not compile). A changed
    /// right-hand side drops an exact solution that was not typed along with it: it solved
    /// the old equation.
    #[allow(clippy::type_complexity)]
    fn draft(&self) -> Option<Result<(ProblemDef, Problem, bool), (ExprSlot, String, usize)>> {
        let def = self.def.as_ref()?;
        if !self.has_draft() {
            return None;
        }
        let mut candidate = def.clone();
        candidate.rhs = self.rhs.iter().map(|f| f.text.clone()).collect();
        if candidate.exact.is_some() {
            candidate.exact = Some(self.exact.iter().map(|f| f.text.clone()).collect());
        }
        let dropped = fit_exact(self.file_def.as_ref(), &mut candidate);
        Some(match candidate.compile(self.named()) {
            Ok(p) => Ok((candidate, p, dropped)),
            Err(e) => {
                let (at, col) = match e.pos {
                    DefPos::InExpr("exact", k, c) => (ExprSlot::Exact(k), c + 1),
                    DefPos::InExpr(_, k, c) => (ExprSlot::Rhs(k), c + 1),
                    DefPos::Item("exact", k) => (ExprSlot::Exact(k), 0),
                    DefPos::Item(_, k) => (ExprSlot::Rhs(k), 0),
                    _ => (ExprSlot::Rhs(0), 0),
                };
                Err((at, e.message, col))
            }
        })
    }

    /// The drafts' equation, for the presenter's preview (`None` when there are no drafts or
    /// they do not compile).
    pub fn draft_problem(&self) -> Option<(ProblemDef, Problem)> {
        match self.draft()? {
            Ok((def, p, _)) => Some((def, p)),
            Err(_) => None,
        }
    }

    /// Enter: the drafts become the equation everyone sees, if they compile (else nothing
    /// changes and the error stays under its field). Returns whether the equation changed.
    pub fn commit(&mut self) -> bool {
        self.sync_params();
        let Some(Ok((def, problem, _))) = self.draft() else {
            return false;
        };
        self.use_committed(def, problem);
        true
    }

    /// Esc: the fields back to the equation everyone sees.
    pub fn revert(&mut self) {
        self.refill_fields();
    }

    /// Why the equation has no exact solution now although its file gives one.
    pub fn dropped_exact(&self) -> Option<&str> {
        self.dropped_exact.as_deref()
    }

    /// Shows `def` (the presenter's preview copy of a widget takes the drafts' equation so);
    /// `false`, and nothing changed, if it does not compile.
    pub fn show_def(&mut self, def: ProblemDef) -> bool {
        match def.compile(self.named()) {
            Ok(p) => {
                self.compiled_params = def.params.clone();
                self.def = Some(def);
                self.problem = Some(p);
                self.revision += 1;
                self.refill_fields();
                true
            }
            Err(_) => false,
        }
    }

    /// Back to the file's equation (`R`).
    pub fn reset(&mut self) {
        if let Some(file_def) = &self.file_def
            && self.def.as_ref() != Some(file_def)
        {
            self.def = Some(file_def.clone());
            if let Ok(p) = file_def.compile(self.named()) {
                self.problem = Some(p);
            }
            self.compiled_params = file_def.params.clone();
            self.revision += 1;
        }
        self.dropped_exact = None;
        self.refill_fields();
    }

    /// The expressions typed live that differ from the file's: (slot, text), for write-back.
    pub fn typed(&self) -> Vec<(ExprSlot, String)> {
        let (Some(def), Some(file)) = (&self.def, &self.file_def) else {
            return Vec::new();
        };
        let mut out: Vec<(ExprSlot, String)> = def
            .rhs
            .iter()
            .zip(&file.rhs)
            .enumerate()
            .filter(|(_, (a, b))| a != b)
            .map(|(k, (a, _))| (ExprSlot::Rhs(k), a.clone()))
            .collect();
        if let (Some(a), Some(b)) = (&def.exact, &file.exact) {
            out.extend(
                a.iter()
                    .zip(b)
                    .enumerate()
                    .filter(|(_, (a, b))| a != b)
                    .map(|(k, (a, _))| (ExprSlot::Exact(k), a.clone())),
            );
        }
        out
    }

    /// After a reload re-made the widget: if the new source does not load, keep `old`'s last
    /// good equation (the error still shows); if it does, keep what was typed live in `old`
    /// wherever the file did not change that very expression.
    pub fn carry_from(&mut self, old: &LiveOde) {
        if self.problem.is_none() {
            if old.problem.is_some() {
                self.file = old.file.clone();
                self.file_def = old.file_def.clone();
                self.def = old.def.clone();
                self.problem = old.problem.clone();
                self.compiled_params = old.compiled_params.clone();
                self.rhs = old.rhs.clone();
                self.exact = old.exact.clone();
                self.revision = old.revision + 1;
            }
            return;
        }
        let (Some(old_file), Some(new_file)) = (&old.file_def, self.file_def.clone()) else {
            return;
        };
        // exact solutions first: a typed one then goes with its typed right-hand side
        let mut typed = old.typed();
        typed.sort_by_key(|(slot, _)| matches!(slot, ExprSlot::Rhs(_)));
        for (slot, text) in typed {
            let (was, now) = match slot {
                ExprSlot::Rhs(k) => (old_file.rhs.get(k), new_file.rhs.get(k)),
                ExprSlot::Exact(k) => (
                    old_file.exact.as_ref().and_then(|e| e.get(k)),
                    new_file.exact.as_ref().and_then(|e| e.get(k)),
                ),
            };
            if was.is_some() && was == now && old_file.vars == new_file.vars {
                self.set_expr(slot, &text);
            }
        }
    }

    /// The equation as the audience reads it: `ẋ = cos(t) − x`, `(ẋ, ẏ) = (−y, x)`.
    pub fn label(&self) -> String {
        self.def.as_ref().map(equation_label).unwrap_or_default()
    }
}

/// The one rule for an exact solution while typing: a right-hand side changed from the
/// file's drops the file's exact solution (it solved the old equation) unless an exact one was
/// typed along with it; back to the file's right-hand side, the file's exact solution belongs
/// again. Returns whether it dropped one.
fn fit_exact(file: Option<&ProblemDef>, candidate: &mut ProblemDef) -> bool {
    let rhs_is_the_files = file.is_some_and(|f| f.rhs == candidate.rhs);
    let exact_is_the_files = file.is_some_and(|f| f.exact == candidate.exact);
    if !rhs_is_the_files && exact_is_the_files && candidate.exact.is_some() {
        candidate.exact = None;
        true
    } else {
        if rhs_is_the_files && candidate.exact.is_none() {
            candidate.exact = file.and_then(|f| f.exact.clone());
        }
        false
    }
}

fn load_message(e: &OdeError) -> String {
    e.message()
}

/// `d/dt` of a variable as a symbol: a dot over x, y, z; a prime otherwise.
fn dotted(var: &str) -> String {
    match var {
        "x" => "ẋ".into(),
        "y" => "ẏ".into(),
        "z" => "ż".into(),
        other => format!("{other}'"),
    }
}

/// An expression as a label: `·` for `*`, `−` for `-`, small whole powers as superscripts,
/// `π` for `pi`.
pub fn pretty_expr(src: &str) -> String {
    const SUP: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
    let chars: Vec<char> = src.chars().collect();
    let mut out = String::with_capacity(src.len());
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        if c.is_alphabetic() || c == '_' {
            let start = i;
            while i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '_') {
                i += 1;
            }
            let name: String = chars[start..i].iter().collect();
            out.push_str(if name == "pi" { "π" } else { &name });
            // `cos(t)` reads `cos t`: a function of one plain name or number needs no brackets
            if crate::ode::expr::is_reserved(&name) && chars.get(i) == Some(&'(') {
                let close = chars[i + 1..].iter().position(|c| *c == ')');
                if let Some(len) = close {
                    let arg: String = chars[i + 1..i + 1 + len].iter().collect();
                    let plain = !arg.is_empty()
                        && arg
                            .chars()
                            .all(|c| c.is_alphanumeric() || c == '_' || c == '.');
                    if plain {
                        out.push(' ');
                        out.push_str(if arg == "pi" { "π" } else { &arg });
                        i += len + 2;
                    }
                }
            }
            continue;
        }
        match c {
            '*' => out.push('·'),
            '-' => out.push('−'),
            '^' if chars.get(i + 1).is_some_and(|d| d.is_ascii_digit()) => {
                let mut j = i + 1;
                while j < chars.len() && chars[j].is_ascii_digit() {
                    j += 1;
                }
                // only a whole power: `x^2`, not `x^2.5`
                if chars.get(j) == Some(&'.') {
                    out.push('^');
                } else {
                    for d in &chars[i + 1..j] {
                        out.push(SUP[d.to_digit(10).unwrap_or(0) as usize]);
                    }
                    i = j;
                    continue;
                }
            }
            other => out.push(other),
        }
        i += 1;
    }
    out
}

/// `ẋ = …` for one variable, `(ẋ, ẏ) = (…, …)` for several.
pub fn equation_label(def: &ProblemDef) -> String {
    if def.vars.len() == 1 {
        let rhs = def.rhs.first().map_or("", String::as_str);
        return format!("{} = {}", dotted(&def.vars[0]), pretty_expr(rhs));
    }
    let lhs: Vec<String> = def.vars.iter().map(|v| dotted(v)).collect();
    let rhs: Vec<String> = def.rhs.iter().map(|r| pretty_expr(r)).collect();
    format!("({}) = ({})", lhs.join(", "), rhs.join(", "))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn forced() -> OdeSource {
        ron::from_str(
            r#"Inline((vars: ["x"], rhs: ["cos(t) - x"], params: {"k": 1.0}, initial: [1.5]))"#,
        )
        .unwrap()
    }

    #[test]
    fn typing_replaces_the_equation_only_when_it_compiles() {
        let mut live = LiveOde::new(&forced(), MadeIn::default());
        let r0 = live.revision();
        assert!(live.set_expr(ExprSlot::Rhs(0), "-2*x + cos(3*t)"));
        assert!(live.revision() > r0);
        let mut d = [0.0];
        crate::ode::System::rhs(live.problem().unwrap(), 0.0, &[1.0], &mut d);
        assert_eq!(d[0], -2.0 + 1.0);
        // `x*(` does not parse: the last good equation stays, the error has its column
        let r1 = live.revision();
        assert!(!live.set_expr(ExprSlot::Rhs(0), "x*("));
        assert_eq!(live.revision(), r1);
        let (rhs, _) = live.fields();
        assert_eq!(rhs[0].text, "x*(");
        let (msg, col) = rhs[0].error.clone().unwrap();
        assert_eq!(col, 4, "{msg}");
        assert_eq!(live.def().unwrap().rhs[0], "-2*x + cos(3*t)");
        assert_eq!(
            live.typed(),
            vec![(ExprSlot::Rhs(0), "-2*x + cos(3*t)".to_string())]
        );
        live.reset();
        assert!(live.typed().is_empty());
        assert_eq!(live.fields().0[0].text, "cos(t) - x");
    }

    #[test]
    fn sliders_recompile_and_labels_read_like_maths() {
        let src: OdeSource = ron::from_str(
            r#"Inline((vars: ["y"], rhs: ["lambda*y"], params: {"lambda": -5.0}, initial: [1.0]))"#,
        )
        .unwrap();
        let mut live = LiveOde::new(&src, MadeIn::default());
        let r0 = live.revision();
        {
            let mut ps = live.params();
            assert_eq!(ps[0].id, "lambda");
            assert_eq!(ps[0].write, WriteTo::OdeParam("lambda".into()));
            ps[0].set(super::super::ParamSnapshot::F64(-2.0)).unwrap();
        }
        assert!(live.revision() > r0);
        let mut d = [0.0];
        crate::ode::System::rhs(live.problem().unwrap(), 0.0, &[1.0], &mut d);
        assert_eq!(d[0], -2.0);
        assert_eq!(pretty_expr("x*sin(t) - x^3/3"), "x·sin t − x³/3");
        assert_eq!(pretty_expr("cos(t) - x"), "cos t − x");
        assert_eq!(pretty_expr("exp(-k*t) + sin(w*t)"), "exp(−k·t) + sin(w·t)");
        assert_eq!(pretty_expr("2*pi*x^2.5"), "2·π·x^2.5");
        assert_eq!(live.label(), "ẏ = lambda·y");
    }

    /// A parameter the typed equation no longer names keeps its slider (bookmarks, tweaks and
    /// write-back still find it), marked unused; typing it back in clears the mark.
    #[test]
    fn a_parameter_the_typed_equation_drops_is_marked_unused() {
        let src: OdeSource = ron::from_str(
            r#"Inline((vars: ["x"], rhs: ["-k*x"], params: {"k": 1.0, "ω": 2.0}, initial: [1.0]))"#,
        )
        .unwrap();
        let mut live = LiveOde::new(&src, MadeIn::default());
        let unused = |live: &mut LiveOde| -> Vec<(String, bool)> {
            live.params()
                .iter()
                .map(|p| (p.id.clone(), p.unused))
                .collect()
        };
        let pair = |k: bool, w: bool| vec![("k".to_string(), k), ("ω".to_string(), w)];
        assert_eq!(unused(&mut live), pair(false, true));
        assert!(live.set_expr(ExprSlot::Rhs(0), "-omega^2*x"));
        assert_eq!(unused(&mut live), pair(true, false));
        assert!(live.set_expr(ExprSlot::Rhs(0), "-k*omega*x"));
        assert_eq!(unused(&mut live), pair(false, false));
    }

    /// The reload path (`carry_from` re-typing with `set_expr`) follows Enter's rule: a typed
    /// right-hand side drops the file's exact solution, which solved the old equation.
    #[test]
    fn a_reload_carrying_a_typed_rhs_drops_the_stale_exact_solution() {
        let with_exact: OdeSource = ron::from_str(
            r#"Inline((vars: ["x"], rhs: ["-x"], initial: [1.0], exact: Some(["exp(-(t - t0))*x"])))"#,
        )
        .unwrap();
        let mut old = LiveOde::new(&with_exact, MadeIn::default());
        assert!(old.set_draft(ExprSlot::Rhs(0), "-2*x"));
        assert!(old.commit());
        assert!(old.drops_files_exact() && old.dropped_exact().is_some());
        // the file reloads (unchanged here): the typed equation is carried, without the exact
        let mut next = LiveOde::new(&with_exact, MadeIn::default());
        next.carry_from(&old);
        assert_eq!(next.def().unwrap().rhs, vec!["-2*x".to_string()]);
        assert_eq!(
            next.def().unwrap().exact,
            None,
            "a stale exact would be kept"
        );
        assert!(next.dropped_exact().is_some() && next.drops_files_exact());
        assert!(
            next.fields().1.is_empty(),
            "no exact field for the typed equation"
        );
        // typing the file's right-hand side back brings its exact solution back
        assert!(next.set_expr(ExprSlot::Rhs(0), "-x"));
        assert!(next.def().unwrap().exact.is_some() && !next.drops_files_exact());
        assert!(next.dropped_exact().is_none());
    }

    #[test]
    fn a_broken_reload_keeps_the_last_good_equation() {
        let good = LiveOde::new(&forced(), MadeIn::default());
        let bad: OdeSource =
            ron::from_str(r#"Inline((vars: ["x"], rhs: ["cos(t) - q"], initial: [1.5]))"#).unwrap();
        let mut next = LiveOde::new(&bad, MadeIn::default());
        assert!(next.load_error().unwrap().contains("unknown name"));
        next.carry_from(&good);
        assert!(next.problem().is_some());
        assert!(next.load_error().is_some(), "the error still shows");
    }
}
