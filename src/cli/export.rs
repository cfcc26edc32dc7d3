//! `lectern export`: render every slide to PNG and/or a PDF (the slides, a speaker's `--notes`
//! sheet, or the students' `--handout`), headless, through the window's slide renderer. Exits
//! non-zero when a formula or a widget failed on some slide (the files are still written)
//! unless `--keep-going`.

use std::path::PathBuf;

use anyhow::Context as _;

use super::export_handout;
use super::export_pdf::{HandoutWriter, Layout};
use crate::app::ink_draw::InkView;
use crate::app::tweak_file::TweakFile;
use crate::app::{OffscreenRenderer, ShowControls, SlideOptions, SlideState};
use crate::deck::ink::Ink;
use crate::deck::{InkFile, load_deck};

/// Render every slide to PNG and/or a PDF handout, headless (any GPU, or Mesa's software
/// adapter).
#[derive(Debug, clap::Args)]
#[command(group(clap::ArgGroup::new("target").args(["out", "pdf"]).required(true).multiple(true)))]
pub struct Args {
    /// The deck to export [default: slides/lecture.ron]
    pub deck: Option<PathBuf>,
    /// Folder for slide-01.png, slide-02.png, …
    #[arg(long, short)]
    pub out: Option<PathBuf>,
    /// Also (or only) write a PDF: one page per slide, the page shaped like the slide.
    #[arg(long, value_name = "FILE.pdf")]
    pub pdf: Option<PathBuf>,
    /// PDF handout layout: A4 pages with the slide on top and its speaker notes below (as
    /// text that can be searched and copied).
    #[arg(long, requires = "pdf")]
    pub notes: bool,
    /// PDF handout for students: A4 pages with 2 or 3 slides each (`--per-page`), in the light
    /// theme whatever the deck's, widgets without their controls, and under each slide its
    /// `handout:` text (never the speaker notes). Pictures at print size (`--size` overrides).
    #[arg(long, requires = "pdf", conflicts_with_all = ["notes", "out"])]
    pub handout: bool,
    /// Slides on each handout page, 2 or 3 [default: 2].
    #[arg(long, requires = "handout", value_parser = clap::value_parser!(u8).range(2..=3))]
    pub per_page: Option<u8>,
    /// Image size in pixels, WIDTHxHEIGHT [default: 1920 wide, at the deck's aspect].
    #[arg(long, value_parser = parse_size)]
    pub size: Option<[u32; 2]>,
    /// Apply the live tweaks the presenter saved (`DECK.tweaks.ron`, written by `E` or
    /// `Ctrl+S` while presenting), so the images show exactly what was presented.
    #[arg(long, value_name = "FILE")]
    pub with_tweaks: Option<PathBuf>,
    /// Also write every plot widget's computed points as CSV, DIR/slide-NN-wK.csv
    /// (header `series,t,<vars>`, one row per integrator step); needs `--out`.
    #[arg(long, requires = "out")]
    pub data: bool,
    /// Exit 0 even when a formula or a widget failed on some slide (the failures are still
    /// listed).
    #[arg(long)]
    pub keep_going: bool,
    /// Leave out the ink drawn while presenting (`DECK.ink.ron` beside the deck, drawn by
    /// default so the handout shows what the class saw).
    #[arg(long)]
    pub no_ink: bool,
}

