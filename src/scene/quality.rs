//! The automatic quality setting: a frame-time budget held by stepping down (or back up) a
//! ladder of render scale, fish detail, shadow filtering, how often the school is stepped and
//! how many of the water and seabed grids' vertices are used.
//! Pure logic — fed measured frame times, it says what to draw and simulate with — so the
//! window, the tests and anything else can drive it.

use super::model::{MAX_WAVES, Quality};

/// Where the water's normal comes from: every wave summed again per pixel, or only the short
/// ones, the long ones' terms summed per vertex and interpolated (smooth over a grid cell, so
/// the picture barely changes while the per-pixel work falls to a fraction: the lower quality
/// rungs). `WATER_VERTEX_WAVES` in shaders/common.wgsl, a pipeline constant.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum WaterNormals {
    #[default]
    PerPixel,
    /// the 12 shortest waves per pixel
    Short12,
    /// the 6 shortest waves per pixel
    Short6,
}

impl WaterNormals {
    pub const ALL: [WaterNormals; 3] = [Self::PerPixel, Self::Short12, Self::Short6];

    /// How many waves the fragment shader sums per pixel.
    pub fn pixel_waves(self) -> u32 {
        match self {
            Self::PerPixel => MAX_WAVES as u32,
            Self::Short12 => 12,
            Self::Short6 => 6,
        }
    }

    /// The slots summed per vertex only (the longest waves come first).
    pub fn vertex_waves(self) -> f64 {
        f64::from(MAX_WAVES as u32 - self.pixel_waves())
    }

    pub fn index(self) -> usize {
        match self {
            Self::PerPixel => 0,
            Self::Short12 => 1,
            Self::Short6 => 2,
        }
    }
}

/// What the scene is drawn and simulated with on one rung of the ladder.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rung {
    /// the fraction of the window's size, in each direction, the scene is drawn at
    pub render_scale: f32,
    /// fish level of detail: 1 = default distances, 0 = the far mesh everywhere
    pub fish_detail: f32,
    /// 3×3 PCF shadow edges; false = one bilinear tap (as soft once a pixel is larger than a
    /// shadow texel, as it is on the rungs that use it)
    pub soft_shadows: bool,
    /// the school takes one step of this many fixed steps' time every this many fixed steps
    /// (a window this slow shows at most one of them anyway); the floating bodies still
    /// take every step
    pub school_every: u32,
    /// the water and seabed grids over every other row and column of their vertices
    pub coarse_grids: bool,
    /// how many of the waves the water's normal sums per pixel (the rest per vertex)
    pub water_normals: WaterNormals,
}

const fn rung(
    render_scale: f32,
    fish_detail: f32,
    soft_shadows: bool,
    school_every: u32,
    water_normals: WaterNormals,
) -> Rung {
    Rung {
        render_scale,
        fish_detail,
        soft_shadows,
        school_every,
        // with one shadow tap: the rungs drawn at half the window's size or less, where the
        // full grids had more triangles than the frame had pixels
        coarse_grids: !soft_shadows,
        water_normals,
    }
}

use WaterNormals::{PerPixel, Short6, Short12};

/// From full quality down; each rung costs less to draw.
pub const LADDER: [Rung; 9] = [
    rung(1.0, 1.0, true, 1, PerPixel),
    rung(1.0, 0.6, true, 1, PerPixel),
    rung(1.0, 0.6, true, 1, Short12),
    rung(0.85, 0.45, true, 1, Short12),
    rung(0.75, 0.3, true, 1, Short12),
    rung(0.65, 0.2, true, 1, Short6),
    rung(0.55, 0.12, false, 2, Short6),
    // the last two drawn smaller than their fixed costs alone would ask: on llvmpipe the
    // window's frame there is mostly per pixel (docs/benchmarks/scene.md, issue #22)
    rung(0.4, 0.06, false, 2, Short6),
    rung(0.28, 0.0, false, 3, Short6),
];

/// The rung the automatic quality starts from, decided here only: the top natively; in a
/// browser, where WebGL2 often runs on a software rasteriser (SwiftShader) and a slow first
/// second is what a student sees, a rung drawn at about half size with the far fish mesh
/// nearly everywhere and the school stepped every other step, from where it climbs when the
/// frames have room. The Scene widget on a slide draws at its render scale too.
pub const fn start_rung() -> usize {
    if cfg!(target_arch = "wasm32") {
        BROWSER_START_RUNG
    } else {
        0
    }
}

/// See [`start_rung`]: `lectern render-scene --rung 7` draws what the browser starts with.
pub const BROWSER_START_RUNG: usize = 6;

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
            rung: start_rung(),
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

    /// What to draw and simulate the next frame with.
    pub fn settings(&self) -> Rung {
        match self.mode {
            Quality::Auto { .. } => LADDER[self.rung],
            Quality::Fixed {
                render_scale,
                fish_detail,
            } => rung(render_scale, fish_detail, true, 1, PerPixel),
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
        cost(&c.settings(), full_ms)
    }

    fn cost(r: &Rung, full_ms: f32) -> f32 {
        let scale = r.render_scale;
        let water = r.water_normals.pixel_waves() as f32 / MAX_WAVES as f32;
        full_ms * (0.1 + 0.5 * scale * scale + 0.3 * r.fish_detail + 0.1 * water)
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
        let above = cost(&LADDER[slow.rung() - 1], 200.0);
        assert!(
            above > 66.0 * ROOM,
            "the rung above would fit with room: {above}"
        );

        let mut fast = QualityController::new(Quality::Auto { budget_ms: 66.0 });
        for _ in 0..300 {
            let ms = frame_ms(&fast, 10.0);
            fast.observe(ms);
        }
        assert_eq!(fast.settings(), LADDER[0]);
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
        assert_eq!(c.settings(), rung(0.5, 0.25, true, 1, PerPixel));
    }

    #[test]
    fn each_rung_costs_no_more_than_the_one_above() {
        for w in LADDER.windows(2) {
            let (a, b) = (&w[0], &w[1]);
            assert!(b.render_scale <= a.render_scale && b.fish_detail <= a.fish_detail);
            assert!(b.soft_shadows <= a.soft_shadows && b.school_every >= a.school_every);
            assert!(b.coarse_grids >= a.coarse_grids);
            assert!(b.water_normals.pixel_waves() <= a.water_normals.pixel_waves());
            assert!(b != a);
        }
        assert_eq!(
            LADDER[0],
            rung(1.0, 1.0, true, 1, PerPixel),
            "the top is full quality"
        );
    }
}
