//! Where an ODE widget's equation comes from: `ode: File("problems/forced.ron")` (a problem
//! file, relative to the deck and confined to the project) or `ode: Inline((vars: ["x"],
//! rhs: ["x*sin(t) - x^3/3"], initial: [0.8]))` with exactly the fields of a problem file
//! ([`ProblemDef`]). [`OdeSource::load`] reads and compiles it; a fault says where it is, so the
//! deck loader can put it at the deck's own line and column ([`OdeError::diagnostic`]).

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::diag::Diagnostic;
use crate::ode::problem::{self, DefError, DefPos, Problem, ProblemDef};
use crate::paths;

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum OdeSource {
    /// A problem file (as `lectern solve` reads it), relative to the deck's folder.
    File(String),
    /// The problem written in the deck (boxed: a deck block stays small).
    Inline(Box<ProblemDef>),
}

/// A loaded source: the definition as written, compiled, and the file it came from.
#[derive(Debug, Clone)]
pub struct LoadedOde {
    pub def: ProblemDef,
    pub problem: Problem,
    /// The problem file, for `File` sources (what a write-back edits, what a reload watches).
    pub file: Option<PathBuf>,
}

/// Why a source did not load.
#[derive(Debug, Clone, PartialEq)]
pub enum OdeError {
    /// A fault in the deck's own text: in the inline definition at `pos`, or (for `File`) the
    /// path itself (`pos` = [`DefPos::Whole`]).
    InDeck(DefError),
    /// A fault inside the problem file, with the file's own position.
    InFile(Diagnostic),
}

impl OdeError {
    /// One line for the widget and the presenter: what is wrong, and where inside the value.
    pub fn message(&self) -> String {
        match self {
            OdeError::InDeck(e) => e.message.clone(),
            OdeError::InFile(d) => d.to_string(),
        }
    }

    /// The fault as a diagnostic of the deck: `ode_at` is the [`crate::ron_tree`] path of the
    /// `ode:` value in `deck_text` (e.g. `slides[3].body[1].ode`). Faults inside a problem file
    /// keep that file's position.
    pub fn diagnostic(&self, deck_text: &str, ode_at: &str, deck_path: &Path) -> Diagnostic {
        match self {
            OdeError::InFile(d) => d.clone(),
            // the path of a File source: the string inside File(..)
            OdeError::InDeck(e) => problem::diagnostic_at(deck_text, ode_at, deck_path, e),
        }
    }
}

/// `written` (a path in the deck) as a file, confined to the project of `deck_path` (or of the
/// current folder when there is no deck file, as in tests).
pub fn resolve_path(deck_path: Option<&Path>, written: &str) -> Result<PathBuf, String> {
    let r = match deck_path {
        Some(deck) => paths::resolve_for(deck, written),
        None => paths::resolve(Path::new("."), Path::new("."), written),
    };
    let path = r.map_err(|e| e.to_string())?;
    // said here in the deck's own words (the OS error names the absolute path)
    if !crate::project_files::is_file(&path) {
        return Err(format!("`{written}`: no such file"));
    }
    Ok(path)
}

fn resolve_file(deck_path: Option<&Path>, written: &str) -> Result<PathBuf, OdeError> {
    resolve_path(deck_path, written).map_err(|m| {
        OdeError::InDeck(DefError {
            pos: DefPos::Whole,
            message: format!("ode: {m}"),
        })
    })
}

impl OdeSource {
    /// The problem file of a `File` source, resolved against the deck (`None` for `Inline`).
    pub fn file(&self, deck_path: Option<&Path>) -> Option<Result<PathBuf, OdeError>> {
        match self {
            OdeSource::File(written) => Some(resolve_file(deck_path, written)),
            OdeSource::Inline(_) => None,
        }
    }

    /// Reads (for `File`) and compiles the problem.
    pub fn load(&self, deck_path: Option<&Path>) -> Result<LoadedOde, OdeError> {
        match self {
            OdeSource::Inline(def) => {
                let named = deck_path.map(Path::to_path_buf).unwrap_or_default();
                let problem = def.compile(&named).map_err(OdeError::InDeck)?;
                Ok(LoadedOde {
                    def: def.as_ref().clone(),
                    problem,
                    file: None,
                })
            }
            OdeSource::File(written) => {
                let file = resolve_file(deck_path, written)?;
                let text = crate::project_files::read_to_string(&file).map_err(|e| {
                    OdeError::InFile(Diagnostic::whole_file(
                        &file,
                        format!("cannot read problem: {e}"),
                    ))
                })?;
                Self::from_file(&text, &file)
            }
        }
    }

    /// A problem file's text as the source it is (what a reload of the file gives).
    pub fn from_file(text: &str, file: &Path) -> Result<LoadedOde, OdeError> {
        let (def, problem) = problem::parse_file(text, file).map_err(OdeError::InFile)?;
        Ok(LoadedOde {
            def,
            problem,
            file: Some(file.to_path_buf()),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn deck() -> &'static Path {
        Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/slides/lecture.ron"))
    }

    #[test]
    fn file_and_inline_sources_load_the_same_problem() {
        let file = OdeSource::File("problems/harmonic.ron".into());
        let a = file.load(Some(deck())).unwrap();
        assert!(
            a.file
                .as_ref()
                .unwrap()
                .ends_with("slides/problems/harmonic.ron")
        );
        let inline: OdeSource = ron::from_str(
            r#"Inline((vars: ["x", "v"], rhs: ["v", "-w*w*x"], params: {"w": 1.0}, initial: [1.0, 0.0]))"#,
        )
        .unwrap();
        let b = inline.load(Some(deck())).unwrap();
        assert_eq!(a.def.rhs, b.def.rhs);
        assert!(b.file.is_none() && b.def.name.is_empty());
    }

    #[test]
    fn faults_say_where_they_are() {
        let e = OdeSource::File("../../outside.ron".into())
            .load(Some(deck()))
            .unwrap_err();
        assert!(
            matches!(&e, OdeError::InDeck(d) if d.pos == DefPos::Whole),
            "{e:?}"
        );
        assert!(
            e.message().contains("outside the project"),
            "{}",
            e.message()
        );
        let e = OdeSource::File("problems/nope.ron".into())
            .load(Some(deck()))
            .unwrap_err();
        assert_eq!(e.message(), "ode: `problems/nope.ron`: no such file");
        let bad: OdeSource =
            ron::from_str(r#"Inline((vars: ["x"], rhs: ["x*("], initial: [1.0]))"#).unwrap();
        match bad.load(None).unwrap_err() {
            OdeError::InDeck(d) => assert_eq!(d.pos, DefPos::InExpr("rhs", 0, 3)),
            other => panic!("{other:?}"),
        }
    }
}
