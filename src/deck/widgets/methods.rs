//! The one way a deck names an integrator, in every widget's `methods:` list:
//! `[Euler, Midpoint, Rk4, Tableau("tableaux/rk4-typo.ron")]`. [`MethodRef::resolve`] turns a
//! name into something the numerics core runs ([`ResolvedMethod`]); new kinds of method (the
//! adaptive pairs) become new variants here and new arms there, without reshaping any widget.
//! The adaptive embedded pairs (`Dopri5`, `Tsit5`, `Vern6` … `Vern9`, `Dop853`) are built-ins
//! too: the work-precision widget sweeps their tolerance through the one adaptive loop; every
//! other widget steps their propagating (higher-order) formula with a fixed h.

use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::ode::{Method, Scheme, Tableau};

#[derive(Debug, Clone, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum MethodRef {
    Euler,
    Midpoint,
    Heun,
    Rk4,
    /// An explicit Butcher tableau from a RON file, relative to the deck (inside the project),
    /// e.g. the notes' typo'd RK4: `Tableau("tableaux/rk4-typo.ron")`.
    Tableau(String),
    /// Dormand–Prince 5(4), the classic adaptive pair (`ode::Method::Dopri5`).
    Dopri5,
    /// Tsitouras 5(4).
    Tsit5,
    /// Verner's efficient 6(5), 7(6), 8(7) and 9(8) pairs.
    Vern6,
    Vern7,
    Vern8,
    Vern9,
    /// Dormand–Prince 8(5,3), Hairer's DOP853.
    Dop853,
}

/// The three methods the lecture compares, the default of every `methods:` list.
pub fn default_methods() -> Vec<MethodRef> {
    vec![MethodRef::Euler, MethodRef::Midpoint, MethodRef::Rk4]
}

impl MethodRef {
    /// A stable short id: the built-in's CLI name (`euler`, `midpoint`, `heun`, `rk4`,
    /// `dopri5`, `tsit5`, `vern6` … `vern9`, `dop853`), or the tableau file's stem
    /// (`rk4-typo`). Parameter ids, CSV series and colours use it.
    pub fn key(&self) -> String {
        match self {
            MethodRef::Tableau(file) => Path::new(file)
                .file_stem()
                .map_or_else(|| file.clone(), |s| s.to_string_lossy().into_owned()),
            builtin => builtin.builtin().map_or("", Method::name).into(),
        }
    }

    /// The built-in method, if this is one.
    pub fn builtin(&self) -> Option<Method> {
        Some(match self {
            MethodRef::Euler => Method::Euler,
            MethodRef::Midpoint => Method::Midpoint,
            MethodRef::Heun => Method::Heun,
            MethodRef::Rk4 => Method::Rk4,
            MethodRef::Dopri5 => Method::Dopri5,
            MethodRef::Tsit5 => Method::Tsit5,
            MethodRef::Vern6 => Method::Vern6,
            MethodRef::Vern7 => Method::Vern7,
            MethodRef::Vern8 => Method::Vern8,
            MethodRef::Vern9 => Method::Vern9,
            MethodRef::Dop853 => Method::Dop853,
            MethodRef::Tableau(_) => return None,
        })
    }

    /// Makes the method runnable: built-ins directly, tableau files read (through
    /// [`crate::paths::resolve_for`], relative to `deck_path`) and validated.
    pub fn resolve(&self, deck_path: Option<&Path>) -> Result<ResolvedMethod, String> {
        let key = self.key();
        if let Some(m) = self.builtin() {
            let name = short_name(m).to_string();
            let tableau = m
                .tableau()
                .ok_or("a built-in explicit method has a tableau")?;
            return Ok(ResolvedMethod {
                reference: self.clone(),
                key,
                name,
                tableau,
                method: Some(m),
            });
        }
        let MethodRef::Tableau(written) = self else {
            unreachable!("every non-built-in is a tableau")
        };
        let path = super::ode::resolve_path(deck_path, written)?;
        let tableau = Tableau::load(&path).map_err(|d| d.to_string())?;
        Ok(ResolvedMethod {
            reference: self.clone(),
            key,
            name: tableau.name.clone(),
            tableau,
            method: None,
        })
    }
}

