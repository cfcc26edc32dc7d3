//! The frame: shadow map → caustics map (when on) → opaque HDR pass (meshes, fish by level of detail, sky background
//! last) → copy of the opaque colour → water pass (reads that copy and the depth) → tone map
//! (scaling the HDR image up to the target) or a debug view into the caller's target. The
//! window, `render-scene`, tests and the benchmark share it. It only renders: it reads the
//! scene model and a per-frame snapshot and never changes either.

use std::path::{Path, PathBuf};

use wgpu::util::DeviceExt;

use crate::diag::Diagnostic;
use crate::scene::Scene;

use super::caps::RenderCaps;
use super::caustics;
use super::frame::Globals;
use super::layouts::Layouts;
use super::pipeline::{BuildEnv, Passes};
use super::resources::SceneResources;
use super::shadow;
use super::sky::{self, Environment, SkyKey};
use super::targets::{Targets, entry};
use super::tonemap::PostParams;

pub use super::shadow::SHADOW_MAP_SIZE;
pub use encode::OutputDraw;

mod encode;

/// What the last frame drew, for the panel and the tests.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct FrameInfo {
    /// the HDR targets' size (the output's, times the render scale)
    pub render_size: (u32, u32),
    /// visible fish per level of detail, finest first
    pub fish_per_lod: [u32; super::fish::LEVELS],
    /// every fish drawn into the shadow map
    pub fish_in_shadow: u32,
}

pub struct Renderer {
    device: wgpu::Device,
    queue: wgpu::Queue,
    layouts: Layouts,
    passes: Passes,
    output_format: wgpu::TextureFormat,
    caps: RenderCaps,
    linear_clamp: wgpu::Sampler,
    linear_repeat: wgpu::Sampler,
    shadow_sampler: wgpu::Sampler,
    shadow_view: wgpu::TextureView,
    caustics_view: wgpu::TextureView,
    /// the caustics map's side now (it follows the render scale)
    caustics_size_px: u32,
    globals: wgpu::Buffer,
    post_params: wgpu::Buffer,
    frame_group: wgpu::BindGroup,
    shadow_frame_group: wgpu::BindGroup,
    debug_group: wgpu::BindGroup,
    env: Environment,
    /// what `env` was made from: the sky and sun, and the generations of their pipelines
    sky_key: SkyKey,
    sky_generations: (u64, u64),
    res: SceneResources,
    targets: Option<Targets>,
    info: FrameInfo,
}

fn sampler(
    device: &wgpu::Device,
    mode: wgpu::AddressMode,
    compare: Option<wgpu::CompareFunction>,
) -> wgpu::Sampler {
    device.create_sampler(&wgpu::SamplerDescriptor {
        address_mode_u: mode,
        address_mode_v: mode,
        address_mode_w: mode,
        mag_filter: wgpu::FilterMode::Linear,
        min_filter: wgpu::FilterMode::Linear,
        mipmap_filter: wgpu::MipmapFilterMode::Linear,
        compare,
        ..Default::default()
    })
}

/// The size the scene is drawn at for an output of `size` at `render_scale`.
pub fn render_size(size: (u32, u32), render_scale: f32) -> (u32, u32) {
    let s = if render_scale.is_finite() {
        render_scale.clamp(0.1, 1.0)
    } else {
        1.0
    };
    (
        ((size.0 as f32 * s).round() as u32).max(1),
        ((size.1 as f32 * s).round() as u32).max(1),
    )
}

