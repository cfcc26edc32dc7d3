//! The automatic quality setting: a frame-time budget held by stepping down (or back up) a
//! ladder of render scale and fish detail. Pure logic — fed measured frame times, it says what
//! to draw with — so the window, the tests and anything else can drive it.

use super::model::Quality;

/// Render scale and fish detail, from full quality down; each rung costs less to draw.
pub const LADDER: [(f32, f32); 8] = [
    (1.0, 1.0),
    (1.0, 0.6),
    (0.85, 0.45),
    (0.75, 0.3),
    (0.65, 0.2),
    (0.55, 0.12),
    (0.45, 0.06),
    (0.35, 0.0),
];

/// Frames to wait after a change before judging the new rung.
const SETTLE_FRAMES: u32 = 4;
/// Slower than budget × this: one rung down.
const TOO_SLOW: f32 = 1.1;
/// Faster than budget × this for `ROOM_FRAMES` frames: one rung up.
const ROOM: f32 = 0.6;
const ROOM_FRAMES: u32 = 30;

#[derive(Debug, Clone, PartialEq)]
pub struct QualityController {
    mode: Quality,
    rung: usize,
    /// smoothed frame time since the last change, ms
    smoothed_ms: Option<f32>,
    frames_since_change: u32,
}

impl QualityController {
    pub fn new(mode: Quality) -> Self {
        Self {
            mode,
            rung: 0,
            smoothed_ms: None,
            frames_since_change: 0,
        }
    }

    /// A reloaded scene may change the mode; an automatic one keeps its rung.
    pub fn set_mode(&mut self, mode: Quality) {
        if mode != self.mode {
            self.mode = mode;
            self.smoothed_ms = None;
            self.frames_since_change = 0;
        }
    }

    pub fn mode(&self) -> Quality {
        self.mode
    }

    /// (render scale, fish detail) to draw the next frame with.
    pub fn settings(&self) -> (f32, f32) {
        match self.mode {
            Quality::Auto { .. } => LADDER[self.rung],
            Quality::Fixed {
                render_scale,
                fish_detail,
            } => (render_scale, fish_detail),
        }
    }

    /// 0 = full quality; higher is coarser.
    pub fn rung(&self) -> usize {
        self.rung
    }

    /// The smoothed frame time the controller is judging, ms.
    pub fn smoothed_ms(&self) -> Option<f32> {
        self.smoothed_ms
    }

    /// Feeds one frame's time (wall time since the previous frame).
    pub fn observe(&mut self, frame_ms: f32) {
        let Quality::Auto { budget_ms } = self.mode else {
            return;
        };
        if !frame_ms.is_finite() || frame_ms <= 0.0 {
            return;
        }
        self.frames_since_change += 1;
        if self.frames_since_change <= SETTLE_FRAMES {
            // the frame that was already under way when the rung changed does not count
            return;
        }
        let s = match self.smoothed_ms {
            None => frame_ms,
            Some(s) => 0.7 * s + 0.3 * frame_ms,
        };
        self.smoothed_ms = Some(s);
        let down = s > budget_ms * TOO_SLOW && self.rung + 1 < LADDER.len();
        let up = s < budget_ms * ROOM
            && self.rung > 0
            && self.frames_since_change >= SETTLE_FRAMES + ROOM_FRAMES;
        if down || up {
            self.rung = if down { self.rung + 1 } else { self.rung - 1 };
            self.smoothed_ms = None;
            self.frames_since_change = 0;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A renderer whose frame time is proportional to the pixels and fish detail drawn.
    fn frame_ms(c: &QualityController, full_ms: f32) -> f32 {
        let (scale, detail) = c.settings();
        full_ms * (0.2 + 0.5 * scale * scale + 0.3 * detail)
    }

    #[test]
    fn a_slow_machine_steps_down_until_the_budget_holds_and_a_fast_one_stays_at_full() {
        let mut slow = QualityController::new(Quality::Auto { budget_ms: 66.0 });
        for _ in 0..300 {
            let ms = frame_ms(&slow, 200.0);
            slow.observe(ms);
        }
        assert!(slow.rung() > 0);
        assert!(
            frame_ms(&slow, 200.0) <= 66.0 * TOO_SLOW,
            "{:?}",
            slow.settings()
        );
        // … and it does not drop further than it needs to
        let one_up = LADDER[slow.rung() - 1];
        let above = 200.0 * (0.2 + 0.5 * one_up.0 * one_up.0 + 0.3 * one_up.1);
        assert!(
            above > 66.0 * ROOM,
            "the rung above would fit with room: {above}"
        );

        let mut fast = QualityController::new(Quality::Auto { budget_ms: 66.0 });
        for _ in 0..300 {
            let ms = frame_ms(&fast, 10.0);
            fast.observe(ms);
        }
        assert_eq!(fast.settings(), (1.0, 1.0));
        // the machine gets faster again (the lecturer closed another program): quality returns
        for _ in 0..1000 {
            let ms = frame_ms(&slow, 20.0);
            slow.observe(ms);
        }
        assert_eq!(slow.rung(), 0);
    }

    #[test]
    fn fixed_quality_is_what_the_file_says() {
        let mut c = QualityController::new(Quality::Fixed {
            render_scale: 0.5,
            fish_detail: 0.25,
        });
        c.observe(1000.0);
        assert_eq!(c.settings(), (0.5, 0.25));
    }
}
