//! Headless rendering: the same egui code the window runs, painted by egui-wgpu into an
//! offscreen texture and read back. `lectern export`, snapshot tests and the presenter's
//! "export this slide" all come through here; any adapter works, including Mesa's software
//! lavapipe / llvmpipe, so no display and no GPU are needed.

use std::cell::Cell;
use std::sync::Arc;
use std::time::Duration;

use egui_wgpu::{RenderState, ScreenDescriptor, WgpuSetup, wgpu};
use image::RgbaImage;

use super::slide_state::SlideState;
use super::slide_view::{SlideOptions, slide_ui_with};
use crate::deck::Deck;

/// How long a software rasteriser may take for one frame before we call the device lost.
const WAIT: Duration = Duration::from_secs(60);

#[derive(Debug, thiserror::Error)]
pub enum OffscreenError {
    #[error(
        "no graphics adapter found (no GPU, and no software one: on Debian install \
         mesa-vulkan-drivers and libvulkan1): {0}"
    )]
    NoAdapter(String),
    #[error("size {0}x{1} is not drawable (each side 16..=8192 pixels)")]
    BadSize(u32, u32),
    #[error("GPU: {0}")]
    Gpu(String),
}

/// How much an adapter is preferred (smaller first): a GPU before a software rasteriser (or
/// after, `software_first`), and Vulkan, Metal or DX12 before GL, which is the fallback where
/// nothing else runs (a VM or lecture-room PC with OpenGL only). The window's choice too.
pub fn adapter_rank(info: &wgpu::AdapterInfo, software_first: bool) -> (i32, i32) {
    let device = match info.device_type {
        wgpu::DeviceType::DiscreteGpu => 0,
        wgpu::DeviceType::IntegratedGpu => 1,
        wgpu::DeviceType::VirtualGpu | wgpu::DeviceType::Other => 2,
        wgpu::DeviceType::Cpu if software_first => -1,
        wgpu::DeviceType::Cpu => 3,
    };
    let backend = match info.backend {
        wgpu::Backend::Vulkan | wgpu::Backend::Metal | wgpu::Backend::Dx12 => 0,
        wgpu::Backend::Gl => 1,
        _ => 2,
    };
    (device, backend)
}

/// An egui context and a wgpu device for drawing UIs to images. Keep one for many images:
/// fonts, textures and widget memory are reused.
pub struct OffscreenRenderer {
    render_state: RenderState,
    ctx: egui::Context,
}

impl OffscreenRenderer {
    /// Finds an adapter: a real GPU if there is one, else a software one.
    pub fn new() -> Result<Self, OffscreenError> {
        Self::with_preference(false, None)
    }

    /// Prefers a software adapter even when a GPU exists: bit-stable images for snapshot tests.
    pub fn software_first() -> Result<Self, OffscreenError> {
        Self::with_preference(true, None)
    }

    /// As [`Self::software_first`], on `backends` only (tests run the GL backend this way).
    pub fn software_first_on(backends: wgpu::Backends) -> Result<Self, OffscreenError> {
        Self::with_preference(true, Some(backends))
    }

    fn with_preference(
        software_first: bool,
        backends: Option<wgpu::Backends>,
    ) -> Result<Self, OffscreenError> {
        let mut setup = egui_wgpu::WgpuSetupCreateNew::without_display_handle();
        if let Some(b) = backends {
            setup.instance_descriptor.backends = b;
        }
        setup
            .instance_descriptor
            .backends
            .remove(wgpu::Backends::BROWSER_WEBGPU);
        setup.native_adapter_selector = Some(Arc::new(move |adapters, _surface| {
            adapters
                .iter()
                .filter(|a| a.get_info().backend != wgpu::Backend::Noop)
                .min_by_key(|a| adapter_rank(&a.get_info(), software_first))
                .cloned()
                .ok_or_else(|| "no adapter found".to_owned())
        }));
        let setup = WgpuSetup::CreateNew(setup);
        let instance = pollster::block_on(setup.new_instance());
        let config = egui_wgpu::WgpuConfiguration {
            wgpu_setup: setup,
            ..Default::default()
        };
        let render_state = pollster::block_on(RenderState::create(
            &config,
            &instance,
            None,
            egui_wgpu::RendererOptions::PREDICTABLE,
        ))
        .map_err(|e| OffscreenError::NoAdapter(e.to_string()))?;
        // The default handler panics on a validation error; an export should fail instead.
        render_state
            .device
            .on_uncaptured_error(Arc::new(|e| tracing::error!("wgpu: {e}")));
        let ctx = egui::Context::default();
        ctx.all_styles_mut(|style| {
            style.animation_time = 0.0;
            style.visuals.text_cursor.blink = false;
        });
        // Scene widgets render on this device, at full size and at their deck's `time_s`.
        crate::widgets::scene::SceneGpu::install(&ctx, render_state.clone(), 1.0, false);
        Ok(Self { render_state, ctx })
    }

