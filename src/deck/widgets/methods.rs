//! The one way a deck names an integrator, in every widget's `methods:` list:
//! `[Euler, Midpoint, Rk4, Tableau("tableaux/rk4-typo.ron")]`. A name is either a built-in
//! [`Method`] — written as its variant name (`Euler`, `Rk4`, `Dop853`, `ImplicitEuler`, …), so a
//! method added to `ode::Method` is usable on slides with no change here — or a Butcher tableau
//! file. [`MethodRef::resolve`] turns it into something the numerics core runs
//! ([`ResolvedMethod`]). The adaptive embedded pairs are built-ins too: the work-precision
//! widget sweeps their tolerance through the one adaptive loop; every other widget steps their
//! propagating (higher-order) formula with a fixed h.

use std::fmt;
use std::path::Path;

use serde::de::{self, EnumAccess, VariantAccess, Visitor};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use crate::ode::stability::Complex;
use crate::ode::{Method, Scheme, Tableau};

#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub enum MethodRef {
    /// A built-in method of the numerics core, written in a deck as its variant name (`Rk4`).
    Builtin(Method),
    /// An explicit Butcher tableau from a RON file, relative to the deck (inside the project),
    /// e.g. the notes' typo'd RK4: `Tableau("tableaux/rk4-typo.ron")`.
    Tableau(String),
}

/// The three methods the lecture compares, the default of every `methods:` list.
pub fn default_methods() -> Vec<MethodRef> {
    [Method::Euler, Method::Midpoint, Method::Rk4]
        .map(MethodRef::Builtin)
        .into()
}

/// How a deck writes a built-in method: the variant's own name (`Rk4`, `ImplicitEuler`).
pub fn deck_name(m: Method) -> String {
    format!("{m:?}")
}

/// The built-in whose deck name is `name`.
pub fn builtin_by_deck_name(name: &str) -> Option<Method> {
    Method::ALL.into_iter().find(|m| deck_name(*m) == name)
}

impl MethodRef {
    /// A stable short id: the built-in's CLI name (`euler`, `rk4`, `dop853`, …), or the
    /// tableau file's stem (`rk4-typo`). Parameter ids, CSV series and colours use it.
    pub fn key(&self) -> String {
        match self {
            MethodRef::Builtin(m) => m.name().into(),
            MethodRef::Tableau(file) => Path::new(file)
                .file_stem()
                .map_or_else(|| file.clone(), |s| s.to_string_lossy().into_owned()),
        }
    }

    /// The built-in method, if this is one.
    pub fn builtin(&self) -> Option<Method> {
        match self {
            MethodRef::Builtin(m) => Some(*m),
            MethodRef::Tableau(_) => None,
        }
    }

    /// Makes the method runnable: built-ins directly, tableau files read (through
    /// [`crate::paths::resolve_for`], relative to `deck_path`) and validated.
    pub fn resolve(&self, deck_path: Option<&Path>) -> Result<ResolvedMethod, String> {
        let key = self.key();
        match self {
            MethodRef::Builtin(m) => Ok(ResolvedMethod {
                reference: self.clone(),
                key,
                name: short_name(*m).to_string(),
                tableau: m.tableau(),
                method: Some(*m),
            }),
            MethodRef::Tableau(written) => {
                let path = super::ode::resolve_path(deck_path, written)?;
                let tableau = Tableau::load(&path).map_err(|d| d.to_string())?;
                Ok(ResolvedMethod {
                    reference: self.clone(),
                    key,
                    name: tableau.name.clone(),
                    tableau: Some(tableau),
                    method: None,
                })
            }
        }
    }
}

impl From<Method> for MethodRef {
    fn from(m: Method) -> Self {
        MethodRef::Builtin(m)
    }
}

const TABLEAU: &str = "Tableau";

impl Serialize for MethodRef {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            MethodRef::Builtin(m) => {
                let index = Method::ALL.iter().position(|x| x == m).unwrap_or(0);
                s.serialize_unit_variant("MethodRef", index as u32, variant_names()[index])
            }
            MethodRef::Tableau(file) => {
                let index = Method::ALL.len() as u32;
                s.serialize_newtype_variant("MethodRef", index, TABLEAU, file)
            }
        }
    }
}

/// Every name a deck may write: each built-in's deck name (in `Method::ALL`'s order), then
/// `Tableau`. serde wants `'static` names; they are made once.
fn variant_names() -> &'static [&'static str] {
    static NAMES: std::sync::OnceLock<Vec<&'static str>> = std::sync::OnceLock::new();
    NAMES.get_or_init(|| {
        Method::ALL
            .into_iter()
            .map(|m| &*Box::leak(deck_name(m).into_boxed_str()))
            .chain([TABLEAU])
            .collect()
    })
}

/// A variant's name as written (serde hands enum variants over as identifiers, not strings).
struct Ident(String);

impl<'de> Deserialize<'de> for Ident {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct IdentVisitor;
        impl Visitor<'_> for IdentVisitor {
            type Value = Ident;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a method name")
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<Ident, E> {
                Ok(Ident(v.to_owned()))
            }
        }
        d.deserialize_identifier(IdentVisitor)
    }
}

