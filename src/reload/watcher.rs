//! Watching folders (not files: editors that save by rename kill a per-file inotify watch),
//! debounced so a burst of events per save becomes one change per path. In the web player the
//! files come from a bundle that never changes: the watcher there reports nothing.

use std::path::Path;

#[cfg(not(target_arch = "wasm32"))]
pub use disk::{DirWatcher, WatchError};
#[cfg(target_arch = "wasm32")]
pub use web::{DirWatcher, WatchError};

#[cfg(not(target_arch = "wasm32"))]
mod disk {
    use std::collections::BTreeSet;
    use std::path::{Path, PathBuf};
    use std::sync::mpsc::{Receiver, RecvTimeoutError, channel};
    use std::time::{Duration, Instant};

    use notify_debouncer_full::notify::{RecommendedWatcher, RecursiveMode};
    use notify_debouncer_full::{DebounceEventResult, Debouncer, RecommendedCache, new_debouncer};

    /// Why a folder could not be watched.
    pub type WatchError = notify_debouncer_full::notify::Error;

    /// Watches folders recursively; the events arrive on a channel and are read on the UI thread,
    /// so nothing is loaded (and no GPU object made) on the watcher's thread.
    pub struct DirWatcher {
        _debouncer: Debouncer<RecommendedWatcher, RecommendedCache>,
        rx: Receiver<DebounceEventResult>,
    }

    impl DirWatcher {
        /// Watches `dirs`; `wake` is called from the watcher thread after each batch (e.g.
        /// `ctx.request_repaint()`), so an idle UI still notices a save.
        pub fn new(
            dirs: &[&Path],
            debounce: Duration,
            wake: impl Fn() + Send + 'static,
        ) -> Result<Self, WatchError> {
            let (tx, rx) = channel();
            let mut debouncer = new_debouncer(debounce, None, move |res: DebounceEventResult| {
                let _ = tx.send(res);
                wake();
            })?;
            for dir in dirs {
                debouncer.watch(dir, RecursiveMode::Recursive)?;
            }
            Ok(Self {
                _debouncer: debouncer,
                rx,
            })
        }

        /// Non-blocking: the paths changed since the last call, each once, sorted.
        pub fn poll(&self) -> Vec<PathBuf> {
            let mut paths = BTreeSet::new();
            while let Ok(res) = self.rx.try_recv() {
                collect(res, &mut paths);
            }
            paths.into_iter().collect()
        }

        /// Blocks until at least one change arrives or `timeout` passes, then drains what is queued.
        pub fn wait(&self, timeout: Duration) -> Vec<PathBuf> {
            let deadline = Instant::now() + timeout;
            let mut paths = BTreeSet::new();
            loop {
                let left = deadline.saturating_duration_since(Instant::now());
                match self.rx.recv_timeout(left) {
                    Ok(res) => {
                        collect(res, &mut paths);
                        if !paths.is_empty() {
                            break;
                        }
                    }
                    Err(RecvTimeoutError::Timeout | RecvTimeoutError::Disconnected) => break,
                }
            }
            paths.extend(self.poll());
            paths.into_iter().collect()
        }
    }

    fn collect(res: DebounceEventResult, paths: &mut BTreeSet<PathBuf>) {
        match res {
            Ok(events) => {
                for ev in events {
                    if ev.kind.is_access() {
                        continue;
                    }
                    paths.extend(ev.event.paths.iter().cloned());
                }
            }
            Err(errors) => {
                for e in errors {
                    tracing::warn!("file watcher: {e}");
                }
            }
        }
    }
}

/// The web player's watcher: its bundle never changes, so no change is ever reported.
#[cfg(target_arch = "wasm32")]
mod web {
    use std::path::{Path, PathBuf};
    use std::time::Duration;

    /// Why a folder could not be watched (never, here).
    pub type WatchError = std::convert::Infallible;

    pub struct DirWatcher;

    impl DirWatcher {
        pub fn new(
            _dirs: &[&Path],
            _debounce: Duration,
            _wake: impl Fn() + Send + 'static,
        ) -> Result<Self, WatchError> {
            Ok(Self)
        }

        pub fn poll(&self) -> Vec<PathBuf> {
            Vec::new()
        }

        pub fn wait(&self, _timeout: Duration) -> Vec<PathBuf> {
            Vec::new()
        }
    }
}

/// What reading a just-changed file gave.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Settled {
    /// Non-empty text: parse it.
    Text(String),
    /// Empty or not valid UTF-8 yet (mid-save by a truncating editor): wait for the next event.
    NotReady,
    /// Gone (deleted, or renamed away mid-save): keep the last good version.
    Missing,
}

/// Reads a file the way a hot reloader should: an empty or half-written file is not an error.
pub fn read_settled(path: &Path) -> Settled {
    match crate::project_files::read(path) {
        Ok(bytes) if bytes.iter().all(u8::is_ascii_whitespace) => Settled::NotReady,
        Ok(bytes) => match String::from_utf8(bytes) {
            Ok(s) => Settled::Text(s),
            Err(_) => Settled::NotReady,
        },
        Err(_) => Settled::Missing,
    }
}
