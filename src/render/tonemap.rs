//! HDR to display (tonemap.wgsl): exposure and the ACES curve in Narkowicz's fit (Narkowicz
//! 2015), with the HDR image scaled up to the display when it was drawn smaller (dynamic
//! resolution). `PostParams` is shared with the debug views.

use bytemuck::{Pod, Zeroable};

use super::layouts::{FLOAT, Layout, sampler, texture, uniform};
use super::pipeline::{Ctx, PipelineDesc, Technique};

/// `Post` in tonemap.wgsl and debug.wgsl.
#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
pub struct PostParams {
    pub exposure: f32,
    pub debug_view: u32,
    pub env_mip_count: f32,
    pub _pad: f32,
    /// the display target, pixels
    pub viewport_size_px: [f32; 2],
    pub _pad2: [f32; 2],
}

/// Group 0 of the tone mapping pass: parameters, the HDR image and a bilinear sampler.
pub fn layout(device: &wgpu::Device) -> Layout {
    let vf = wgpu::ShaderStages::VERTEX | wgpu::ShaderStages::FRAGMENT;
    Layout::new(
        device,
        "tonemap",
        &[
            uniform::<PostParams>(0, vf),
            texture(1, wgpu::TextureViewDimension::D2, FLOAT),
            sampler(2, wgpu::SamplerBindingType::Filtering),
        ],
    )
}

pub struct TonemapPipeline {
    pub pipeline: wgpu::RenderPipeline,
}

impl Technique for TonemapPipeline {
    const SHADER: &'static str = "tonemap.wgsl";

    fn build(ctx: &Ctx, m: &wgpu::ShaderModule) -> Self {
        Self {
            pipeline: ctx.output_pipeline(
                m,
                PipelineDesc {
                    label: "tonemap",
                    groups: &[&ctx.layouts.tonemap],
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
