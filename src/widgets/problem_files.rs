//! The problem files the deck's widgets read (`ode: File("problems/forced.ron")`) while
//! presenting: one [`LiveFile`] per file, however many widgets on however many slides use it —
//! the one holder of its last good version. A widget is made from that version (never by reading
//! the file itself again); a save that breaks the file leaves every widget drawing the last good
//! equation with the file's error at its line and column; a save with the same bytes, or one
//! caught half-written, changes nothing.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use crate::deck::widgets::{LoadedOde, OdeError, OdeSource};
use crate::reload::{LiveFile, Reloaded, file_key};

/// Where a widget being made reads its files: its problem and tableau files relative to the
/// deck at `deck_path`, and, while presenting, the problem files' last good versions from
/// `problems` instead of the disk.
#[derive(Clone, Copy, Default)]
pub struct MadeIn<'a> {
    pub deck_path: Option<&'a Path>,
    pub problems: Option<&'a ProblemFiles>,
}

impl<'a> MadeIn<'a> {
    /// Files read from the disk (the project's source of files) as the widget is made: the
    /// exports, `lectern check`, tests.
    pub fn deck(deck_path: Option<&'a Path>) -> Self {
        Self {
            deck_path,
            problems: None,
        }
    }

    /// `source` loaded: from its file's holder when there is one (with the file's newest error,
    /// if that save is broken), otherwise read now.
    pub fn load(&self, source: &OdeSource) -> (Result<LoadedOde, OdeError>, Option<String>) {
        if let (Some(problems), Some(Ok(file))) = (self.problems, source.file(self.deck_path))
            && let Some(live) = problems.files.get(&file_key(&file))
        {
            let error = live.error().map(ToString::to_string);
            return match live.value() {
                Some(loaded) => (Ok(loaded.clone()), error),
                None => (
                    Err(OdeError::InFile(live.error().cloned().unwrap_or_else(
                        || crate::diag::Diagnostic::whole_file(&file, "the problem did not load"),
                    ))),
                    None,
                ),
            };
        }
        (source.load(self.deck_path), None)
    }
}

/// What one batch of changed paths did to a problem file (by its [`file_key`]).
pub type FileOutcomes = Vec<(PathBuf, Reloaded)>;

#[derive(Default)]
pub struct ProblemFiles {
    /// by [`file_key`]
    files: HashMap<PathBuf, LiveFile<LoadedOde>>,
}

fn parse(text: &str, file: &Path) -> Result<LoadedOde, crate::diag::Diagnostic> {
    OdeSource::from_file(text, file).map_err(|e| match e {
        OdeError::InFile(d) => d,
        OdeError::InDeck(e) => crate::diag::Diagnostic::whole_file(file, e.message),
    })
}

impl ProblemFiles {
    /// Opens `source`'s file (read once, here) if it is a problem file not held yet.
    pub fn open(&mut self, source: &OdeSource, deck_path: Option<&Path>) {
        let Some(Ok(file)) = source.file(deck_path) else {
            return;
        };
        self.files
            .entry(file_key(&file))
            .or_insert_with(|| LiveFile::open(file, parse));
    }

    /// Takes a batch of changed paths: each held file among them is re-read once.
    pub fn on_changes(&mut self, changed: &[PathBuf]) -> FileOutcomes {
        (self.files.iter_mut())
            .filter(|(_, live)| live.is_affected_by(changed))
            .map(|(key, live)| (key.clone(), live.on_changes(changed)))
            .collect()
    }

    /// The file held for `file` (tests, the presenter).
    pub fn get(&self, file: &Path) -> Option<&LiveFile<LoadedOde>> {
        self.files.get(&file_key(file))
    }

    pub fn len(&self) -> usize {
        self.files.len()
    }

    pub fn is_empty(&self) -> bool {
        self.files.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const GOOD: &str = r#"(vars: ["x"], rhs: ["-k*x"], initial: [1.0], params: {"k": 2.0})"#;

    #[test]
    fn one_read_per_file_and_a_broken_save_keeps_the_last_good_version() {
        let dir = tempfile::tempdir().unwrap();
        let deck = dir.path().join("deck.ron");
        let file = dir.path().join("p.ron");
        std::fs::write(&file, GOOD).unwrap();
        let source = OdeSource::File("p.ron".into());
        let mut files = ProblemFiles::default();
        files.open(&source, Some(&deck));
        // a second widget naming the file another way shares the holder
        files.open(&OdeSource::File("./p.ron".into()), Some(&deck));
        assert_eq!(files.len(), 1);
        let at = MadeIn {
            deck_path: Some(&deck),
            problems: Some(&files),
        };
        // the file changes on disk, unseen: widgets are still made from the held version
        std::fs::write(&file, GOOD.replace("2.0", "3.0")).unwrap();
        let (loaded, error) = at.load(&source);
        assert_eq!(loaded.unwrap().def.params["k"], 2.0);
        assert!(error.is_none());

        std::fs::write(&file, GOOD.replace("-k*x", "-k*q")).unwrap();
        let outcomes = files.on_changes(std::slice::from_ref(&file));
        assert!(matches!(outcomes.as_slice(), [(_, Reloaded::Failed(_))]));
        let at = MadeIn {
            deck_path: Some(&deck),
            problems: Some(&files),
        };
        let (loaded, error) = at.load(&source);
        assert_eq!(loaded.unwrap().def.rhs, vec!["-k*x".to_string()]);
        let error = error.expect("the broken save's error");
        assert!(error.contains("p.ron:1:"), "{error}");
        assert!(error.contains("unknown name"), "{error}");

        // the same bytes again: nothing to do; fixed: the new version
        let outcomes = files.on_changes(std::slice::from_ref(&file));
        assert!(matches!(outcomes.as_slice(), [(_, Reloaded::Untouched)]));
        std::fs::write(&file, GOOD.replace("2.0", "4.0")).unwrap();
        let outcomes = files.on_changes(&[dir.path().join("other.ron"), file.clone()]);
        assert!(matches!(outcomes.as_slice(), [(_, Reloaded::Updated)]));
        let at = MadeIn {
            deck_path: Some(&deck),
            problems: Some(&files),
        };
        let (loaded, error) = at.load(&source);
        assert_eq!(loaded.unwrap().def.params["k"], 4.0);
        assert!(error.is_none());
    }

    #[test]
    fn a_file_that_never_loaded_says_why_and_inline_sources_need_no_holder() {
        let dir = tempfile::tempdir().unwrap();
        let deck = dir.path().join("deck.ron");
        std::fs::write(dir.path().join("bad.ron"), "(vars: [").unwrap();
        let source = OdeSource::File("bad.ron".into());
        let mut files = ProblemFiles::default();
        files.open(&source, Some(&deck));
        let inline: OdeSource = ron::from_str(&format!("Inline({GOOD})")).unwrap();
        files.open(&inline, Some(&deck));
        assert_eq!(files.len(), 1);
        let at = MadeIn {
            deck_path: Some(&deck),
            problems: Some(&files),
        };
        let (loaded, _) = at.load(&source);
        let message = loaded.err().unwrap().message();
        assert!(message.contains("bad.ron:1:"), "{message}");
        assert!(at.load(&inline).0.is_ok());
    }
}
