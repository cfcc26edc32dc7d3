//! Files the presenter writes while presenting: `E`'s PNG of the current slide, the live
//! tweaks of every slide (`DECK.tweaks.ron`), and the rehearsal timings (`DECK.timings.ron`).
//! All through temp file + atomic rename, so a crash never leaves half a file.

use std::path::PathBuf;

use super::lectern_app::LecternApp;
use super::offscreen::OffscreenRenderer;
use super::tweak_file::{TweakFile, tweak_file_path};

impl LecternApp {
    /// Rehearsal: the actual seconds per slide so far, after each slide change.
    pub(super) fn write_rehearsal(&self) {
        if let Some(file) = &self.rehearsal_file {
            let text = self.pacing.rehearsal_ron(self.session.deck());
            if let Err(e) = crate::deck::write_back::write_atomic(file, &text) {
                tracing::warn!("cannot write {}: {e}", file.display());
            }
        }
    }

    /// Writes the live tweaks of every slide to `DECK.tweaks.ron` beside the deck (for
    /// `lectern export --with-tweaks`); returns the file, or why it could not be written.
    pub fn save_tweak_file(&mut self) -> Result<PathBuf, String> {
        let file = tweak_file_path(self.session.path());
        let tweaks = TweakFile::from_states(self.session.deck(), &mut self.states);
        crate::deck::write_back::write_atomic(&file, &tweaks.to_ron())
            .map_err(|e| format!("cannot write {}: {e}", file.display()))?;
        Ok(file)
    }

    /// `E`: the current slide, exactly as shown (live tweaks included), to a PNG beside the
    /// deck, and the live tweaks of all slides to `DECK.tweaks.ron`.
    pub(super) fn export_current(&mut self, ctx: &egui::Context) {
        if let Err(e) = self.save_tweak_file() {
            tracing::warn!("{e}");
        }
        let index = self.session.nav().index();
        let folder = self.session.folder();
        if self.offscreen.is_none() {
            match OffscreenRenderer::new() {
                Ok(r) => self.offscreen = Some(r),
                Err(e) => return self.say(ctx, e.to_string()),
            }
        }
        let deck = self.session.deck();
        let slide = &deck.slides[index];
        let state = self.states.slide(slide);
        let Some(r) = self.offscreen.as_mut() else {
            return;
        };
        let file = folder.join(format!("{}-live.png", slide.key()));
        // As shown: with the slide's ink (the laser and a stroke in progress are not ink).
        let options = super::SlideOptions {
            ink: super::ink_draw::InkView {
                strokes: self.ink.file().ink().strokes(slide.key()),
                ..Default::default()
            },
            ..Default::default()
        };
        let msg = match r.render_slide_with(deck, index, state, [1920, 1080], options) {
            Ok(img) => match img.save(&file) {
                Ok(()) => format!("exported {}", file.display()),
                Err(e) => format!("cannot write {}: {e}", file.display()),
            },
            Err(e) => e.to_string(),
        };
        self.say(ctx, msg);
    }
}
