//! The `lectern` command line: one file per subcommand, each with its clap `Args` and `run`.

pub mod bench;
pub mod check;
pub mod check_deck;
pub mod export;
pub mod export_data;
pub mod export_handout;
pub mod export_pdf;
pub mod inertia;
pub mod new;
pub mod present;
pub mod render_scene;
pub mod solve;
pub mod typeset_bench;
