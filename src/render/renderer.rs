//! The frame: shadow map → caustics map (when on) → opaque HDR pass (meshes, fish by level of detail, sky background
//! last) → copy of the opaque colour → water pass (reads that copy and the depth) → tone map
//! (scaling the HDR image up to the target) or a debug view into the caller's target. The
//! window, `render-scene`, tests and the benchmark share it. It only renders: it reads the
//! scene model and a per-frame snapshot and never changes either.

use std::path::{Path, PathBuf};

use wgpu::util::DeviceExt;

use crate::diag::Diagnostic;
use crate::scene::{FrameSnapshot, Scene};

use super::caustics;
use super::fish::LodView;
use super::frame::{self, DebugView, Globals, RenderSettings};
use super::pipeline::{BuildEnv, Layouts, Passes};
use super::resources::SceneResources;
use super::shadow;
use super::sky::{self, Environment, SkyKey};
use super::targets::{Targets, entry};
use super::tonemap::PostParams;

pub use super::shadow::SHADOW_MAP_SIZE;

/// What the last frame drew, for the panel and the tests.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct FrameInfo {
    /// the HDR targets' size (the output's, times the render scale)
    pub render_size: (u32, u32),
    /// visible fish per level of detail, finest first
    pub fish_per_lod: [u32; 3],
    /// every fish drawn into the shadow map
    pub fish_in_shadow: u32,
}

