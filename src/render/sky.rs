//! The procedural sky cube map and its roughness-blurred mips (environment mapping with the
//! split-sum prefiltering of Karis 2013). Made once per scene (or sky edit), not per frame.

use bytemuck::{Pod, Zeroable};
use wgpu::util::DeviceExt;

use crate::scene::Scene;

use super::pipelines::{CUBE_FORMAT, Layouts, Pipelines};

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct SkyParams {
    zenith: [f32; 4],
    horizon: [f32; 4],
    ground: [f32; 4],
    sun_dir: [f32; 4],
    sun_color: [f32; 4],
    face: [u32; 4],
}

pub struct Environment {
    pub texture: wgpu::Texture,
    pub view: wgpu::TextureView,
    pub mips: u32,
}

/// GGX samples per texel of the blurred mips.
const PREFILTER_SAMPLES: f32 = 64.0;

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

fn cube_texture(device: &wgpu::Device, label: &str, size: u32, mips: u32) -> wgpu::Texture {
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
        format: CUBE_FORMAT,
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
        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
            view,
            resolve_target: None,
            depth_slice: None,
            ops: wgpu::Operations {
                load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                store: wgpu::StoreOp::Store,
            },
        })],
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
    pipelines: &Pipelines,
    scene: &Scene,
    sampler: &wgpu::Sampler,
) -> Environment {
    let size = scene.sky.cube_size;
    // down to 8×8: rougher lobes than that are flat anyway
    let mips = (size.trailing_zeros() + 1).saturating_sub(3).max(1);
    let raw = cube_texture(device, "sky raw", size, 1);
    let env = cube_texture(device, "sky env", size, mips);
    let sun = glam::Vec3::from(scene.sun.direction).normalize();
    let k = &scene.sky;
    let sun_rgb = glam::Vec3::from(scene.sun.color) * k.sun_disc_intensity;
    let empty = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: None,
        layout: &layouts.empty,
        entries: &[],
    });
    let mut enc = device.create_command_encoder(&Default::default());
    for face in 0..6 {
        let params = SkyParams {
            zenith: [k.zenith_color[0], k.zenith_color[1], k.zenith_color[2], 0.0],
            horizon: [
                k.horizon_color[0],
                k.horizon_color[1],
                k.horizon_color[2],
                0.0,
            ],
            ground: [k.ground_color[0], k.ground_color[1], k.ground_color[2], 0.0],
            sun_dir: [sun.x, sun.y, sun.z, k.sun_size_deg.to_radians().cos()],
            sun_color: [sun_rgb.x, sun_rgb.y, sun_rgb.z, 0.0],
            face: [face, 0, 0, 0],
        };
        let buf = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("sky params"),
            contents: bytemuck::bytes_of(&params),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &layouts.sky_params,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: buf.as_entire_binding(),
            }],
        });
        fullscreen_pass(
            &mut enc,
            &face_view(&raw, face, 0),
            pipelines.get("sky.cube"),
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
            let params: [f32; 4] = [roughness, face as f32, PREFILTER_SAMPLES, 0.0];
            let buf = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("prefilter params"),
                contents: bytemuck::bytes_of(&params),
                usage: wgpu::BufferUsages::UNIFORM,
            });
            let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: None,
                layout: &layouts.prefilter,
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
                pipelines.get("prefilter"),
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
