//! The per-frame uniform block (`Globals` in shaders/common.wgsl, same layout: a test compares
//! the offsets naga computes with Rust's), its bind groups' layouts, and the teaching toggles
//! that feed it.

use bytemuck::{Pod, Zeroable};
use glam::Vec3;

use crate::scene::model::MAX_WAVES;
use crate::scene::quality::Rung;
pub use crate::scene::quality::WaterNormals;
use crate::scene::snapshot::{FAR_M, NEAR_M};
use crate::scene::{FrameSnapshot, Scene};

use super::layouts::{FLOAT, Layout, sampler, texture, uniform};

#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum DebugView {
    #[default]
    None,
    ShadowMap,
    Normals,
    EnvCube,
    CausticsMap,
}

impl DebugView {
    pub const ALL: [DebugView; 5] = [
        Self::None,
        Self::ShadowMap,
        Self::Normals,
        Self::EnvCube,
        Self::CausticsMap,
    ];

    /// `DEBUG_*` in common.wgsl.
    pub fn code(self) -> u32 {
        match self {
            Self::None => 0,
            Self::ShadowMap => 1,
            Self::Normals => 2,
            Self::EnvCube => 3,
            Self::CausticsMap => 4,
        }
    }

    pub fn label(self) -> &'static str {
        match self {
            Self::None => "final image",
            Self::ShadowMap => "shadow map",
            Self::Normals => "normals",
            Self::EnvCube => "environment cube",
            Self::CausticsMap => "caustics map",
        }
    }
}

/// How the lit shaders filter the sun's shadow map: 3×3 bilinear comparison taps (soft edges
/// a few shadow texels wide), or one (a quarter of the cost per lit pixel on a software
/// rasteriser, and as soft once a pixel covers more than a shadow texel: the lowest quality
/// rungs). `SHADOW_PCF_RADIUS` in common.wgsl, a pipeline constant.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ShadowFilter {
    #[default]
    Pcf3x3,
    Bilinear,
}

impl ShadowFilter {
    pub const ALL: [ShadowFilter; 2] = [Self::Pcf3x3, Self::Bilinear];

    /// Taps on each side of the centre one.
    pub fn pcf_radius_texels(self) -> f64 {
        match self {
            Self::Pcf3x3 => 1.0,
            Self::Bilinear => 0.0,
        }
    }
}

/// What the lecturer can switch on and off to show each technique's contribution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RenderSettings {
    pub env_map: bool,
    pub normal_maps: bool,
    pub shadows: bool,
    /// Cook–Torrance; false = Lambert only
    pub brdf: bool,
    pub fresnel: bool,
    /// light focused by the waves onto what lies under water (GPU Gems 1 ch. 2)
    pub caustics: bool,
    pub debug_view: DebugView,
    pub exposure: f32,
    /// The scene is rendered at this fraction of the output's size in each direction and
    /// scaled up by the tone mapping pass (dynamic resolution); 1 = full size.
    pub render_scale: f32,
    /// Fish level of detail: 1 = the full mesh up to the default distances, smaller values
    /// switch to the coarser meshes nearer the camera (see [`super::fish::LodView`]).
    pub fish_detail: f32,
    pub shadow_filter: ShadowFilter,
    /// Draw the water and seabed grids over every other row and column of their vertices (a
    /// quarter of the triangles; the lowest quality rungs, where the grid had more triangles
    /// than the frame had pixels).
    pub coarse_grids: bool,
    pub water_normals: WaterNormals,
    /// The fish cast shadows (into the same shadow map as the rocks and bodies); `shadows`
    /// off switches every shadow off.
    pub fish_shadows: bool,
    /// FXAA on the geometric edges in the tone mapping pass (Lottes 2011, fxaa.wgsl)
    pub fxaa: bool,
}

impl RenderSettings {
    /// Draws with a rung of the quality ladder (the simulation's part of it, the school's
    /// stepping, is the caller's to set on the simulation).
    pub fn apply_rung(&mut self, rung: &Rung) {
        self.render_scale = rung.render_scale;
        self.fish_detail = rung.fish_detail;
        self.shadow_filter = if rung.soft_shadows {
            ShadowFilter::Pcf3x3
        } else {
            ShadowFilter::Bilinear
        };
        self.coarse_grids = rung.coarse_grids;
        self.water_normals = rung.water_normals;
    }
}

