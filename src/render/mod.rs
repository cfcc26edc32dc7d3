//! The wgpu renderer of scene mode: one module per technique, each beside its WGSL file in
//! `shaders/` (see docs/scene.md for the technique → file → reference table).

pub mod frame;
pub mod gpu;
pub mod headless;
pub mod mesh;
pub mod normal_map;
pub mod pipelines;
pub mod renderer;
pub mod resources;
pub mod shaders;
pub mod sky;
pub mod view;

pub use frame::{DebugView, RenderSettings};
pub use headless::Headless;
pub use renderer::Renderer;
pub use view::SceneView;

/// Shaders relative to the project folder.
pub const SHADER_DIR: &str = "shaders";
