//! HDR to display (tonemap.wgsl): a white balance (D50 to D65, Bradford), exposure and the ACES curve in Narkowicz's fit (Narkowicz
//! 2015), with the HDR image scaled up to the display when it was drawn smaller (dynamic
//! resolution). Two passes: tone mapping (and FXAA on the edges, Lottes 2011, fxaa.wgsl, where
//! the settings ask for it) at the render size into the display image, then that image scaled
//! up to the output: the anti-aliasing costs per drawn pixel, not per output pixel. `PostParams` is shared with the debug views.

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
    /// HDR to the display image at the render size, with FXAA on the geometric edges
    /// (fxaa.wgsl)
    pub with_fxaa: wgpu::RenderPipeline,
    /// … without
    pub plain: wgpu::RenderPipeline,
    /// the display image scaled up to the output (bilinear)
    pub upscale: wgpu::RenderPipeline,
}

impl TonemapPipeline {
    pub fn get(&self, fxaa: bool) -> &wgpu::RenderPipeline {
        if fxaa { &self.with_fxaa } else { &self.plain }
    }
}

impl Technique for TonemapPipeline {
    const SHADER: &'static str = "tonemap.wgsl";

    fn build(ctx: &Ctx, m: &wgpu::ShaderModule) -> Self {
        let d = PipelineDesc {
            label: "tonemap",
            groups: &[&ctx.layouts.tonemap],
            vs: "vs_fullscreen",
            fs: Some("fs_main"),
            buffers: &[],
            color: Some(ctx.caps.display_format),
            depth: None,
            cull: None,
        };
        // the display image is sRGB encoded on store
        let srgb = ("TARGET_IS_SRGB", 1.0);
        Self {
            with_fxaa: ctx.pipeline_with(m, d.clone(), &[srgb, ("FXAA_ON", 1.0)], true),
            plain: ctx.pipeline_with(m, d.clone(), &[srgb, ("FXAA_ON", 0.0)], false),
            upscale: ctx.output_pipeline(
                m,
                PipelineDesc {
                    label: "upscale",
                    fs: Some("fs_upscale"),
                    color: Some(ctx.output_format),
                    ..d
                },
            ),
        }
    }
}