/// The default image size for a deck: 1920 pixels wide, as tall as its aspect asks.
pub fn default_size(aspect: crate::deck::Aspect) -> [u32; 2] {
    let h = (1920.0 / aspect.ratio()).round() as u32;
    [1920, h.clamp(16, 8192)]
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
    let mut deck = load_deck(&path).map_err(|d| anyhow::anyhow!("{d}"))?;
    let layout = if args.handout {
        Layout::Handout {
            per_page: (args.per_page).unwrap_or(export_handout::DEFAULT_PER_PAGE),
        }
    } else if args.notes {
        Layout::Notes
    } else {
        Layout::Slides
    };
    if let Layout::Handout { per_page } = layout {
        for warning in export_handout::prepare(&mut deck, per_page) {
            eprintln!("lectern: warning: {warning}");
        }
    }
    let size = args.size.unwrap_or_else(|| match layout {
        Layout::Handout { per_page } => {
            export_handout::picture_size_px(deck.aspect.ratio(), per_page)
        }
        Layout::Slides | Layout::Notes => default_size(deck.aspect),
    });
    let tweaks = match &args.with_tweaks {
        Some(file) => TweakFile::load(file).map_err(|d| anyhow::anyhow!("{d}"))?,
        None => TweakFile::default(),
    };
    for key in tweaks.unknown_slides(&deck) {
        eprintln!("lectern: warning: the tweaks are for slide {key:?}, which the deck lacks");
    }
    let ink = if args.no_ink {
        Ink::default()
    } else {
        load_ink(&path, &deck)
    };
    // A still image cannot wait for a background study: work-precision runs on this thread
    // (timings then from a fixed cost per f-evaluation, so exports are reproducible).
    crate::widgets::work_precision::DETERMINISTIC.store(true, std::sync::atomic::Ordering::Relaxed);
    if args.data {
        let Some(out) = &args.out else {
            anyhow::bail!("--data writes CSV files into a folder: give one with --out DIR");
        };
        let files = super::export_data::write_data(&deck, out, &tweaks)?;
        eprintln!(
            "lectern: wrote the data of {} plot widgets to {}",
            files.len(),
            out.display()
        );
    }
    let mut renderer = OffscreenRenderer::new()?;
    if let Some(out) = &args.out {
        std::fs::create_dir_all(out).with_context(|| format!("cannot create {}", out.display()))?;
    }
    let mut handout = args.pdf.clone().map(|p| HandoutWriter::new(p, layout));
    let digits = deck.slides.len().to_string().len().max(2);
    let mut failures: Vec<String> = (deck.broken_slides.iter())
        .map(|b| format!("{} (exported as an error slide)", b.diagnostic))
        .collect();
    for (index, slide) in deck.slides.iter().enumerate() {
        let mut state = SlideState::default();
        for problem in tweaks.apply(&deck, index, &mut state) {
            eprintln!("lectern: warning: {problem}");
        }
        let options = SlideOptions {
            ink: InkView {
                strokes: ink.strokes(deck.slides[index].key()),
                ..InkView::default()
            },
            // plots, legends and values: a slider cannot be dragged on paper
            controls: match layout {
                Layout::Handout { .. } => ShowControls::Never,
                Layout::Slides | Layout::Notes => ShowControls::AsDeck,
            },
            ..SlideOptions::default()
        };
        let image = renderer.render_slide_with(&deck, index, &mut state, size, options)?;
        let controls = crate::widgets::controls::control_rects(renderer.egui_ctx());
        if matches!(layout, Layout::Handout { .. }) && !controls.is_empty() {
            // a widget that calls `controls::control` where controls are hidden
            failures.push(format!(
                "{}: slide {} ({:?}): {} control(s) drawn in the handout's picture",
                path.display(),
                index + 1,
                slide.key(),
                controls.len()
            ));
        }
        // e.g. a formula stopped at its time budget: the slide shows its source instead
        for problem in state.problems() {
            failures.push(format!(
                "{}: slide {} ({:?}): {problem}",
                path.display(),
                index + 1,
                slide.key()
            ));
        }
        if let Some(out) = &args.out {
            let file = out.join(format!("slide-{:0digits$}.png", index + 1));
            image
                .save(&file)
                .with_context(|| format!("cannot write {}", file.display()))?;
        }
        if let Some(h) = &mut handout {
            h.push(&image, slide).map_err(anyhow::Error::msg)?;
        }
    }
    let mut wrote = Vec::new();
    if let Some(out) = &args.out {
        wrote.push(format!("{} PNGs to {}", deck.slides.len(), out.display()));
    }
    if let Some(h) = handout {
        let file = h.path.clone();
        let pages = h.finish(&deck.title).map_err(anyhow::Error::msg)?;
        let shape = match layout {
            Layout::Slides => "slides".to_owned(),
            Layout::Notes => "slides with notes".to_owned(),
            Layout::Handout { per_page } => format!("handout, {per_page} slides a page"),
        };
        wrote.push(format!(
            "a {pages}-page PDF ({shape}) to {}",
            file.display()
        ));
    }
    eprintln!(
        "lectern: wrote {} of {} at {}x{} ({})",
        wrote.join(" and "),
        path.display(),
        size[0],
        size[1],
        renderer.adapter_name()
    );
    report_failures(&failures, args.keep_going)
}

/// Lists every failure; an error (non-zero exit) when there is one, unless `keep_going`.
fn report_failures(failures: &[String], keep_going: bool) -> anyhow::Result<()> {
    for f in failures {
        eprintln!("lectern: {f}");
    }
    match failures.len() {
        0 => Ok(()),
        _ if keep_going => Ok(()),
        n => Err(anyhow::anyhow!(
            "{n} problem(s) on the slides above (the files were written anyway; \
             `lectern check` shows where, `--keep-going` exits 0)"
        )),
    }
}

/// The ink beside the deck; a damaged file is a warning and no ink, never a failed export.
fn load_ink(deck_path: &std::path::Path, deck: &crate::deck::Deck) -> Ink {
    let file = InkFile::for_deck(deck_path);
    if let Some(problem) = file.problem() {
        eprintln!("lectern: warning: ink left out: {problem}");
    }
    for key in file.ink().slides.keys() {
        if deck.find(key).is_none() {
            eprintln!("lectern: warning: ink for slide {key:?}, which the deck lacks");
        }
    }
    file.ink().clone()
}
