//! The wgpu side of the Scene widget: egui's device and the scene renderers made on it
//! ([`SceneGpu`], shared through the egui context; each a [`SceneHost`], as scene mode's), and
//! the texture a widget's frame is rendered into and egui shows ([`Output`]).

use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

use super::host::SceneHost;
use crate::render::Renderer;
use crate::scene::Scene;

/// The format a slide's scene is rendered in: plain 8-bit, the output shader writing sRGB-encoded
/// values itself (`to_target`, srgb.wgsl), which is what egui reads from a texture. No sRGB
/// texture with a plain view format beside it: WebGL2 has no view formats (issue #25).
pub const OUTPUT_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

/// egui's wgpu device and the scene renderers made on it, shared through the egui context.
#[derive(Clone)]
pub struct SceneGpu {
    pub render_state: egui_wgpu::RenderState,
    /// The fraction of the widget's pixels the scene is drawn at, each way (scaled up by the
    /// tone-mapping pass): below 1 in a window on a software adapter, 1 for export and tests.
    pub render_scale: f32,
    /// Whether `playing` widgets advance with the clock (the window); exports and snapshots
    /// always show the deck's `time_s`.
    pub animate: bool,
    /// Watch `shaders/` and the scene files in the window (exports and tests read them once).
    watch_files: bool,
    /// for the watcher to wake an idle window
    ctx: egui::Context,
    renderers: Arc<Mutex<Vec<SharedRenderer>>>,
}

struct SharedRenderer {
    scene_path: PathBuf,
    /// the scene the renderer's meshes and materials were built from
    scene: Scene,
    /// the renderer, the shader folder and the scene's folder watched as in scene mode
    host: SceneHost,
    /// bumped when a shader or the scene file changed on disk: frames drawn before are stale
    generation: u64,
}

impl SceneGpu {
    /// Makes the device reachable from every Scene widget drawn with `ctx`.
    pub fn install(
        ctx: &egui::Context,
        render_state: egui_wgpu::RenderState,
        render_scale: f32,
        animate: bool,
    ) {
        let gpu = Self {
            render_state,
            render_scale: render_scale.clamp(0.25, 1.0),
            animate,
            // (a page's bundle never changes: nothing to watch in a browser)
            watch_files: animate && !cfg!(target_arch = "wasm32"),
            ctx: ctx.clone(),
            renderers: Arc::default(),
        };
        ctx.data_mut(|d| d.insert_temp(egui::Id::NULL.with("lectern-scene-gpu"), gpu));
    }

    pub fn get(ctx: &egui::Context) -> Option<Self> {
        ctx.data(|d| d.get_temp::<Self>(egui::Id::NULL.with("lectern-scene-gpu")))
    }

    /// The window's choice: a software adapter draws the scene at half size; a browser at
    /// the render scale of the rung scene mode starts from there
    /// ([`crate::scene::quality::start_rung`]).
    pub fn render_scale_for(adapter: &wgpu::Adapter) -> f32 {
        if cfg!(target_arch = "wasm32") {
            crate::scene::quality::LADDER[crate::scene::quality::start_rung()].render_scale
        } else if adapter.get_info().device_type == wgpu::DeviceType::Cpu {
            0.5
        } else {
            1.0
        }
    }

    /// How many scene renderers exist (one per scene file some Scene widget has drawn).
    pub fn renderer_count(&self) -> usize {
        self.renderers.lock().map_or(0, |all| all.len())
    }

    /// Applies saved shaders to the renderer of `scene_path` (the old pipelines stay when one
    /// does not build) and returns its file generation, which changes whenever a shader or the
    /// scene file was saved: a widget then reloads its scene and draws again. 0 before the
    /// renderer exists.
    pub(super) fn poll_files(&self, scene_path: &Path) -> u64 {
        let Ok(mut all) = self.renderers.lock() else {
            return 0;
        };
        let Some(shared) = all.iter_mut().find(|r| r.scene_path == scene_path) else {
            return 0;
        };
        let changed = shared.host.poll();
        let shaders_saved = changed
            .iter()
            .any(|p| p.extension().is_some_and(|e| e == "wgsl"));
        let scene_saved = crate::reload::any_is(&changed, &crate::reload::file_key(scene_path));
        if shaders_saved || scene_saved {
            shared.generation += 1;
        }
        shared.generation
    }

    /// Shader errors of the renderer of `scene_path` (`file:line:col: message`), shown by the
    /// widget while the last good pipelines keep drawing.
    pub(super) fn shader_errors(&self, scene_path: &Path) -> Vec<String> {
        let Ok(all) = self.renderers.lock() else {
            return Vec::new();
        };
        (all.iter().find(|r| r.scene_path == scene_path))
            .map(|r| {
                r.host
                    .renderer
                    .shader_errors()
                    .iter()
                    .map(|d| d.to_string())
                    .collect()
            })
            .unwrap_or_default()
    }

