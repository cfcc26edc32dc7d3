//! The scene as written in `scenes/*.ron`: camera, sun, sky, water waves, materials, objects and
//! the fish school. Parsing reports `file:line:col`; values out of range are rejected with the
//! offending field named, before anything is allocated for them (a scene asking for 1e9 fish
//! must fail fast, not run out of memory).

use serde::{Deserialize, Serialize};

use crate::rigid::Integrator;
use crate::school::SchoolParams;
use crate::waves::{GerstnerWave, WaveSpectrum, WaveSum};

/// The most waves the water shader sums (its uniform array has this many slots): the
/// explicit `waves` and the spectrum's together.
pub const MAX_WAVES: usize = 32;
/// The most fish the renderer draws; the instance buffer is sized from this at most.
pub const MAX_FISH: usize = 20_000;
pub const MAX_OBJECTS: usize = 256;

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    pub camera: Camera,
    pub sun: Sun,
    #[serde(default)]
    pub sky: Sky,
    pub water: Water,
    pub materials: Vec<Material>,
    pub objects: Vec<Object>,
    #[serde(default = "default_school")]
    pub school: SchoolParams,
    #[serde(default)]
    pub simulation: Simulation,
    #[serde(default)]
    pub quality: Quality,
}

/// The school of the shipped scene (`scenes/water.ron`): what a scene file without a `school`
/// gets. (The school's own defaults in `crate::school` are for its tests and widgets.)
pub fn default_school() -> SchoolParams {
    SchoolParams {
        count: 450,
        max_speed: 1.6,
        fish_scale: 0.9,
        schools: 3,
        alignment_weight: 2.0,
        goal_weight: 0.5,
        spawn_radius: 1.5,
        ..SchoolParams::default()
    }
}

/// How the window trades detail for frame rate. `render-scene` and the golden images always
/// draw at full quality unless told otherwise.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Quality {
    /// Hold the frame time under `budget_ms`: when frames are slower the scene is drawn at a
    /// lower resolution (scaled up to the window) and the fish switch to coarser meshes nearer
    /// the camera; both come back when there is room.
    Auto { budget_ms: f32 },
    /// Always these settings: `render_scale` (0.25–1) of the window's size in each direction,
    /// `fish_detail` (0–4; 1 = default distances, 0 = coarsest mesh everywhere).
    Fixed { render_scale: f32, fish_detail: f32 },
}

impl Default for Quality {
    fn default() -> Self {
        // 15 frames per second: fluid enough to orbit on a software renderer
        Self::Auto { budget_ms: 66.0 }
    }
}

/// How the scene is stepped: a fixed step for everything (so `render-scene --time T` is
/// reproducible), the rigid bodies' own step and integrator (switchable live), water drag and
/// where the fish may swim.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Simulation {
    /// the fixed simulation step, seconds
    pub dt_secs: f32,
    /// the rigid bodies' step h, seconds (a multiple of `dt_secs` or a fraction of it)
    pub body_h_secs: f32,
    pub integrator: Integrator,
    /// linear drag in water per unit mass, 1/s (N per m/s per kg, at full submersion)
    pub linear_drag_per_sec: f32,
    /// angular drag per unit of mean inertia, 1/s
    pub angular_drag_per_sec: f32,
    /// fish stay within ±this many metres of the origin horizontally
    pub school_half_width: f32,
}

impl Default for Simulation {
    fn default() -> Self {
        Self {
            dt_secs: 1.0 / 60.0,
            body_h_secs: 1.0 / 60.0,
            integrator: Integrator::Rk4,
            linear_drag_per_sec: 1.0,
            angular_drag_per_sec: 1.5,
            school_half_width: 7.5,
        }
    }
}