pub struct Renderer {
    device: wgpu::Device,
    queue: wgpu::Queue,
    layouts: Layouts,
    passes: Passes,
    output_format: wgpu::TextureFormat,
    linear_clamp: wgpu::Sampler,
    linear_repeat: wgpu::Sampler,
    shadow_sampler: wgpu::Sampler,
    shadow_view: wgpu::TextureView,
    caustics_view: wgpu::TextureView,
    /// the caustics map's side now (it follows the render scale)
    caustics_size_px: u32,
    globals: wgpu::Buffer,
    post_params: wgpu::Buffer,
    frame_group: wgpu::BindGroup,
    shadow_frame_group: wgpu::BindGroup,
    debug_group: wgpu::BindGroup,
    env: Environment,
    /// what `env` was made from: the sky and sun, and the generations of their pipelines
    sky_key: SkyKey,
    sky_generations: (u64, u64),
    res: SceneResources,
    targets: Option<Targets>,
    info: FrameInfo,
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

/// The size the scene is drawn at for an output of `size` at `render_scale`.
pub fn render_size(size: (u32, u32), render_scale: f32) -> (u32, u32) {
    let s = if render_scale.is_finite() {
        render_scale.clamp(0.1, 1.0)
    } else {
        1.0
    };
    (
        ((size.0 as f32 * s).round() as u32).max(1),
        ((size.1 as f32 * s).round() as u32).max(1),
    )
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
        let passes = Passes::new(
            &BuildEnv {
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
        let shadow_view = shadow::shadow_map(device);
        let caustics_size_px = caustics::CAUSTICS_MAP_SIZE;
        let caustics_view = caustics::caustics_map(device, caustics_size_px);
        let globals = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("globals"),
            size: std::mem::size_of::<Globals>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let post_params = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("post params"),
            contents: &[0u8; std::mem::size_of::<PostParams>()],
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        });
        let sky_key = SkyKey::of(scene);
        let env = sky::build(
            device,
            queue,
            &layouts,
            (&passes.sky.current, &passes.prefilter.current),
            &sky_key,
            &linear_clamp,
        );
        let res = SceneResources::new(device, queue, &layouts, scene, &linear_repeat);
        let shadow_frame_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("shadow frame"),
            layout: &layouts.shadow_frame.layout,
            entries: &[entry(0, globals.as_entire_binding())],
        });
        let (frame_group, debug_group) = env_groups(
            device,
            &layouts,
            &globals,
            &post_params,
            &env,
            (&linear_clamp, &shadow_sampler),
            (&shadow_view, &caustics_view),
        );
        Ok(Self {
            device: device.clone(),
            queue: queue.clone(),
            layouts,
            passes,
            output_format,
            linear_clamp,
            linear_repeat,
            shadow_sampler,
            shadow_view,
            caustics_view,
            caustics_size_px,
            globals,
            post_params,
            frame_group,
            shadow_frame_group,
            debug_group,
            env,
            sky_key,
            sky_generations: (0, 0),
            res,
            targets: None,
            info: FrameInfo::default(),
        })
    }

    fn env_changed(&mut self) {
        (self.frame_group, self.debug_group) = env_groups(
            &self.device,
            &self.layouts,
            &self.globals,
            &self.post_params,
            &self.env,
            (&self.linear_clamp, &self.shadow_sampler),
            (&self.shadow_view, &self.caustics_view),
        );
    }

    /// A new scene (reload): meshes and materials are rebuilt, the sky only if it or the sun
    /// changed; camera and time live in the simulation, not here, so they are untouched.
    pub fn set_scene(&mut self, scene: &Scene) {
        let key = SkyKey::of(scene);
        if key != self.sky_key {
            self.sky_key = key;
            self.rebuild_environment();
        }
        self.res = SceneResources::new(
            &self.device,
            &self.queue,
            &self.layouts,
            scene,
            &self.linear_repeat,
        );
    }

    fn rebuild_environment(&mut self) {
        self.env = sky::build(
            &self.device,
            &self.queue,
            &self.layouts,
            (&self.passes.sky.current, &self.passes.prefilter.current),
            &self.sky_key,
            &self.linear_clamp,
        );
        self.sky_generations = (self.passes.sky.generation, self.passes.prefilter.generation);
        self.env_changed();
    }

    /// Hot reload of shaders: rebuilds the techniques that use a changed file (and the sky
    /// cube when its own shaders were rebuilt). Returns whether any technique was affected.
    pub fn reload_shaders(&mut self, changed: &[PathBuf]) -> bool {
        let env = BuildEnv {
            device: &self.device,
            layouts: &self.layouts,
            output_format: self.output_format,
        };
        let any = self.passes.reload(&env, changed);
        if (self.passes.sky.generation, self.passes.prefilter.generation) != self.sky_generations {
            self.rebuild_environment();
        }
        any
    }

    /// The current shader errors (the previous pipelines are in use meanwhile).
    pub fn shader_errors(&self) -> Vec<&Diagnostic> {
        self.passes.errors()
    }

    /// Fish the instance buffer holds now (it grows with the count, to the next power of two).
    pub fn fish_capacity(&self) -> usize {
        self.res.fish_capacity
    }

    /// Indices of the water grid in use.
    pub fn water_index_count(&self) -> u32 {
        self.res.water_index_count
    }

    pub fn output_format(&self) -> wgpu::TextureFormat {
        self.output_format
    }

    /// What the last frame drew.
    pub fn frame_info(&self) -> &FrameInfo {
        &self.info
    }

    fn ensure_targets(&mut self, size: (u32, u32)) {
        if self.targets.as_ref().is_some_and(|t| t.size == size) {
            return;
        }
        self.targets = Some(Targets::new(
            &self.device,
            &self.layouts,
            size,
            &self.post_params,
            &self.linear_clamp,
        ));
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
        let inner = render_size(size, settings.render_scale);
        self.ensure_targets(inner);
        let caustics_size_px = caustics::map_size(settings.render_scale);
        if caustics_size_px != self.caustics_size_px {
            self.caustics_size_px = caustics_size_px;
            self.caustics_view = caustics::caustics_map(&self.device, caustics_size_px);
            // the lit passes' and the debug view's groups hold the map
            self.env_changed();
        }
        let g = frame::globals(scene, snap, settings, inner, self.env.mips);
        self.queue
            .write_buffer(&self.globals, 0, bytemuck::bytes_of(&g));
        let post = PostParams {
            exposure: settings.exposure,
            debug_view: settings.debug_view.code(),
            env_mip_count: self.env.mips as f32,
            _pad: 0.0,
            viewport_size_px: [size.0 as f32, size.1 as f32],
            _pad2: [0.0; 2],
        };
        self.queue
            .write_buffer(&self.post_params, 0, bytemuck::bytes_of(&post));
        let aspect = inner.0 as f32 / inner.1 as f32;
        let lod_view = LodView {
            clip_from_world: snap.camera.clip_from_view(aspect) * snap.camera.view_from_world(),
            px_per_m_at_1m: inner.1 as f32 / (2.0 * (0.5 * snap.camera.fov_y_rad).tan()),
            eye: snap.camera.eye,
            detail: settings.fish_detail,
        };
        self.res
            .update(&self.device, &self.queue, scene, snap, &lod_view);
        let ranges = &self.res.fish_ranges;
        self.info = FrameInfo {
            render_size: inner,
            fish_per_lod: ranges.visible.clone().map(|r| r.len() as u32),
            fish_in_shadow: ranges.all.len() as u32,
        };

        let t = self.targets.as_ref().expect("targets made above");
        let p = &self.passes;
        let res = &self.res;
        let mut enc = self
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("scene frame"),
            });

        // 1. shadow map from the sun: rocks, floating bodies, every fish at the coarsest level
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
            pass.set_pipeline(&p.shadow.current.pipeline);
            pass.set_bind_group(0, &self.shadow_frame_group, &[]);
            for o in res.objects.iter().filter(|o| o.casts_shadow) {
                pass.set_bind_group(1, &o.bind_group, &[]);
                o.mesh.draw(&mut pass, 1);
            }
            if !ranges.all.is_empty() {
                pass.set_pipeline(&p.fish.current.shadow);
                pass.set_bind_group(0, &self.shadow_frame_group, &[]);
                pass.set_vertex_buffer(1, res.fish_instances.slice(..));
                res.fish_meshes.lods[2].draw_instances(&mut pass, ranges.all.clone());
            }
        }

        // 2. the caustics map, only while they are on (off, the lit shaders weigh it by 0) or
        //    shown
        if settings.caustics || settings.debug_view == DebugView::CausticsMap {
            caustics::encode(
                &mut enc,
                &p.caustics.current,
                &self.shadow_frame_group,
                &self.caustics_view,
            );
        }

        // 3. opaque HDR pass
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
            pass.set_pipeline(&p.pbr.current.pipeline);
            for o in &res.objects {
                pass.set_bind_group(1, &res.materials[o.material].bind_group, &[]);
                pass.set_bind_group(2, &o.bind_group, &[]);
                o.mesh.draw(&mut pass, 1);
            }
            if ranges.visible_count() > 0 {
                pass.set_pipeline(&p.fish.current.main);
                pass.set_bind_group(1, &res.materials[res.fish_material].bind_group, &[]);
                pass.set_vertex_buffer(1, res.fish_instances.slice(..));
                for (mesh, range) in res.fish_meshes.lods.iter().zip(&ranges.visible) {
                    mesh.draw_instances(&mut pass, range.clone());
                }
            }
            // last, so the depth test skips every covered pixel
            pass.set_pipeline(&p.sky.current.background);
            pass.draw(0..3, 0..1);
        }

        // 4. what lies below the water, for refraction
        enc.copy_texture_to_texture(
            t.hdr.as_image_copy(),
            t.scene_color.as_image_copy(),
            t.scene_color.size(),
        );

        // 5. water: depth tested against the opaque depth, which it also samples (read-only)
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
            pass.set_pipeline(&p.water.current.pipeline);
            pass.set_bind_group(0, &self.frame_group, &[]);
            pass.set_bind_group(1, &t.water_inputs, &[]);
            pass.set_vertex_buffer(0, res.water_vertices.slice(..));
            pass.set_index_buffer(res.water_indices.slice(..), wgpu::IndexFormat::Uint32);
            pass.draw_indexed(0..res.water_index_count, 0, 0..1);
        }

        // 6. to the display: tone map (scaling up), or a debug view
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
                DebugView::ShadowMap | DebugView::EnvCube | DebugView::CausticsMap => {
                    pass.set_pipeline(&p.debug.current.pipeline);
                    pass.set_bind_group(0, &self.debug_group, &[]);
                }
                DebugView::None | DebugView::Normals => {
                    pass.set_pipeline(&p.tonemap.current.pipeline);
                    pass.set_bind_group(0, &t.tonemap, &[]);
                }
            }
            pass.draw(0..3, 0..1);
        }
        enc
    }
}

