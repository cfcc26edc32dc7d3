//! What the adapter can do, read once ([`AdapterCaps`]), and every format and size the renderer
//! picks from it, decided in one place ([`RenderCaps::decide`]). Nothing else in `render/` asks
//! the adapter, and nothing decides by backend name: a WebGL2 context without
//! `EXT_color_buffer_float`, a GL driver, lavapipe and a real GPU differ only in what they
//! report here.
//!
//! Float render targets where the adapter renders to and filters them; otherwise 8-bit targets
//! with the encodings of encoding.wgsl (HDR colour scaled down into an sRGB-encoded target, the
//! eye distance as the fraction d / (d + 16 m), the caustics factor scaled down). Texture sides are fitted to `max_texture_dimension_2d`, the fish instance buffer to
//! `max_buffer_size`.

/// Whether a format can be drawn into and linearly filtered when sampled.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct FormatSupport {
    pub renderable: bool,
    pub filterable: bool,
}

impl FormatSupport {
    fn of(adapter: &wgpu::Adapter, format: wgpu::TextureFormat) -> Self {
        let f = adapter.get_texture_format_features(format);
        Self {
            renderable: f
                .allowed_usages
                .contains(wgpu::TextureUsages::RENDER_ATTACHMENT),
            filterable: f
                .flags
                .contains(wgpu::TextureFormatFeatureFlags::FILTERABLE),
        }
    }

    /// A float target for the HDR passes: drawn into, then sampled bilinearly.
    pub fn usable_target(self) -> bool {
        self.renderable && self.filterable
    }
}

/// The adapter's capabilities as the renderer needs them, read once when the device is made.
#[derive(Debug, Clone)]
pub struct AdapterCaps {
    /// for the scene panel ("GL · llvmpipe"); never used to decide anything
    pub backend: wgpu::Backend,
    pub adapter_name: String,
    pub downlevel: wgpu::DownlevelFlags,
    /// the device's limits (what was requested, not what the adapter could give)
    pub limits: wgpu::Limits,
    pub rgba16_float: FormatSupport,
    pub r16_float: FormatSupport,
    pub r32_float: FormatSupport,
}

impl AdapterCaps {
    /// Reads `adapter` for a device made with `device_limits`.
    pub fn of(adapter: &wgpu::Adapter, device_limits: &wgpu::Limits) -> Self {
        let info = adapter.get_info();
        Self {
            backend: info.backend,
            adapter_name: info.name,
            downlevel: adapter.get_downlevel_capabilities().flags,
            limits: device_limits.clone(),
            rgba16_float: FormatSupport::of(adapter, wgpu::TextureFormat::Rgba16Float),
            r16_float: FormatSupport::of(adapter, wgpu::TextureFormat::R16Float),
            r32_float: FormatSupport::of(adapter, wgpu::TextureFormat::R32Float),
        }
    }

    /// A WebGL2 context as a browser without `EXT_color_buffer_float` gives it: WebGL2's
    /// limits and downlevel flags, no float render targets (for tests on a native adapter).
    pub fn webgl2_like() -> Self {
        let no_float = FormatSupport {
            renderable: false,
            filterable: true,
        };
        Self {
            backend: wgpu::Backend::Gl,
            adapter_name: "WebGL2-like".into(),
            downlevel: wgpu::DownlevelFlags::empty(),
            limits: wgpu::Limits::downlevel_webgl2_defaults(),
            rgba16_float: no_float,
            r16_float: no_float,
            r32_float: FormatSupport {
                renderable: false,
                filterable: false,
            },
        }
    }

    /// "Vulkan · llvmpipe (LLVM 15.0.6, 256 bits)": the scene panel's first line.
    pub fn describe(&self) -> String {
        format!("{} · {}", backend_name(self.backend), self.adapter_name)
    }
}

/// The backend as people call it.
pub fn backend_name(backend: wgpu::Backend) -> &'static str {
    match backend {
        wgpu::Backend::Vulkan => "Vulkan",
        wgpu::Backend::Metal => "Metal",
        wgpu::Backend::Dx12 => "DX12",
        wgpu::Backend::Gl => "GL",
        wgpu::Backend::BrowserWebGpu => "WebGPU",
        wgpu::Backend::Noop => "no GPU",
    }
}

