//! Recording a frame: the scene into the HDR targets, then the output (tone mapping or a
//! debug view) into a render pass — the renderer's own over a target texture, or one the caller
//! owns (scene mode draws straight into egui's pass over the window, so the picture is not
//! drawn once into a texture and again by egui).

use crate::render::targets::{cleared_color, cleared_depth};
use crate::scene::{FrameSnapshot, Scene};

use super::{FrameInfo, Renderer, render_size};
use crate::render::caustics;
use crate::render::fish::{FAR_LEVEL, LodView};
use crate::render::frame::{self, DebugView, RenderSettings};
use crate::render::tonemap::PostParams;

/// What draws a frame's output into a render pass: the tone mapping or debug-view pipeline
/// (for the renderer's output format) and its bind group. Cheap to clone; it stays valid
/// while the frame's HDR targets do (until the output size or render scale changes).
#[derive(Clone)]
pub struct OutputDraw {
    pipeline: wgpu::RenderPipeline,
    bind_group: wgpu::BindGroup,
}

impl OutputDraw {
    /// A full-screen triangle over the pass's viewport.
    pub fn draw(&self, pass: &mut wgpu::RenderPass<'_>) {
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &self.bind_group, &[]);
        pass.draw(0..3, 0..1);
    }
}

impl Renderer {
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
        let mut enc = self.encode_scene(scene, snap, settings, size);
        let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("output"),
            color_attachments: &[cleared_color(target, wgpu::Color::BLACK)],
            ..Default::default()
        });
        if let Some(output) = self.output(settings) {
            output.draw(&mut pass);
        }
        drop(pass);
        enc
    }

    /// What draws the last encoded frame into an output pass: the tone-mapped image scaled up
    /// to the pass's viewport, or the debug view `settings` asks for. None before the
    /// first frame.
    pub fn output(&self, settings: &RenderSettings) -> Option<OutputDraw> {
        let t = self.targets.as_ref()?;
        let p = &self.passes;
        Some(match settings.debug_view {
            DebugView::ShadowMap | DebugView::EnvCube | DebugView::CausticsMap => OutputDraw {
                pipeline: p.debug.current().pipeline.clone(),
                bind_group: self.debug_group.clone(),
            },
            DebugView::None | DebugView::Normals => OutputDraw {
                pipeline: p.tonemap.current().upscale.clone(),
                bind_group: t.upscale.clone(),
            },
        })
    }

    /// Everything before the output, into the HDR targets at `render_size(size, render_scale)`:
    /// the uniforms and uploads, the shadow map, the caustics map, the opaque pass and the
    /// water. `size` is the output's, pixels. [`Self::output`] then draws the result.
    pub fn encode_scene(
        &mut self,
        scene: &Scene,
        snap: &FrameSnapshot,
        settings: &RenderSettings,
        size: (u32, u32),
    ) -> wgpu::CommandEncoder {
        let size = (size.0.max(1), size.1.max(1));
        let inner = self.caps.fit(render_size(size, settings.render_scale));
        self.ensure_targets(inner);
        let caustics_size_px =
            caustics::map_size(settings.render_scale, self.caps.caustics_map_size_px);
        if caustics_size_px != self.caustics_size_px {
            self.caustics_size_px = caustics_size_px;
            self.caustics_view =
                caustics::caustics_map(&self.device, caustics_size_px, self.caps.caustics_format);
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
        self.res.update(
            &self.device,
            &self.queue,
            scene,
            snap,
            &lod_view,
            self.caps.max_fish_instances,
        );
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

        // 1. shadow map from the sun: rocks, floating bodies, every fish at the far level
        {
            let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("shadow"),
                depth_stencil_attachment: cleared_depth(&self.shadow_view),
                ..Default::default()
            });
            pass.set_pipeline(&p.shadow.current().pipeline);
            pass.set_bind_group(0, &self.shadow_frame_group, &[]);
            for o in res.objects.iter().filter(|o| o.casts_shadow) {
                pass.set_bind_group(1, &o.bind_group, &[]);
                o.mesh.draw(&mut pass, 1);
            }
            if settings.fish_shadows && !ranges.all.is_empty() {
                pass.set_pipeline(&p.fish.current().shadow);
                pass.set_bind_group(0, &self.shadow_frame_group, &[]);
                pass.set_vertex_buffer(1, res.fish_instances.slice(..));
                res.fish_meshes.lods[FAR_LEVEL].draw_instances(&mut pass, ranges.all.clone());
            }
        }

        // 2. the caustics map, only while they are on (off, the lit shaders weigh it by 0) or
        //    shown
        if settings.caustics || settings.debug_view == DebugView::CausticsMap {
            caustics::encode(
                &mut enc,
                p.caustics.current(),
                &self.shadow_frame_group,
                &self.caustics_view,
                f64::from(self.caps.encoding.caustics_store_scale),
            );
        }

        // 3. opaque HDR pass
        {
            let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("opaque"),
                color_attachments: &[cleared_color(&t.hdr_view, wgpu::Color::BLACK)],
                depth_stencil_attachment: cleared_depth(&t.depth_view),
                ..Default::default()
            });
            pass.set_bind_group(0, &self.frame_group, &[]);
            pass.set_pipeline(p.pbr.current().pipeline.get(settings.shadow_filter));
            for o in &res.objects {
                pass.set_bind_group(1, &res.materials[o.material].bind_group, &[]);
                pass.set_bind_group(2, &o.bind_group, &[]);
                o.mesh.draw_detail(&mut pass, settings.coarse_grids);
            }
            if ranges.visible_count() > 0 {
                pass.set_pipeline(p.fish.current().main.get(settings.shadow_filter));
                pass.set_bind_group(1, &res.materials[res.fish_material].bind_group, &[]);
                pass.set_vertex_buffer(1, res.fish_instances.slice(..));
                for (mesh, range) in res.fish_meshes.lods.iter().zip(&ranges.visible) {
                    mesh.draw_instances(&mut pass, range.clone());
                }
            }
            // last, so the depth test skips every covered pixel
            pass.set_pipeline(&p.sky.current().background);
            pass.draw(0..3, 0..1);
        }

        // 4. what lies below the water and how far away, for refraction and absorption
        enc.copy_texture_to_texture(
            t.hdr.as_image_copy(),
            t.scene_color.as_image_copy(),
            t.scene_color.size(),
        );

        // 5. water: depth tested against the opaque depth (attached read-only, never sampled:
        //    the distances it needs are the copy's alpha)
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
            pass.set_pipeline(
                p.water
                    .current()
                    .get(settings.shadow_filter, settings.water_normals),
            );
            pass.set_bind_group(0, &self.frame_group, &[]);
            pass.set_bind_group(1, &t.water_inputs, &[]);
            pass.set_vertex_buffer(0, res.water_vertices.slice(..));
            let (indices, count) = if settings.coarse_grids {
                (&res.water_indices_coarse, res.water_index_count_coarse)
            } else {
                (&res.water_indices, res.water_index_count)
            };
            pass.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint32);
            pass.draw_indexed(0..count, 0, 0..1);
        }

        // 6. tone mapping (and FXAA) at the render size; the output pass scales it up
        {
            let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("tonemap"),
                color_attachments: &[cleared_color(&t.display_view, wgpu::Color::BLACK)],
                ..Default::default()
            });
            pass.set_pipeline(p.tonemap.current().get(settings.fxaa));
            pass.set_bind_group(0, &t.tonemap, &[]);
            pass.draw(0..3, 0..1);
        }
        enc
    }
}
