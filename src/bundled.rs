//! What the `lectern` binary carries inside it (embedded by `build.rs` from the repository's
//! folders): the scene shaders, used when a project has no `shaders/` folder of its own, the
//! water scene, used when a project has a scene widget but no scene file, and the starter
//! project `lectern new` writes.
//!
//! wgpu's pipelines, hot reload and `lectern check` all read shaders and scenes from files, so
//! the bundled ones are written once to a folder of the user's cache
//! (`$XDG_CACHE_HOME/lectern/bundled-VERSION/{shaders,scenes}`, else `~/.cache/…`, else the
//! temp folder) and used from there: one way to load a shader or a scene, whichever set it is.
//! Folders of other versions beside it are removed when it is written.

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
    // (the bundled scene's own folder holds the bundled shaders: those count as bundled)
    let in_bundled = own.starts_with(bundled_root_path());
    // (through the project's files: in the web player a bundle path, never the disk)
    if crate::project_files::is_dir(&own) && !in_bundled {
        return Ok(ShaderFolder {
            dir: own,
            bundled: false,
        });
    }
    if cfg!(target_arch = "wasm32") {
        // export puts the bundled shaders under `shaders/` ([`in_bundled_folder`]): none there
        // means a page that was not written by `export --web`
        return Err(format!(
            "the page has no shaders (no {} in its bundle): export it again",
            own.display()
        ));
    }
    bundled_shader_dir().map(|dir| ShaderFolder { dir, bundled: true })
}

/// `path` relative to the folder the bundled files are written to (`shaders/pbr.wgsl`,
/// `scenes/water.ron`), when it is one of them: `export --web` puts them into the page at that
/// path of the project, where the player looks for a project's own.
pub fn in_bundled_folder(path: &Path) -> Option<PathBuf> {
    let root = bundled_root_path();
    let real = root.canonicalize().unwrap_or(root);
    (path.strip_prefix(&real).ok()).map(Path::to_path_buf)
}

/// The bundled shaders written out (once per process; a file already there with the same
/// bytes is kept, so several lectern processes share the folder).
pub fn bundled_shader_dir() -> Result<PathBuf, String> {
    bundled_root().map(|root| root.join(crate::render::SHADER_DIR))
}

/// The scene file a scene widget (or scene mode) draws: `resolved`, the file `written` names
/// in the project; or, when that is the default scene (`../scenes/water.ron`) and the project
/// has no such file, the water scene built into lectern (`bundled` set, for `check`'s note).
/// Its shaders are then looked up from the bundled scene's folder: the bundled ones.
pub fn scene_file(
    resolved: Result<PathBuf, crate::paths::PathError>,
    written: &str,
) -> Result<SceneFile, String> {
    let is_default = written == crate::deck::widgets::scene::default_scene();
    match resolved {
        Ok(path) if crate::project_files::is_file(&path) || !is_default => Ok(SceneFile {
            path,
            bundled: false,
        }),
        Err(e) if !is_default => Err(e.to_string()),
        _ => bundled_scene_file().map(|path| SceneFile {
            path,
            bundled: true,
        }),
    }
}

/// A scene file to draw, and whether it is the one built into lectern.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SceneFile {
    pub path: PathBuf,
    pub bundled: bool,
}

/// The bundled water scene written out, as `scenes/water.ron` in the bundled folder.
pub fn bundled_scene_file() -> Result<PathBuf, String> {
    bundled_root().map(|root| root.join(crate::scene::DEFAULT_SCENE))
}

