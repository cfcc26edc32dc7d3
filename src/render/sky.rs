//! The analytic daylight sky (sky.wgsl, Preetham, Shirley & Smits 1999) rendered into a cube map and drawn as the background
//! (environment mapping: Blinn & Newell 1976; cube maps: Greene 1986), the sun disc drawn
//! over it per pixel (the cube holds the sky only: reflections take the sun from the light's
//! specular lobe), and its
//! roughness-blurred mips (prefilter.wgsl; the split-sum prefiltering of Karis 2013). The cube
//! is made when the sky or the sun changes, never per frame.

use super::targets::cleared_color;
use bytemuck::{Pod, Zeroable};
use wgpu::util::DeviceExt;

use crate::scene::Scene;

use super::caps::RenderCaps;
use super::layouts::{FLOAT, Layout, Layouts, sampler, texture, uniform};
use super::pipeline::{Ctx, NO_BIAS, PipelineDesc, Technique};

/// Group 1 of the cube-face pass: the sky's colours and the face being drawn.
pub fn params_layout(device: &wgpu::Device) -> Layout {
    let vf = wgpu::ShaderStages::VERTEX | wgpu::ShaderStages::FRAGMENT;
    Layout::new(device, "sky params", &[uniform::<SkyParams>(0, vf)])
}

/// Group 0 of the prefilter pass: roughness and face, the raw sky cube, a sampler.
pub fn prefilter_layout(device: &wgpu::Device) -> Layout {
    let vf = wgpu::ShaderStages::VERTEX | wgpu::ShaderStages::FRAGMENT;
    Layout::new(
        device,
        "prefilter",
        &[
            uniform::<PrefilterParams>(0, vf),
            texture(1, wgpu::TextureViewDimension::Cube, FLOAT),
            sampler(2, wgpu::SamplerBindingType::Filtering),
        ],
    )
}

/// The sky's pipelines: into a cube face, and as the background of the opaque pass.
pub struct SkyPipelines {
    pub cube: wgpu::RenderPipeline,
    pub background: wgpu::RenderPipeline,
}

impl Technique for SkyPipelines {
    const SHADER: &'static str = "sky.wgsl";

    fn build(ctx: &Ctx, m: &wgpu::ShaderModule) -> Self {
        let l = ctx.layouts;
        Self {
            cube: ctx.pipeline(
                m,
                PipelineDesc {
                    label: "sky.cube",
                    groups: &[&l.empty, &l.sky_params],
                    vs: "vs_fullscreen",
                    fs: Some("fs_cube_face"),
                    buffers: &[],
                    color: Some(ctx.caps.cube_format),
                    depth: None,
                    cull: None,
                },
            ),
            background: ctx.pipeline(
                m,
                PipelineDesc {
                    label: "sky.background",
                    groups: &[&l.frame],
                    vs: "vs_fullscreen",
                    fs: Some("fs_background"),
                    buffers: &[],
                    color: Some(ctx.caps.hdr_format),
                    depth: Some((false, wgpu::CompareFunction::LessEqual, NO_BIAS)),
                    cull: None,
                },
            ),
        }
    }
}

pub struct PrefilterPipeline {
    pub pipeline: wgpu::RenderPipeline,
}

impl Technique for PrefilterPipeline {
    const SHADER: &'static str = "prefilter.wgsl";

    fn build(ctx: &Ctx, m: &wgpu::ShaderModule) -> Self {
        Self {
            pipeline: ctx.pipeline(
                m,
                PipelineDesc {
                    label: "prefilter",
                    groups: &[&ctx.layouts.prefilter],
                    vs: "vs_fullscreen",
                    fs: Some("fs_main"),
                    buffers: &[],
                    color: Some(ctx.caps.cube_format),
                    depth: None,
                    cull: None,
                },
            ),
        }
    }
}

/// `Params` in prefilter.wgsl.
#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
pub struct PrefilterParams {
    pub roughness: f32,
    pub face: u32,
    pub _pad: [u32; 2],
}

/// What the environment is made from: when this is unchanged (a scene reload that touched the
/// fish, say) the cube is kept.
#[derive(Debug, Clone, PartialEq)]
pub struct SkyKey {
    pub sky: crate::scene::model::Sky,
    pub sun: crate::scene::model::Sun,
}

impl SkyKey {
    pub fn of(scene: &Scene) -> Self {
        Self {
            sky: scene.sky.clone(),
            sun: scene.sun.clone(),
        }
    }
}

/// `SkyParams` in sky.wgsl.
#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
pub struct SkyParams {
    sun_dir: [f32; 4],
    ground: [f32; 4],
    turbidity: f32,
    radiance_per_kcd: f32,
    _pad: [f32; 2],
    face: [u32; 4],
}