/// The name on tick boxes and legends: short enough that a slide's row of methods fits
/// (`Method::label` is the long form, "Dormand–Prince 8(5,3)").
fn short_name(m: Method) -> &'static str {
    match m {
        Method::Rk4 => "RK4",
        Method::Dopri5 => "Dopri5",
        Method::Tsit5 => "Tsit5",
        Method::Vern6 => "Vern6",
        Method::Vern7 => "Vern7",
        Method::Vern8 => "Vern8",
        Method::Vern9 => "Vern9",
        Method::Dop853 => "DOP853",
        other => other.label(),
    }
}

/// A method ready to run.
#[derive(Debug, Clone, PartialEq)]
pub struct ResolvedMethod {
    pub reference: MethodRef,
    pub key: String,
    /// For people: "Euler", "RK4", the tableau's own name.
    pub name: String,
    /// Its Butcher tableau (stability regions, stage counts).
    pub tableau: Tableau,
    method: Option<Method>,
}

impl ResolvedMethod {
    /// The scheme the numerics core steps with (built-ins keep their fast paths).
    pub fn scheme(&self) -> Scheme<'_> {
        match self.method {
            Some(m) => Scheme::Method(m),
            None => Scheme::Tableau(&self.tableau),
        }
    }

    /// The built-in method, if this is one.
    pub fn builtin(&self) -> Option<Method> {
        self.method
    }

    /// The adaptive embedded pair, if this is one (`scheme()` then steps its propagating
    /// formula with a fixed h; the work-precision widget sweeps its tolerance instead).
    pub fn adaptive(&self) -> Option<Method> {
        self.method.filter(|m| m.is_adaptive())
    }

    /// The global order of its (propagating) formula, for built-ins.
    pub fn order(&self) -> Option<u32> {
        self.method.map(Method::order)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_keys_and_tableau_files() {
        let deck = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/slides/lecture.ron"));
        let rk4 = MethodRef::Rk4.resolve(Some(deck)).unwrap();
        assert_eq!((rk4.key.as_str(), rk4.name.as_str()), ("rk4", "RK4"));
        let typo = MethodRef::Tableau("tableaux/rk4-typo.ron".into())
            .resolve(Some(deck))
            .unwrap();
        assert_eq!(typo.key, "rk4-typo");
        // the notes' typo: the last stage samples at the midpoint again
        assert_eq!(typo.tableau.c, Tableau::rk4_typo().c);
        let e = MethodRef::Tableau("../../etc/passwd".into())
            .resolve(Some(deck))
            .unwrap_err();
        assert!(e.contains("outside the project"), "{e}");
        let e = MethodRef::Tableau("tableaux/none.ron".into())
            .resolve(Some(deck))
            .unwrap_err();
        assert!(e.contains("none.ron"), "{e}");
        let parsed: Vec<MethodRef> =
            ron::from_str("[Euler, Rk4, Tableau(\"tableaux/ralston.ron\")]").unwrap();
        assert_eq!(parsed[2].key(), "ralston");
    }

    #[test]
    fn adaptive_pairs_are_named_by_their_cli_names_and_map_onto_ode_methods() {
        let parsed: Vec<MethodRef> =
            ron::from_str("[Dopri5, Tsit5, Vern6, Vern7, Vern8, Vern9, Dop853, Rk4]").unwrap();
        for r in &parsed {
            let m = r.builtin().unwrap();
            assert_eq!(r.key(), m.name());
            assert_eq!(Method::from_name(&r.key()), Some(m));
            let resolved = r.resolve(None).unwrap();
            assert_eq!(resolved.adaptive().is_some(), m != Method::Rk4, "{m}");
            // the tableau is the propagating formula: its order conditions hold to its order
            assert_eq!(resolved.tableau.b.len(), m.tableau().unwrap().b.len());
        }
        let keys: Vec<String> = parsed.iter().map(MethodRef::key).collect();
        assert_eq!(
            keys,
            [
                "dopri5", "tsit5", "vern6", "vern7", "vern8", "vern9", "dop853", "rk4"
            ]
        );
        assert_eq!(MethodRef::Dop853.resolve(None).unwrap().name, "DOP853");
        assert_eq!(MethodRef::Vern9.resolve(None).unwrap().order(), Some(9));
        // a misspelt pair is a parse error that lists the names a deck may use
        let e = ron::from_str::<Vec<MethodRef>>("[Vern10]")
            .unwrap_err()
            .to_string();
        assert!(e.contains("Dop853") && e.contains("Vern9"), "{e}");
    }
}
