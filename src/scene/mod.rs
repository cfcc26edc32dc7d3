//! The water scene: its model as written in `scenes/*.ron`, the per-frame simulation step, and
//! the immutable per-frame snapshot the renderer reads.

mod load;
pub mod model;
pub mod orbit;
pub mod sim;
pub mod snapshot;
pub mod surface;

pub use load::{check_file, load_scene, parse_scene};
pub use model::{Material, NormalPattern, Object, Scene, Shape};
pub use orbit::OrbitCamera;
pub use sim::SceneSim;
pub use snapshot::{BodyPose, CameraPose, FrameSnapshot};

/// The default scene, relative to the project folder.
pub const DEFAULT_SCENE: &str = "scenes/water.ron";