impl Default for RenderSettings {
    fn default() -> Self {
        Self {
            env_map: true,
            normal_maps: true,
            shadows: true,
            brdf: true,
            fresnel: true,
            caustics: true,
            debug_view: DebugView::None,
            exposure: 1.0,
            render_scale: 1.0,
            fish_detail: 1.0,
            shadow_filter: ShadowFilter::Pcf3x3,
            coarse_grids: false,
            water_normals: WaterNormals::PerPixel,
            fish_shadows: true,
            fxaa: true,
        }
    }
}

#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
pub struct WaveGpu {
    /// unit direction of travel (xz)
    pub direction: [f32; 2],
    /// k = 2π / wavelength, 1/m
    pub wavenumber_per_m: f32,
    pub amplitude_m: f32,
    /// ω = k · speed, rad/s
    pub angular_freq_per_sec: f32,
    /// Q k A = steepness / N: how far crests lean (dimensionless)
    pub steepness_qka: f32,
    pub _pad: [f32; 2],
}

#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
pub struct Globals {
    pub clip_from_world: [[f32; 4]; 4],
    pub world_from_clip: [[f32; 4]; 4],
    pub light_clip_from_world: [[f32; 4]; 4],
    pub eye_m: [f32; 3],
    pub time_secs: f32,
    /// unit, towards the sun
    pub sun_dir: [f32; 3],
    pub sun_intensity: f32,
    pub sun_color: [f32; 3],
    pub exposure: f32,
    pub absorption_per_m: [f32; 3],
    /// the camera's far plane, metres
    pub far_m: f32,
    pub scatter_color: [f32; 3],
    /// the camera's near plane, metres
    pub near_m: f32,
    pub water_level_m: f32,
    pub wave_count: u32,
    pub env_mip_count: f32,
    pub debug_view: u32,
    /// size of the HDR target being drawn, pixels
    pub viewport_size_px: [f32; 2],
    pub env_map_on: u32,
    pub normal_maps_on: u32,
    pub shadows_on: u32,
    pub cook_torrance_on: u32,
    pub fresnel_on: u32,
    pub caustics_on: u32,
    /// the caustics map covers |x|, |z| ≤ this, metres
    pub caustics_half_extent_m: f32,
    /// below the water level: the floor the caustics map is focused on, metres
    pub caustics_depth_m: f32,
    /// the angle one pixel of the HDR target subtends, radians (waves shorter than a few
    /// pixels fade out)
    pub rad_per_px: f32,
    /// the sum of the waves' amplitudes: no crest or trough is farther from the mean level,
    /// metres
    pub wave_reach_m: f32,
    /// linear RGB radiance at the sun disc's centre (the background draws it; the
    /// environment cube holds the sky without it)
    pub sun_disc_radiance: [f32; 3],
    /// cos of the disc's angular radius
    pub sun_cos_radius: f32,
    pub waves: [WaveGpu; MAX_WAVES],
}

/// Group 0 of the lit passes: the globals, the environment cube, the shadow map and the
/// caustics map.
pub fn frame_layout(device: &wgpu::Device) -> Layout {
    use wgpu::{SamplerBindingType as S, TextureSampleType as T, TextureViewDimension as D};
    let vf = wgpu::ShaderStages::VERTEX | wgpu::ShaderStages::FRAGMENT;
    Layout::new(
        device,
        "frame",
        &[
            uniform::<Globals>(0, vf),
            texture(1, D::Cube, FLOAT),
            sampler(2, S::Filtering),
            texture(3, D::D2, T::Depth),
            sampler(4, S::Comparison),
            texture(5, D::D2, FLOAT),
            sampler(6, S::Filtering),
        ],
    )
}

/// Group 0 of the shadow passes: the globals only (the shadow map is their target).
pub fn shadow_frame_layout(device: &wgpu::Device) -> Layout {
    let vf = wgpu::ShaderStages::VERTEX | wgpu::ShaderStages::FRAGMENT;
    Layout::new(device, "shadow frame", &[uniform::<Globals>(0, vf)])
}