impl Renderer {
    /// Builds pipelines from `shader_dir` (every shader must be valid the first time) and the
    /// scene's GPU resources. `output_format` is what `render` draws into; every other format
    /// and size comes from `caps` (decided once from the adapter, [`RenderCaps::decide`]).
    pub fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        shader_dir: &Path,
        scene: &Scene,
        output_format: wgpu::TextureFormat,
        caps: RenderCaps,
    ) -> Result<Self, Diagnostic> {
        let layouts = Layouts::new(device);
        let passes = Passes::new(
            &BuildEnv {
                device,
                layouts: &layouts,
                output_format,
                caps: &caps,
            },
            shader_dir,
        )?;
        let linear_clamp = sampler(device, wgpu::AddressMode::ClampToEdge, None);
        let linear_repeat = sampler(device, wgpu::AddressMode::Repeat, None);
        let shadow_sampler = sampler(
            device,
            wgpu::AddressMode::ClampToEdge,
            Some(wgpu::CompareFunction::LessEqual),
        );
        let shadow_view = shadow::shadow_map(device, &caps);
        let caustics_size_px = caps.caustics_map_size_px;
        let caustics_view = caustics::caustics_map(device, caustics_size_px, caps.caustics_format);
        let globals = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("globals"),
            size: std::mem::size_of::<Globals>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let post_params = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("post params"),
            contents: &[0u8; std::mem::size_of::<PostParams>()],
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        });
        let sky_key = SkyKey::of(scene);
        let env = sky::build(
            device,
            queue,
            &layouts,
            (passes.sky.current(), passes.prefilter.current()),
            &sky_key,
            &linear_clamp,
            &caps,
        );
        let res = SceneResources::new(device, queue, &layouts, scene, &linear_repeat);
        let shadow_frame_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("shadow frame"),
            layout: &layouts.shadow_frame.layout,
            entries: &[entry(0, globals.as_entire_binding())],
        });
        let (frame_group, debug_group) = env_groups(
            device,
            &layouts,
            &globals,
            &post_params,
            &env,
            (&linear_clamp, &shadow_sampler),
            (&shadow_view, &caustics_view),
        );
        Ok(Self {
            device: device.clone(),
            queue: queue.clone(),
            layouts,
            passes,
            output_format,
            caps,
            linear_clamp,
            linear_repeat,
            shadow_sampler,
            shadow_view,
            caustics_view,
            caustics_size_px,
            globals,
            post_params,
            frame_group,
            shadow_frame_group,
            debug_group,
            env,
            sky_key,
            sky_generations: (0, 0),
            res,
            targets: None,
            info: FrameInfo::default(),
        })
    }

    fn env_changed(&mut self) {
        (self.frame_group, self.debug_group) = env_groups(
            &self.device,
            &self.layouts,
            &self.globals,
            &self.post_params,
            &self.env,
            (&self.linear_clamp, &self.shadow_sampler),
            (&self.shadow_view, &self.caustics_view),
        );
    }

    /// A new scene (reload): meshes and materials are rebuilt, the sky only if it or the sun
    /// changed; camera and time live in the simulation, not here, so they are untouched.
    pub fn set_scene(&mut self, scene: &Scene) {
        let key = SkyKey::of(scene);
        if key != self.sky_key {
            self.sky_key = key;
            self.rebuild_environment();
        }
        self.res = SceneResources::new(
            &self.device,
            &self.queue,
            &self.layouts,
            scene,
            &self.linear_repeat,
        );
    }

    fn rebuild_environment(&mut self) {
        self.env = sky::build(
            &self.device,
            &self.queue,
            &self.layouts,
            (self.passes.sky.current(), self.passes.prefilter.current()),
            &self.sky_key,
            &self.linear_clamp,
            &self.caps,
        );
        self.sky_generations = (
            self.passes.sky.generation(),
            self.passes.prefilter.generation(),
        );
        self.env_changed();
    }

    /// Hot reload of shaders: rebuilds the techniques that use a changed file (and the sky
    /// cube when its own shaders were rebuilt). Returns whether any technique was affected.
    pub fn reload_shaders(&mut self, changed: &[PathBuf]) -> bool {
        let env = BuildEnv {
            device: &self.device,
            layouts: &self.layouts,
            output_format: self.output_format,
            caps: &self.caps,
        };
        let any = self.passes.reload(&env, changed);
        if (
            self.passes.sky.generation(),
            self.passes.prefilter.generation(),
        ) != self.sky_generations
        {
            self.rebuild_environment();
        }
        any
    }

    /// The current shader errors (the previous pipelines are in use meanwhile).
    pub fn shader_errors(&self) -> Vec<&Diagnostic> {
        self.passes.errors()
    }

    /// Fish the instance buffer holds now (it grows with the count, to the next power of two).
    pub fn fish_capacity(&self) -> usize {
        self.res.fish_capacity
    }

    /// Indices of the water grid in use.
    pub fn water_index_count(&self) -> u32 {
        self.res.water_index_count
    }

    /// Indices of the water grid's coarse list (every other row and column).
    pub fn water_index_count_coarse(&self) -> u32 {
        self.res.water_index_count_coarse
    }

    pub fn output_format(&self) -> wgpu::TextureFormat {
        self.output_format
    }

    /// The formats and sizes in use.
    pub fn caps(&self) -> &RenderCaps {
        &self.caps
    }

    /// What the last frame drew.
    pub fn frame_info(&self) -> &FrameInfo {
        &self.info
    }

    fn ensure_targets(&mut self, size: (u32, u32)) {
        if self.targets.as_ref().is_some_and(|t| t.size == size) {
            return;
        }
        self.targets = Some(Targets::new(
            &self.device,
            &self.layouts,
            size,
            &self.post_params,
            &self.linear_clamp,
            &self.caps,
        ));
    }
}

/// The bind groups that read the environment cube: group 0 of the lit passes, and the debug
/// views'.
fn env_groups(
    device: &wgpu::Device,
    layouts: &Layouts,
    globals: &wgpu::Buffer,
    post_params: &wgpu::Buffer,
    env: &Environment,
    (linear_clamp, shadow_sampler): (&wgpu::Sampler, &wgpu::Sampler),
    (shadow_view, caustics_view): (&wgpu::TextureView, &wgpu::TextureView),
) -> (wgpu::BindGroup, wgpu::BindGroup) {
    let frame = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("frame"),
        layout: &layouts.frame.layout,
        entries: &[
            entry(0, globals.as_entire_binding()),
            entry(1, wgpu::BindingResource::TextureView(&env.view)),
            entry(2, wgpu::BindingResource::Sampler(linear_clamp)),
            entry(3, wgpu::BindingResource::TextureView(shadow_view)),
            entry(4, wgpu::BindingResource::Sampler(shadow_sampler)),
            entry(5, wgpu::BindingResource::TextureView(caustics_view)),
            entry(6, wgpu::BindingResource::Sampler(linear_clamp)),
        ],
    });
    let debug = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("debug"),
        layout: &layouts.debug.layout,
        entries: &[
            entry(0, post_params.as_entire_binding()),
            entry(1, wgpu::BindingResource::TextureView(shadow_view)),
            entry(2, wgpu::BindingResource::TextureView(&env.view)),
            entry(3, wgpu::BindingResource::Sampler(linear_clamp)),
            entry(4, wgpu::BindingResource::TextureView(caustics_view)),
        ],
    });
    (frame, debug)
}
