//! The scene's floating bodies as `crate::rigid` bodies: a closed triangle mesh per shape (the
//! same proportions the renderer draws), mass properties by Mirtich, buoyancy sample points
//! from a lattice inside the mesh, and the forces of [`WaterForces`].

use glam::{DMat3, DQuat, DVec3, Quat, Vec3};

use crate::rigid::{
    BodyConstants, BuoyancySamples, Integrator, RigidBody, RigidState, TriMesh, WaterForces,
    mirtich,
};
use crate::waves::WaveSum;

use super::model::{Object, Shape, Simulation, WATER_DENSITY};

pub const GRAVITY: DVec3 = DVec3::new(0.0, -9.81, 0.0);
/// Lattice cells per axis for the buoyancy sample points (≤ n³ samples per body).
const SAMPLE_LATTICE: usize = 5;
/// A body this far from where it started, or this fast, has blown up (explicit Euler at a
/// large h does): it is put back at its start so the demo goes on.
const RESET_DISTANCE_M: f64 = 40.0;
const RESET_SPEED_M_PER_S: f64 = 50.0;

/// A closed, outward mesh of a floating shape, centred at the origin like the render mesh.
/// Spheres and capsules are lathed about y; the capsule is then turned so its axis is x, as
/// drawn.
pub fn shape_mesh(shape: &Shape) -> TriMesh {
    match *shape {
        Shape::Box { size } => TriMesh::centred_box(glam::Vec3::from(size).as_dvec3()),
        Shape::Sphere { radius } => TriMesh::lathe(&round_profile(radius as f64, 0.0), 24),
        Shape::Capsule { radius, length } => {
            TriMesh::lathe(&round_profile(radius as f64, 0.5 * length as f64), 24)
                .transformed(DMat3::from_rotation_z(-std::f64::consts::FRAC_PI_2))
        }
    }
}

/// (radius, y) from bottom to top of a sphere of `r` split at the equator by a cylinder of
/// half-length `half`.
fn round_profile(r: f64, half: f64) -> Vec<(f64, f64)> {
    const N: usize = 12; // rings per hemisphere
    let mut p = Vec::new();
    for k in 1..=N {
        let a = std::f64::consts::FRAC_PI_2 * k as f64 / N as f64; // from the bottom pole
        p.push((r * a.sin(), -half - r * a.cos()));
    }
    for k in (1..N).rev() {
        let a = std::f64::consts::FRAC_PI_2 * k as f64 / N as f64;
        p.push((r * a.sin(), half + r * a.cos()));
    }
    p
}

/// One floating body of the scene.
pub struct FloatingBody {
    /// index into `Scene::objects`
    pub object_index: usize,
    pub body: RigidBody,
    pub samples: BuoyancySamples,
    /// centre of mass in the render mesh's coordinates (≈ 0 for these symmetric shapes)
    pub center_in_mesh: DVec3,
    start: (DVec3, DQuat),
    /// how often it blew up and was put back
    pub resets: u32,
}

impl FloatingBody {
    /// The body of `scene.objects[object_index]`, if that object floats.
    pub fn from_object(object_index: usize, object: &Object, level: f32) -> Option<Self> {
        let Object::Floating {
            shape,
            position,
            density,
            tilt_deg,
            ..
        } = object
        else {
            return None;
        };
        let mesh = shape_mesh(shape);
        let unit = mirtich(&mesh);
        let props = unit.with_density(*density as f64);
        let samples = BuoyancySamples::from_mesh(&mesh, &unit, unit.volume(), SAMPLE_LATTICE);
        let x = DVec3::new(position[0] as f64, level as f64, position[1] as f64);
        let yaw = 0.7 * object_index as f64;
        let q = DQuat::from_rotation_y(yaw) * DQuat::from_rotation_x(tilt_deg.to_radians() as f64);
        Some(Self {
            object_index,
            body: RigidBody::from_mass_properties(&props, x, q),
            samples,
            center_in_mesh: unit.center,
            start: (x, q),
            resets: 0,
        })
    }

    /// Gravity, buoyancy against `waves` and drag: the wrench the scene steps this body with
    /// (the simulation-loop slide shows it too).
    pub fn water_forces<'a>(&'a self, waves: &'a WaveSum, sim: &Simulation) -> WaterForces<'a> {
        water_forces(&self.body.constants, &self.samples, waves, sim)
    }

    pub fn advance(
        &mut self,
        until_secs: f64,
        waves: &WaveSum,
        sim: &Simulation,
        method: Integrator,
    ) {
        let h = sim.body_h_secs as f64;
        self.body.integrator = method;
        let forces = water_forces(&self.body.constants, &self.samples, waves, sim);
        // a half-step tolerance keeps h = dt in lockstep despite rounding
        while self.body.time + 0.5 * h <= until_secs {
            self.body.step(h, &forces);
            guard(&mut self.body, self.start, &mut self.resets);
        }
    }

    /// World pose of the render mesh's origin.
    pub fn mesh_pose(&self) -> (Vec3, Quat) {
        let s = &self.body.state;
        let origin = s.x - s.q * self.center_in_mesh;
        (origin.as_vec3(), s.q.as_quat())
    }

    /// Kinetic energy (J), gravitational potential energy relative to y = 0 (J), |L| (kg m²/s).
    pub fn readout(&self) -> (f64, f64, f64) {
        (
            self.body.energy(),
            self.body.potential_energy(GRAVITY),
            self.body.angular_momentum().length(),
        )
    }
}

fn water_forces<'a>(
    c: &BodyConstants,
    samples: &'a BuoyancySamples,
    waves: &'a WaveSum,
    sim: &Simulation,
) -> WaterForces<'a> {
    let i = c.inertia_body;
    let mean_inertia = (i.x_axis.x + i.y_axis.y + i.z_axis.z) / 3.0;
    WaterForces {
        gravity: GRAVITY,
        water_density: WATER_DENSITY as f64,
        waves,
        samples,
        linear_drag: sim.linear_drag_per_sec as f64 * c.mass,
        angular_drag: sim.angular_drag_per_sec as f64 * mean_inertia,
        wave_time_offset: 0.0,
    }
}

/// Puts a blown-up body back at its start, at rest (its clock goes on).
fn guard(body: &mut RigidBody, start: (DVec3, DQuat), resets: &mut u32) {
    let s = &body.state;
    let far = (s.x - start.0).length() > RESET_DISTANCE_M;
    let fast = body.velocity().length() > RESET_SPEED_M_PER_S;
    if far || fast || !s.x.is_finite() || !s.l.is_finite() {
        body.state = RigidState::at_rest(start.0, start.1);
        *resets += 1;
    }
}