fn on(b: bool) -> u32 {
    u32::from(b)
}

/// The waves as the shaders read them: sorted long to short and ending at the last slot, so
/// the water's vertex shader can take the first slots (the long waves, smooth over a grid
/// cell) and its fragment shader the rest (`WATER_VERTEX_WAVES` in common.wgsl). The sum does
/// not depend on the order: it is the CPU twin's (`crate::waves::WaveSum`).
pub fn waves_gpu(scene: &Scene) -> [WaveGpu; MAX_WAVES] {
    let mut all = scene.water.all_waves();
    all.truncate(MAX_WAVES);
    let n_waves = all.len();
    all.sort_by(|a, b| b.wavelength.total_cmp(&a.wavelength));
    let mut waves = [WaveGpu::zeroed(); MAX_WAVES];
    for (slot, w) in waves[MAX_WAVES - n_waves..].iter_mut().zip(&all) {
        let d = glam::Vec2::from(w.direction).normalize_or(glam::Vec2::X);
        let k = std::f32::consts::TAU / w.wavelength;
        *slot = WaveGpu {
            direction: [d.x, d.y],
            wavenumber_per_m: k,
            amplitude_m: w.amplitude,
            angular_freq_per_sec: k * w.speed,
            // a wave of zero amplitude moves nothing (as in crate::waves)
            steepness_qka: if w.amplitude == 0.0 {
                0.0
            } else {
                w.steepness / n_waves.max(1) as f32
            },
            _pad: [0.0; 2],
        };
    }
    waves
}

