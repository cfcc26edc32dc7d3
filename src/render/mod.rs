//! The wgpu renderer of scene mode. It only renders: it reads the scene model and a per-frame
//! snapshot, never steps or edits them. One module per technique, each beside its WGSL file of
//! the same name in `shaders/` with its bind-group layouts and a typed pipeline struct (see
//! docs/scene.md for the technique → file → reference table); `pipeline` builds them all the
//! same way (naga, the interface check, wgpu in an error scope) for the renderer, hot reload
//! and `lectern check` (`check`).

pub mod caps;
pub mod caustics;
pub mod check;
pub mod debug;
pub mod fish;
pub mod fish_mesh;
pub mod frame;
pub mod gpu;
pub mod headless;
pub mod interface;
pub mod layouts;
pub mod mesh;
pub mod normal_map;
pub mod pbr;
pub mod pipeline;
pub mod renderer;
pub mod resources;
pub mod shaders;
pub mod shadow;
pub mod sky;
pub mod targets;
pub mod tonemap;
pub mod water;

pub use check::{check_shader_file, pipeline_check_skipped};
pub use frame::{DebugView, RenderSettings};
pub use headless::Headless;
pub use renderer::{FrameInfo, OutputDraw, Renderer};

/// Shaders relative to the project folder.
pub const SHADER_DIR: &str = "shaders";
