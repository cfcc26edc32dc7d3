//! Where the windows go: given the monitors (rectangles in physical pixels, as winit reports
//! them), the audience window takes the projector full-screen and the presenter window the
//! laptop's screen. Pure: no winit or egui types, so the choice is unit-tested.

/// One monitor as the windowing system reports it.
#[derive(Debug, Clone, PartialEq)]
pub struct MonitorRect {
    /// Top-left corner in the virtual desktop, physical pixels.
    pub pos_px: [i32; 2],
    pub size_px: [u32; 2],
    /// Physical pixels per logical point.
    pub scale: f64,
    /// The system's primary monitor (on a laptop, its built-in screen).
    pub primary: bool,
    pub name: String,
}

impl MonitorRect {
    fn area(&self) -> u64 {
        u64::from(self.size_px[0]) * u64::from(self.size_px[1])
    }

    /// Top-left corner in logical points (what `ViewportBuilder::with_position` takes).
    pub fn pos_points(&self) -> [f32; 2] {
        let s = self.scale.max(0.1);
        [
            (f64::from(self.pos_px[0]) / s) as f32,
            (f64::from(self.pos_px[1]) / s) as f32,
        ]
    }

    /// Size in logical points.
    pub fn size_points(&self) -> [f32; 2] {
        let s = self.scale.max(0.1);
        [
            (f64::from(self.size_px[0]) / s) as f32,
            (f64::from(self.size_px[1]) / s) as f32,
        ]
    }
}

/// What the lecturer asked for on the command line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ScreenChoice {
    /// Two windows when a second monitor is present, else one (with `P` for the overlay).
    #[default]
    Auto,
    /// `--presenter`: the presenter window even on one monitor.
    Presenter,
    /// `--single-screen`: one window whatever is connected.
    Single,
}

/// The decision: which monitor (index into the list given) each window goes to.
#[derive(Debug, Clone, PartialEq)]
pub enum ScreenPlan {
    /// One window; the presenter view is the `P` overlay.
    Single,
    /// The audience window (the root one) and a presenter window. `audience` is the monitor
    /// the audience window goes full-screen on, `presenter` the one the presenter window
    /// fills; `None` where there is only one monitor (or none known): the windows are left
    /// where the system puts them.
    Dual {
        audience: Option<usize>,
        presenter: Option<usize>,
    },
}

impl ScreenPlan {
    pub fn has_presenter_window(&self) -> bool {
        matches!(self, Self::Dual { .. })
    }
}

/// Chooses where the windows go.
///
/// Mirrored outputs (same rectangle) count as one monitor. With two or more distinct
/// monitors, the presenter's is the primary one (the laptop), else the one at the desktop's
/// origin; the audience gets the largest of the others (the projector), ties broken by list
/// order so the choice is stable.
pub fn plan_screens(monitors: &[MonitorRect], choice: ScreenChoice) -> ScreenPlan {
    if choice == ScreenChoice::Single {
        return ScreenPlan::Single;
    }
    let distinct: Vec<usize> = (0..monitors.len())
        .filter(|&i| monitors[i].size_px[0] > 0 && monitors[i].size_px[1] > 0)
        .filter(|&i| {
            !monitors[..i]
                .iter()
                .any(|m| m.pos_px == monitors[i].pos_px && m.size_px == monitors[i].size_px)
        })
        .collect();
    if distinct.len() < 2 {
        return match choice {
            ScreenChoice::Presenter => ScreenPlan::Dual {
                audience: None,
                presenter: None,
            },
            _ => ScreenPlan::Single,
        };
    }
    let presenter = distinct
        .iter()
        .copied()
        .find(|&i| monitors[i].primary)
        .or_else(|| {
            distinct
                .iter()
                .copied()
                .min_by_key(|&i| (monitors[i].pos_px[1], monitors[i].pos_px[0]))
        })
        .unwrap_or(distinct[0]);
    let audience =
        distinct
            .iter()
            .copied()
            .filter(|&i| i != presenter)
            .fold(None::<usize>, |best, i| match best {
                Some(b) if monitors[b].area() >= monitors[i].area() => Some(b),
                _ => Some(i),
            });
    ScreenPlan::Dual {
        audience,
        presenter: Some(presenter),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mon(x: i32, y: i32, w: u32, h: u32, primary: bool) -> MonitorRect {
        MonitorRect {
            pos_px: [x, y],
            size_px: [w, h],
            scale: 1.0,
            primary,
            name: format!("{w}x{h}+{x}+{y}"),
        }
    }

    #[test]
    fn one_monitor_gives_one_window_unless_forced() {
        let one = [mon(0, 0, 1280, 800, true)];
        assert_eq!(plan_screens(&one, ScreenChoice::Auto), ScreenPlan::Single);
        assert_eq!(plan_screens(&[], ScreenChoice::Auto), ScreenPlan::Single);
        assert_eq!(
            plan_screens(&one, ScreenChoice::Presenter),
            ScreenPlan::Dual {
                audience: None,
                presenter: None
            }
        );
    }

    #[test]
    fn laptop_keeps_presenter_projector_gets_audience() {
        // Projector listed first, laptop primary to its right.
        let ms = [mon(0, 0, 1920, 1080, false), mon(1920, 0, 1280, 800, true)];
        assert_eq!(
            plan_screens(&ms, ScreenChoice::Auto),
            ScreenPlan::Dual {
                audience: Some(0),
                presenter: Some(1)
            }
        );
    }

    #[test]
    fn without_a_primary_the_origin_monitor_is_the_presenters() {
        let ms = [mon(1280, 0, 1920, 1080, false), mon(0, 0, 1280, 800, false)];
        assert_eq!(
            plan_screens(&ms, ScreenChoice::Auto),
            ScreenPlan::Dual {
                audience: Some(0),
                presenter: Some(1)
            }
        );
    }

    #[test]
    fn largest_other_monitor_is_the_audiences() {
        let ms = [
            mon(0, 0, 1280, 800, true),
            mon(1280, 0, 1024, 768, false),
            mon(2304, 0, 3840, 2160, false),
        ];
        assert_eq!(
            plan_screens(&ms, ScreenChoice::Auto),
            ScreenPlan::Dual {
                audience: Some(2),
                presenter: Some(0)
            }
        );
    }

    #[test]
    fn mirrored_outputs_count_as_one_screen() {
        let ms = [mon(0, 0, 1920, 1080, true), mon(0, 0, 1920, 1080, false)];
        assert_eq!(plan_screens(&ms, ScreenChoice::Auto), ScreenPlan::Single);
    }

    #[test]
    fn single_screen_flag_wins_over_two_monitors() {
        let ms = [mon(0, 0, 1280, 800, true), mon(1280, 0, 1920, 1080, false)];
        assert_eq!(plan_screens(&ms, ScreenChoice::Single), ScreenPlan::Single);
        assert!(plan_screens(&ms, ScreenChoice::Presenter).has_presenter_window());
    }

    #[test]
    fn points_divide_by_the_scale_factor() {
        let mut m = mon(2560, 0, 2560, 1600, false);
        m.scale = 2.0;
        assert_eq!(m.pos_points(), [1280.0, 0.0]);
        assert_eq!(m.size_points(), [1280.0, 800.0]);
    }
}
