//! The one source of project files: every deck, problem file, tableau, scene, picture and ink
//! file the app reads comes through [`read`], so the same loading code runs on the desktop
//! (files on disk, changes reported by [`crate::reload::DirWatcher`]) and in the web player (an
//! in-memory [`Bundle`] written by `lectern export --web`; it never changes, so the watcher
//! there reports nothing).
//!
//! Paths are the ones [`crate::paths`] resolves; a bundle stores them in the same lexical form,
//! so a deck that names `problems/a.ron` finds it in the bundle exactly where it found it on
//! disk.

use std::collections::HashMap;
use std::io;
use std::path::{Path, PathBuf};
use std::sync::{Arc, OnceLock};

/// Where project files come from: "read this file". (Being told when one changed is the
/// [`crate::reload::DirWatcher`]'s half; a bundle never changes.)
pub trait FileSource: Send + Sync {
    /// The file's bytes, or why not (missing, unreadable).
    fn read(&self, path: &Path) -> io::Result<Vec<u8>>;
    /// Whether `path` is a file this source can read.
    fn is_file(&self, path: &Path) -> bool;
    /// Whether `path` is a folder holding files of this source (a project's `shaders/`).
    fn is_dir(&self, path: &Path) -> bool;
    /// What names the file at `path` however the path is written (relative or absolute, with
    /// `.` and `..`, through symbolic links where the source has them): two paths are the same
    /// file exactly when their identities are equal ([`crate::reload::same_file`]). Without a
    /// disk there are no links: the lexical form, as a [`Bundle`] stores its paths.
    fn identity(&self, path: &Path) -> PathBuf {
        crate::paths::lexical(path)
    }
}

/// A path's identity on disk: canonical (links followed) where the file exists; while it is
/// momentarily gone (an editor's rename save) its canonical folder and its name, so a watcher's
/// event for the vanished file still names the same file; lexical when not even the folder is
/// there.
fn disk_identity(path: &Path) -> PathBuf {
    let lexical = crate::paths::lexical(path);
    if let Ok(real) = lexical.canonicalize() {
        return real;
    }
    match (lexical.parent(), lexical.file_name()) {
        (Some(dir), Some(name)) => dir
            .canonicalize()
            .map(|d| d.join(name))
            .unwrap_or_else(|_| lexical.clone()),
        _ => lexical,
    }
}

/// The files on disk (the desktop app, `lectern check`, `export`).
pub struct Disk;

impl FileSource for Disk {
    fn read(&self, path: &Path) -> io::Result<Vec<u8>> {
        std::fs::read(path)
    }
    fn is_file(&self, path: &Path) -> bool {
        path.is_file()
    }
    fn is_dir(&self, path: &Path) -> bool {
        path.is_dir()
    }
    fn identity(&self, path: &Path) -> PathBuf {
        disk_identity(path)
    }
}

/// Files held in memory, by path: the web player's copy of a project.
#[derive(Default, Clone)]
pub struct Bundle {
    files: HashMap<PathBuf, Arc<[u8]>>,
}

impl Bundle {
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds (or replaces) the file at `path`.
    pub fn insert(&mut self, path: impl AsRef<Path>, bytes: impl Into<Arc<[u8]>>) {
        self.files
            .insert(crate::paths::lexical(path.as_ref()), bytes.into());
    }

    pub fn len(&self) -> usize {
        self.files.len()
    }

    pub fn is_empty(&self) -> bool {
        self.files.is_empty()
    }
}

impl FileSource for Bundle {
    fn read(&self, path: &Path) -> io::Result<Vec<u8>> {
        self.files
            .get(&crate::paths::lexical(path))
            .map(|b| b.to_vec())
            .ok_or_else(|| {
                io::Error::new(
                    io::ErrorKind::NotFound,
                    format!("{} is not in the bundle", path.display()),
                )
            })
    }
    fn is_file(&self, path: &Path) -> bool {
        self.files.contains_key(&crate::paths::lexical(path))
    }
    /// A bundle has no folders of its own: one is there when a file lies under it.
    fn is_dir(&self, path: &Path) -> bool {
        let dir = crate::paths::lexical(path);
        (self.files.keys()).any(|f| f.starts_with(&dir) && *f != dir)
    }
}

