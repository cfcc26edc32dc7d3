//! Opaque meshes — seabed, rocks, floating bodies — lit physically (pbr.wgsl): vertex + index
//! buffers with an explicit layout, tangent-space normal maps (Blinn 1978; Mikkelsen 2008) and
//! the Cook–Torrance BRDF of brdf.wgsl (Walter et al. 2007; Heitz 2014; Schlick 1994). The
//! material and object bind groups are defined here; the fish use the material one too.

use bytemuck::{Pod, Zeroable};

use crate::scene::Material;

use super::layouts::{FLOAT, Layout, sampler, texture, uniform};
use super::mesh::Vertex;
use super::pipeline::{Ctx, OPAQUE_DEPTH, PerShadowFilter, PipelineDesc, Technique};

/// `MaterialParams` in brdf.wgsl.
#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
pub struct MaterialGpu {
    pub base_color: [f32; 4],
    pub metallic: f32,
    pub roughness: f32,
    pub reflectance: f32,
    pub normal_strength: f32,
    pub uv_scale: f32,
    pub _pad: [f32; 3],
}

impl MaterialGpu {
    pub fn from(m: &Material) -> Self {
        Self {
            base_color: [m.base_color[0], m.base_color[1], m.base_color[2], 1.0],
            metallic: m.metallic,
            roughness: m.roughness,
            reflectance: m.reflectance,
            normal_strength: m.normal_strength,
            uv_scale: m.uv_scale,
            _pad: [0.0; 3],
        }
    }
}

/// `Object` in pbr.wgsl and shadow.wgsl.
#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
pub struct ObjectGpu {
    pub world_from_object: [[f32; 4]; 4],
    /// 1: world xz as texture coordinates (terrain); 0: the mesh's own
    pub world_uv: f32,
    pub ambient_occlusion: f32,
    pub _pad: [f32; 2],
}

/// Group 1 of the lit meshes and fish: material constants and the normal map.
pub fn material_layout(device: &wgpu::Device) -> Layout {
    let vf = wgpu::ShaderStages::VERTEX | wgpu::ShaderStages::FRAGMENT;
    Layout::new(
        device,
        "material",
        &[
            uniform::<MaterialGpu>(0, vf),
            texture(1, wgpu::TextureViewDimension::D2, FLOAT),
            sampler(2, wgpu::SamplerBindingType::Filtering),
        ],
    )
}

/// The object transform (group 2 of the lit meshes, group 1 of their shadow pass).
pub fn object_layout(device: &wgpu::Device) -> Layout {
    let vf = wgpu::ShaderStages::VERTEX | wgpu::ShaderStages::FRAGMENT;
    Layout::new(device, "object", &[uniform::<ObjectGpu>(0, vf)])
}

pub struct PbrPipeline {
    pub pipeline: PerShadowFilter<wgpu::RenderPipeline>,
}

impl Technique for PbrPipeline {
    const SHADER: &'static str = "pbr.wgsl";

    fn build(ctx: &Ctx, m: &wgpu::ShaderModule) -> Self {
        let l = ctx.layouts;
        Self {
            pipeline: ctx.lit_pipelines(
                m,
                PipelineDesc {
                    label: "pbr",
                    groups: &[&l.frame, &l.material, &l.object],
                    vs: "vs_main",
                    fs: Some("fs_main"),
                    buffers: &[Some(Vertex::layout())],
                    color: Some(ctx.caps.hdr_format),
                    depth: OPAQUE_DEPTH,
                    cull: Some(wgpu::Face::Back),
                },
            ),
        }
    }
}