/// The uniforms of one frame drawn at `size_px` (the HDR target's size).
pub fn globals(
    scene: &Scene,
    snap: &FrameSnapshot,
    settings: &RenderSettings,
    size_px: (u32, u32),
    env_mips: u32,
) -> Globals {
    let aspect = size_px.0 as f32 / size_px.1.max(1) as f32;
    let clip_from_world = snap.camera.clip_from_view(aspect) * snap.camera.view_from_world();
    let sun = Vec3::from(scene.sun.direction).normalize();
    let w = &scene.water;
    Globals {
        clip_from_world: clip_from_world.to_cols_array_2d(),
        world_from_clip: clip_from_world.inverse().to_cols_array_2d(),
        light_clip_from_world: super::shadow::light_clip_from_world(scene).to_cols_array_2d(),
        eye_m: snap.camera.eye.to_array(),
        time_secs: snap.time_secs,
        sun_dir: sun.to_array(),
        sun_intensity: scene.sun.intensity,
        sun_color: scene.sun.color,
        exposure: settings.exposure,
        absorption_per_m: w.absorption,
        far_m: FAR_M,
        scatter_color: w.scatter_color,
        near_m: NEAR_M,
        water_level_m: w.level,
        wave_count: (w.waves.len() + w.spectrum.as_ref().map_or(0, |s| s.count as usize))
            .min(MAX_WAVES) as u32,
        env_mip_count: env_mips as f32,
        debug_view: settings.debug_view.code(),
        viewport_size_px: [size_px.0 as f32, size_px.1 as f32],
        env_map_on: on(settings.env_map),
        normal_maps_on: on(settings.normal_maps),
        shadows_on: on(settings.shadows),
        cook_torrance_on: on(settings.brdf),
        fresnel_on: on(settings.fresnel),
        caustics_on: on(settings.caustics),
        caustics_half_extent_m: super::caustics::half_extent_m(scene),
        caustics_depth_m: super::caustics::focus_depth_m(scene),
        rad_per_px: snap.camera.fov_y_rad / size_px.1.max(1) as f32,
        wave_reach_m: w.all_waves().iter().map(|w| w.amplitude.abs()).sum(),
        sun_disc_radiance: (Vec3::from(scene.sun.color) * scene.sky.sun_disc_intensity).to_array(),
        sun_cos_radius: scene.sky.sun_size_deg.to_radians().cos(),
        waves: waves_gpu(scene),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rust's `Globals` and WGSL's must agree field by field (a mismatch shifts every value
    /// after it, and nothing else would notice).
    #[test]
    fn globals_match_common_wgsl_field_by_field() {
        // common.wgsl declares the bindings; with encoding.wgsl, whose functions it calls
        let text = std::fs::read_to_string("shaders/common.wgsl").unwrap()
            + &std::fs::read_to_string("shaders/encoding.wgsl").unwrap();
        let module = naga::front::wgsl::parse_str(&text).unwrap();
        let (_, ty) = module
            .types
            .iter()
            .find(|(_, t)| t.name.as_deref() == Some("Globals"))
            .expect("struct Globals");
        let naga::TypeInner::Struct { members, span } = &ty.inner else {
            panic!("Globals is a struct");
        };
        assert_eq!(*span as usize, std::mem::size_of::<Globals>(), "size");
        let rust: &[(&str, usize)] = &[
            (
                "clip_from_world",
                std::mem::offset_of!(Globals, clip_from_world),
            ),
            (
                "world_from_clip",
                std::mem::offset_of!(Globals, world_from_clip),
            ),
            (
                "light_clip_from_world",
                std::mem::offset_of!(Globals, light_clip_from_world),
            ),
            ("eye_m", std::mem::offset_of!(Globals, eye_m)),
            ("time_secs", std::mem::offset_of!(Globals, time_secs)),
            ("sun_dir", std::mem::offset_of!(Globals, sun_dir)),
            (
                "sun_intensity",
                std::mem::offset_of!(Globals, sun_intensity),
            ),
            ("sun_color", std::mem::offset_of!(Globals, sun_color)),
            ("exposure", std::mem::offset_of!(Globals, exposure)),
            (
                "absorption_per_m",
                std::mem::offset_of!(Globals, absorption_per_m),
            ),
            ("far_m", std::mem::offset_of!(Globals, far_m)),
            (
                "scatter_color",
                std::mem::offset_of!(Globals, scatter_color),
            ),
            ("near_m", std::mem::offset_of!(Globals, near_m)),
            (
                "water_level_m",
                std::mem::offset_of!(Globals, water_level_m),
            ),
            ("wave_count", std::mem::offset_of!(Globals, wave_count)),
            (
                "env_mip_count",
                std::mem::offset_of!(Globals, env_mip_count),
            ),
            ("debug_view", std::mem::offset_of!(Globals, debug_view)),
            (
                "viewport_size_px",
                std::mem::offset_of!(Globals, viewport_size_px),
            ),
            ("env_map_on", std::mem::offset_of!(Globals, env_map_on)),
            (
                "normal_maps_on",
                std::mem::offset_of!(Globals, normal_maps_on),
            ),
            ("shadows_on", std::mem::offset_of!(Globals, shadows_on)),
            (
                "cook_torrance_on",
                std::mem::offset_of!(Globals, cook_torrance_on),
            ),
            ("fresnel_on", std::mem::offset_of!(Globals, fresnel_on)),
            ("caustics_on", std::mem::offset_of!(Globals, caustics_on)),
            (
                "caustics_half_extent_m",
                std::mem::offset_of!(Globals, caustics_half_extent_m),
            ),
            (
                "caustics_depth_m",
                std::mem::offset_of!(Globals, caustics_depth_m),
            ),
            ("rad_per_px", std::mem::offset_of!(Globals, rad_per_px)),
            ("wave_reach_m", std::mem::offset_of!(Globals, wave_reach_m)),
            (
                "sun_disc_radiance",
                std::mem::offset_of!(Globals, sun_disc_radiance),
            ),
            (
                "sun_cos_radius",
                std::mem::offset_of!(Globals, sun_cos_radius),
            ),
            ("waves", std::mem::offset_of!(Globals, waves)),
        ];
        let wgsl: Vec<(&str, usize)> = members
            .iter()
            .map(|m| (m.name.as_deref().unwrap_or("?"), m.offset as usize))
            .collect();
        assert_eq!(wgsl, rust);
        let (_, wave) = module
            .types
            .iter()
            .find(|(_, t)| t.name.as_deref() == Some("Wave"))
            .expect("struct Wave");
        let naga::TypeInner::Struct { span, .. } = &wave.inner else {
            panic!("Wave is a struct");
        };
        assert_eq!(*span as usize, std::mem::size_of::<WaveGpu>());
    }
}