/// The bundled files' folder, written out once per process (a file already there with the
/// same bytes is kept, so several lectern processes share it); other versions' folders are
/// removed then.
fn bundled_root() -> Result<PathBuf, String> {
    static DIR: std::sync::OnceLock<Result<PathBuf, String>> = std::sync::OnceLock::new();
    DIR.get_or_init(|| {
        let root = bundled_root_path();
        let cache = cache_root();
        let name = format!("{BUNDLED_PREFIX}{}", env!("CARGO_PKG_VERSION"));
        let shaders = root.join(crate::render::SHADER_DIR);
        write_files(&shaders, SHADERS).map_err(|e| {
            format!(
                "cannot write the bundled shaders to {}: {e}",
                shaders.display()
            )
        })?;
        let scene = [(crate::scene::DEFAULT_SCENE, WATER_SCENE.as_bytes())];
        write_files(&root, &scene)
            .map_err(|e| format!("cannot write the bundled scene to {}: {e}", root.display()))?;
        remove_other_versions(&cache, &name);
        Ok(root)
    })
    .clone()
}

/// Where [`bundled_root`] writes the bundled files (nothing written).
fn bundled_root_path() -> PathBuf {
    cache_root().join(format!("{BUNDLED_PREFIX}{}", env!("CARGO_PKG_VERSION")))
}

/// The bundled folders' names: this prefix, then lectern's version. (`shaders-VERSION` was
/// the name before the scene was bundled too.)
const BUNDLED_PREFIX: &str = "bundled-";
const OLD_PREFIXES: [&str; 2] = [BUNDLED_PREFIX, "shaders-"];

/// Removes the bundled folders of other lectern versions from `cache`, keeping `keep`; a
/// folder another version still uses is written again by it when it next starts.
fn remove_other_versions(cache: &Path, keep: &str) {
    let Ok(entries) = std::fs::read_dir(cache) else {
        return;
    };
    for e in entries.flatten() {
        let name = e.file_name().to_string_lossy().into_owned();
        let ours = OLD_PREFIXES.iter().any(|p| name.starts_with(p));
        if ours && name != keep && e.path().is_dir() {
            if let Err(err) = std::fs::remove_dir_all(e.path()) {
                tracing::debug!("cannot remove {}: {err}", e.path().display());
            }
        }
    }
}

/// In a browser there is no file system (std's `temp_dir` panics there): a name that every
/// read and write simply fails on, so the built-in files are "not found" as anywhere else.
#[cfg(target_arch = "wasm32")]
fn cache_root() -> PathBuf {
    PathBuf::from("lectern-cache")
}

#[cfg(not(target_arch = "wasm32"))]
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

    #[test]
    fn the_default_scene_falls_back_to_the_bundled_one_and_a_named_one_does_not() {
        let p = tempfile::tempdir().unwrap();
        let deck_dir = p.path().join("slides");
        std::fs::create_dir_all(&deck_dir).unwrap();
        let default = crate::deck::widgets::scene::default_scene();
        let resolve = |w: &str| crate::paths::resolve_in(&deck_dir, w);
        let f = scene_file(resolve(&default), &default).unwrap();
        assert!(f.bundled);
        assert_eq!(std::fs::read_to_string(&f.path).unwrap(), WATER_SCENE);
        // the bundled scene is drawn with the bundled shaders
        assert!(shader_folder_for_scene(&f.path).unwrap().bundled);
        // a scene the deck names by hand must exist: a typo is not papered over
        let named = scene_file(resolve("../scenes/mine.ron"), "../scenes/mine.ron").unwrap();
        assert!(!named.bundled && !named.path.exists());
        // the project's own scene file wins
        std::fs::create_dir_all(p.path().join("scenes")).unwrap();
        std::fs::write(p.path().join("scenes/water.ron"), "()").unwrap();
        let own = scene_file(resolve(&default), &default).unwrap();
        assert!(!own.bundled && own.path.ends_with("scenes/water.ron"));
    }

    #[test]
    fn other_versions_bundled_folders_are_removed() {
        let cache = tempfile::tempdir().unwrap();
        for name in ["shaders-0.0.1", "bundled-0.0.2", "bundled-9.9.9", "notes"] {
            std::fs::create_dir_all(cache.path().join(name).join("x")).unwrap();
        }
        remove_other_versions(cache.path(), "bundled-9.9.9");
        let mut left: Vec<String> = std::fs::read_dir(cache.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        left.sort();
        assert_eq!(left, vec!["bundled-9.9.9", "notes"]);
    }
}