    /// Runs `draw` with the renderer of `scene_path` (made on first use; its meshes rebuilt when
    /// the scene changed).
    pub(super) fn with_renderer<R>(
        &self,
        scene_path: &Path,
        scene: &Scene,
        draw: impl FnOnce(&mut Renderer) -> R,
    ) -> Result<R, String> {
        let mut all = self
            .renderers
            .lock()
            .map_err(|_| "the scene renderer failed earlier".to_owned())?;
        let index = match all.iter().position(|r| r.scene_path == scene_path) {
            Some(i) => i,
            None => {
                let started = web_time::Instant::now();
                let wake = self.watch_files.then(|| {
                    let ctx = self.ctx.clone();
                    Box::new(move || ctx.request_repaint()) as Box<dyn Fn() + Send>
                });
                let host =
                    SceneHost::new(&self.render_state, scene_path, scene, OUTPUT_FORMAT, wake)?;
                tracing::debug!("scene renderer for slides made in {:?}", started.elapsed());
                all.push(SharedRenderer {
                    scene_path: scene_path.to_path_buf(),
                    scene: scene.clone(),
                    host,
                    generation: 0,
                });
                all.len() - 1
            }
        };
        let shared = &mut all[index];
        if shared.scene != *scene {
            shared.host.renderer.set_scene(scene);
            shared.scene = scene.clone();
        }
        Ok(draw(&mut shared.host.renderer))
    }
}

/// A texture the scene renders into (`view`, sRGB) and the id egui shows the same bytes under.
pub struct SceneTexture {
    pub texture: wgpu::Texture,
    pub view: wgpu::TextureView,
    pub id: egui::TextureId,
}

/// Makes a `size` texture for the scene and hands it to egui: under `reuse` (the id of the
/// texture it replaces, so the frame that shows it needs no new id) or a new id. The Scene
/// widget renders into it only when its picture changes and egui shows it every frame; scene
/// mode, which draws a new picture every frame, draws into egui's own pass instead
/// (`app::scene_mode`), so the picture is not written twice.
pub fn scene_texture(
    rs: &egui_wgpu::RenderState,
    label: &str,
    size: (u32, u32),
    reuse: Option<egui::TextureId>,
) -> SceneTexture {
    let texture = rs.device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width: size.0,
            height: size.1,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: OUTPUT_FORMAT,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
        view_formats: &[],
    });
    let view = texture.create_view(&Default::default());
    // egui treats a texture's values as gamma-encoded, as the output shader wrote them
    let egui_view = &view;
    let mut egui_renderer = rs.renderer.write();
    let id = match reuse {
        Some(id) => {
            egui_renderer.update_egui_texture_from_wgpu_texture(
                &rs.device,
                egui_view,
                wgpu::FilterMode::Linear,
                id,
            );
            id
        }
        None => {
            egui_renderer.register_native_texture(&rs.device, egui_view, wgpu::FilterMode::Linear)
        }
    };
    SceneTexture { texture, view, id }
}

/// The texture the scene is rendered into, registered with egui once.
pub(super) struct Output {
    render_state: egui_wgpu::RenderState,
    pub(super) size: (u32, u32),
    _texture: wgpu::Texture,
    pub(super) view: wgpu::TextureView,
    pub(super) id: egui::TextureId,
    /// false once the id has been handed to a larger texture
    owns_id: bool,
}

impl Output {
    /// The output texture, at least `size` pixels (grown, never shrunk: the presenter's smaller
    /// copy of the slide shows the same frame scaled down instead of rendering its own).
    pub(super) fn ensure(
        current: &mut Option<Output>,
        rs: &egui_wgpu::RenderState,
        size: (u32, u32),
    ) -> bool {
        if let Some(o) = current.as_ref()
            && o.size.0 >= size.0
            && o.size.1 >= size.1
        {
            return false;
        }
        let size = match current.as_ref() {
            Some(o) => (o.size.0.max(size.0), o.size.1.max(size.1)),
            None => size,
        };
        let reuse = current.as_ref().map(|o| o.id);
        let SceneTexture { texture, view, id } = scene_texture(rs, "scene on a slide", size, reuse);
        if let Some(mut old) = current.take() {
            // the id now names the new texture: do not free it with the old one
            old.owns_id = false;
        }
        *current = Some(Output {
            render_state: rs.clone(),
            size,
            _texture: texture,
            view,
            id,
            owns_id: true,
        });
        true
    }
}

impl Drop for Output {
    fn drop(&mut self) {
        if self.owns_id {
            self.render_state.renderer.write().free_texture(&self.id);
        }
    }
}
