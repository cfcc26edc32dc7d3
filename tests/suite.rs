//! The integration tests, as one test binary: 41 binaries each linking the whole app
//! (~220 MB apiece in a debug build) filled a CI disk. One file a subject, as before;
//! `cargo test --test suite SUBJECT::` runs one. Three stay binaries of their own, as they are
//! about the whole process: `scene_soak` and `typeset_bounds` read its resident memory, which
//! tests running beside them would grow, and `project_files` installs the process's one source
//! of files (an in-memory bundle), which every other test would then read from.

mod common;

mod app;
mod authoring;
mod check_cli;
mod check_fuzz;
mod check_positions;
mod confinement;
mod deck;
mod export;
mod handout;
mod ink;
mod inline_maths;
mod lecture_data;
mod lecture_readouts;
mod live_odes;
mod math;
mod ode_accuracy;
mod ode_files;
mod ode_fixed;
mod ode_pairs;
mod ode_stiff;
mod presenter;
mod reference;
mod reload;
mod render_scene;
mod rigid;
mod scene_backends;
mod scene_default_frame;
mod scene_file;
mod scene_slide;
mod scene_techniques;
mod school;
mod shader_check;
mod slide_frame_cost;
mod slides;
mod typeset_live;
mod waves;
mod web_export;
mod web_player;
mod web_scene;
mod widgets;
