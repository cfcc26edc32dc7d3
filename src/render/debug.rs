//! Teaching views (debug.wgsl): the sun's shadow map as grey levels, the environment cube
//! unfolded with its roughness mips, and the caustics map seen from above, drawn straight into
//! the display target.

use super::layouts::{FLOAT, Layout, sampler, texture, uniform};
use super::pipeline::{Ctx, PipelineDesc, Technique};
use super::tonemap::PostParams;

/// Group 0 of the debug views: parameters, the shadow map, the environment cube, a sampler,
/// the caustics map.
pub fn layout(device: &wgpu::Device) -> Layout {
    use wgpu::{TextureSampleType as T, TextureViewDimension as D};
    let vf = wgpu::ShaderStages::VERTEX | wgpu::ShaderStages::FRAGMENT;
    Layout::new(
        device,
        "debug",
        &[
            uniform::<PostParams>(0, vf),
            // the depth map as unfilterable floats (see debug.wgsl)
            texture(1, D::D2, T::Float { filterable: false }),
            texture(2, D::Cube, FLOAT),
            sampler(3, wgpu::SamplerBindingType::Filtering),
            texture(4, D::D2, FLOAT),
        ],
    )
}

pub struct DebugPipeline {
    pub pipeline: wgpu::RenderPipeline,
}

impl Technique for DebugPipeline {
    const SHADER: &'static str = "debug.wgsl";

    fn build(ctx: &Ctx, m: &wgpu::ShaderModule) -> Self {
        Self {
            pipeline: ctx.output_pipeline(
                m,
                PipelineDesc {
                    label: "debug",
                    groups: &[&ctx.layouts.debug],
                    vs: "vs_fullscreen",
                    fs: Some("fs_main"),
                    buffers: &[],
                    color: Some(ctx.output_format),
                    depth: None,
                    cull: None,
                },
            ),
        }
    }
}
