//! `lectern present`: present a deck in a window.

use std::path::PathBuf;

use anyhow::Context as _;

use crate::app::LecternApp;
use crate::deck::DeckSession;

/// Present a deck in a window (the default command).
#[derive(Debug, Default, clap::Args)]
pub struct Args {
    /// The deck to present [default: slides/lecture.ron]
    pub deck: Option<PathBuf>,
    /// Start on this slide (1-based).
    #[arg(long, value_name = "N")]
    pub slide: Option<usize>,
    /// Start fullscreen.
    #[arg(long)]
    pub fullscreen: bool,
    /// Open a second window with the presenter view (notes, timer, next slide, controls) for
    /// the lecturer's screen; the main window shows only the slides. One screen: press P.
    #[arg(long)]
    pub presenter: bool,
    /// Rehearsal: record the actual time per slide in DECK.timings.ron beside the deck.
    #[arg(long)]
    pub rehearse: bool,
}

/// The bundled lecture: `slides/lecture.ron` under the current folder, else in the source tree
/// this binary was built from (so `cargo run` works from anywhere inside the project).
pub fn default_deck() -> PathBuf {
    let local = PathBuf::from("slides/lecture.ron");
    if local.exists() {
        return local;
    }
    let built = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/slides/lecture.ron"));
    if built.exists() { built } else { local }
}

pub fn run(args: Args) -> anyhow::Result<()> {
    let path = args.deck.unwrap_or_else(default_deck);
    let mut session = DeckSession::open(&path).map_err(|d| anyhow::anyhow!("{d}"))?;
    if let Some(n) = args.slide {
        session
            .navigate(|nav, deck| nav.goto_number(deck, n))
            .map_err(|m| anyhow::anyhow!(m))?;
    }
    let title = format!("lectern — {}", session.deck().title);
    let rehearsal = args.rehearse.then(|| path.with_extension("timings.ron"));
    let presenter = args.presenter;
    let viewport = egui::ViewportBuilder::default()
        .with_title(&title)
        .with_app_id("lectern")
        .with_inner_size([1280.0, 720.0])
        .with_min_inner_size([320.0, 180.0])
        .with_fullscreen(args.fullscreen);
    let options = eframe::NativeOptions {
        viewport,
        renderer: eframe::Renderer::Wgpu,
        ..Default::default()
    };
    eframe::run_native(
        &title,
        options,
        Box::new(move |cc| {
            let mut app = LecternApp::new(session);
            app.render_state = cc.wgpu_render_state.clone();
            app.watch(&cc.egui_ctx);
            app.presenter_window = presenter;
            app.rehearsal_file = rehearsal;
            Ok(Box::new(app))
        }),
    )
    .map_err(|e| anyhow::anyhow!("{e}"))
    .context(
        "cannot open the window (no display? set DISPLAY or WAYLAND_DISPLAY, \
         or use `lectern export` headless)",
    )
}