    /// "Vulkan llvmpipe (LLVM 15.0.6, 256 bits)" and the like.
    pub fn adapter_name(&self) -> String {
        let info = self.render_state.adapter.get_info();
        format!("{:?} {}", info.backend, info.name)
    }

    /// The wgpu state (device, queue, egui renderer), for widgets that paint with wgpu.
    pub fn render_state(&self) -> &RenderState {
        &self.render_state
    }

    pub fn egui_ctx(&self) -> &egui::Context {
        &self.ctx
    }

    /// Runs `ui` for a few passes (egui lays out in one pass what it measured in the one before;
    /// plots fit their bounds on the first) and returns the last as an image of `size` pixels.
    pub fn render(
        &mut self,
        size: [u32; 2],
        pixels_per_point: f32,
        ui: impl FnMut(&mut egui::Ui),
    ) -> Result<RgbaImage, OffscreenError> {
        self.render_cleared(size, pixels_per_point, ui, &Cell::new(egui::Color32::BLACK))
    }

    /// [`Self::render`] onto a target cleared to `clear` (read when the last pass is painted,
    /// so `ui` may set it, as the window's clear colour follows the app's state).
    pub fn render_cleared(
        &mut self,
        size: [u32; 2],
        pixels_per_point: f32,
        mut ui: impl FnMut(&mut egui::Ui),
        clear: &Cell<egui::Color32>,
    ) -> Result<RgbaImage, OffscreenError> {
        let [w, h] = size;
        if !(16..=8192).contains(&w) || !(16..=8192).contains(&h) {
            return Err(OffscreenError::BadSize(w, h));
        }
        let points = egui::vec2(w as f32, h as f32) / pixels_per_point;
        let mut input = egui::RawInput {
            screen_rect: Some(egui::Rect::from_min_size(egui::Pos2::ZERO, points)),
            max_texture_side: Some(
                self.render_state.device.limits().max_texture_dimension_2d as usize,
            ),
            ..Default::default()
        };
        if let Some(vp) = input.viewports.get_mut(&egui::ViewportId::ROOT) {
            vp.native_pixels_per_point = Some(pixels_per_point);
        }
        let mut last = None;
        for pass in 0..3 {
            input.time = Some(pass as f64 / 60.0);
            let mut out = self.ctx.run_ui(input.clone(), |ui_root| ui(ui_root));
            let mut delta = std::mem::take(&mut out.textures_delta);
            self.apply_textures(&delta);
            if pass < 2 {
                self.free_textures(&delta);
                delta.clear();
            }
            last = Some((out, delta));
        }
        let (out, mut delta) = last.expect("three passes ran");
        let image = self.paint(&out, [w, h], pixels_per_point, clear.get());
        // egui frees textures only after the frame that last used them is painted.
        self.free_textures(&delta);
        delta.clear();
        image
    }

    /// Slide `index` of `deck` at `size` pixels, as a 1280-point-wide window shows it (see
    /// [`slide_pixels_per_point`]), so a 720p, a 1080p and a 4K export are the same picture.
    pub fn render_slide(
        &mut self,
        deck: &Deck,
        index: usize,
        state: &mut SlideState,
        size: [u32; 2],
    ) -> Result<RgbaImage, OffscreenError> {
        self.render_slide_with(deck, index, state, size, SlideOptions::default())
    }

    /// Slide `index` of `deck` at `size` pixels, drawn with `options` (e.g. with its ink).
    pub fn render_slide_with(
        &mut self,
        deck: &Deck,
        index: usize,
        state: &mut SlideState,
        size: [u32; 2],
        options: SlideOptions,
    ) -> Result<RgbaImage, OffscreenError> {
        let ppp = slide_pixels_per_point(deck, size);
        self.render(size, ppp, |ui| {
            slide_ui_with(ui, deck, index, state, options);
        })
    }

    fn apply_textures(&mut self, set: &egui::TexturesDelta) {
        let mut renderer = self.render_state.renderer.write();
        for (id, deltas) in &set.set {
            for delta in deltas {
                renderer.update_texture(
                    &self.render_state.device,
                    &self.render_state.queue,
                    *id,
                    delta,
                );
            }
        }
    }

    fn free_textures(&mut self, delta: &egui::TexturesDelta) {
        let mut renderer = self.render_state.renderer.write();
        for id in &delta.free {
            renderer.free_texture(id);
        }
    }

