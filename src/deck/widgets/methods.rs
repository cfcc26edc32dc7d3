//! The one way a deck names an integrator, in every widget's `methods:` list:
//! `[Euler, Midpoint, Rk4, Tableau("tableaux/rk4-typo.ron")]`. [`MethodRef::resolve`] turns a
//! name into something the numerics core runs ([`ResolvedMethod`]); new kinds of method (the
//! adaptive pairs) become new variants here and new arms there, without reshaping any widget.

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
}

/// The three methods the lecture compares, the default of every `methods:` list.
pub fn default_methods() -> Vec<MethodRef> {
    vec![MethodRef::Euler, MethodRef::Midpoint, MethodRef::Rk4]
}

impl MethodRef {
    /// A stable short id: `euler`, `midpoint`, `heun`, `rk4`, or the tableau file's stem
    /// (`rk4-typo`). Parameter ids, CSV series and colours use it.
    pub fn key(&self) -> String {
        match self {
            MethodRef::Euler => "euler".into(),
            MethodRef::Midpoint => "midpoint".into(),
            MethodRef::Heun => "heun".into(),
            MethodRef::Rk4 => "rk4".into(),
            MethodRef::Tableau(file) => Path::new(file)
                .file_stem()
                .map_or_else(|| file.clone(), |s| s.to_string_lossy().into_owned()),
        }
    }

    /// The built-in method, if this is one.
    pub fn builtin(&self) -> Option<Method> {
        Some(match self {
            MethodRef::Euler => Method::Euler,
            MethodRef::Midpoint => Method::Midpoint,
            MethodRef::Heun => Method::Heun,
            MethodRef::Rk4 => Method::Rk4,
            MethodRef::Tableau(_) => return None,
        })
    }

    /// Makes the method runnable: built-ins directly, tableau files read (through
    /// [`crate::paths::resolve_for`], relative to `deck_path`) and validated.
    pub fn resolve(&self, deck_path: Option<&Path>) -> Result<ResolvedMethod, String> {
        let key = self.key();
        if let Some(m) = self.builtin() {
            let name = match m {
                Method::Rk4 => "RK4".to_string(),
                other => other.label().to_string(),
            };
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
}
