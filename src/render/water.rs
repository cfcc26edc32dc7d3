//! The sea surface (water.wgsl): a projected grid (Johanson 2004) reaching the horizon,
//! displaced in the vertex shader by the Gerstner sum (Finch 2004, GPU Gems 1 ch. 1), Fresnel
//! (Schlick 1994) between the reflected sky and the refracted opaque image, absorbed and
//! in-scattered along the path through the water (Beer–Lambert); Snell's window from below.
//! It reads a copy of the opaque colour whose alpha is the distance from the eye (its inputs
//! bind group, defined here): never the depth texture it tests against, which WebGL2 and GLES
//! cannot sample while it is attached.

use super::frame::{ShadowFilter, WaterNormals};
use super::layouts::{FLOAT, Layout, sampler, texture};
use super::pipeline::{Ctx, NO_BIAS, PerShadowFilter, PipelineDesc, Technique};

/// Group 1 of the water: the opaque colour (a copy; alpha the distance from the eye), a
/// sampler.
pub fn inputs_layout(device: &wgpu::Device) -> Layout {
    Layout::new(
        device,
        "water inputs",
        &[
            texture(0, wgpu::TextureViewDimension::D2, FLOAT),
            sampler(1, wgpu::SamplerBindingType::Filtering),
        ],
    )
}

/// The grid's vertices: screen positions (ndc) only.
pub fn vertex_layout() -> wgpu::VertexBufferLayout<'static> {
    const ATTR: [wgpu::VertexAttribute; 1] = wgpu::vertex_attr_array![0 => Float32x2];
    wgpu::VertexBufferLayout {
        array_stride: 8,
        step_mode: wgpu::VertexStepMode::Vertex,
        attributes: &ATTR,
    }
}

pub struct WaterPipeline {
    /// per shadow filter, then per [`WaterNormals`] (its `index`)
    pipeline: PerShadowFilter<[wgpu::RenderPipeline; 3]>,
}

impl WaterPipeline {
    pub fn get(&self, filter: ShadowFilter, normals: WaterNormals) -> &wgpu::RenderPipeline {
        &self.pipeline.get(filter)[normals.index()]
    }
}

impl Technique for WaterPipeline {
    const SHADER: &'static str = "water.wgsl";

    fn build(ctx: &Ctx, m: &wgpu::ShaderModule) -> Self {
        let l = ctx.layouts;
        Self {
            pipeline: ctx.water_pipelines(
                m,
                PipelineDesc {
                    label: "water",
                    groups: &[&l.frame, &l.water_inputs],
                    vs: "vs_main",
                    fs: Some("fs_main"),
                    buffers: &[Some(vertex_layout())],
                    color: Some(ctx.caps.hdr_format),
                    // tests against the opaque depth, never writes it
                    depth: Some((false, wgpu::CompareFunction::Less, NO_BIAS)),
                    cull: None,
                },
            ),
        }
    }
}