/// The bind groups that read the environment cube: group 0 of the lit passes, and the debug
/// views'.
fn env_groups(
    device: &wgpu::Device,
    layouts: &Layouts,
    globals: &wgpu::Buffer,
    post_params: &wgpu::Buffer,
    env: &Environment,
    (linear_clamp, shadow_sampler): (&wgpu::Sampler, &wgpu::Sampler),
    (shadow_view, caustics_view): (&wgpu::TextureView, &wgpu::TextureView),
) -> (wgpu::BindGroup, wgpu::BindGroup) {
    let frame = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("frame"),
        layout: &layouts.frame.layout,
        entries: &[
            entry(0, globals.as_entire_binding()),
            entry(1, wgpu::BindingResource::TextureView(&env.view)),
            entry(2, wgpu::BindingResource::Sampler(linear_clamp)),
            entry(3, wgpu::BindingResource::TextureView(shadow_view)),
            entry(4, wgpu::BindingResource::Sampler(shadow_sampler)),
            entry(5, wgpu::BindingResource::TextureView(caustics_view)),
            entry(6, wgpu::BindingResource::Sampler(linear_clamp)),
        ],
    });
    let debug = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("debug"),
        layout: &layouts.debug.layout,
        entries: &[
            entry(0, post_params.as_entire_binding()),
            entry(1, wgpu::BindingResource::TextureView(shadow_view)),
            entry(2, wgpu::BindingResource::TextureView(&env.view)),
            entry(3, wgpu::BindingResource::Sampler(linear_clamp)),
            entry(4, wgpu::BindingResource::TextureView(caustics_view)),
        ],
    });
    (frame, debug)
}
