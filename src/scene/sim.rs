//! The scene's simulation: the fish school ([`crate::school::School`]) and the floating rigid
//! bodies ([`crate::rigid`], see [`super::bodies`]) on the Gerstner surface
//! ([`crate::waves::WaveSum`]), stepped at the scene's fixed `dt_secs`. Time only ever moves in
//! whole fixed steps, so the state at time T is the same however it was reached: a window
//! catching up after a slow frame, or `render-scene --time T` stepping from zero.
//! Produces a [`FrameSnapshot`] for the renderer and knows nothing of the GPU.

use glam::Vec3;

use crate::rigid::Integrator;
use crate::school::{Aabb, Environment, FishInstance, School};
use crate::waves::WaveSum;

use super::bodies::FloatingBody;
use super::model::{Object, Scene};
use super::orbit::OrbitCamera;
use super::snapshot::{BodyPose, FrameSnapshot};

/// A window that fell behind catches up by at most this many steps per frame, then drops the
/// rest (no spiral of death when a frame takes long).
const MAX_CATCH_UP_STEPS: u32 = 3;

pub struct SceneSim {
    pub scene: Scene,
    pub camera: OrbitCamera,
    /// the point the fish flee from (the lecturer's pointer on the water), world metres
    pub flee_point: Option<Vec3>,
    steps: u64,
    /// real time not yet stepped, seconds
    pending_secs: f64,
    waves: WaveSum,
    /// the rocks' bounding spheres, which the fish keep out of
    obstacles: Vec<(Vec3, f32)>,
    school: School,
    bodies: Vec<FloatingBody>,
    fish: Vec<FishInstance>,
    /// the school steps once every this many fixed steps, by that many steps' time
    school_every: u32,
}

/// Per-body figures for the presenter panel.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyReadout {
    pub object_index: usize,
    pub mass_kg: f64,
    pub kinetic_j: f64,
    /// M g y, relative to y = 0
    pub potential_j: f64,
    pub angular_momentum: f64,
    pub resets: u32,
}

impl SceneSim {
    pub fn new(scene: Scene) -> Self {
        let waves = wave_sum(&scene);
        let obstacles = rock_obstacles(&scene);
        let school = School::new(
            &scene.school,
            &environment(&scene, &waves, None, &obstacles),
        );
        let mut sim = Self {
            camera: OrbitCamera::from_scene(&scene.camera),
            flee_point: None,
            steps: 0,
            pending_secs: 0.0,
            bodies: Vec::new(),
            fish: Vec::new(),
            school_every: 1,
            waves,
            obstacles,
            school,
            scene,
        };
        sim.bodies = make_bodies(&sim.scene);
        sim.school.fill_instances(&mut sim.fish);
        sim
    }

    pub fn dt_secs(&self) -> f64 {
        self.scene.simulation.dt_secs as f64
    }

    /// Fixed steps taken since t = 0.
    pub fn steps(&self) -> u64 {
        self.steps
    }

    pub fn time_secs(&self) -> f64 {
        self.steps as f64 * self.dt_secs()
    }

    pub fn fish_count(&self) -> usize {
        self.school.len()
    }

    /// Sets the state to the one at `time_secs` (rounded to whole steps): continues stepping
    /// if that is ahead, else starts again from t = 0. Deterministic renders at `--time T`.
    pub fn set_time(&mut self, time_secs: f64) {
        let target = if time_secs.is_finite() && time_secs > 0.0 {
            (time_secs / self.dt_secs()).round() as u64
        } else {
            0
        };
        if target < self.steps {
            self.restart();
        }
        while self.steps < target {
            self.tick();
        }
        self.pending_secs = 0.0;
    }

    /// Back to t = 0: fish and bodies respawn from the scene (camera kept).
    pub fn restart(&mut self) {
        self.waves = wave_sum(&self.scene);
        self.obstacles = rock_obstacles(&self.scene);
        self.school = School::new(
            &self.scene.school,
            &environment(&self.scene, &self.waves, None, &self.obstacles),
        );
        self.bodies = make_bodies(&self.scene);
        self.steps = 0;
        self.pending_secs = 0.0;
        self.school.fill_instances(&mut self.fish);
    }

    /// Advances by real time `dt_secs` in whole fixed steps (the remainder waits for the
    /// next call).
    pub fn step(&mut self, dt_secs: f64) {
        if !(dt_secs.is_finite() && dt_secs > 0.0) {
            return;
        }
        self.pending_secs += dt_secs;
        let dt = self.dt_secs();
        let mut n = 0;
        while self.pending_secs >= dt && n < MAX_CATCH_UP_STEPS {
            self.tick();
            self.pending_secs -= dt;
            n += 1;
        }
        if n == MAX_CATCH_UP_STEPS {
            self.pending_secs = 0.0;
        }
    }

    /// Exactly one fixed step, whatever real time passed ("step" while paused).
    pub fn step_once(&mut self) {
        self.tick();
    }

    /// The school takes one step of `n` fixed steps' time every `n` fixed steps (1 = every
    /// step, the default). A window drawing a few frames a second sets more (the automatic
    /// quality's lowest rungs): it shows one state of them per frame anyway. The state at a
    /// time is reproducible for a given `n`.
    pub fn set_school_every(&mut self, n: u32) {
        self.school_every = n.clamp(1, 8);
    }

