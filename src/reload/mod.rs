//! Live reload: watch folders, debounce, and keep the last good version of each file's model.

mod last_good;
mod live;
mod same_file;
mod watcher;

/// Quiet time after a save before a changed file is re-read, for every watcher of the app
/// (decks, problem files, scenes, shaders): editors write a file in several events, a rename
/// save within a few milliseconds.
pub const DEBOUNCE: std::time::Duration = std::time::Duration::from_millis(50);

pub use last_good::LastGood;
pub use live::{LiveFile, Parser, Reloaded};
pub use same_file::{any_is, file_key, same_file};
pub use watcher::{DirWatcher, Settled, WatchError, read_settled};
