//! The one way a path written in a deck or scene becomes a file on disk: relative to the file
//! that names it, and confined to the project folder. A deck from a colleague or a student can
//! therefore not show (or export into a handout) any other file on the lecturer's disk.
//!
//! The project folder is the folder holding the deck's `slides/` (or the scene's `scenes/`),
//! else the naming file's own folder. Absolute paths, `..` that climbs out, and symbolic links
//! that lead outside are refused, each with a message saying why. Whether the file exists is
//! the caller's question ([`resolve`] only decides where it would be and whether it may be read).

use std::fmt;
use std::path::{Component, Path, PathBuf};

/// Why a written path was refused.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum PathError {
    Empty,
    /// `/etc/passwd`, `C:\…`
    Absolute(String),
    /// `../../x`: climbs above the project folder.
    Escapes {
        written: String,
        root: PathBuf,
    },
    /// Inside the project by name, but a symbolic link on the way leads outside.
    LinksOutside {
        written: String,
        target: PathBuf,
    },
}

impl fmt::Display for PathError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PathError::Empty => write!(f, "the path is empty"),
            PathError::Absolute(p) => write!(
                f,
                "`{p}` is an absolute path; write it relative to the deck's folder (files must be inside the project)"
            ),
            PathError::Escapes { written, root } => write!(
                f,
                "`{written}` leads outside the project folder {}; only files inside it can be used",
                root.display()
            ),
            PathError::LinksOutside { written, target } => write!(
                f,
                "`{written}` is a symbolic link to {}, outside the project folder; only files inside it can be used",
                target.display()
            ),
        }
    }
}

impl std::error::Error for PathError {}

/// The project folder for a file (deck, scene, ink or tweak file) at `file`: the parent of its
/// `slides/` or `scenes/` folder when it sits in one, else the file's own folder. The file's
/// path is made absolute first (symbolic links followed where it exists), so the answer does not
/// depend on how the path was typed: `~/talk/slides/a.ron`, `./slides/a.ron` and, from inside
/// `slides/`, `a.ron` all give `~/talk`.
pub fn project_root(file: &Path) -> PathBuf {
    let file = absolute(file);
    let dir = file.parent().unwrap_or(Path::new("/"));
    let in_project_subdir = dir
        .file_name()
        .is_some_and(|n| n == "slides" || n == "scenes");
    let root = if in_project_subdir {
        dir.parent().unwrap_or(dir)
    } else {
        dir
    };
    root.to_path_buf()
}

/// `file` as an absolute path: canonical when it (or its folder) exists, else lexically
/// against the current directory.
fn absolute(file: &Path) -> PathBuf {
    if let Ok(real) = file.canonicalize() {
        return real;
    }
    let parent = file.parent().filter(|p| !p.as_os_str().is_empty());
    let dir = parent.unwrap_or(Path::new("."));
    match (dir.canonicalize(), file.file_name()) {
        (Ok(real_dir), Some(name)) => real_dir.join(name),
        _ => lexical(file),
    }
}

/// Resolves `written` (as it appears in the file at `naming_file`) against that file's folder,
/// confined to [`project_root`]`(naming_file)`.
pub fn resolve_for(naming_file: &Path, written: &str) -> Result<PathBuf, PathError> {
    let naming_file = absolute(naming_file);
    let base = naming_file.parent().unwrap_or(Path::new("/"));
    resolve(base, &project_root(&naming_file), written)
}

/// Like [`resolve_for`], for a file named from inside the folder `naming_dir` (a widget knows
/// its deck's folder, not the deck file).
pub fn resolve_in(naming_dir: &Path, written: &str) -> Result<PathBuf, PathError> {
    resolve_for(&naming_dir.join("_"), written)
}

/// Resolves `written` against `base_dir`, refusing anything that is not inside `root`.
pub fn resolve(base_dir: &Path, root: &Path, written: &str) -> Result<PathBuf, PathError> {
    if written.trim().is_empty() {
        return Err(PathError::Empty);
    }
    let rel = Path::new(written);
    if rel.has_root()
        || rel.is_absolute()
        || rel.components().any(|c| matches!(c, Component::Prefix(_)))
    {
        return Err(PathError::Absolute(written.to_string()));
    }
    let escapes = || PathError::Escapes {
        written: written.to_string(),
        root: lexical(root),
    };
    // Lexically: where is `base_dir/written` relative to `root`? `base_dir` must be in `root`.
    let base_in_root = lexical(base_dir)
        .strip_prefix(lexical(root))
        .map(Path::to_path_buf)
        .map_err(|_| escapes())?;
    let mut inside: Vec<&std::ffi::OsStr> = Vec::new();
    for c in base_in_root.components().chain(rel.components()) {
        match c {
            Component::Normal(name) => inside.push(name),
            Component::CurDir => {}
            Component::ParentDir => {
                if inside.pop().is_none() {
                    return Err(escapes());
                }
            }
            Component::RootDir | Component::Prefix(_) => {
                return Err(PathError::Absolute(written.to_string()));
            }
        }
    }
    let mut full = root.to_path_buf();
    full.extend(inside);
    // Symbolic links: the deepest existing part of the path, with links followed, must still
    // be inside the (also canonical) root.
    if let Ok(canon_root) = root.canonicalize() {
        let mut probe = full.as_path();
        loop {
            if let Ok(real) = probe.canonicalize() {
                if !real.starts_with(&canon_root) {
                    return Err(PathError::LinksOutside {
                        written: written.to_string(),
                        target: real,
                    });
                }
                break;
            }
            match probe.parent() {
                Some(p) => probe = p,
                None => break,
            }
        }
    }
    Ok(full)
}

