//! `lectern check`: validate decks, scenes, shaders, ODE problems and tableaux; print
//! `file:line:col: message` for each problem and a one-line summary.

use std::path::{Path, PathBuf};

use super::check_deck::DeckChecker;
use crate::diag::Diagnostic;

/// Validate decks, scenes, shaders and problems.
#[derive(Debug, Default, clap::Args)]
pub struct Args {
    /// Files or folders to check [default: slides/ scenes/ shaders/]
    pub paths: Vec<PathBuf>,
}

/// What a file is, from where it lives and its extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    Deck,
    Scene,
    Shader,
    Problem,
    Tableau,
}

/// Files lectern writes beside a deck (live tweaks, rehearsal timings, ink): not decks.
const COMPANION_SUFFIXES: [&str; 3] = [".tweaks.ron", ".timings.ron", ".ink.ron"];

/// Whether `path` is one of the files lectern writes beside a deck.
pub fn is_companion(path: &Path) -> bool {
    path.file_name()
        .and_then(|n| n.to_str())
        .is_some_and(|n| COMPANION_SUFFIXES.iter().any(|s| n.ends_with(s)))
}

impl Kind {
    pub fn of(path: &Path) -> Option<Kind> {
        if is_companion(path) {
            return None;
        }
        let ext = path.extension()?.to_str()?;
        let under = |name: &str| {
            path.parent()
                .is_some_and(|p| p.components().any(|c| c.as_os_str() == name))
        };
        match ext {
            "wgsl" => Some(Kind::Shader),
            "ron" if under("problems") => Some(Kind::Problem),
            "ron" if under("tableaux") => Some(Kind::Tableau),
            "ron" if under("scenes") => Some(Kind::Scene),
            "ron" => Some(Kind::Deck),
            _ => None,
        }
    }
}

/// The result of checking files: the problems, and a line per good deck.
#[derive(Debug, Default)]
pub struct Report {
    pub problems: Vec<Diagnostic>,
    /// `slides/lecture.ron: 26 slides, 15:00 planned`
    pub deck_lines: Vec<String>,
    /// Worth knowing, not a problem: which shaders a deck's scene uses.
    pub notes: Vec<String>,
    pub counts: [usize; 5],
}

impl Report {
    pub fn summary(&self) -> String {
        let [d, s, sh, p, t] = self.counts;
        let plural =
            |n: usize, one: &str, many: &str| format!("{n} {}", if n == 1 { one } else { many });
        let mut parts = vec![plural(d, "deck", "decks")];
        for (n, one, many) in [
            (s, "scene", "scenes"),
            (sh, "shader", "shaders"),
            (p, "problem file", "problem files"),
            (t, "tableau", "tableaux"),
        ] {
            if n > 0 {
                parts.push(plural(n, one, many));
            }
        }
        let verdict = match self.problems.len() {
            0 => "all good".to_owned(),
            n => plural(n, "problem", "problems"),
        };
        format!("checked {}: {verdict}", parts.join(", "))
    }
}

/// `m:ss` for a number of seconds.
pub fn minutes(secs: f32) -> String {
    let s = secs.max(0.0).round() as u64;
    format!("{}:{:02}", s / 60, s % 60)
}

/// Checks every file under `paths` (files or folders, walked recursively in sorted order).
/// Missing default folders are skipped; a missing path the user named is a problem.
pub fn check_paths(paths: &[PathBuf], defaults: bool) -> Report {
    let mut report = Report::default();
    let mut decks = DeckChecker::new();
    for path in paths {
        if !path.exists() {
            if !defaults {
                report
                    .problems
                    .push(Diagnostic::whole_file(path, "no such file or folder"));
            }
            continue;
        }
        let mut files = Vec::new();
        collect_files(path, &mut files);
        if path.is_file() && Kind::of(path).is_none() {
            let why = if is_companion(path) {
                "a file lectern writes beside the deck (tweaks, timings or ink), not checked"
            } else {
                "not a deck, scene, shader, problem or tableau (.ron or .wgsl)"
            };
            report.problems.push(Diagnostic::whole_file(path, why));
        }
        for file in files {
            check_file(&file, &mut decks, &mut report);
        }
    }
    // A fault reached twice (an include-only shader named alone and through the shader that
    // includes it, one shader in two pipelines) is printed once.
    let mut seen = std::collections::HashSet::new();
    report.problems.retain(|d| seen.insert(d.to_string()));
    report
}

