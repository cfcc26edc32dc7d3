//! The water scene: its model as written in `scenes/*.ron`, the per-frame simulation step, and
//! the immutable per-frame snapshot the renderer reads.

pub mod bodies;
mod load;
pub mod model;
pub mod orbit;
pub mod quality;
pub mod sim;
pub mod snapshot;

pub use load::{check_file, load_scene, parse_scene};
pub use model::{Material, NormalPattern, Object, Quality, Scene, Shape, Simulation};
pub use orbit::OrbitCamera;
pub use quality::QualityController;
pub use sim::{BodyReadout, SceneSim};
pub use snapshot::{BodyPose, CameraPose, FrameSnapshot};

/// The default scene, relative to the project folder.
pub const DEFAULT_SCENE: &str = "scenes/water.ron";
