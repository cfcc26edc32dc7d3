//! The ink of a deck as a file, `DECK.ink.ron` beside it: loaded at start, written after every
//! change (temp file + atomic rename), reloaded through [`LiveFile`] when it changes on disk.
//! A missing file is no ink; a damaged one is reported and ignored (never a reason not to
//! present), and is moved aside to `DECK.ink.ron.damaged` before the first write replaces it.

use std::path::{Path, PathBuf};

use super::ink::{Ink, Stroke, ink_file_path};
use super::write_back::write_atomic;
use crate::diag::Diagnostic;
use crate::reload::{LiveFile, Reloaded};

pub struct InkFile {
    live: LiveFile<Ink>,
    /// What is drawn and edited; the file follows it.
    ink: Ink,
    /// The newest problem: a damaged file, or a write that failed.
    problem: Option<Diagnostic>,
    /// The file on disk is damaged: keep a copy before overwriting it.
    damaged_on_disk: bool,
}

impl InkFile {
    /// The ink beside the deck at `deck_path` (none if there is no ink file yet).
    pub fn for_deck(deck_path: &Path) -> Self {
        Self::open(ink_file_path(deck_path))
    }

    pub fn open(path: PathBuf) -> Self {
        let exists = crate::project_files::is_file(&path);
        let live = LiveFile::open(path, Ink::parse);
        let ink = live.value().cloned().unwrap_or_default();
        let problem = if exists { live.error().cloned() } else { None };
        if let Some(p) = &problem {
            tracing::warn!("ink ignored: {p}");
        }
        Self {
            damaged_on_disk: problem.is_some(),
            live,
            ink,
            problem,
        }
    }

    pub fn path(&self) -> &Path {
        self.live.path()
    }

    pub fn ink(&self) -> &Ink {
        &self.ink
    }

    /// Why the file's ink is not shown, or the last write failed.
    pub fn problem(&self) -> Option<&Diagnostic> {
        self.problem.as_ref()
    }

    /// Takes a batch of changed paths (from the deck folder's watcher); true if the ink on
    /// screen changed. The app's own writes are not reloads.
    pub fn on_changes(&mut self, changed: &[PathBuf]) -> bool {
        if !self.live.is_affected_by(changed) {
            return false;
        }
        match self.live.on_changes(changed) {
            Reloaded::Updated => {
                self.ink = self.live.value().cloned().unwrap_or_default();
                self.problem = None;
                self.damaged_on_disk = false;
                true
            }
            // Deleted on disk: the ink on screen stays, and comes back with the next stroke.
            Reloaded::Failed(_) if !crate::project_files::is_file(self.live.path()) => false,
            Reloaded::Failed(d) => {
                tracing::warn!("ink file ignored: {d}");
                self.problem = Some(d);
                self.damaged_on_disk = true;
                false
            }
            Reloaded::Untouched | Reloaded::Waiting => false,
        }
    }

    /// Adds a stroke to slide `key` and writes the file.
    pub fn add(&mut self, key: &str, stroke: Stroke) -> Result<(), Diagnostic> {
        self.ink.add(key, stroke);
        self.save()
    }

    /// Removes the newest stroke of slide `key`; writes the file if there was one.
    pub fn undo(&mut self, key: &str) -> Result<bool, Diagnostic> {
        if self.ink.undo(key).is_none() {
            return Ok(false);
        }
        self.save().map(|()| true)
    }

    /// Removes all strokes of slide `key`; writes the file if there were any.
    pub fn clear(&mut self, key: &str) -> Result<usize, Diagnostic> {
        let n = self.ink.clear(key);
        if n > 0 {
            self.save()?;
        }
        Ok(n)
    }

    /// Writes the ink to the file (temp file + atomic rename).
    pub fn save(&mut self) -> Result<(), Diagnostic> {
        let path = self.live.path().to_path_buf();
        if self.damaged_on_disk {
            let mut aside = path.clone().into_os_string();
            aside.push(".damaged");
            if let Err(e) = std::fs::rename(&path, &aside) {
                tracing::warn!("cannot keep the damaged {}: {e}", path.display());
            }
            self.damaged_on_disk = false;
        }
        let text = self.ink.to_ron();
        let result = write_atomic(&path, &text)
            .map_err(|e| Diagnostic::whole_file(&path, format!("cannot write the ink: {e}")));
        match &result {
            Ok(()) => {
                self.live.note_written(text);
                self.problem = None;
            }
            Err(d) => self.problem = Some(d.clone()),
        }
        result
    }
}
