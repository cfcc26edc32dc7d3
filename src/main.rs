//! `lectern`: present the lecture (default), or export, check, solve, bench, inertia, render-scene.

use clap::{Parser, Subcommand};
use lectern::cli;

#[derive(Parser)]
#[command(
    name = "lectern",
    version,
    about = "A live-reloading lecture on physically based animation"
)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Subcommand)]
enum Command {
    /// Present a deck in a window (the default).
    Present(cli::present::Args),
    /// Make a starter project (deck, problem file, tableau, picture, water scene) in DIR.
    New(cli::new::Args),
    /// Render every slide to PNG and/or a PDF handout, headless.
    Export(cli::export::Args),
    /// Validate decks, scenes, shaders and problems; print file:line:col for each problem.
    Check(cli::check::Args),
    /// Integrate an ODE problem file and print the final state or the trajectory.
    Solve(cli::solve::Args),
    /// Work-precision report: error against f-evaluations and time for each method.
    Bench(cli::bench::Args),
    /// Mass, centre of mass and inertia tensor of a closed triangle mesh (OBJ).
    Inertia(cli::inertia::Args),
    /// Render the water scene to PNG frames, headless.
    RenderScene(cli::render_scene::Args),
    /// (internal) Measure typesetting off the UI thread on a deck (docs/benchmarks/typeset.md).
    #[command(name = "typeset-bench", hide = true)]
    TypesetBench(cli::typeset_bench::Args),
    /// (internal) Typeset formulas sent over stdin, for the bounded worker pool.
    #[command(name = "typeset-worker", hide = true)]
    TypesetWorker {
        /// Memory a formula may use beyond the worker's own, in MiB.
        #[arg(long, default_value_t = 512)]
        memory_mb: u64,
    },
}

fn main() -> std::process::ExitCode {
    let cli = Cli::parse();
    let window = matches!(cli.command, None | Some(Command::Present(_)));
    // wgpu also probes OpenGL; without a GL driver its EGL probe logs an ERROR that is none
    // (the Vulkan adapter, lavapipe included, is used): keep it quiet. The headless commands
    // name their adapter themselves, so egui-wgpu's "software rasterizer" warning is noise
    // there; the window keeps it (it explains a slow window).
    let default_filter = if window {
        "warn,lectern=info,wgpu_hal::gles::egl=off"
    } else {
        "warn,lectern=info,wgpu_hal::gles::egl=off,egui_wgpu=error"
    };
    tracing_subscriber::fmt()
        .with_env_filter(
            tracing_subscriber::EnvFilter::try_from_default_env()
                .unwrap_or_else(|_| default_filter.into()),
        )
        .with_writer(std::io::stderr)
        .init();
    quiet_runtime_dir();
    let result = match cli.command {
        None => cli::present::run(cli::present::Args::default()),
        Some(Command::Present(a)) => cli::present::run(a),
        Some(Command::New(a)) => cli::new::run(a),
        Some(Command::Export(a)) => cli::export::run(a),
        Some(Command::Check(a)) => cli::check::run(a),
        Some(Command::Solve(a)) => cli::solve::run(a),
        Some(Command::Bench(a)) => cli::bench::run(a),
        Some(Command::Inertia(a)) => cli::inertia::run(a),
        Some(Command::RenderScene(a)) => cli::render_scene::run(a),
        Some(Command::TypesetBench(a)) => cli::typeset_bench::run(a),
        Some(Command::TypesetWorker { memory_mb }) => {
            return std::process::ExitCode::from(lectern::math::worker::serve(memory_mb) as u8);
        }
    };
    match result {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("lectern: {e:#}");
            std::process::ExitCode::FAILURE
        }
    }
}

/// Mesa's Vulkan software driver (lavapipe) prints "XDG_RUNTIME_DIR is invalid or not set" when
/// the variable names no folder (a server, CI, a `sudo` shell, a bare Xvfb). Every command,
/// the window included, then gets a private one and the line goes away: a valid one (a
/// desktop session's, which Wayland needs) is never replaced.
fn quiet_runtime_dir() {
    let valid = std::env::var_os("XDG_RUNTIME_DIR")
        .map(std::path::PathBuf::from)
        .is_some_and(|d| d.is_absolute() && d.is_dir());
    if valid {
        return;
    }
    #[cfg(unix)]
    let (dir, made) = {
        use std::os::unix::fs::{DirBuilderExt, MetadataExt};
        // SAFETY: getuid has no preconditions and cannot fail.
        let uid = unsafe { libc::getuid() };
        let dir = std::env::temp_dir().join(format!("lectern-runtime-{uid}"));
        let _ = std::fs::DirBuilder::new().mode(0o700).create(&dir);
        // only a folder of ours that nobody else may read is used (another user could have
        // made one under that name first)
        let ours = std::fs::symlink_metadata(&dir)
            .is_ok_and(|m| m.is_dir() && m.uid() == uid && m.mode() & 0o077 == 0);
        (dir, ours)
    };
    #[cfg(not(unix))]
    let (dir, made) = (std::path::PathBuf::new(), false);
    if made {
        // SAFETY: called at the start of `main`, before any thread is started.
        unsafe { std::env::set_var("XDG_RUNTIME_DIR", &dir) };
    }
}
