//! The frame: shadow map → opaque HDR pass (sky background, meshes, instanced fish) → copy of
//! the opaque colour → water pass (reads that copy and the depth) → tone map or debug view
//! into the caller's target. Window, `render-scene`, tests and the benchmark share it.

use std::path::{Path, PathBuf};

use anyhow::Result;
use wgpu::util::DeviceExt;

use crate::diag::Diagnostic;
use crate::scene::{FrameSnapshot, Scene};

use super::frame::{self, DebugView, Globals, RenderSettings};
use super::pipelines::{Ctx, DEPTH_FORMAT, HDR_FORMAT, Layouts, Pipelines};
use super::resources::SceneResources;
use super::sky::{self, Environment};

pub const SHADOW_MAP_SIZE: u32 = 1024;

struct Targets {
    size: (u32, u32),
    hdr: wgpu::Texture,
    hdr_view: wgpu::TextureView,
    depth_view: wgpu::TextureView,
    scene_color: wgpu::Texture,
    water_inputs: wgpu::BindGroup,
    tonemap: wgpu::BindGroup,
}

pub struct Renderer {
    device: wgpu::Device,
    queue: wgpu::Queue,
    layouts: Layouts,
    pipelines: Pipelines,
    output_format: wgpu::TextureFormat,
    linear_clamp: wgpu::Sampler,
    linear_repeat: wgpu::Sampler,
    shadow_view: wgpu::TextureView,
    globals: wgpu::Buffer,
    post_params: wgpu::Buffer,
    frame_group: wgpu::BindGroup,
    shadow_frame_group: wgpu::BindGroup,
    debug_group: wgpu::BindGroup,
    env: Environment,
    res: SceneResources,
    targets: Option<Targets>,
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

fn tex(
    device: &wgpu::Device,
    label: &str,
    size: (u32, u32),
    format: wgpu::TextureFormat,
    usage: wgpu::TextureUsages,
) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width: size.0.max(1),
            height: size.1.max(1),
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage,
        view_formats: &[],
    })
}

