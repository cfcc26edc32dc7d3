//! The renderer's bind-group layouts: each technique defines its own beside its code, and
//! [`Layouts`] makes them all once. A [`Layout`] keeps the entries it was made from, which the
//! interface check (`super::interface`) compares with each shader's bindings.

use super::{debug, frame, pbr, sky, tonemap, water};

/// A bind group layout and the entries it was made from (wgpu does not give them back, and the
/// interface check compares them with the shader's bindings).
pub struct Layout {
    pub label: &'static str,
    pub layout: wgpu::BindGroupLayout,
    pub entries: Vec<wgpu::BindGroupLayoutEntry>,
}

impl Layout {
    pub fn new(
        device: &wgpu::Device,
        label: &'static str,
        entries: &[wgpu::BindGroupLayoutEntry],
    ) -> Self {
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(label),
            entries,
        });
        Self {
            label,
            layout,
            entries: entries.to_vec(),
        }
    }
}

/// A uniform buffer of exactly `T`'s size (wgpu then checks the shader's struct fits it).
pub fn uniform<T>(binding: u32, visibility: wgpu::ShaderStages) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: wgpu::BufferSize::new(std::mem::size_of::<T>() as u64),
        },
        count: None,
    }
}

pub fn texture(
    binding: u32,
    view_dimension: wgpu::TextureViewDimension,
    sample_type: wgpu::TextureSampleType,
) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Texture {
            sample_type,
            view_dimension,
            multisampled: false,
        },
        count: None,
    }
}

pub fn sampler(binding: u32, ty: wgpu::SamplerBindingType) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Sampler(ty),
        count: None,
    }
}

pub const FLOAT: wgpu::TextureSampleType = wgpu::TextureSampleType::Float { filterable: true };

/// Every bind group layout of the renderer, made once; each is defined beside the technique
/// that owns it.
pub struct Layouts {
    pub empty: Layout,
    pub frame: Layout,
    pub shadow_frame: Layout,
    pub material: Layout,
    pub object: Layout,
    pub water_inputs: Layout,
    pub sky_params: Layout,
    pub prefilter: Layout,
    pub tonemap: Layout,
    pub debug: Layout,
}

impl Layouts {
    pub fn new(device: &wgpu::Device) -> Self {
        Self {
            empty: Layout::new(device, "empty", &[]),
            frame: frame::frame_layout(device),
            shadow_frame: frame::shadow_frame_layout(device),
            material: pbr::material_layout(device),
            object: pbr::object_layout(device),
            water_inputs: water::inputs_layout(device),
            sky_params: sky::params_layout(device),
            prefilter: sky::prefilter_layout(device),
            tonemap: tonemap::layout(device),
            debug: debug::layout(device),
        }
    }
}
