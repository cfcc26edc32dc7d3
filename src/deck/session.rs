//! A deck being presented: the file (hot-reloaded through a folder watcher, last good version
//! kept) and the presenter's place in it. No UI types, so the whole reload path — editor saves,
//! debouncing, broken files, keeping the place — is driven by tests exactly as the app drives it.

use std::path::{Path, PathBuf};
use std::time::Duration;

use super::{Deck, Nav, parse_deck_file};
use crate::diag::Diagnostic;
use crate::reload::{DirWatcher, LiveFile, Reloaded};

pub struct DeckSession {
    live: LiveFile<Deck>,
    nav: Nav,
    watcher: Option<DirWatcher>,
    /// The deck a successful reload replaced, for whoever wants to compare (tweaks).
    replaced: Option<Deck>,
    /// Other files the watcher saw change (problem files widgets read), until taken.
    other_changes: Vec<PathBuf>,
}

impl DeckSession {
    /// Loads the deck at `path`; fails if it is missing or invalid (there is nothing to show).
    pub fn open(path: impl Into<PathBuf>) -> Result<Self, Diagnostic> {
        let live = LiveFile::open(path, parse_deck_file);
        let Some(deck) = live.value() else {
            return Err(live
                .error()
                .cloned()
                .unwrap_or_else(|| Diagnostic::whole_file(live.path(), "cannot load the deck")));
        };
        let nav = Nav::new(deck);
        Ok(Self {
            live,
            nav,
            watcher: None,
            replaced: None,
            other_changes: Vec::new(),
        })
    }

    /// Starts watching the deck's folder (recursively: images beside it count too). `wake` runs
    /// on the watcher's thread after each batch of changes, e.g. to request a repaint.
    pub fn watch(
        &mut self,
        debounce: Duration,
        wake: impl Fn() + Send + 'static,
    ) -> Result<(), String> {
        let dir = self.folder();
        let watcher = DirWatcher::new(&[dir.as_path()], debounce, wake)
            .map_err(|e| format!("cannot watch {}: {e}", dir.display()))?;
        self.watcher = Some(watcher);
        Ok(())
    }

    /// The folder the deck lives in (what is watched).
    pub fn folder(&self) -> PathBuf {
        match self.live.path().parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        }
    }

    /// Applies whatever the watcher has seen since the last call; never blocks. Returns the
    /// outcome for the deck file, or `None` if nothing touched it.
    pub fn pump(&mut self) -> Option<Reloaded> {
        self.pump_changes().1
    }

    /// [`Self::pump`], also handing back the changed paths (other files beside the deck, such
    /// as its ink, reload from the same watcher).
    pub fn pump_changes(&mut self) -> (Vec<PathBuf>, Option<Reloaded>) {
        let Some(watcher) = self.watcher.as_ref() else {
            return (Vec::new(), None);
        };
        let changed = watcher.poll();
        let outcome = self.apply_changed(&changed);
        (changed, outcome)
    }

    /// Waits up to `timeout` for the watcher to report changes, then applies them (for tests
    /// and command-line tools; the app uses [`Self::pump`]).
    pub fn wait(&mut self, timeout: Duration) -> Option<Reloaded> {
        let changed = self.watcher.as_ref()?.wait(timeout);
        self.apply_changed(&changed)
    }

    /// Applies a batch of changed paths (as a watcher reports them).
    pub fn apply_changed(&mut self, changed: &[PathBuf]) -> Option<Reloaded> {
        let deck = self.live.path().to_path_buf();
        let others = changed
            .iter()
            .filter(|p| !p.ends_with(&deck) && !deck.ends_with(p));
        self.other_changes.extend(others.cloned());
        if changed.is_empty() || !self.live.is_affected_by(changed) {
            return None;
        }
        let old = self.live.value().cloned();
        let outcome = self.live.on_changes(changed);
        if outcome == Reloaded::Updated
            && let Some(new) = self.live.value()
        {
            self.nav.on_reload(new);
            self.replaced = old;
        }
        Some(outcome)
    }

    /// The deck on screen: the last version that parsed.
    pub fn deck(&self) -> &Deck {
        self.live
            .value()
            .expect("a session always holds a deck: `open` refuses a file without one")
    }

    pub fn path(&self) -> &Path {
        self.live.path()
    }

    /// The error of the newest save, while it is broken.
    pub fn error(&self) -> Option<&Diagnostic> {
        self.live.error()
    }

    /// Bumped on every successful (re)load.
    pub fn generation(&self) -> u64 {
        self.live.generation()
    }

    pub fn nav(&self) -> &Nav {
        &self.nav
    }

    /// Moves through the deck: `session.navigate(|nav, deck| nav.next(deck))`.
    pub fn navigate<R>(&mut self, f: impl FnOnce(&mut Nav, &Deck) -> R) -> R {
        let deck = self.live.value().expect("a session always holds a deck");
        f(&mut self.nav, deck)
    }

    /// Files other than the deck that changed since the last call (e.g. problem files that
    /// widgets read: they re-read them).
    pub fn take_other_changes(&mut self) -> Vec<PathBuf> {
        std::mem::take(&mut self.other_changes)
    }

    /// The deck the last successful reload replaced (once; then `None`).
    pub fn take_replaced(&mut self) -> Option<Deck> {
        self.replaced.take()
    }
}