/// How values are stored in the 8-bit targets (encoding.wgsl; 1, false, 1 with float targets).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Encoding {
    /// HDR colour (and the environment cube) stored times this
    pub hdr_store_scale: f32,
    /// the eye distance stored as d / (d + 16 m), not in metres (encoding.wgsl)
    pub dist_encoded: bool,
    /// the caustics focusing factor stored times this
    pub caustics_store_scale: f32,
}

impl Encoding {
    pub const FLOAT: Self = Self {
        hdr_store_scale: 1.0,
        dist_encoded: false,
        caustics_store_scale: 1.0,
    };

    /// The pipeline constants of encoding.wgsl (a pipeline gets those its shader declares).
    pub fn constants(&self) -> [(&'static str, f64); 3] {
        [
            ("HDR_STORE_SCALE", f64::from(self.hdr_store_scale)),
            ("DIST_ENCODED", if self.dist_encoded { 1.0 } else { 0.0 }),
            ("CAUSTICS_STORE_SCALE", f64::from(self.caustics_store_scale)),
        ]
    }
}

/// In 8 bits, HDR colour up to this is kept (ACES maps 8 to 98 % white; the sRGB encoding keeps
/// the dark tones' steps small).
pub const HDR_8BIT_RANGE: f32 = 8.0;
/// In 8 bits, focusing factors up to this are kept (flat water is 1, the folds reach ~6).
pub const CAUSTICS_8BIT_RANGE: f32 = 8.0;

/// Every format and size the renderer uses, decided once from [`AdapterCaps`].
#[derive(Debug, Clone, PartialEq)]
pub struct RenderCaps {
    /// the opaque and water passes' colour (alpha: the eye distance) and its copy
    pub hdr_format: wgpu::TextureFormat,
    pub cube_format: wgpu::TextureFormat,
    pub caustics_format: wgpu::TextureFormat,
    pub depth_format: wgpu::TextureFormat,
    /// the tone-mapped image at the render size, sRGB encoded: 8 bits keep the dark tones and
    /// filtering happens on linear values
    pub display_format: wgpu::TextureFormat,
    pub encoding: Encoding,
    /// the largest side of any 2D target (render size, output, maps)
    pub max_texture_side_px: u32,
    pub shadow_map_size_px: u32,
    pub caustics_map_size_px: u32,
    /// fish the instance buffer may hold
    pub max_fish_instances: usize,
}

/// The shadow map's side where the adapter allows it.
pub const SHADOW_MAP_SIZE: u32 = 1024;
/// Texels per side of the caustics map where the adapter allows it: 256² over the ±12 m swim
/// box is ~9.6 cm a texel, finer than the focused lines of the shipped waves (shortest
/// wavelength 1.7 m), and 65 536 texels of five Gerstner sums each cost little next to one lit
/// pixel per screen pixel (~9 ms of CPU a frame on llvmpipe, docs/benchmarks/scene.md).
pub const CAUSTICS_MAP_SIZE: u32 = 256;

impl RenderCaps {
    pub fn decide(a: &AdapterCaps) -> Self {
        use wgpu::TextureFormat as F;
        let float_hdr = a.rgba16_float.usable_target();
        let float_caustics = a.r16_float.usable_target();
        let side = a.limits.max_texture_dimension_2d.max(1);
        let instance_bytes = std::mem::size_of::<super::fish::FishInstanceGpu>() as u64;
        let max_fish = (a.limits.max_buffer_size / instance_bytes).min(1 << 24) as usize;
        Self {
            hdr_format: if float_hdr {
                F::Rgba16Float
            } else {
                F::Rgba8UnormSrgb
            },
            cube_format: if float_hdr {
                F::Rgba16Float
            } else {
                F::Rgba8UnormSrgb
            },
            caustics_format: if float_caustics {
                F::R16Float
            } else {
                F::R8Unorm
            },
            depth_format: F::Depth32Float,
            display_format: F::Rgba8UnormSrgb,
            encoding: Encoding {
                hdr_store_scale: if float_hdr { 1.0 } else { 1.0 / HDR_8BIT_RANGE },
                dist_encoded: !float_hdr,
                caustics_store_scale: if float_caustics {
                    1.0
                } else {
                    1.0 / CAUSTICS_8BIT_RANGE
                },
            },
            max_texture_side_px: side,
            shadow_map_size_px: SHADOW_MAP_SIZE.min(side),
            caustics_map_size_px: CAUSTICS_MAP_SIZE.min(side),
            max_fish_instances: max_fish.max(1),
        }
    }