impl<'de> Deserialize<'de> for MethodRef {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct RefVisitor;
        impl<'de> Visitor<'de> for RefVisitor {
            type Value = MethodRef;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a method name (`Euler`, `Rk4`, …) or `Tableau(\"file.ron\")`")
            }
            fn visit_enum<A: EnumAccess<'de>>(self, data: A) -> Result<MethodRef, A::Error> {
                let (Ident(name), variant) = data.variant()?;
                if name == TABLEAU {
                    return variant.newtype_variant::<String>().map(MethodRef::Tableau);
                }
                match builtin_by_deck_name(&name) {
                    Some(m) => variant.unit_variant().map(|()| MethodRef::Builtin(m)),
                    None => Err(de::Error::unknown_variant(&name, variant_names())),
                }
            }
        }
        d.deserialize_enum("MethodRef", variant_names(), RefVisitor)
    }
}

/// The name on tick boxes and legends: short enough that a slide's row of methods fits
/// (`Method::label` is the long form, "Dormand–Prince 8(5,3)").
fn short_name(m: Method) -> &'static str {
    match m {
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
    /// Its Butcher tableau (stage counts; for an embedded pair its propagating formula), for
    /// explicit Runge–Kutta methods; `None` for implicit and symplectic built-ins.
    pub tableau: Option<Tableau>,
    method: Option<Method>,
}

impl ResolvedMethod {
    /// The scheme the numerics core steps with (built-ins keep their fast paths).
    pub fn scheme(&self) -> Scheme<'_> {
        match (self.method, &self.tableau) {
            (Some(m), _) => Scheme::Method(m),
            (None, Some(t)) => Scheme::Tableau(t),
            // resolve() builds a tableau method with its tableau; never reached
            (None, None) => Scheme::Method(Method::Rk4),
        }
    }

    /// The stability function R(z), z = hλ: one step of y' = λy multiplies y by it. `None` for
    /// methods that have none (symplectic splittings).
    pub fn stability(&self, z: Complex) -> Option<Complex> {
        match (self.method, &self.tableau) {
            (Some(m), _) => m.stability(z),
            (None, Some(t)) => Some(t.stability(z)),
            (None, None) => None,
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
        let rk4 = MethodRef::Builtin(Method::Rk4).resolve(Some(deck)).unwrap();
        assert_eq!((rk4.key.as_str(), rk4.name.as_str()), ("rk4", "RK4"));
        let typo = MethodRef::Tableau("tableaux/rk4-typo.ron".into())
            .resolve(Some(deck))
            .unwrap();
        assert_eq!(typo.key, "rk4-typo");
        // the notes' typo: the last stage samples at the midpoint again
        assert_eq!(typo.tableau.unwrap().c, Tableau::rk4_typo().c);
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
            assert_eq!(
                resolved.tableau.unwrap().b.len(),
                m.tableau().unwrap().b.len()
            );
        }
        let keys: Vec<String> = parsed.iter().map(MethodRef::key).collect();
        assert_eq!(
            keys,
            [
                "dopri5", "tsit5", "vern6", "vern7", "vern8", "vern9", "dop853", "rk4"
            ]
        );
        assert_eq!(
            MethodRef::Builtin(Method::Dop853)
                .resolve(None)
                .unwrap()
                .name,
            "DOP853"
        );
        assert_eq!(
            MethodRef::Builtin(Method::Vern9)
                .resolve(None)
                .unwrap()
                .order(),
            Some(9)
        );
        // a misspelt pair is a parse error that lists the names a deck may use
        let e = ron::from_str::<Vec<MethodRef>>("[Vern10]")
            .unwrap_err()
            .to_string();
        assert!(e.contains("Dop853") && e.contains("Vern9"), "{e}");
    }

    #[test]
    fn every_built_in_is_written_by_its_variant_name_and_round_trips() {
        for m in Method::ALL {
            let r = MethodRef::Builtin(m);
            let text = ron::to_string(&r).unwrap();
            assert_eq!(text, format!("{m:?}"));
            assert_eq!(ron::from_str::<MethodRef>(&text).unwrap(), r);
            let resolved = r.resolve(None).unwrap();
            assert_eq!(resolved.builtin(), Some(m));
            // every built-in but the symplectic splittings has a stability function
            let r_half = resolved.stability((-0.5, 0.0));
            assert_eq!(r_half.is_some(), !m.needs_second_order_system(), "{m}");
        }
        let t = MethodRef::Tableau("tableaux/rk4.ron".into());
        let text = ron::to_string(&t).unwrap();
        assert_eq!(text, "Tableau(\"tableaux/rk4.ron\")");
        assert_eq!(ron::from_str::<MethodRef>(&text).unwrap(), t);
        // implicit built-ins have no tableau but run and have R(z): implicit Euler 1/(1 - z)
        let ie = MethodRef::Builtin(Method::ImplicitEuler)
            .resolve(None)
            .unwrap();
        assert!(ie.tableau.is_none());
        let r = ie.stability((-1.0, 0.0)).unwrap();
        assert!((r.0 - 0.5).abs() < 1e-15 && r.1 == 0.0);
    }
}
