//! The `lectern` command line: one file per subcommand, each with its clap `Args` and `run`.

pub mod bench;
pub mod check;
pub mod export;
pub mod inertia;
pub mod present;
pub mod render_scene;
pub mod solve;
pub mod typeset_bench;
