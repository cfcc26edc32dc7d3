//! Live reload: watch folders, debounce, and keep the last good version of each file's model.

mod last_good;
mod live;
mod watcher;

pub use last_good::LastGood;
pub use live::{LiveFile, Parser, Reloaded};
pub use watcher::{DirWatcher, Settled, WatchError, read_settled};
