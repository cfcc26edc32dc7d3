//! The device for headless use (render-scene, tests, benchmarks), the uncaptured-error
//! backstop, and reading a texture back to an image.

use std::sync::{Arc, Mutex};

use anyhow::{Context, Result};

use super::caps::AdapterCaps;

/// Errors wgpu could not attribute to an error scope. The default handler panics, which would
/// take the talk down with it; this one logs and keeps the message for the UI.
#[derive(Clone, Default)]
pub struct UncapturedErrors(Arc<Mutex<Vec<String>>>);

impl UncapturedErrors {
    pub fn install(device: &wgpu::Device) -> Self {
        let errors = Self::default();
        let sink = errors.0.clone();
        device.on_uncaptured_error(Arc::new(move |e: wgpu::Error| {
            tracing::error!("wgpu: {e}");
            if let Ok(mut v) = sink.lock() {
                v.push(e.to_string());
                if v.len() > 16 {
                    v.remove(0);
                }
            }
        }));
        errors
    }

    pub fn take(&self) -> Vec<String> {
        self.0
            .lock()
            .map(|mut v| std::mem::take(&mut *v))
            .unwrap_or_default()
    }
}

/// What an error scope caught: waited for natively; in a browser taken only if already known
/// (WebGL2 runs wgpu's own validation, which answers at once; a browser's WebGPU answers later,
/// and its errors then reach the uncaptured-error handler instead). No blocking on wasm.
pub fn scope_result(
    pending: impl std::future::Future<Output = Option<wgpu::Error>>,
) -> Option<wgpu::Error> {
    #[cfg(not(target_arch = "wasm32"))]
    {
        pollster::block_on(pending)
    }
    #[cfg(target_arch = "wasm32")]
    {
        let mut pending = std::pin::pin!(pending);
        let mut cx = std::task::Context::from_waker(std::task::Waker::noop());
        match pending.as_mut().poll(&mut cx) {
            std::task::Poll::Ready(e) => e,
            std::task::Poll::Pending => None,
        }
    }
}

pub struct Gpu {
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    pub adapter_info: wgpu::AdapterInfo,
    /// what the adapter can do, read once (the renderer's formats are decided from it)
    pub caps: AdapterCaps,
    pub errors: UncapturedErrors,
    pub timestamps: bool,
}

/// Which device [`Gpu::new`] makes.
#[derive(Debug, Clone)]
pub struct GpuRequest {
    /// None: `WGPU_BACKEND`, else every backend (Vulkan preferred, then GL)
    pub backends: Option<wgpu::Backends>,
    /// None: the adapter's own
    pub limits: Option<wgpu::Limits>,
    /// ask for the optional features the renderer can use (timestamps)
    pub optional_features: bool,
}

impl Default for GpuRequest {
    fn default() -> Self {
        Self {
            backends: None,
            limits: None,
            optional_features: true,
        }
    }
}

impl Gpu {
    /// Any adapter, software included; `WGPU_BACKEND` selects one.
    pub fn headless() -> Result<Self> {
        Self::new(&GpuRequest::default())
    }

    /// The device `request` asks for (tests ask for the GL backend, or WebGL2's limits).
    pub fn new(request: &GpuRequest) -> Result<Self> {
        let mut desc = wgpu::InstanceDescriptor::new_without_display_handle_from_env();
        if let Some(b) = request.backends {
            desc.backends = b;
        }
        let instance = wgpu::Instance::new(desc);
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            force_fallback_adapter: false,
            compatible_surface: None,
            apply_limit_buckets: false,
        }))
        .context("no wgpu adapter (install mesa-vulkan-drivers for lavapipe)")?;
        let want = if request.optional_features {
            wgpu::Features::TIMESTAMP_QUERY
        } else {
            wgpu::Features::empty()
        };
        let features = adapter.features() & want;
        let limits = request.limits.clone().unwrap_or_else(|| adapter.limits());
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("lectern headless"),
            required_features: features,
            required_limits: limits.clone(),
            ..Default::default()
        }))
        .context("requesting a wgpu device")?;
        let errors = UncapturedErrors::install(&device);
        Ok(Self {
            adapter_info: adapter.get_info(),
            caps: AdapterCaps::of(&adapter, &limits),
            timestamps: features.contains(wgpu::Features::TIMESTAMP_QUERY),
            device,
            queue,
            errors,
        })
    }
}

/// Copies an RGBA8 texture to the CPU (rows unpadded).
pub fn read_rgba8(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
) -> Result<image::RgbaImage> {
    let (w, h) = (texture.width(), texture.height());
    let row = w * 4;
    let padded =
        row.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("readback"),
        size: (padded * h) as u64,
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let mut enc = device.create_command_encoder(&Default::default());
    enc.copy_texture_to_buffer(
        texture.as_image_copy(),
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded),
                rows_per_image: Some(h),
            },
        },
        texture.size(),
    );
    let index = queue.submit([enc.finish()]);
    let slice = buffer.slice(..);
    slice.map_async(wgpu::MapMode::Read, |_| {});
    device
        .poll(wgpu::PollType::Wait {
            submission_index: Some(index),
            timeout: None,
        })
        .context("waiting for the GPU")?;
    let data = slice
        .get_mapped_range()
        .map_err(|e| anyhow::anyhow!("mapping readback: {e:?}"))?;
    let mut pixels = Vec::with_capacity((row * h) as usize);
    for y in 0..h {
        let start = (y * padded) as usize;
        pixels.extend_from_slice(&data[start..start + row as usize]);
    }
    drop(data);
    buffer.unmap();
    image::RgbaImage::from_raw(w, h, pixels).context("readback size")
}