    fn paint(
        &mut self,
        out: &egui::FullOutput,
        [w, h]: [u32; 2],
        pixels_per_point: f32,
        clear: egui::Color32,
    ) -> Result<RgbaImage, OffscreenError> {
        let rs = &self.render_state;
        let screen = ScreenDescriptor {
            size_in_pixels: [w, h],
            pixels_per_point,
        };
        let primitives = self.ctx.tessellate(out.shapes.clone(), pixels_per_point);
        let texture = rs.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("lectern offscreen"),
            size: wgpu::Extent3d {
                width: w,
                height: h,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: rs.target_format,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
        let mut encoder = rs
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("lectern offscreen"),
            });
        let mut renderer = rs.renderer.write();
        let user_buffers =
            renderer.update_buffers(&rs.device, &rs.queue, &mut encoder, &primitives, &screen);
        {
            let mut pass = encoder
                .begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: Some("lectern offscreen"),
                    color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                        view: &view,
                        resolve_target: None,
                        ops: wgpu::Operations {
                            load: wgpu::LoadOp::Clear(clear_color(clear)),
                            store: wgpu::StoreOp::Store,
                        },
                        depth_slice: None,
                    })],
                    ..Default::default()
                })
                .forget_lifetime();
            renderer.render(&mut pass, &primitives, &screen);
        }
        drop(renderer);
        rs.queue
            .submit(user_buffers.into_iter().chain(Some(encoder.finish())));
        read_back(&rs.device, &rs.queue, &texture)
    }
}

/// Width in points of the window whose layout an exported slide shows: the size the slides are
/// designed and snapshot-tested at.
pub const SLIDE_LAYOUT_WIDTH_PT: f32 = 1280.0;

/// Pixels per point for an image of `size` pixels of a slide of `deck`: the slide is laid out
/// as on a [`SLIDE_LAYOUT_WIDTH_PT`]-wide window and scaled to the pixels. With one point per
/// pixel at every size, a 4K image would lay out on a 3840-point canvas: text scales with the
/// slide but plot strokes, ticks and markers keep their size in points and the plots come out
/// thin and differently ticked.
pub fn slide_pixels_per_point(deck: &Deck, size: [u32; 2]) -> f32 {
    let [w, h] = size.map(|v| v.max(1) as f32);
    let layout_h = SLIDE_LAYOUT_WIDTH_PT / deck.aspect.ratio();
    (w / SLIDE_LAYOUT_WIDTH_PT).min(h / layout_h)
}

/// `c` as the render pass's clear value: egui paints gamma-encoded colours into a target that
/// stores them as they are (no sRGB conversion), so the clear takes the same encoding.
fn clear_color(c: egui::Color32) -> wgpu::Color {
    let [r, g, b, a] = c.to_normalized_gamma_f32().map(f64::from);
    wgpu::Color { r, g, b, a }
}

/// Copies an RGBA8 texture into an image (rows padded to wgpu's 256-byte alignment, then
/// stripped).
fn read_back(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
) -> Result<RgbaImage, OffscreenError> {
    let (w, h) = (texture.width(), texture.height());
    let unpadded = w as usize * 4;
    let align = wgpu::COPY_BYTES_PER_ROW_ALIGNMENT as usize;
    let padded = unpadded.div_ceil(align) * align;
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("lectern read-back"),
        size: (padded * h as usize) as u64,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("lectern read-back"),
    });
    encoder.copy_texture_to_buffer(
        texture.as_image_copy(),
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded as u32),
                rows_per_image: None,
            },
        },
        wgpu::Extent3d {
            width: w,
            height: h,
            depth_or_array_layers: 1,
        },
    );
    let index = queue.submit(Some(encoder.finish()));
    let (tx, rx) = std::sync::mpsc::channel();
    buffer
        .slice(..)
        .map_async(wgpu::MapMode::Read, move |r| drop(tx.send(r)));
    device
        .poll(wgpu::PollType::Wait {
            submission_index: Some(index),
            timeout: Some(WAIT),
        })
        .map_err(|e| OffscreenError::Gpu(format!("waiting for the frame: {e}")))?;
    rx.recv()
        .map_err(|e| OffscreenError::Gpu(e.to_string()))?
        .map_err(|e| OffscreenError::Gpu(format!("mapping the frame: {e}")))?;
    let data = buffer
        .slice(..)
        .get_mapped_range()
        .map_err(|e| OffscreenError::Gpu(format!("reading the frame: {e:?}")))?;
    let mut pixels = Vec::with_capacity(unpadded * h as usize);
    for row in data.chunks_exact(padded) {
        pixels.extend_from_slice(&row[..unpadded]);
    }
    drop(data);
    buffer.unmap();
    RgbaImage::from_raw(w, h, pixels).ok_or_else(|| OffscreenError::Gpu("short read-back".into()))
}

/// Slide `index` of `deck` as an image of `size` pixels, with a fresh renderer (convenient for
/// one image; for many, keep an [`OffscreenRenderer`]).
pub fn render_slide_png(
    deck: &Deck,
    index: usize,
    size: [u32; 2],
) -> Result<RgbaImage, OffscreenError> {
    let mut r = OffscreenRenderer::new()?;
    r.render_slide(deck, index, &mut SlideState::default(), size)
}
