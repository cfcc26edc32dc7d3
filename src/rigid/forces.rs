//! The forces of the water scene: gravity, buoyancy from sample points against the Gerstner
//! surface (the same [`WaveSum`] the water shader draws), and linear and angular drag in water.

use super::mass::{MassProperties, lattice_points};
use super::mesh::TriMesh;
use super::state::{BodyConstants, Forces, RigidState, Wrench};
use crate::waves::WaveSum;
use glam::DVec3;

/// Points inside the body (body axes, relative to the centre of mass), each standing for a
/// small cube of water it displaces when submerged.
#[derive(Debug, Clone, PartialEq)]
pub struct BuoyancySamples {
    pub points_body: Vec<DVec3>,
    /// m³ per sample
    pub volume_each: f64,
    /// metres; a sample is fully wet when the surface is this far above it, dry this far below
    pub half_height: f64,
}

impl BuoyancySamples {
    /// The inside cell centres of an `n³` lattice over the mesh (the "approximation with
    /// points"), re-centred on the solid's centre of mass. The total volume is the exact one
    /// (`props` at density 1 or not: only `center` is used), spread evenly over the samples.
    pub fn from_mesh(mesh: &TriMesh, props: &MassProperties, exact_volume: f64, n: usize) -> Self {
        let (points, cell_volume) = lattice_points(mesh, n);
        let count = points.len().max(1) as f64;
        let volume_each = if exact_volume > 0.0 {
            exact_volume / count
        } else {
            cell_volume
        };
        let half_height = 0.5 * cell_volume.cbrt();
        Self {
            points_body: points.into_iter().map(|p| p - props.center).collect(),
            volume_each,
            half_height,
        }
    }

    pub fn total_volume(&self) -> f64 {
        self.volume_each * self.points_body.len() as f64
    }
}

/// Gravity, buoyancy and drag for one body in the water scene.
#[derive(Debug, Clone, Copy)]
pub struct WaterForces<'a> {
    /// m/s², e.g. (0, −9.81, 0)
    pub gravity: DVec3,
    /// kg/m³ (1000 for fresh water)
    pub water_density: f64,
    pub waves: &'a WaveSum,
    pub samples: &'a BuoyancySamples,
    /// N per (m/s) at full submersion
    pub linear_drag: f64,
    /// N m per (rad/s) at full submersion
    pub angular_drag: f64,
    /// seconds added to the body's clock to get the wave clock
    pub wave_time_offset: f64,
}

impl WaterForces<'_> {
    /// Submerged fraction of one sample at world point `p` (0 dry … 1 wet), linear across
    /// the sample's height so the waterline moves continuously.
    pub fn wet_fraction(&self, p: DVec3, t: f64) -> f64 {
        let surface = self.waves.height(glam::DVec2::new(p.x, p.z), t);
        let h = self.samples.half_height.max(1e-9);
        ((surface - p.y) / (2.0 * h) + 0.5).clamp(0.0, 1.0)
    }

    /// Displaced volume (m³) of the body in `state`.
    pub fn submerged_volume(&self, state: &RigidState, t: f64) -> f64 {
        let t = t + self.wave_time_offset;
        self.samples
            .points_body
            .iter()
            .map(|pb| self.wet_fraction(state.x + state.q * *pb, t))
            .sum::<f64>()
            * self.samples.volume_each
    }
}

impl Forces for WaterForces<'_> {
    fn wrench(&self, body: &BodyConstants, s: &RigidState, t: f64) -> Wrench {
        let t = t + self.wave_time_offset;
        let up_per_m3 = -self.gravity * self.water_density;
        let mut force = self.gravity * body.mass;
        let mut torque = DVec3::ZERO;
        let mut wet_total = 0.0;
        for pb in &self.samples.points_body {
            let arm = s.q * *pb;
            let wet = self.wet_fraction(s.x + arm, t);
            if wet > 0.0 {
                let f = up_per_m3 * (wet * self.samples.volume_each);
                force += f;
                torque += arm.cross(f);
                wet_total += wet;
            }
        }
        let wet_share = wet_total / self.samples.points_body.len().max(1) as f64;
        force -= self.linear_drag * wet_share * body.velocity(s.p);
        torque -= self.angular_drag * wet_share * body.omega(s.q, s.l);
        Wrench { force, torque }
    }
}

/// Uniform gravity only (a body in air).
#[derive(Debug, Clone, Copy)]
pub struct Gravity(pub DVec3);

impl Forces for Gravity {
    fn wrench(&self, body: &BodyConstants, _: &RigidState, _: f64) -> Wrench {
        Wrench {
            force: self.0 * body.mass,
            torque: DVec3::ZERO,
        }
    }
}
