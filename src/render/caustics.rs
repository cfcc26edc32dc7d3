//! Water caustics (caustics.wgsl), after Guardado & Sánchez-Crespo, "Rendering Water
//! Caustics", GPU Gems 1, ch. 2 (2004): once per frame a full-screen triangle draws, into a
//! small single-channel texture over the swim box in x and z, how much the Gerstner surface
//! focuses the refracted sunlight onto a floor `caustics_depth_m` below the water (1 = as
//! flat water would let through). The lit shaders multiply the sun's direct light by it
//! (`caustics_light` in common.wgsl), read at each point's xz shifted along the refracted sun.

use super::targets::cleared_color;
use crate::scene::Scene;

use super::pipeline::{Ctx, PipelineDesc, Technique};

pub use super::caps::CAUSTICS_MAP_SIZE;

/// When the automatic quality draws the scene below this scale, the map is drawn at half the
/// size (a quarter of the cost): the image is blurred by the scaling up anyway.
pub const HALF_SIZE_BELOW_RENDER_SCALE: f32 = 0.7;

/// The caustics map's side for a frame drawn at `render_scale`, `full_px` at full quality
/// (`RenderCaps::caustics_map_size_px`).
pub fn map_size(render_scale: f32, full_px: u32) -> u32 {
    if render_scale < HALF_SIZE_BELOW_RENDER_SCALE {
        (full_px / 2).max(1)
    } else {
        full_px
    }
}

/// The caustics map covers |x|, |z| ≤ this (metres): the fish's swim box, a fish length and a
/// metre more, where the camera looks and the shadow map already concentrates its texels.
pub fn half_extent_m(scene: &Scene) -> f32 {
    scene.simulation.school_half_width + scene.school.fish_scale + 1.0
}

/// The depth below the water level the map is focused on: the seabed's.
pub fn focus_depth_m(scene: &Scene) -> f32 {
    scene.seabed_depth().max(0.1)
}

pub struct CausticsPipeline {
    pub pipeline: wgpu::RenderPipeline,
}

impl Technique for CausticsPipeline {
    const SHADER: &'static str = "caustics.wgsl";

    fn build(ctx: &Ctx, m: &wgpu::ShaderModule) -> Self {
        Self {
            pipeline: ctx.pipeline(
                m,
                PipelineDesc {
                    label: "caustics",
                    // the globals only: the lit passes' group 0 also holds the map itself
                    groups: &[&ctx.layouts.shadow_frame],
                    vs: "vs_fullscreen",
                    fs: Some("fs_caustics"),
                    buffers: &[],
                    color: Some(ctx.caps.caustics_format),
                    depth: None,
                    cull: None,
                },
            ),
        }
    }
}

/// The caustics map, `size_px` a side (rendered by the caustics pass, read by the lit passes):
/// one channel of focusing factor, half floats keeping the bright folds (up to 6) unclipped
/// where the adapter renders to them (`RenderCaps::caustics_format`).
pub fn caustics_map(
    device: &wgpu::Device,
    size_px: u32,
    format: wgpu::TextureFormat,
) -> wgpu::TextureView {
    device
        .create_texture(&wgpu::TextureDescriptor {
            label: Some("caustics map"),
            size: wgpu::Extent3d {
                width: size_px,
                height: size_px,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        })
        .create_view(&Default::default())
}

/// Records the caustics pass into `map` (group 0: the globals, already written this frame).
pub fn encode(
    enc: &mut wgpu::CommandEncoder,
    pipeline: &CausticsPipeline,
    globals_group: &wgpu::BindGroup,
    map: &wgpu::TextureView,
    flat_water: f64,
) {
    // cleared to flat water's factor as stored (1, or its 8-bit encoding)
    let clear = wgpu::Color {
        r: flat_water,
        g: 0.0,
        b: 0.0,
        a: 1.0,
    };
    let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some("caustics"),
        color_attachments: &[cleared_color(map, clear)],
        ..Default::default()
    });
    pass.set_pipeline(&pipeline.pipeline);
    pass.set_bind_group(0, globals_group, &[]);
    pass.draw(0..3, 0..1);
}
