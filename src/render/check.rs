//! `lectern check` for shaders: each file as the renderer would build it. naga parses and
//! validates; then, on a headless adapter (the software one is fine), each technique's
//! pipelines are created by the renderer's own builders against its real bind-group and vertex
//! layouts (see [`super::pipeline::build`]), so a shader that is valid WGSL but does not fit
//! the renderer is reported at its binding, entry point or vertex input. An include-only file
//! (no entry point, e.g. `brdf.wgsl`) is checked through every shader of its folder that
//! includes it and reports at its own lines. With no adapter the pipeline step is skipped and
//! [`pipeline_check_skipped`] says so in one line.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, OnceLock};

use crate::diag::Diagnostic;

use super::caps::RenderCaps;
use super::gpu::Gpu;
use super::layouts::Layouts;
use super::pipeline::{BuildEnv, TECHNIQUE_SHADERS, check_techniques};
use super::shaders;

/// The output format the renderer is built for in the app and headless alike.
const OUTPUT_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;

struct Checker {
    /// the device and layouts, or why there is none
    gpu: Result<(Gpu, Layouts), String>,
    /// whether a check ran without the pipeline step
    skipped: bool,
    /// results per shader, keyed by its path and the text it expanded to
    cache: HashMap<(PathBuf, String), Vec<Diagnostic>>,
}

fn checker() -> &'static Mutex<Checker> {
    static CHECKER: OnceLock<Mutex<Checker>> = OnceLock::new();
    CHECKER.get_or_init(|| {
        let gpu = Gpu::headless()
            .map(|gpu| {
                let layouts = Layouts::new(&gpu.device);
                (gpu, layouts)
            })
            .map_err(|e| format!("{e:#}"));
        Mutex::new(Checker {
            gpu,
            skipped: false,
            cache: HashMap::new(),
        })
    })
}

/// The problems of one shader file: naga's, then (with an adapter) pipeline creation's.
pub fn check_shader_file(path: &Path) -> Vec<Diagnostic> {
    let src = match shaders::load(path) {
        Ok(s) => s,
        Err(d) => return vec![d],
    };
    let dir = path.parent().unwrap_or(Path::new("."));
    let mut checker = match checker().lock() {
        Ok(c) => c,
        Err(poisoned) => poisoned.into_inner(),
    };
    if shaders::has_entry_point(&src.text) {
        return checker.check_entry(path, &src.text);
    }
    // include-only: through every shader of the folder that includes it
    let me = crate::reload::file_key(path);
    let mut out: Vec<Diagnostic> = Vec::new();
    for user in shaders::list(dir) {
        let Ok(user_src) = shaders::load(&user) else {
            continue;
        };
        if crate::reload::same_file(&user, path)
            || !shaders::has_entry_point(&user_src.text)
            || !crate::reload::any_is(&user_src.files, &me)
        {
            continue;
        }
        for d in checker.check_entry(&user, &user_src.text) {
            if crate::reload::file_key(&d.file) == me && !out.contains(&d) {
                out.push(d);
            }
        }
    }
    out
}

impl Checker {
    /// A shader with entry points: its technique built the renderer's way, or (an unknown
    /// file, or no adapter) naga only.
    fn check_entry(&mut self, path: &Path, text: &str) -> Vec<Diagnostic> {
        let key = (path.to_path_buf(), text.to_owned());
        if let Some(hit) = self.cache.get(&key) {
            return hit.clone();
        }
        let is_technique = path
            .file_name()
            .and_then(|n| n.to_str())
            .is_some_and(|n| TECHNIQUE_SHADERS.contains(&n));
        let problems = match (&self.gpu, is_technique) {
            (Ok((gpu, layouts)), true) => {
                let caps = RenderCaps::decide(&gpu.caps);
                let env = BuildEnv {
                    device: &gpu.device,
                    layouts,
                    output_format: OUTPUT_FORMAT,
                    caps: &caps,
                };
                let dir = path.parent().unwrap_or(Path::new("."));
                let built = check_techniques(&env, dir, &|files: &[PathBuf]| {
                    files
                        .first()
                        .is_some_and(|f| crate::reload::same_file(f, path))
                });
                // anything wgpu could not attribute to a scope would otherwise be lost
                let stray = gpu.errors.take();
                let mut v: Vec<Diagnostic> = built.into_iter().flat_map(|(_, ds)| ds).collect();
                v.extend(stray.into_iter().map(|e| Diagnostic::whole_file(path, e)));
                v
            }
            (Err(_), true) => {
                self.skipped = true;
                shaders::check_file(path)
            }
            (_, false) => shaders::check_file(path),
        };
        self.cache.insert(key, problems.clone());
        problems
    }
}

/// One line for `lectern check` when shaders were checked without the pipeline step (no wgpu
/// adapter at all); `None` when the step ran or no shader was checked.
pub fn pipeline_check_skipped() -> Option<String> {
    let checker = checker().lock().ok()?;
    match (&checker.gpu, checker.skipped) {
        (Err(why), true) => Some(format!(
            "shaders: the pipeline step was skipped (no wgpu adapter: {}); naga checks ran",
            why.lines().next().unwrap_or("unknown")
        )),
        _ => None,
    }
}
