//! The one host of the scene renderer, for scene mode (`app::scene_mode`) and the Scene widget
//! ([`super::gpu::SceneGpu`]): it finds the shader folder for a scene file, reads the adapter's
//! capabilities once and builds a [`Renderer`] with the formats decided from them, watches the
//! shader folder and the scene's folder (with the app's one [`reload::DEBOUNCE`]), and applies
//! saved shaders. What a changed scene file means (a [`crate::reload::LiveFile`] in scene mode,
//! a re-read spec in the widget) stays with the caller.

use std::path::{Path, PathBuf};

use crate::reload::{self, DirWatcher};
use crate::render::Renderer;
use crate::render::caps::{AdapterCaps, RenderCaps};
use crate::scene::Scene;

pub struct SceneHost {
    pub renderer: Renderer,
    /// what the adapter can do (the panel's first line names its backend)
    adapter: AdapterCaps,
    watcher: Option<DirWatcher>,
}

impl SceneHost {
    /// The renderer for `scene` (read from `scene_path`) on egui's device, drawing into
    /// `output_format`. With `wake`, the shader folder and the scene's folder are watched and
    /// `wake` is called after a change settled.
    pub fn new(
        render_state: &egui_wgpu::RenderState,
        scene_path: &Path,
        scene: &Scene,
        output_format: wgpu::TextureFormat,
        wake: Option<Box<dyn Fn() + Send + 'static>>,
    ) -> Result<Self, String> {
        let shader_dir = crate::bundled::shader_folder_for_scene(scene_path)?.dir;
        let adapter = AdapterCaps::of(&render_state.adapter, &render_state.device.limits());
        let renderer = Renderer::new(
            &render_state.device,
            &render_state.queue,
            &shader_dir,
            scene,
            output_format,
            RenderCaps::decide(&adapter),
        )
        .map_err(|e| format!("the scene renderer could not start: {e:#}"))?;
        let watcher = wake.and_then(|wake| {
            let scene_dir = scene_path.parent().unwrap_or(Path::new("."));
            DirWatcher::new(&[&shader_dir, scene_dir], reload::DEBOUNCE, wake)
                .map_err(|e| tracing::warn!("not watching shaders and scenes: {e}"))
                .ok()
        });
        Ok(Self {
            renderer,
            adapter,
            watcher,
        })
    }

    /// The files changed since the last poll (settled), with saved shaders already applied
    /// (the old pipelines stay where one does not build). Empty without a watcher.
    pub fn poll(&mut self) -> Vec<PathBuf> {
        let changed = self
            .watcher
            .as_ref()
            .map(DirWatcher::poll)
            .unwrap_or_default();
        self.apply_shaders(&changed);
        changed
    }

    /// Rebuilds the techniques that use any `.wgsl` file of `changed`; whether there was one.
    pub fn apply_shaders(&mut self, changed: &[PathBuf]) -> bool {
        let shaders: Vec<PathBuf> = (changed.iter())
            .filter(|p| p.extension().is_some_and(|e| e == "wgsl"))
            .cloned()
            .collect();
        if !shaders.is_empty() {
            self.renderer.reload_shaders(&shaders);
        }
        !shaders.is_empty()
    }

    /// "GL · llvmpipe (LLVM 15.0.6, 256 bits)", and "8-bit targets" when float ones are missing.
    pub fn backend_line(&self) -> String {
        let mut line = self.adapter.describe();
        if self.renderer.caps().eight_bit_hdr() {
            line.push_str(" · 8-bit targets");
        }
        line
    }
}
