//! `lectern export --data`: every plot widget's computed points as CSV, for students and tests to
//! check the numbers: `DIR/slide-NN-wK.csv` (K counts the slide's widgets from 1, in file order),
//! long format with the header `series,t,<var1>[,<var2>…]`, one row per integrator step (not the
//! decimated draw data); series named by `MethodRef::key` (`euler`, `midpoint`, `rk4`, `dop853`,
//! `vern9`, a tableau file's stem), and `exact` (the closed form at the reference's times) or
//! `reference` (a fine RK4 solve, when there is no closed form). The convergence widget writes
//! `series,h,error` and the work-precision widget `series,sweep,h_or_tol,f_evals,error`, one row
//! per run; the stability widget writes `series,re,im`, one closed polyline per method (its
//! region's edge, |R(z)| = 1; further islands as `key.2`, …) and the z = hλ marker as `z`.
//! Beside each, `DIR/slide-NN-wK-readouts.csv` (`readout,series,value`) holds the numbers the
//! widget prints (errors at the end, stable-h limits, λ, slopes, matrices), unrounded.

use std::path::{Path, PathBuf};

use anyhow::Context as _;

use crate::app::tweak_file::TweakFile;
use crate::app::{SlideState, plot_data};
use crate::deck::Deck;
use crate::widgets::Readout;

/// Writes the CSV files of every plot widget of `deck` into `dir`, with `tweaks` applied (the
/// values the presenter saved, as the PNGs show them); returns the files written.
pub fn write_data(deck: &Deck, dir: &Path, tweaks: &TweakFile) -> anyhow::Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let digits = deck.slides.len().to_string().len().max(2);
    let mut written = Vec::new();
    for (i, slide) in deck.slides.iter().enumerate() {
        let mut state = SlideState::default();
        state.set_deck_path(deck.file.as_deref());
        state.ensure_widgets(slide);
        // warnings about stale tweaks are printed by the PNG export
        let _ = tweaks.apply(deck, i, &mut state);
        for widget in plot_data::slide_data(slide, &mut state) {
            let stem = format!("slide-{:0digits$}-w{}", i + 1, widget.ordinal);
            let files = [
                (format!("{stem}.csv"), widget.csv),
                (
                    format!("{stem}-readouts.csv"),
                    (!widget.readouts.is_empty()).then(|| Readout::to_csv(&widget.readouts)),
                ),
            ];
            for (name, text) in files {
                let Some(text) = text else { continue };
                let file = dir.join(name);
                std::fs::write(&file, text)
                    .with_context(|| format!("cannot write {}", file.display()))?;
                written.push(file);
            }
        }
    }
    Ok(written)
}