pub struct Environment {
    pub texture: wgpu::Texture,
    pub view: wgpu::TextureView,
    pub mips: u32,
}

fn face_view(texture: &wgpu::Texture, face: u32, mip: u32) -> wgpu::TextureView {
    texture.create_view(&wgpu::TextureViewDescriptor {
        dimension: Some(wgpu::TextureViewDimension::D2),
        base_array_layer: face,
        array_layer_count: Some(1),
        base_mip_level: mip,
        mip_level_count: Some(1),
        ..Default::default()
    })
}

fn cube_view(texture: &wgpu::Texture) -> wgpu::TextureView {
    texture.create_view(&wgpu::TextureViewDescriptor {
        dimension: Some(wgpu::TextureViewDimension::Cube),
        ..Default::default()
    })
}

fn cube_texture(
    device: &wgpu::Device,
    label: &str,
    size: u32,
    mips: u32,
    format: wgpu::TextureFormat,
) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width: size,
            height: size,
            depth_or_array_layers: 6,
        },
        mip_level_count: mips,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
        view_formats: &[],
    })
}

fn fullscreen_pass(
    enc: &mut wgpu::CommandEncoder,
    view: &wgpu::TextureView,
    pipeline: &wgpu::RenderPipeline,
    groups: &[&wgpu::BindGroup],
) {
    let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some("cube face"),
        color_attachments: &[cleared_color(view, wgpu::Color::BLACK)],
        ..Default::default()
    });
    pass.set_pipeline(pipeline);
    for (i, g) in groups.iter().enumerate() {
        pass.set_bind_group(i as u32, Some(*g), &[]);
    }
    pass.draw(0..3, 0..1);
}

/// Renders the sky into a cube map, then prefilters it into a mip chain (mip m holds roughness
/// m / (mips − 1)).
pub fn build(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    layouts: &Layouts,
    (sky, prefilter): (&SkyPipelines, &PrefilterPipeline),
    key: &SkyKey,
    sampler: &wgpu::Sampler,
    caps: &RenderCaps,
) -> Environment {
    let size = key.sky.cube_size.min(caps.max_texture_side_px);
    // down to 8×8: rougher lobes than that are flat anyway
    let mips = (size.trailing_zeros() + 1).saturating_sub(3).max(1);
    let raw = cube_texture(device, "sky raw", size, 1, caps.cube_format);
    let env = cube_texture(device, "sky env", size, mips, caps.cube_format);
    let sun = glam::Vec3::from(key.sun.direction).normalize();
    let k = &key.sky;
    let empty = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: None,
        layout: &layouts.empty.layout,
        entries: &[],
    });
    let mut enc = device.create_command_encoder(&Default::default());
    for face in 0..6 {
        let params = SkyParams {
            sun_dir: [sun.x, sun.y, sun.z, 0.0],
            ground: [k.ground_color[0], k.ground_color[1], k.ground_color[2], 0.0],
            turbidity: k.turbidity,
            radiance_per_kcd: k.radiance_per_kcd,
            _pad: [0.0; 2],
            face: [face, 0, 0, 0],
        };
        let buf = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("sky params"),
            contents: bytemuck::bytes_of(&params),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &layouts.sky_params.layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: buf.as_entire_binding(),
            }],
        });
        fullscreen_pass(
            &mut enc,
            &face_view(&raw, face, 0),
            &sky.cube,
            &[&empty, &group],
        );
    }
    let raw_cube = cube_view(&raw);
    for mip in 0..mips {
        let roughness = if mips > 1 {
            mip as f32 / (mips - 1) as f32
        } else {
            0.0
        };
        for face in 0..6 {
            let params = PrefilterParams {
                roughness,
                face,
                _pad: [0; 2],
            };
            let buf = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("prefilter params"),
                contents: bytemuck::bytes_of(&params),
                usage: wgpu::BufferUsages::UNIFORM,
            });
            let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: None,
                layout: &layouts.prefilter.layout,
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: buf.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: wgpu::BindingResource::TextureView(&raw_cube),
                    },
                    wgpu::BindGroupEntry {
                        binding: 2,
                        resource: wgpu::BindingResource::Sampler(sampler),
                    },
                ],
            });
            fullscreen_pass(
                &mut enc,
                &face_view(&env, face, mip),
                &prefilter.pipeline,
                &[&group],
            );
        }
    }
    queue.submit([enc.finish()]);
    Environment {
        view: cube_view(&env),
        texture: env,
        mips,
    }
}
