//! Rendering a scene without a window: `lectern render-scene`, the golden-image tests and the
//! frame benchmark all go through here.

use std::path::Path;
use std::time::{Duration, Instant};

use anyhow::{Context, Result};

use crate::scene::{FrameSnapshot, Quality, Scene, SceneSim};

use super::caps::RenderCaps;
use super::frame::RenderSettings;
use super::gpu::{self, Gpu};
use super::renderer::Renderer;

pub const OUTPUT_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;

pub struct Headless {
    pub gpu: Gpu,
    pub renderer: Renderer,
    pub sim: SceneSim,
    pub settings: RenderSettings,
    target: Option<(wgpu::Texture, wgpu::TextureView)>,
}

impl Headless {
    pub fn new(scene: Scene, shader_dir: &Path) -> Result<Self> {
        let gpu = Gpu::headless()?;
        let caps = RenderCaps::decide(&gpu.caps);
        Self::with_gpu(gpu, caps, scene, shader_dir)
    }

    /// On a device of the caller's (another backend, smaller limits) with formats from `caps`.
    pub fn with_gpu(gpu: Gpu, caps: RenderCaps, scene: Scene, shader_dir: &Path) -> Result<Self> {
        let renderer = Renderer::new(
            &gpu.device,
            &gpu.queue,
            shader_dir,
            &scene,
            OUTPUT_FORMAT,
            caps,
        )?;
        // headless frames are drawn at full quality unless the scene fixes it
        let mut settings = RenderSettings::default();
        if let Quality::Fixed {
            render_scale,
            fish_detail,
        } = scene.quality
        {
            (settings.render_scale, settings.fish_detail) = (render_scale, fish_detail);
        }
        Ok(Self {
            gpu,
            renderer,
            sim: SceneSim::new(scene),
            settings,
            target: None,
        })
    }

    fn target(&mut self, size: (u32, u32)) -> &(wgpu::Texture, wgpu::TextureView) {
        let stale = self
            .target
            .as_ref()
            .is_none_or(|(t, _)| (t.width(), t.height()) != size);
        if stale {
            let texture = super::targets::texture_2d(
                &self.gpu.device,
                "headless output",
                size,
                OUTPUT_FORMAT,
                wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
            );
            let view = texture.create_view(&Default::default());
            self.target = Some((texture, view));
        }
        self.target.as_ref().expect("made above")
    }

    /// Renders the simulation's current state and reads it back.
    pub fn render(&mut self, size: (u32, u32)) -> Result<image::RgbaImage> {
        let snap = self.sim.snapshot();
        self.render_snapshot(&snap, size)
    }

    /// One frame, timed in two parts: CPU (simulation snapshot, uniform uploads, command
    /// recording) and GPU (submit until the device is idle; on a software adapter this is the
    /// rasteriser's work). Used by the frame benchmark.
    pub fn timed_frame(&mut self, size: (u32, u32)) -> Result<(Duration, Duration)> {
        self.target(size);
        let t0 = Instant::now();
        let snap = self.sim.snapshot();
        let (_, view) = self.target.as_ref().expect("made above");
        let commands = self
            .renderer
            .encode(&self.sim.scene, &snap, &self.settings, view, size)
            .finish();
        let cpu = t0.elapsed();
        let t1 = Instant::now();
        let index = self.gpu.queue.submit([commands]);
        self.gpu
            .device
            .poll(wgpu::PollType::Wait {
                submission_index: Some(index),
                timeout: None,
            })
            .context("waiting for the GPU")?;
        Ok((cpu, t1.elapsed()))
    }

    pub fn render_snapshot(
        &mut self,
        snap: &FrameSnapshot,
        size: (u32, u32),
    ) -> Result<image::RgbaImage> {
        let max = self.renderer.caps().max_texture_side_px.min(8192);
        anyhow::ensure!(
            size.0 > 0 && size.1 > 0 && size.0 <= max && size.1 <= max,
            "image size {}x{} must be 1..={max} per side on this adapter",
            size.0,
            size.1
        );
        self.target(size);
        let (texture, view) = self.target.as_ref().expect("made above");
        self.renderer
            .render(&self.sim.scene, snap, &self.settings, view, size);
        let image = gpu::read_rgba8(&self.gpu.device, &self.gpu.queue, texture)
            .context("reading the frame back")?;
        let errors = self.gpu.errors.take();
        anyhow::ensure!(errors.is_empty(), "wgpu reported: {}", errors.join("; "));
        Ok(image)
    }
}