/// The files on disk, noting every one read (`lectern export --web` bundles exactly the files
/// the deck's loading and drawing read).
#[derive(Default)]
pub struct Recording {
    read: std::sync::Mutex<std::collections::BTreeSet<PathBuf>>,
}

impl Recording {
    /// The files read so far (as asked for: resolved, absolute where the project's are).
    pub fn files_read(&self) -> Vec<PathBuf> {
        let read = self.read.lock().unwrap_or_else(|e| e.into_inner());
        read.iter().cloned().collect()
    }
}

impl FileSource for Recording {
    fn read(&self, path: &Path) -> io::Result<Vec<u8>> {
        let bytes = std::fs::read(path)?;
        self.read
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .insert(disk_identity(path));
        Ok(bytes)
    }
    fn is_file(&self, path: &Path) -> bool {
        path.is_file()
    }
    fn is_dir(&self, path: &Path) -> bool {
        path.is_dir()
    }
    fn identity(&self, path: &Path) -> PathBuf {
        disk_identity(path)
    }
}

impl<T: FileSource + ?Sized> FileSource for Arc<T> {
    fn read(&self, path: &Path) -> io::Result<Vec<u8>> {
        (**self).read(path)
    }
    fn is_file(&self, path: &Path) -> bool {
        (**self).is_file(path)
    }
    fn is_dir(&self, path: &Path) -> bool {
        (**self).is_dir(path)
    }
    fn identity(&self, path: &Path) -> PathBuf {
        (**self).identity(path)
    }
}

static INSTALLED: OnceLock<Box<dyn FileSource>> = OnceLock::new();

/// Makes `source` the process's source of project files, once, before anything is loaded (the
/// web player at start with its bundle; a test process with its own). Without it, [`Disk`].
pub fn install(source: impl FileSource + 'static) -> Result<(), &'static str> {
    INSTALLED
        .set(Box::new(source))
        .map_err(|_| "a source of project files is installed already")
}

/// The source in use.
pub fn source() -> &'static dyn FileSource {
    match INSTALLED.get() {
        Some(s) => s.as_ref(),
        None => &Disk,
    }
}

/// The bytes of the project file at `path`.
pub fn read(path: &Path) -> io::Result<Vec<u8>> {
    source().read(path)
}

/// The text of the project file at `path` (UTF-8).
pub fn read_to_string(path: &Path) -> io::Result<String> {
    String::from_utf8(read(path)?).map_err(|e| io::Error::new(io::ErrorKind::InvalidData, e))
}

/// What names the file at `path` in the source in use (see [`FileSource::identity`]).
pub fn identity(path: &Path) -> PathBuf {
    source().identity(path)
}

/// Whether the project file at `path` exists.
pub fn is_file(path: &Path) -> bool {
    source().is_file(path)
}

/// Whether the project folder at `path` exists (in a bundle: holds a file).
pub fn is_dir(path: &Path) -> bool {
    source().is_dir(path)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_bundle_finds_a_file_however_its_path_is_written() {
        let mut b = Bundle::new();
        b.insert("slides/problems/a.ron", b"(x: 1)".to_vec());
        for written in [
            "slides/problems/a.ron",
            "./slides/problems/a.ron",
            "slides/figures/../problems/a.ron",
        ] {
            assert_eq!(b.read(Path::new(written)).unwrap(), b"(x: 1)", "{written}");
            assert!(b.is_file(Path::new(written)));
        }
        let e = b.read(Path::new("slides/problems/b.ron")).unwrap_err();
        assert_eq!(e.kind(), io::ErrorKind::NotFound);
        assert!(!b.is_file(Path::new("slides/problems")));
        assert!(b.is_dir(Path::new("slides/problems")) && b.is_dir(Path::new("./slides")));
        assert!(!b.is_dir(Path::new("slides/problems/a.ron")) && !b.is_dir(Path::new("shaders")));
    }

    #[test]
    fn a_bundles_identity_is_lexical_and_tells_namesakes_apart() {
        // no disk behind a bundle: `.` and `..` fold, two folders stay two folders
        let b = Bundle::new();
        let id = |p: &str| b.identity(Path::new(p));
        assert_eq!(
            id("slides/../problems/x.ron"),
            id("./problems/x.ron"),
            "one file however it is written"
        );
        assert_ne!(id("shaders/common.wgsl"), id("other/common.wgsl"));
    }
}