/// An orbit camera around `target`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Camera {
    pub target: [f32; 3],
    /// metres from the target
    pub distance: f32,
    /// rotation about +y, degrees
    pub yaw_deg: f32,
    /// elevation above the horizontal, degrees
    pub pitch_deg: f32,
    /// vertical field of view, degrees
    pub fov_deg: f32,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Sun {
    /// direction *towards* the sun (normalised on use)
    pub direction: [f32; 3],
    /// linear RGB
    pub color: [f32; 3],
    /// irradiance scale of the directional light
    pub intensity: f32,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Sky {
    /// Preetham's turbidity T: 2 a clear blue sky, 10 a hazy one (valid 1.7..=10)
    pub turbidity: f32,
    /// scene radiance per kcd/m² of the model's luminance (sets the sky's brightness against
    /// the sun's `intensity`)
    pub radiance_per_kcd: f32,
    /// linear RGB below the horizon, in the environment cube
    pub ground_color: [f32; 3],
    /// angular radius of the sun disc, degrees
    pub sun_size_deg: f32,
    /// HDR radiance of the sun disc relative to the sun colour
    pub sun_disc_intensity: f32,
    /// edge length of one cube face, texels (a power of two)
    pub cube_size: u32,
}

impl Default for Sky {
    fn default() -> Self {
        Self {
            turbidity: 2.2,
            radiance_per_kcd: 0.009,
            ground_color: [0.03, 0.06, 0.08],
            sun_size_deg: 1.2,
            sun_disc_intensity: 60.0,
            cube_size: 128,
        }
    }
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Water {
    /// height of the still surface, metres
    pub level: f32,
    /// vertices per side of the projected grid (a grid over the screen, met with the water
    /// plane: the water reaches the horizon at any resolution)
    pub resolution: u32,
    /// Beer–Lambert absorption per metre of water, per RGB channel
    pub absorption: [f32; 3],
    /// colour of light scattered back by deep water (linear RGB)
    pub scatter_color: [f32; 3],
    /// waves placed by hand
    #[serde(default)]
    pub waves: Vec<GerstnerWave>,
    /// and a wind sea drawn from a spectrum, after them
    #[serde(default)]
    pub spectrum: Option<WaveSpectrum>,
}

impl Water {
    /// Every wave the surface sums: the hand-placed ones, then the spectrum's.
    pub fn all_waves(&self) -> Vec<GerstnerWave> {
        let mut w = self.waves.clone();
        if let Some(s) = &self.spectrum {
            w.extend(s.waves());
        }
        w
    }

    /// The surface the simulation floats bodies on and the shader draws (its CPU twin).
    pub fn wave_sum(&self) -> WaveSum {
        WaveSum::new(self.all_waves(), self.level)
    }
}

/// A procedurally generated normal map pattern.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum NormalPattern {
    Flat,
    /// wind ripples in sand
    Ripples,
    /// value-noise bumps (rock)
    Bumps,
    /// planks and grain (wood)
    Planks,
    /// fine anisotropic scratches (brushed metal)
    Brushed,
    /// overlapping scales (fish skin)
    Scales,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Material {
    pub name: String,
    /// linear RGB albedo
    pub base_color: [f32; 3],
    pub metallic: f32,
    /// perceptual roughness, squared to GGX alpha in the shader
    pub roughness: f32,
    /// dielectric reflectance at normal incidence, Filament's mapping F0 = 0.16 r²
    #[serde(default = "default_reflectance")]
    pub reflectance: f32,
    pub normal_map: NormalPattern,
    #[serde(default = "one")]
    pub normal_strength: f32,
    /// texture repeats per metre (world-space UVs for terrain, per object otherwise)
    #[serde(default = "one")]
    pub uv_scale: f32,
}

fn default_reflectance() -> f32 {
    0.5
}
fn one() -> f32 {
    1.0
}
fn default_density() -> f32 {
    500.0
}

/// Density of the water the bodies float in, kg/m³.
pub const WATER_DENSITY: f32 = 1000.0;

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum Object {
    /// The sandy floor: a height field of `size` metres, `depth` below the water level.
    Seabed {
        material: String,
        size: f32,
        depth: f32,
        resolution: u32,
        /// amplitude of the dunes, metres
        relief: f32,
    },
    /// A noisy boulder resting on the seabed.
    Rock {
        material: String,
        position: [f32; 3],
        radius: f32,
        seed: u32,
    },
    /// A rigid body floating on the waves: mass and inertia from its mesh (Mirtich), pushed
    /// by gravity, buoyancy against the Gerstner surface and drag. It starts at rest with its
    /// centre at the still water level.
    Floating {
        material: String,
        shape: Shape,
        /// start (x, z), metres
        position: [f32; 2],
        /// kg/m³; below water's 1000 so it floats (500: half submerged)
        #[serde(default = "default_density")]
        density: f32,
        /// initial tilt about the body's x axis, degrees (it rights itself on the water)
        #[serde(default)]
        tilt_deg: f32,
    },
}

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum Shape {
    Box { size: [f32; 3] },
    Sphere { radius: f32 },
    Capsule { radius: f32, length: f32 },
}

impl Object {
    pub fn material(&self) -> &str {
        match self {
            Object::Seabed { material, .. }
            | Object::Rock { material, .. }
            | Object::Floating { material, .. } => material,
        }
    }
}

impl Scene {
    pub fn material_index(&self, name: &str) -> Option<usize> {
        self.materials.iter().position(|m| m.name == name)
    }

    pub fn seabed_depth(&self) -> f32 {
        self.objects
            .iter()
            .find_map(|o| match o {
                Object::Seabed { depth, .. } => Some(*depth),
                _ => None,
            })
            .unwrap_or(4.0)
    }
}