    /// What a WebGL2 context without float render targets gets.
    pub fn webgl2_like() -> Self {
        Self::decide(&AdapterCaps::webgl2_like())
    }

    /// Float targets and WebGPU's default limits: what a desktop adapter gets (for code that
    /// has no adapter at hand, e.g. shader checks).
    pub fn float_targets() -> Self {
        let support = FormatSupport {
            renderable: true,
            filterable: true,
        };
        Self::decide(&AdapterCaps {
            backend: wgpu::Backend::Noop,
            adapter_name: String::new(),
            downlevel: wgpu::DownlevelFlags::all(),
            limits: wgpu::Limits::default(),
            rgba16_float: support,
            r16_float: support,
            r32_float: support,
        })
    }

    /// Whether the 8-bit fallback is in use (for the scene panel).
    pub fn eight_bit_hdr(&self) -> bool {
        self.encoding.dist_encoded
    }

    /// `size` shrunk, keeping its aspect, so neither side exceeds the largest texture.
    pub fn fit(&self, size: (u32, u32)) -> (u32, u32) {
        let max = self.max_texture_side_px as f64;
        let longest = f64::from(size.0.max(size.1));
        if longest <= max {
            return size;
        }
        let s = max / longest;
        (
            ((f64::from(size.0) * s).floor() as u32).clamp(1, self.max_texture_side_px),
            ((f64::from(size.1) * s).floor() as u32).clamp(1, self.max_texture_side_px),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn float_targets_where_renderable_else_eight_bits_with_encodings() {
        let float = RenderCaps::float_targets();
        assert_eq!(float.hdr_format, wgpu::TextureFormat::Rgba16Float);
        assert_eq!(float.caustics_format, wgpu::TextureFormat::R16Float);
        assert_eq!(float.encoding, Encoding::FLOAT);
        assert!(!float.eight_bit_hdr());

        let web = RenderCaps::webgl2_like();
        assert_eq!(web.hdr_format, wgpu::TextureFormat::Rgba8UnormSrgb);
        assert_eq!(web.cube_format, wgpu::TextureFormat::Rgba8UnormSrgb);
        assert_eq!(web.caustics_format, wgpu::TextureFormat::R8Unorm);
        assert!(web.encoding.dist_encoded);
        assert_eq!(web.encoding.hdr_store_scale, 1.0 / HDR_8BIT_RANGE);
        assert!(web.eight_bit_hdr());
        // WebGL2's 2048 texels a side: the maps fit, a 4K output is scaled into it
        assert_eq!(web.max_texture_side_px, 2048);
        assert_eq!(web.shadow_map_size_px, SHADOW_MAP_SIZE);
        assert_eq!(web.fit((3840, 2160)), (2048, 1152));
        assert_eq!(web.fit((1280, 720)), (1280, 720));

        // only the caustics' half float missing: HDR stays float
        let mut a = AdapterCaps::webgl2_like();
        a.rgba16_float = FormatSupport {
            renderable: true,
            filterable: true,
        };
        let mixed = RenderCaps::decide(&a);
        assert_eq!(mixed.hdr_format, wgpu::TextureFormat::Rgba16Float);
        assert!(!mixed.encoding.dist_encoded);
        assert_eq!(mixed.caustics_format, wgpu::TextureFormat::R8Unorm);
    }

    #[test]
    fn small_limits_shrink_the_maps_and_the_fish_buffer() {
        let mut a = AdapterCaps::webgl2_like();
        a.limits.max_texture_dimension_2d = 512;
        a.limits.max_buffer_size = 1 << 16;
        let c = RenderCaps::decide(&a);
        assert_eq!(c.shadow_map_size_px, 512);
        assert_eq!(c.caustics_map_size_px, CAUSTICS_MAP_SIZE);
        let per_fish = std::mem::size_of::<crate::render::fish::FishInstanceGpu>();
        assert_eq!(c.max_fish_instances, (1 << 16) / per_fish);
    }
}
