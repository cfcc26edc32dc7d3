//! The frame's own render targets: the HDR colour and depth the scene is drawn into (at the
//! render size, which dynamic resolution may make smaller than the display), the copy of the
//! opaque colour the water refracts (its alpha the distance from the eye), the tone-mapped
//! display image at the same size (scaled up to the output by the last pass), and the bind
//! groups that read them.

use super::caps::RenderCaps;
use super::layouts::Layouts;

/// A colour attachment cleared to `clear` and stored (every pass that draws a new target).
pub fn cleared_color(
    view: &wgpu::TextureView,
    clear: wgpu::Color,
) -> Option<wgpu::RenderPassColorAttachment<'_>> {
    Some(wgpu::RenderPassColorAttachment {
        view,
        resolve_target: None,
        depth_slice: None,
        ops: wgpu::Operations {
            load: wgpu::LoadOp::Clear(clear),
            store: wgpu::StoreOp::Store,
        },
    })
}

/// A depth attachment cleared to the far plane and stored.
pub fn cleared_depth(
    view: &wgpu::TextureView,
) -> Option<wgpu::RenderPassDepthStencilAttachment<'_>> {
    Some(wgpu::RenderPassDepthStencilAttachment {
        view,
        depth_ops: Some(wgpu::Operations {
            load: wgpu::LoadOp::Clear(1.0),
            store: wgpu::StoreOp::Store,
        }),
        stencil_ops: None,
    })
}

pub fn texture_2d(
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

pub fn entry(binding: u32, resource: wgpu::BindingResource<'_>) -> wgpu::BindGroupEntry<'_> {
    wgpu::BindGroupEntry { binding, resource }
}

pub struct Targets {
    pub size: (u32, u32),
    pub hdr: wgpu::Texture,
    pub hdr_view: wgpu::TextureView,
    pub depth_view: wgpu::TextureView,
    pub scene_color: wgpu::Texture,
    /// group 1 of the water pass
    pub water_inputs: wgpu::BindGroup,
    /// group 0 of the tone mapping pass (reads `hdr`)
    pub tonemap: wgpu::BindGroup,
    /// the tone-mapped (and anti-aliased) image at the render size
    pub display_view: wgpu::TextureView,
    /// group 0 of the pass that scales `display_view` up to the output
    pub upscale: wgpu::BindGroup,
}

impl Targets {
    pub fn new(
        device: &wgpu::Device,
        layouts: &Layouts,
        size: (u32, u32),
        post_params: &wgpu::Buffer,
        linear_clamp: &wgpu::Sampler,
        caps: &RenderCaps,
    ) -> Self {
        use wgpu::TextureUsages as U;
        let hdr = texture_2d(
            device,
            "hdr",
            size,
            caps.hdr_format,
            U::RENDER_ATTACHMENT | U::TEXTURE_BINDING | U::COPY_SRC,
        );
        let depth = texture_2d(
            device,
            "depth",
            size,
            caps.depth_format,
            U::RENDER_ATTACHMENT,
        );
        let scene_color = texture_2d(
            device,
            "scene colour",
            size,
            caps.hdr_format,
            U::COPY_DST | U::TEXTURE_BINDING,
        );
        let hdr_view = hdr.create_view(&Default::default());
        let depth_view = depth.create_view(&Default::default());
        let scene_view = scene_color.create_view(&Default::default());
        let water_inputs = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("water inputs"),
            layout: &layouts.water_inputs.layout,
            entries: &[
                entry(0, wgpu::BindingResource::TextureView(&scene_view)),
                entry(1, wgpu::BindingResource::Sampler(linear_clamp)),
            ],
        });
        let tonemap = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("tonemap"),
            layout: &layouts.tonemap.layout,
            entries: &[
                entry(0, post_params.as_entire_binding()),
                entry(1, wgpu::BindingResource::TextureView(&hdr_view)),
                entry(2, wgpu::BindingResource::Sampler(linear_clamp)),
            ],
        });
        let display = texture_2d(
            device,
            "display",
            size,
            caps.display_format,
            U::RENDER_ATTACHMENT | U::TEXTURE_BINDING,
        );
        let display_view = display.create_view(&Default::default());
        let upscale = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("upscale"),
            layout: &layouts.tonemap.layout,
            entries: &[
                entry(0, post_params.as_entire_binding()),
                entry(1, wgpu::BindingResource::TextureView(&display_view)),
                entry(2, wgpu::BindingResource::Sampler(linear_clamp)),
            ],
        });
        Self {
            size,
            hdr,
            hdr_view,
            depth_view,
            scene_color,
            water_inputs,
            tonemap,
            display_view,
            upscale,
        }
    }
}
