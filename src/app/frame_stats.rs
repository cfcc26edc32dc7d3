//! Frame statistics: the wall time between drawn frames, for anyone measuring the live app
//! (`lectern present --frame-stats FILE` appends `mode,frame_ms` per frame) and for the
//! presenter's scene panel, which shows the same numbers rather than a guess of its own.

use std::collections::VecDeque;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;
use web_time::Instant;

use super::lectern_app::Mode;

/// How many recent frames the shown mean covers.
const RECENT: usize = 30;

#[derive(Default)]
pub struct FrameClock {
    last: Option<Instant>,
    /// The egui frame number last counted: a frame that egui runs twice (a discarded pass)
    /// is one drawn frame.
    last_frame_nr: Option<u64>,
    /// Recent intervals in the current mode (cleared when the mode changes).
    recent_ms: VecDeque<f32>,
    mode: Option<Mode>,
    file: Option<BufWriter<File>>,
}

impl FrameClock {
    /// A clock that also appends `mode,frame_ms` lines to `path` (created if missing).
    pub fn with_file(path: &Path) -> std::io::Result<Self> {
        let file = std::fs::OpenOptions::new()
            .create(true)
            .append(true)
            .open(path)?;
        Ok(Self {
            file: Some(BufWriter::new(file)),
            ..Self::default()
        })
    }

    /// Counts frame `frame_nr`, drawn in `mode` at `now`; returns the milliseconds since the
    /// previous drawn frame (none for the first, or a repeated pass of the same frame).
    pub fn tick(&mut self, frame_nr: u64, mode: Mode, now: Instant) -> Option<f32> {
        if self.last_frame_nr == Some(frame_nr) {
            return None;
        }
        self.last_frame_nr = Some(frame_nr);
        let ms = self
            .last
            .replace(now)
            .map(|t| (now - t).as_secs_f64() as f32 * 1e3)?;
        if self.mode != Some(mode) {
            self.mode = Some(mode);
            self.recent_ms.clear();
        }
        if self.recent_ms.len() == RECENT {
            self.recent_ms.pop_front();
        }
        self.recent_ms.push_back(ms);
        if let Some(f) = &mut self.file {
            let name = match mode {
                Mode::Slides => "slides",
                Mode::Scene => "scene",
            };
            // Flushed every frame: the file is read while the app runs, and a line is cheap.
            let written = writeln!(f, "{name},{ms:.2}").and_then(|()| f.flush());
            if let Err(e) = written {
                tracing::warn!("frame stats off: {e}");
                self.file = None;
            }
        }
        Some(ms)
    }

    /// The mean interval of the recent frames in the current mode, in milliseconds.
    pub fn mean_ms(&self) -> Option<f32> {
        (!self.recent_ms.is_empty())
            .then(|| self.recent_ms.iter().sum::<f32>() / self.recent_ms.len() as f32)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Duration;

    #[test]
    fn one_line_per_drawn_frame_with_its_mode() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("frames.csv");
        std::fs::write(&path, "slides,1.00\n").unwrap();
        let mut c = FrameClock::with_file(&path).unwrap();
        let t0 = Instant::now();
        let at = |ms: u64| t0 + Duration::from_millis(ms);
        assert_eq!(c.tick(1, Mode::Slides, at(0)), None, "no interval yet");
        assert_eq!(c.tick(2, Mode::Slides, at(40)), Some(40.0));
        assert_eq!(
            c.tick(2, Mode::Slides, at(45)),
            None,
            "same frame, second pass"
        );
        assert_eq!(c.tick(3, Mode::Scene, at(540)), Some(500.0));
        assert_eq!(c.tick(4, Mode::Scene, at(640)), Some(100.0));
        assert_eq!(c.mean_ms(), Some(300.0), "scene frames only");
        drop(c);
        let text = std::fs::read_to_string(&path).unwrap();
        assert_eq!(
            text, "slides,1.00\nslides,40.00\nscene,500.00\nscene,100.00\n",
            "appended"
        );
    }
}
