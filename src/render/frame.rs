//! The per-frame uniform block (`Globals` in shaders/common.wgsl, same layout) and the teaching
//! toggles that feed it.

use bytemuck::{Pod, Zeroable};
use glam::{Mat4, Vec3};

use crate::scene::model::MAX_WAVES;
use crate::scene::snapshot::{FAR_M, NEAR_M};
use crate::scene::{FrameSnapshot, Scene};

#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum DebugView {
    #[default]
    None,
    ShadowMap,
    Normals,
    EnvCube,
}

impl DebugView {
    pub const ALL: [DebugView; 4] = [Self::None, Self::ShadowMap, Self::Normals, Self::EnvCube];

    pub fn code(self) -> f32 {
        match self {
            Self::None => 0.0,
            Self::ShadowMap => 1.0,
            Self::Normals => 2.0,
            Self::EnvCube => 3.0,
        }
    }

    pub fn label(self) -> &'static str {
        match self {
            Self::None => "final image",
            Self::ShadowMap => "shadow map",
            Self::Normals => "normals",
            Self::EnvCube => "environment cube",
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
    pub debug_view: DebugView,
    pub exposure: f32,
}

impl Default for RenderSettings {
    fn default() -> Self {
        Self {
            env_map: true,
            normal_maps: true,
            shadows: true,
            brdf: true,
            fresnel: true,
            debug_view: DebugView::None,
            exposure: 1.0,
        }
    }
}

#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
pub struct WaveGpu {
    pub dir_k_amp: [f32; 4],
    pub omega_qka: [f32; 4],
}

#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
pub struct Globals {
    pub clip_from_world: [[f32; 4]; 4],
    pub world_from_clip: [[f32; 4]; 4],
    pub light_clip_from_world: [[f32; 4]; 4],
    pub camera_pos_time: [f32; 4],
    pub sun_dir_intensity: [f32; 4],
    pub sun_color: [f32; 4],
    pub water: [f32; 4],
    pub absorption: [f32; 4],
    pub scatter: [f32; 4],
    pub toggles: [f32; 4],
    pub toggles2: [f32; 4],
    pub waves: [WaveGpu; MAX_WAVES],
}

fn flag(b: bool) -> f32 {
    if b { 1.0 } else { 0.0 }
}

/// The sun's orthographic shadow camera, framing the lagoon's centre where fish, rocks and
/// floating bodies are.
pub fn light_clip_from_world(scene: &Scene) -> Mat4 {
    let sun = Vec3::from(scene.sun.direction).normalize();
    let centre = Vec3::new(0.0, scene.water.level - 0.5 * scene.seabed_depth(), 0.0);
    let half_extent = 9.0;
    let eye = centre + sun * 30.0;
    let up = if sun.y.abs() > 0.99 { Vec3::Z } else { Vec3::Y };
    glam::camera::rh::proj::directx::orthographic(
        -half_extent,
        half_extent,
        -half_extent,
        half_extent,
        1.0,
        60.0,
    ) * glam::camera::rh::view::look_at_mat4(eye, centre, up)
}

pub fn globals(
    scene: &Scene,
    snap: &FrameSnapshot,
    settings: &RenderSettings,
    size: (u32, u32),
    env_mips: u32,
) -> Globals {
    let aspect = size.0 as f32 / size.1.max(1) as f32;
    let clip_from_world = snap.camera.clip_from_view(aspect) * snap.camera.view_from_world();
    let sun = Vec3::from(scene.sun.direction).normalize();
    let n_waves = scene.water.waves.len().min(MAX_WAVES);
    let mut waves = [WaveGpu::zeroed(); MAX_WAVES];
    for (slot, w) in waves.iter_mut().zip(&scene.water.waves) {
        let d = glam::Vec2::from(w.direction).normalize_or(glam::Vec2::X);
        let k = std::f32::consts::TAU / w.wavelength;
        *slot = WaveGpu {
            dir_k_amp: [d.x, d.y, k, w.amplitude],
            // a wave of zero amplitude moves nothing (as in crate::waves)
            omega_qka: [
                k * w.speed,
                if w.amplitude == 0.0 {
                    0.0
                } else {
                    w.steepness / n_waves.max(1) as f32
                },
                0.0,
                0.0,
            ],
        };
    }
    let e = snap.camera.eye;
    let w = &scene.water;
    Globals {
        clip_from_world: clip_from_world.to_cols_array_2d(),
        world_from_clip: clip_from_world.inverse().to_cols_array_2d(),
        light_clip_from_world: light_clip_from_world(scene).to_cols_array_2d(),
        camera_pos_time: [e.x, e.y, e.z, snap.time_secs],
        sun_dir_intensity: [sun.x, sun.y, sun.z, scene.sun.intensity],
        sun_color: [
            scene.sun.color[0],
            scene.sun.color[1],
            scene.sun.color[2],
            0.0,
        ],
        water: [w.level, n_waves as f32, env_mips as f32, settings.exposure],
        absorption: [w.absorption[0], w.absorption[1], w.absorption[2], FAR_M],
        scatter: [
            w.scatter_color[0],
            w.scatter_color[1],
            w.scatter_color[2],
            NEAR_M,
        ],
        toggles: [
            flag(settings.env_map),
            flag(settings.normal_maps),
            flag(settings.shadows),
            flag(settings.brdf),
        ],
        toggles2: [
            flag(settings.fresnel),
            settings.debug_view.code(),
            size.0 as f32,
            size.1 as f32,
        ],
        waves,
    }
}
