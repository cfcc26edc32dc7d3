//! `lectern export`: render every slide to PNG, headless, through the window's slide renderer.

use std::path::PathBuf;

use anyhow::Context as _;

use crate::app::tweak_file::TweakFile;
use crate::app::{OffscreenRenderer, SlideState};
use crate::deck::load_deck;

/// Render every slide to PNG, headless (any GPU, or Mesa's software adapter).
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The deck to export [default: slides/lecture.ron]
    pub deck: Option<PathBuf>,
    /// Folder for slide-01.png, slide-02.png, …
    #[arg(long, short)]
    pub out: PathBuf,
    /// Image size in pixels, WIDTHxHEIGHT.
    #[arg(long, default_value = "1920x1080", value_parser = parse_size)]
    pub size: [u32; 2],
    /// Apply the live tweaks the presenter saved (`DECK.tweaks.ron`, written by `E` or
    /// `Ctrl+S` while presenting), so the images show exactly what was presented.
    #[arg(long, value_name = "FILE")]
    pub with_tweaks: Option<PathBuf>,
}

/// "1920x1080" → [1920, 1080].
pub fn parse_size(s: &str) -> Result<[u32; 2], String> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("expected WIDTHxHEIGHT, like 1920x1080, got {s:?}"))?;
    let parse = |v: &str| {
        v.trim()
            .parse::<u32>()
            .map_err(|_| format!("{v:?} is not a whole number of pixels"))
    };
    let size = [parse(w)?, parse(h)?];
    if size.iter().any(|&v| !(16..=8192).contains(&v)) {
        return Err(format!("each side must be 16..=8192 pixels, got {s}"));
    }
    Ok(size)
}

pub fn run(args: Args) -> anyhow::Result<()> {
    let path = args.deck.unwrap_or_else(super::present::default_deck);
    let deck = load_deck(&path).map_err(|d| anyhow::anyhow!("{d}"))?;
    let tweaks = match &args.with_tweaks {
        Some(file) => TweakFile::load(file).map_err(|d| anyhow::anyhow!("{d}"))?,
        None => TweakFile::default(),
    };
    for key in tweaks.unknown_slides(&deck) {
        eprintln!("lectern: warning: the tweaks are for slide {key:?}, which the deck lacks");
    }
    // A still image cannot wait for a background study: work-precision runs on this thread
    // (timings then from a fixed cost per f-evaluation, so exports are reproducible).
    crate::widgets::work_precision::DETERMINISTIC.store(true, std::sync::atomic::Ordering::Relaxed);
    let mut renderer = OffscreenRenderer::new()?;
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("cannot create {}", args.out.display()))?;
    let digits = deck.slides.len().to_string().len().max(2);
    for index in 0..deck.slides.len() {
        let mut state = SlideState::default();
        for problem in tweaks.apply(&deck, index, &mut state) {
            eprintln!("lectern: warning: {problem}");
        }
        let image = renderer.render_slide(&deck, index, &mut state, args.size)?;
        // e.g. a formula stopped at its time budget: the slide shows its source instead
        for problem in state.problems() {
            eprintln!("lectern: warning: {problem}");
        }
        let file = args.out.join(format!("slide-{:0digits$}.png", index + 1));
        image
            .save(&file)
            .with_context(|| format!("cannot write {}", file.display()))?;
    }
    eprintln!(
        "lectern: wrote {} slides of {} at {}x{} to {} ({})",
        deck.slides.len(),
        path.display(),
        args.size[0],
        args.size[1],
        args.out.display(),
        renderer.adapter_name()
    );
    Ok(())
}