    /// One fixed step. Live edits to the scene (fish count, school weights, waves) are
    /// picked up here.
    fn tick(&mut self) {
        self.waves = wave_sum(&self.scene);
        let env = environment(&self.scene, &self.waves, self.flee_point, &self.obstacles);
        if self.school.params() != &self.scene.school {
            self.school.set_params(&self.scene.school, &env);
        }
        let dt = self.dt_secs();
        let every = u64::from(self.school_every);
        let school_steps = (self.steps + 1).is_multiple_of(every);
        if school_steps {
            self.school.step((dt * every as f64) as f32, &env);
        }
        self.steps += 1;
        let t = self.time_secs();
        let method = self.scene.simulation.integrator;
        for b in &mut self.bodies {
            b.advance(t, &self.waves, &self.scene.simulation, method);
        }
        if school_steps {
            self.school.fill_instances(&mut self.fish);
        }
    }

    /// A reloaded scene replaces the model; camera and time stay where the lecturer left
    /// them, the fish swim on (a new count adds or removes fish), and the floating bodies are
    /// rebuilt only if their objects changed.
    pub fn replace_scene(&mut self, scene: Scene) {
        let floating = |s: &Scene| -> Vec<Object> {
            s.objects
                .iter()
                .filter(|o| matches!(o, Object::Floating { .. }))
                .cloned()
                .collect()
        };
        let rebuild = floating(&scene) != floating(&self.scene);
        let time = self.time_secs();
        self.scene = scene;
        // keep the clock when the step changes: same time, counted in the new steps
        self.steps = (time / self.dt_secs()).round() as u64;
        self.waves = wave_sum(&self.scene);
        self.obstacles = rock_obstacles(&self.scene);
        let env = environment(&self.scene, &self.waves, self.flee_point, &self.obstacles);
        self.school.set_params(&self.scene.school, &env);
        if rebuild {
            self.bodies = make_bodies(&self.scene);
            for b in &mut self.bodies {
                b.body.time = time;
            }
        }
        self.school.fill_instances(&mut self.fish);
    }

    pub fn integrator(&self) -> Integrator {
        self.scene.simulation.integrator
    }

    pub fn readouts(&self) -> Vec<BodyReadout> {
        self.bodies
            .iter()
            .map(|b| {
                let (kinetic_j, potential_j, angular_momentum) = b.readout();
                BodyReadout {
                    object_index: b.object_index,
                    mass_kg: b.body.constants.mass,
                    kinetic_j,
                    potential_j,
                    angular_momentum,
                    resets: b.resets,
                }
            })
            .collect()
    }

    /// Refreshes `snap` to this state, reusing its buffers (the window does this every frame).
    pub fn snapshot_into(&self, snap: &mut FrameSnapshot) {
        snap.time_secs = self.time_secs() as f32;
        snap.camera = self.camera.pose();
        snap.fish.clone_from(&self.fish);
        snap.bodies.clear();
        snap.bodies.extend(self.bodies.iter().map(|b| {
            let (position, orientation) = b.mesh_pose();
            BodyPose {
                object_index: b.object_index,
                position,
                orientation,
            }
        }));
    }

    pub fn snapshot(&self) -> FrameSnapshot {
        FrameSnapshot {
            time_secs: self.time_secs() as f32,
            camera: self.camera.pose(),
            fish: self.fish.clone(),
            bodies: self
                .bodies
                .iter()
                .map(|b| {
                    let (position, orientation) = b.mesh_pose();
                    BodyPose {
                        object_index: b.object_index,
                        position,
                        orientation,
                    }
                })
                .collect(),
        }
    }
}

fn wave_sum(scene: &Scene) -> WaveSum {
    scene.water.wave_sum()
}

fn make_bodies(scene: &Scene) -> Vec<FloatingBody> {
    scene
        .objects
        .iter()
        .enumerate()
        .filter_map(|(i, o)| FloatingBody::from_object(i, o, scene.water.level))
        .collect()
}

/// Where the fish swim: a box `school_half_width` wide around the origin, from the seabed's
/// highest dune up to the water (the school keeps below the lowest trough).
pub fn environment<'a>(
    scene: &Scene,
    waves: &'a WaveSum,
    flee_point: Option<Vec3>,
    obstacles: &'a [(Vec3, f32)],
) -> Environment<'a> {
    let w = scene.simulation.school_half_width;
    let seabed = scene
        .objects
        .iter()
        .find_map(|o| match o {
            Object::Seabed { depth, relief, .. } => Some(-depth + relief),
            _ => None,
        })
        .unwrap_or(scene.water.level - 4.0);
    let bounds = Aabb::new(
        Vec3::new(-w, seabed, -w),
        Vec3::new(w, scene.water.level, w),
    );
    Environment {
        bounds,
        surface: Some(waves),
        seabed_height: seabed,
        flee_point,
        obstacles,
    }
}

/// How far a rock's lumps reach, in units of its radius (`render::mesh::rock` adds up to
/// seven lumps of at most 0.15 each; a test checks the shipped rocks against this bound).
pub const ROCK_BOUND: f32 = 1.35;

/// The spheres the fish keep out of: each rock's bound, plus a fish's length.
pub fn rock_obstacles(scene: &Scene) -> Vec<(Vec3, f32)> {
    let fish = scene.school.fish_scale.max(0.0);
    scene
        .objects
        .iter()
        .filter_map(|o| match o {
            Object::Rock {
                position, radius, ..
            } => Some((Vec3::from(*position), radius * ROCK_BOUND + fish)),
            _ => None,
        })
        .collect()
}
