//! What the `lectern` binary carries inside it (embedded by `build.rs` from the repository's
//! folders): the scene shaders, used when a project has no `shaders/` folder of its own, the
//! water scene, and the starter project `lectern new` writes.
//!
//! wgpu's pipelines, hot reload and `lectern check` all read shaders from a folder, so the
//! bundled shaders are written once to a folder of the user's cache
//! (`$XDG_CACHE_HOME/lectern/shaders-VERSION`, else `~/.cache/…`, else the temp folder) and
//! used from there: one way to load a shader, whichever set it is.

use std::path::{Path, PathBuf};

include!(concat!(env!("OUT_DIR"), "/bundled.rs"));

/// The water scene, as `scenes/water.ron` of the repository.
pub const WATER_SCENE: &str = include_str!("../scenes/water.ron");

/// The shader folder a scene is drawn with.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ShaderFolder {
    pub dir: PathBuf,
    /// The project has no `shaders/`: these are the ones built into lectern.
    pub bundled: bool,
}

/// The shader folder for the scene file at `scene_path`: the project's own `shaders/` when it
/// has one (the project folder found by [`crate::paths::project_root`]), else the bundled
/// shaders. An error only when the bundled ones cannot be written out.
pub fn shader_folder_for_scene(scene_path: &Path) -> Result<ShaderFolder, String> {
    let own = crate::paths::project_root(scene_path).join(crate::render::SHADER_DIR);
    if own.is_dir() {
        return Ok(ShaderFolder {
            dir: own,
            bundled: false,
        });
    }
    bundled_shader_dir().map(|dir| ShaderFolder { dir, bundled: true })
}

/// The bundled shaders written out (once per process; a file already there with the same
/// bytes is kept, so several lectern processes share the folder).
pub fn bundled_shader_dir() -> Result<PathBuf, String> {
    static DIR: std::sync::OnceLock<Result<PathBuf, String>> = std::sync::OnceLock::new();
    DIR.get_or_init(|| {
        let dir = cache_root().join(format!("shaders-{}", env!("CARGO_PKG_VERSION")));
        write_files(&dir, SHADERS)
            .map_err(|e| format!("cannot write the bundled shaders to {}: {e}", dir.display()))?;
        Ok(dir)
    })
    .clone()
}

fn cache_root() -> PathBuf {
    let from_env = |k: &str| {
        std::env::var_os(k)
            .filter(|v| !v.is_empty())
            .map(PathBuf::from)
    };
    from_env("XDG_CACHE_HOME")
        .or_else(|| from_env("HOME").map(|h| h.join(".cache")))
        .unwrap_or_else(std::env::temp_dir)
        .join("lectern")
}

/// Writes `files` (relative path, bytes) under `dir`, each through a temp file and an atomic
/// rename; a file that already holds the same bytes is left alone.
pub fn write_files(dir: &Path, files: &[(&str, &[u8])]) -> std::io::Result<()> {
    for (rel, bytes) in files {
        let path = dir.join(rel);
        if std::fs::read(&path).is_ok_and(|have| have == *bytes) {
            continue;
        }
        write_atomic(&path, bytes)?;
    }
    Ok(())
}

/// `bytes` to `path` through a temp file beside it and a rename (folders made as needed).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let parent = path.parent().unwrap_or(Path::new("."));
    std::fs::create_dir_all(parent)?;
    let tmp = parent.join(format!(
        ".{}.{}.tmp",
        path.file_name().and_then(|n| n.to_str()).unwrap_or("file"),
        std::process::id()
    ));
    std::fs::write(&tmp, bytes)?;
    std::fs::rename(&tmp, path)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_shader_of_the_repository_is_bundled_byte_for_byte() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("shaders");
        let on_disk = crate::render::shaders::list(&dir);
        assert_eq!(on_disk.len(), SHADERS.len());
        for path in on_disk {
            let name = path.file_name().unwrap().to_str().unwrap();
            let (_, bytes) = (SHADERS.iter().find(|(n, _)| *n == name))
                .unwrap_or_else(|| panic!("{name} is not bundled"));
            assert_eq!(*bytes, std::fs::read(&path).unwrap(), "{name}");
        }
    }

    #[test]
    fn a_project_without_shaders_gets_the_bundled_ones_and_one_with_them_its_own() {
        let p = tempfile::tempdir().unwrap();
        std::fs::create_dir_all(p.path().join("scenes")).unwrap();
        let scene = p.path().join("scenes/water.ron");
        let folder = shader_folder_for_scene(&scene).unwrap();
        assert!(folder.bundled);
        for (name, bytes) in SHADERS {
            assert_eq!(std::fs::read(folder.dir.join(name)).unwrap(), *bytes);
        }
        std::fs::create_dir_all(p.path().join("shaders")).unwrap();
        let folder = shader_folder_for_scene(&scene).unwrap();
        assert!(!folder.bundled);
        assert_eq!(folder.dir, p.path().canonicalize().unwrap().join("shaders"));
    }
}
