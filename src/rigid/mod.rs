//! Rigid bodies: the 13-number state (x, q, P, L), body-space inertia from a closed triangle
//! mesh (Mirtich 1996) or a point lattice, and the forces the water scene needs.
//!
//! State is f64 throughout: the energy and quaternion-norm tests need 1e-9 accuracy. The
//! renderer reads `RigidBody::pose()` as f32.

pub mod batch;
pub mod body;
pub mod forces;
pub mod free_rotation;
pub mod lanes;
pub mod mass;
pub mod mesh;
pub mod principal;
pub mod state;
pub mod step;

pub use batch::{BatchForces, BodyBatch, FreeBodies};
pub use body::{BodySystem, RigidBody, quat_euler_update};
pub use forces::{BuoyancySamples, Gravity, WaterForces};
pub use mass::{MassProperties, mirtich, point_lattice};
pub use mesh::TriMesh;
pub use principal::{PrincipalAxes, principal_axes};
pub use state::{BodyConstants, Forces, Integrator, NoForces, RigidState, Wrench};