/// `p` with `.` removed and `x/..` folded, without touching the disk; relative paths are taken
/// against the current directory so that `slides` and `./slides/..` compare equal to their
/// absolute forms (in a browser, which has none, they stay relative).
pub fn lexical(p: &Path) -> PathBuf {
    let abs = if p.is_absolute() {
        p.to_path_buf()
    } else {
        std::env::current_dir().unwrap_or_default().join(p)
    };
    let mut out = PathBuf::new();
    for c in abs.components() {
        match c {
            Component::CurDir => {}
            Component::ParentDir => {
                out.pop();
            }
            other => out.push(other),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn project() -> tempfile::TempDir {
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir_all(dir.path().join("slides/figures")).unwrap();
        std::fs::create_dir_all(dir.path().join("assets")).unwrap();
        std::fs::write(dir.path().join("slides/figures/a.png"), b"x").unwrap();
        std::fs::write(dir.path().join("assets/b.png"), b"x").unwrap();
        dir
    }

    #[test]
    fn the_project_root_is_above_slides_and_scenes() {
        assert_eq!(
            project_root(Path::new("/p/slides/lecture.ron")),
            Path::new("/p")
        );
        assert_eq!(
            project_root(Path::new("/p/scenes/water.ron")),
            Path::new("/p")
        );
        assert_eq!(
            project_root(Path::new("/tmp/talk/deck.ron")),
            Path::new("/tmp/talk")
        );
        let cwd = std::env::current_dir().unwrap().canonicalize().unwrap();
        assert_eq!(project_root(Path::new("deck.ron")), cwd);
    }

    #[test]
    fn paths_inside_the_project_resolve_including_subfolders_and_siblings() {
        let p = project();
        let deck = p.path().join("slides/lecture.ron");
        let a = resolve_for(&deck, "figures/a.png").unwrap();
        assert!(a.is_file(), "{}", a.display());
        let b = resolve_for(&deck, "../assets/b.png").unwrap();
        assert!(b.is_file(), "{}", b.display());
        let c = resolve_for(&deck, "./figures/../figures/a.png").unwrap();
        assert!(c.is_file());
        // a missing file inside the project is not refused here: the caller reports it
        assert!(resolve_for(&deck, "figures/missing.png").is_ok());
    }

    #[test]
    fn escapes_are_refused() {
        let p = project();
        let deck = p.path().join("slides/lecture.ron");
        assert!(matches!(
            resolve_for(&deck, "../../../../etc/passwd"),
            Err(PathError::Escapes { .. })
        ));
        assert!(matches!(
            resolve_for(&deck, "/etc/passwd"),
            Err(PathError::Absolute(_))
        ));
        assert!(matches!(resolve_for(&deck, ""), Err(PathError::Empty)));
        assert!(matches!(
            resolve_for(&deck, "figures/../../.."),
            Err(PathError::Escapes { .. })
        ));
        let msg = resolve_for(&deck, "../../x.png").unwrap_err().to_string();
        assert!(msg.contains("outside the project"), "{msg}");
    }

    #[cfg(unix)]
    #[test]
    fn symlinks_leading_outside_are_refused_and_inside_ones_work() {
        let p = project();
        let outside = tempfile::tempdir().unwrap();
        std::fs::write(outside.path().join("secret.png"), b"x").unwrap();
        let figs = p.path().join("slides/figures");
        std::os::unix::fs::symlink(outside.path().join("secret.png"), figs.join("s.png")).unwrap();
        std::os::unix::fs::symlink(outside.path(), figs.join("out")).unwrap();
        std::os::unix::fs::symlink(figs.join("a.png"), figs.join("in.png")).unwrap();
        let deck = p.path().join("slides/lecture.ron");
        for bad in [
            "figures/s.png",
            "figures/out/secret.png",
            "figures/out/missing.png",
        ] {
            assert!(
                matches!(resolve_for(&deck, bad), Err(PathError::LinksOutside { .. })),
                "{bad}"
            );
        }
        assert!(resolve_for(&deck, "figures/in.png").is_ok());
    }
}