fn collect_files(path: &Path, out: &mut Vec<PathBuf>) {
    if path.is_file() {
        if Kind::of(path).is_some() {
            out.push(path.to_path_buf());
        }
        return;
    }
    let Ok(entries) = std::fs::read_dir(path) else {
        return;
    };
    let mut entries: Vec<PathBuf> = entries.filter_map(|e| e.ok().map(|e| e.path())).collect();
    entries.sort();
    for e in entries {
        let hidden = e
            .file_name()
            .and_then(|n| n.to_str())
            .is_some_and(|n| n.starts_with('.'));
        if !hidden {
            collect_files(&e, out);
        }
    }
}

/// Checks one file by its kind, adding its problems (and, for a deck, its line) to `report`.
pub fn check_file(file: &Path, decks: &mut DeckChecker, report: &mut Report) {
    let Some(kind) = Kind::of(file) else { return };
    report.counts[kind as usize] += 1;
    let problems = match kind {
        // a shader is read with its includes
        Kind::Shader => crate::render::check_shader_file(file),
        _ => match std::fs::read_to_string(file) {
            Ok(text) => check_text(kind, &text, file, decks, report),
            Err(e) => vec![Diagnostic::whole_file(file, format!("cannot read: {e}"))],
        },
    };
    report.problems.extend(problems);
}

/// The problems of `text`, read from `file` as a `kind` (a shader is checked from its file).
/// A deck that parsed adds its line to `report`.
pub fn check_text(
    kind: Kind,
    text: &str,
    file: &Path,
    decks: &mut DeckChecker,
    report: &mut Report,
) -> Vec<Diagnostic> {
    let first = |r: Result<(), Diagnostic>| r.err().into_iter().collect();
    match kind {
        Kind::Deck => {
            let checked = decks.check_text(text, file);
            if let Some(deck) = &checked.deck {
                let n = deck.slides.len();
                report.deck_lines.push(format!(
                    "{}: {n} slide{}, {} planned",
                    file.display(),
                    if n == 1 { "" } else { "s" },
                    minutes(deck.planned_secs())
                ));
            }
            report.notes.extend(checked.notes);
            checked.problems
        }
        Kind::Scene => first(crate::scene::parse_scene(text, file).map(|_| ())),
        Kind::Shader => crate::render::check_shader_file(file),
        Kind::Problem => first(crate::ode::problem::Problem::parse(text, file).map(|_| ())),
        Kind::Tableau => first(crate::ode::Tableau::parse(text, file).map(|_| ())),
    }
}

pub fn run(args: Args) -> anyhow::Result<()> {
    let defaults = args.paths.is_empty();
    let paths = if defaults {
        ["slides", "scenes", "shaders"]
            .iter()
            .map(PathBuf::from)
            .collect()
    } else {
        args.paths
    };
    let report = check_paths(&paths, defaults);
    for line in &report.deck_lines {
        println!("{line}");
    }
    for note in &report.notes {
        println!("{note}");
    }
    for d in &report.problems {
        println!("{d}");
    }
    if let Some(note) = crate::render::pipeline_check_skipped() {
        println!("{note}");
    }
    println!("{}", report.summary());
    if report.problems.is_empty() {
        Ok(())
    } else {
        Err(anyhow::anyhow!("{} problem(s)", report.problems.len()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_fault_reached_twice_is_reported_once() {
        let dir = tempfile::tempdir().unwrap();
        let shaders = dir.path().join("shaders");
        std::fs::create_dir_all(&shaders).unwrap();
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("shaders");
        for entry in std::fs::read_dir(&root).unwrap() {
            let from = entry.unwrap().path();
            std::fs::copy(&from, shaders.join(from.file_name().unwrap())).unwrap();
        }
        let brdf = shaders.join("brdf.wgsl");
        let text = std::fs::read_to_string(&brdf).unwrap();
        std::fs::write(&brdf, text.replacen("fn ", "fn fn ", 1)).unwrap();
        let report = check_paths(&[brdf.clone(), shaders.join("pbr.wgsl")], false);
        let at_brdf: Vec<_> = (report.problems.iter())
            .filter(|d| d.file == brdf)
            .collect();
        assert_eq!(at_brdf.len(), 1, "{:?}", report.problems);
    }

    #[test]
    fn kinds_by_folder_and_companions_skipped() {
        let kind = |p: &str| Kind::of(Path::new(p));
        assert_eq!(kind("slides/lecture.ron"), Some(Kind::Deck));
        assert_eq!(kind("slides/problems/kepler.ron"), Some(Kind::Problem));
        assert_eq!(kind("slides/tableaux/rk4.ron"), Some(Kind::Tableau));
        assert_eq!(kind("scenes/water.ron"), Some(Kind::Scene));
        assert_eq!(kind("shaders/pbr.wgsl"), Some(Kind::Shader));
        for companion in [
            "lecture.tweaks.ron",
            "lecture.timings.ron",
            "lecture.ink.ron",
        ] {
            assert_eq!(kind(&format!("slides/{companion}")), None);
        }
    }
}
