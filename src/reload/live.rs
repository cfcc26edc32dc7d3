//! One watched file and its last good model: the piece between "a path changed" and "the app
//! shows the new version or an error". Generic over the model, so decks, scenes and problems
//! reload the same way, and pure enough to be driven by tests with no window.

use std::path::{Path, PathBuf};

use super::{LastGood, Settled, read_settled};
use crate::diag::Diagnostic;

/// Parses a file's text; the path only names the file in errors and resolves relative paths.
pub type Parser<T> = fn(&str, &Path) -> Result<T, Diagnostic>;

/// What one batch of changed paths did to a [`LiveFile`].
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Reloaded {
    /// None of the paths is this file (or its content did not change).
    Untouched,
    /// A new valid version replaced the old one.
    Updated,
    /// The new version is invalid; the last good one stays and the error is recorded.
    Failed(Diagnostic),
    /// Empty or half-written: nothing done, the next event will bring the rest.
    Waiting,
}

pub struct LiveFile<T> {
    path: PathBuf,
    /// `path`'s [`super::file_key`], once, to compare with what the watcher reports.
    key: PathBuf,
    parse: Parser<T>,
    holder: LastGood<Option<T>>,
    /// The text of the last version parsed (good or bad), so a save with unchanged bytes
    /// (editors touch files; watchers send duplicates) is not a reload.
    last_text: Option<String>,
}

impl<T> LiveFile<T> {
    /// Loads `path` now. A missing or invalid file gives a holder with no value and the error,
    /// which the caller may treat as fatal at start-up.
    pub fn open(path: impl Into<PathBuf>, parse: Parser<T>) -> Self {
        let path = path.into();
        let key = super::file_key(&path);
        let mut live = Self {
            path,
            key,
            parse,
            holder: LastGood::default(),
            last_text: None,
        };
        match read_settled(&live.path) {
            Settled::Text(_) => {
                live.reload();
            }
            Settled::NotReady => live
                .holder
                .update_some(Err(Diagnostic::whole_file(&live.path, "the file is empty"))),
            Settled::Missing => live.holder.update_some(Err(Diagnostic::whole_file(
                &live.path,
                "cannot read the file (missing or no permission)",
            ))),
        }
        live
    }

    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The last good version, if there ever was one.
    pub fn value(&self) -> Option<&T> {
        self.holder.value().as_ref()
    }

    pub fn value_mut(&mut self) -> Option<&mut T> {
        self.holder.value_mut().as_mut()
    }

    /// The error of the newest version, if it is broken.
    pub fn error(&self) -> Option<&Diagnostic> {
        self.holder.error()
    }

    /// Bumped on every successful load.
    pub fn generation(&self) -> u64 {
        self.holder.generation()
    }

    /// Tells the holder that the app itself just wrote `text` to the file (files the app edits,
    /// like ink): the watcher's echo of that write is then not a reload.
    pub fn note_written(&mut self, text: String) {
        self.last_text = Some(text);
    }

    /// Whether any of `changed` (as reported by a [`super::DirWatcher`]) is this file.
    pub fn is_affected_by(&self, changed: &[PathBuf]) -> bool {
        super::any_is(changed, &self.key)
    }

    /// Takes a batch of changed paths; reloads if this file is among them.
    pub fn on_changes(&mut self, changed: &[PathBuf]) -> Reloaded {
        if self.is_affected_by(changed) {
            self.reload()
        } else {
            Reloaded::Untouched
        }
    }

    /// Re-reads the file now, whatever the watcher said.
    pub fn reload(&mut self) -> Reloaded {
        let text = match read_settled(&self.path) {
            Settled::Text(t) => t,
            Settled::NotReady => return Reloaded::Waiting,
            Settled::Missing => {
                // Mid-rename by an editor, or deleted: keep showing the last good version, and
                // say so; the notice goes when the file is back.
                let d = Diagnostic::whole_file(
                    &self.path,
                    "the file is gone; showing the last good version",
                );
                self.last_text = None;
                self.holder.update_some(Err(d.clone()));
                return Reloaded::Failed(d);
            }
        };
        if self.last_text.as_deref() == Some(text.as_str()) {
            return Reloaded::Untouched;
        }
        let result = (self.parse)(&text, &self.path);
        self.last_text = Some(text);
        match result {
            Ok(v) => {
                self.holder.update_some(Ok(v));
                Reloaded::Updated
            }
            Err(d) => {
                self.holder.update_some(Err(d.clone()));
                Reloaded::Failed(d)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse_num(text: &str, file: &Path) -> Result<u32, Diagnostic> {
        text.trim()
            .parse()
            .map_err(|_| Diagnostic::new(file, 1, 1, "not a number"))
    }

    #[test]
    fn broken_then_fixed() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("n.txt");
        std::fs::write(&path, "1").unwrap();
        let mut live = LiveFile::open(&path, parse_num);
        assert_eq!(live.value(), Some(&1));
        std::fs::write(&path, "x").unwrap();
        assert!(matches!(
            live.on_changes(std::slice::from_ref(&path)),
            Reloaded::Failed(_)
        ));
        assert_eq!(live.value(), Some(&1));
        std::fs::write(&path, "").unwrap();
        assert_eq!(
            live.on_changes(std::slice::from_ref(&path)),
            Reloaded::Waiting
        );
        assert!(live.error().is_some(), "waiting keeps the last error");
        std::fs::write(&path, "2").unwrap();
        assert_eq!(
            live.on_changes(std::slice::from_ref(&path)),
            Reloaded::Updated
        );
        assert_eq!(live.value(), Some(&2));
        assert!(live.error().is_none());
        let other = dir.path().join("other.txt");
        assert_eq!(live.on_changes(&[other]), Reloaded::Untouched);
    }
}