fn entry(binding: u32, resource: wgpu::BindingResource<'_>) -> wgpu::BindGroupEntry<'_> {
    wgpu::BindGroupEntry { binding, resource }
}

impl Renderer {
    /// Builds pipelines from `shader_dir` (every shader must be valid the first time) and the
    /// scene's GPU resources. `output_format` is what `render` draws into.
    pub fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        shader_dir: &Path,
        scene: &Scene,
        output_format: wgpu::TextureFormat,
    ) -> Result<Self, Diagnostic> {
        let layouts = Layouts::new(device);
        let pipelines = Pipelines::new(
            &Ctx {
                device,
                layouts: &layouts,
                output_format,
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
        let shadow = tex(
            device,
            "shadow map",
            (SHADOW_MAP_SIZE, SHADOW_MAP_SIZE),
            DEPTH_FORMAT,
            wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
        );
        let shadow_view = shadow.create_view(&Default::default());
        let globals = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("globals"),
            size: std::mem::size_of::<Globals>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let post_params = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("post params"),
            contents: &[0u8; 16],
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        });
        let env = sky::build(device, queue, &layouts, &pipelines, scene, &linear_clamp);
        let res = SceneResources::new(device, queue, &layouts, scene, &linear_repeat);
        let shadow_frame_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("shadow frame"),
            layout: &layouts.shadow_frame,
            entries: &[entry(0, globals.as_entire_binding())],
        });
        let mut r = Self {
            frame_group: shadow_frame_group.clone(),
            debug_group: shadow_frame_group.clone(),
            shadow_frame_group,
            device: device.clone(),
            queue: queue.clone(),
            layouts,
            pipelines,
            output_format,
            linear_clamp,
            linear_repeat,
            shadow_view,
            globals,
            post_params,
            env,
            res,
            targets: None,
        };
        r.frame_group = r.make_frame_group(&shadow_sampler);
        r.debug_group = r.make_debug_group();
        Ok(r)
    }

    fn make_frame_group(&self, shadow_sampler: &wgpu::Sampler) -> wgpu::BindGroup {
        self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("frame"),
            layout: &self.layouts.frame,
            entries: &[
                entry(0, self.globals.as_entire_binding()),
                entry(1, wgpu::BindingResource::TextureView(&self.env.view)),
                entry(2, wgpu::BindingResource::Sampler(&self.linear_clamp)),
                entry(3, wgpu::BindingResource::TextureView(&self.shadow_view)),
                entry(4, wgpu::BindingResource::Sampler(shadow_sampler)),
            ],
        })
    }

    fn make_debug_group(&self) -> wgpu::BindGroup {
        self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("debug"),
            layout: &self.layouts.debug,
            entries: &[
                entry(0, self.post_params.as_entire_binding()),
                entry(1, wgpu::BindingResource::TextureView(&self.shadow_view)),
                entry(2, wgpu::BindingResource::TextureView(&self.env.view)),
                entry(3, wgpu::BindingResource::Sampler(&self.linear_clamp)),
            ],
        })
    }

    /// A new scene (reload): meshes, materials and sky are rebuilt; camera and time live in
    /// the simulation, not here, so they are untouched.
    pub fn set_scene(&mut self, scene: &Scene) {
        self.env = sky::build(
            &self.device,
            &self.queue,
            &self.layouts,
            &self.pipelines,
            scene,
            &self.linear_clamp,
        );
        self.res = SceneResources::new(
            &self.device,
            &self.queue,
            &self.layouts,
            scene,
            &self.linear_repeat,
        );
        let shadow_sampler = sampler(
            &self.device,
            wgpu::AddressMode::ClampToEdge,
            Some(wgpu::CompareFunction::LessEqual),
        );
        self.frame_group = self.make_frame_group(&shadow_sampler);
        self.debug_group = self.make_debug_group();
    }

    /// Hot reload of shaders: rebuilds those that use a changed file. Returns whether any did.
    pub fn reload_shaders(&mut self, changed: &[PathBuf]) -> bool {
        let ctx = Ctx {
            device: &self.device,
            layouts: &self.layouts,
            output_format: self.output_format,
        };
        self.pipelines.reload(&ctx, changed)
    }

    /// The current shader errors (the previous pipelines are in use meanwhile).
    pub fn shader_errors(&self) -> Vec<&Diagnostic> {
        self.pipelines.errors()
    }

    /// Fish the instance buffer holds now (it grows with the count, to the next power of two).
    pub fn fish_capacity(&self) -> usize {
        self.res.fish_capacity
    }

    /// Vertices per side of the water grid in use.
    pub fn water_index_count(&self) -> u32 {
        self.res.water_index_count
    }

    pub fn output_format(&self) -> wgpu::TextureFormat {
        self.output_format
    }

    fn ensure_targets(&mut self, size: (u32, u32)) {
        if self.targets.as_ref().is_some_and(|t| t.size == size) {
            return;
        }
        use wgpu::TextureUsages as U;
        let d = &self.device;
        let hdr = tex(
            d,
            "hdr",
            size,
            HDR_FORMAT,
            U::RENDER_ATTACHMENT | U::TEXTURE_BINDING | U::COPY_SRC,
        );
        let depth = tex(
            d,
            "depth",
            size,
            DEPTH_FORMAT,
            U::RENDER_ATTACHMENT | U::TEXTURE_BINDING,
        );
        let scene_color = tex(
            d,
            "scene colour",
            size,
            HDR_FORMAT,
            U::COPY_DST | U::TEXTURE_BINDING,
        );
        let hdr_view = hdr.create_view(&Default::default());
        let depth_view = depth.create_view(&Default::default());
        let scene_view = scene_color.create_view(&Default::default());
        let water_inputs = d.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("water inputs"),
            layout: &self.layouts.water_inputs,
            entries: &[
                entry(0, wgpu::BindingResource::TextureView(&scene_view)),
                entry(1, wgpu::BindingResource::TextureView(&depth_view)),
                entry(2, wgpu::BindingResource::Sampler(&self.linear_clamp)),
            ],
        });
        let tonemap = d.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("tonemap"),
            layout: &self.layouts.tonemap,
            entries: &[
                entry(0, self.post_params.as_entire_binding()),
                entry(1, wgpu::BindingResource::TextureView(&hdr_view)),
            ],
        });
        self.targets = Some(Targets {
            size,
            hdr,
            hdr_view,
            depth_view,
            scene_color,
            water_inputs,
            tonemap,
        });
    }

    /// Records and submits one frame into `target` (of `output_format`, `size` pixels).
    pub fn render(
        &mut self,
        scene: &Scene,
        snap: &FrameSnapshot,
        settings: &RenderSettings,
        target: &wgpu::TextureView,
        size: (u32, u32),
    ) -> wgpu::SubmissionIndex {
        let enc = self.encode(scene, snap, settings, target, size);
        self.queue.submit([enc.finish()])
    }

    /// As `render`, but returns the recorded encoder unsubmitted (the benchmark times the CPU
    /// side of recording separately from the GPU's work).
    pub fn encode(
        &mut self,
        scene: &Scene,
        snap: &FrameSnapshot,
        settings: &RenderSettings,
        target: &wgpu::TextureView,
        size: (u32, u32),
    ) -> wgpu::CommandEncoder {
        let size = (size.0.max(1), size.1.max(1));
        self.ensure_targets(size);
        let g = frame::globals(scene, snap, settings, size, self.env.mips);
        self.queue
            .write_buffer(&self.globals, 0, bytemuck::bytes_of(&g));
        let post: [f32; 4] = [
            settings.exposure,
            settings.debug_view.code(),
            size.0 as f32,
            size.1 as f32,
        ];
        let post = match settings.debug_view {
            DebugView::EnvCube => [3.0, self.env.mips as f32, size.0 as f32, size.1 as f32],
            _ => post,
        };
        self.queue
            .write_buffer(&self.post_params, 0, bytemuck::bytes_of(&post));
        self.res.update(&self.device, &self.queue, scene, snap);

        let t = self.targets.as_ref().expect("targets made above");
        let p = &self.pipelines;
        let res = &self.res;
        let mut enc = self
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("scene frame"),
            });

        // 1. shadow map from the sun: rocks, floating bodies, fish
        {
            let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("shadow"),
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &self.shadow_view,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(1.0),
                        store: wgpu::StoreOp::Store,
                    }),
                    stencil_ops: None,
                }),
                ..Default::default()
            });
            pass.set_pipeline(p.get("shadow"));
            pass.set_bind_group(0, &self.shadow_frame_group, &[]);
            for o in res.objects.iter().filter(|o| o.casts_shadow) {
                pass.set_bind_group(1, &o.bind_group, &[]);
                o.mesh.draw(&mut pass, 1);
            }
            if res.fish_count > 0 {
                pass.set_pipeline(p.get("fish.shadow"));
                pass.set_bind_group(0, &self.shadow_frame_group, &[]);
                pass.set_vertex_buffer(1, res.fish_instances.slice(..));
                res.fish_mesh.draw(&mut pass, res.fish_count);
            }
        }

        // 2. opaque HDR pass
        {
            let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("opaque"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &t.hdr_view,
                    resolve_target: None,
                    depth_slice: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &t.depth_view,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(1.0),
                        store: wgpu::StoreOp::Store,
                    }),
                    stencil_ops: None,
                }),
                ..Default::default()
            });
            pass.set_bind_group(0, &self.frame_group, &[]);
            pass.set_pipeline(p.get("pbr"));
            for o in &res.objects {
                pass.set_bind_group(1, &res.materials[o.material].bind_group, &[]);
                pass.set_bind_group(2, &o.bind_group, &[]);
                o.mesh.draw(&mut pass, 1);
            }
            if res.fish_count > 0 {
                pass.set_pipeline(p.get("fish"));
                pass.set_bind_group(1, &res.materials[res.fish_material].bind_group, &[]);
                pass.set_vertex_buffer(1, res.fish_instances.slice(..));
                res.fish_mesh.draw(&mut pass, res.fish_count);
            }
            // last, so the depth test skips every covered pixel
            pass.set_pipeline(p.get("sky.background"));
            pass.draw(0..3, 0..1);
        }

        // 3. what lies below the water, for refraction
        enc.copy_texture_to_texture(
            t.hdr.as_image_copy(),
            t.scene_color.as_image_copy(),
            t.scene_color.size(),
        );

        // 4. water: depth tested against the opaque depth, which it also samples (read-only)
        {
            let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("water"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &t.hdr_view,
                    resolve_target: None,
                    depth_slice: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Load,
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &t.depth_view,
                    depth_ops: None,
                    stencil_ops: None,
                }),
                ..Default::default()
            });
            pass.set_pipeline(p.get("water"));
            pass.set_bind_group(0, &self.frame_group, &[]);
            pass.set_bind_group(1, &t.water_inputs, &[]);
            pass.set_vertex_buffer(0, res.water_vertices.slice(..));
            pass.set_index_buffer(res.water_indices.slice(..), wgpu::IndexFormat::Uint32);
            pass.draw_indexed(0..res.water_index_count, 0, 0..1);
        }

        // 5. to the display: tone map, or a debug view
        {
            let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("output"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: target,
                    resolve_target: None,
                    depth_slice: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                ..Default::default()
            });
            match settings.debug_view {
                DebugView::ShadowMap | DebugView::EnvCube => {
                    pass.set_pipeline(p.get("debug"));
                    pass.set_bind_group(0, &self.debug_group, &[]);
                }
                _ => {
                    pass.set_pipeline(p.get("tonemap"));
                    pass.set_bind_group(0, &t.tonemap, &[]);
                }
            }
            pass.draw(0..3, 0..1);
        }
        enc
    }
}
