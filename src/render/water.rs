//! The sea surface (water.wgsl): a flat grid displaced in the vertex shader by the Gerstner sum
//! (Finch 2004, GPU Gems 1 ch. 1), Fresnel (Schlick 1994) between the reflected sky and the
//! refracted opaque image, absorbed along the path through the water (Beer–Lambert). It reads
//! a copy of the opaque colour and the opaque depth (its inputs bind group, defined here).

use super::layouts::{FLOAT, Layout, sampler, texture};
use super::pipeline::{Ctx, HDR_FORMAT, NO_BIAS, PerShadowFilter, PipelineDesc, Technique};

/// Group 1 of the water: the opaque colour (a copy), the opaque depth, a sampler.
pub fn inputs_layout(device: &wgpu::Device) -> Layout {
    use wgpu::{TextureSampleType as T, TextureViewDimension as D};
    Layout::new(
        device,
        "water inputs",
        &[
            texture(0, D::D2, FLOAT),
            texture(1, D::D2, T::Depth),
            sampler(2, wgpu::SamplerBindingType::Filtering),
        ],
    )
}

/// The grid's vertices: rest (x, z) positions only.
pub fn vertex_layout() -> wgpu::VertexBufferLayout<'static> {
    const ATTR: [wgpu::VertexAttribute; 1] = wgpu::vertex_attr_array![0 => Float32x2];
    wgpu::VertexBufferLayout {
        array_stride: 8,
        step_mode: wgpu::VertexStepMode::Vertex,
        attributes: &ATTR,
    }
}

pub struct WaterPipeline {
    pub pipeline: PerShadowFilter<wgpu::RenderPipeline>,
}

impl Technique for WaterPipeline {
    const SHADER: &'static str = "water.wgsl";

    fn build(ctx: &Ctx, m: &wgpu::ShaderModule) -> Self {
        let l = ctx.layouts;
        Self {
            pipeline: ctx.lit_pipelines(
                m,
                PipelineDesc {
                    label: "water",
                    groups: &[&l.frame, &l.water_inputs],
                    vs: "vs_main",
                    fs: Some("fs_main"),
                    buffers: &[Some(vertex_layout())],
                    color: Some(HDR_FORMAT),
                    // reads the opaque depth as a texture in the same pass: test, never write
                    depth: Some((false, wgpu::CompareFunction::Less, NO_BIAS)),
                    cull: None,
                },
            ),
        }
    }
}
