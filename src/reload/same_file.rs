//! The one rule for "is this the same file", for every place a changed path (the watcher's,
//! absolute) is matched with a file in use (written in a deck or scene: relative, with `..`,
//! perhaps through a symbolic link): both sides become their identity in the source of project
//! files ([`crate::project_files::identity`]: canonical on disk, lexical in the web player's
//! bundle), and are equal or not. Never by file name: two `common.wgsl` in two shader folders
//! are two files.

use std::path::{Path, PathBuf};

/// A file's identity, to compare many changed paths with it (see [`same_file`]).
pub fn file_key(path: &Path) -> PathBuf {
    crate::project_files::identity(path)
}

/// Whether `a` and `b` name the same file.
pub fn same_file(a: &Path, b: &Path) -> bool {
    a == b || file_key(a) == file_key(b)
}

/// Whether any of `changed` names the file whose [`file_key`] is `key`.
pub fn any_is(changed: &[PathBuf], key: &Path) -> bool {
    changed.iter().any(|c| file_key(c) == key)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn relative_absolute_dotdot_and_links_are_one_file_and_a_namesake_is_not() {
        let dir = tempfile::tempdir().unwrap();
        let root = dir.path();
        for sub in ["slides", "problems", "other"] {
            std::fs::create_dir_all(root.join(sub)).unwrap();
        }
        std::fs::write(root.join("problems/x.ron"), "()").unwrap();
        std::fs::write(root.join("other/x.ron"), "()").unwrap();
        let watched = root.canonicalize().unwrap().join("problems/x.ron");
        // as a deck in slides/ writes it, made absolute by joining (not resolving)
        let written = root.join("slides/../problems/x.ron");
        assert!(same_file(&written, &watched));
        assert!(!same_file(&root.join("other/x.ron"), &watched));
        assert!(any_is(
            &[root.join("other/x.ron"), written.clone()],
            &file_key(&watched)
        ));
        assert!(!any_is(&[root.join("other/x.ron")], &file_key(&watched)));
        #[cfg(unix)]
        {
            std::os::unix::fs::symlink(root.join("problems"), root.join("linked")).unwrap();
            assert!(same_file(&root.join("linked/x.ron"), &watched));
        }
        // gone mid-save (renamed away): still the same file by its folder and name
        std::fs::remove_file(root.join("problems/x.ron")).unwrap();
        assert!(same_file(&written, &watched));
        assert!(!same_file(&root.join("other/x.ron"), &watched));
    }

    #[test]
    fn a_relative_path_is_taken_against_the_current_folder() {
        let here = std::env::current_dir().unwrap().join("Cargo.toml");
        assert!(same_file(Path::new("Cargo.toml"), &here));
        assert!(same_file(Path::new("./src/../Cargo.toml"), &here));
        assert!(!same_file(Path::new("src/Cargo.toml"), &here));
    }
}
