//! `lectern check`: validate decks, scenes, shaders, ODE problems and tableaux; print
//! `file:line:col: message` for each problem and a one-line summary.

use std::path::{Path, PathBuf};

use crate::deck::load_deck;
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

impl Kind {
    pub fn of(path: &Path) -> Option<Kind> {
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
    /// `slides/lecture.ron: 18 slides, 15:00 planned`
    pub deck_lines: Vec<String>,
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
            report.problems.push(Diagnostic::whole_file(
                path,
                "not a deck, scene, shader, problem or tableau (.ron or .wgsl)",
            ));
        }
        for file in files {
            check_file(&file, &mut report);
        }
    }
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

fn check_file(file: &Path, report: &mut Report) {
    let Some(kind) = Kind::of(file) else { return };
    report.counts[kind as usize] += 1;
    let result: Result<(), Vec<Diagnostic>> = match kind {
        Kind::Deck => match load_deck(file) {
            Ok(deck) => {
                report.deck_lines.push(format!(
                    "{}: {} slides, {} planned",
                    file.display(),
                    deck.slides.len(),
                    minutes(deck.planned_secs())
                ));
                // The files it names (confined to the project) and its formulas (typeset
                // within the same time and memory bounds as in the window).
                let text = std::fs::read_to_string(file).unwrap_or_default();
                let mut problems = crate::deck::files::check_deck_files(file, &text, &deck);
                problems.extend(crate::math::deck::check_formulas(file, &text, &deck));
                problems.sort_by_key(|d| (d.line, d.col));
                as_result(problems)
            }
            Err(d) => Err(vec![d]),
        },
        Kind::Scene => as_result(crate::scene::check_file(file)),
        Kind::Shader => as_result(crate::render::check_shader_file(file)),
        Kind::Problem => crate::ode::problem::Problem::load(file)
            .map(|_| ())
            .map_err(|d| vec![d]),
        Kind::Tableau => crate::ode::Tableau::load(file)
            .map(|_| ())
            .map_err(|d| vec![d]),
    };
    if let Err(mut ds) = result {
        report.problems.append(&mut ds);
    }
}

fn as_result(problems: Vec<Diagnostic>) -> Result<(), Vec<Diagnostic>> {
    if problems.is_empty() {
        Ok(())
    } else {
        Err(problems)
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
