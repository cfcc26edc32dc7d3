//! Shared look of the plot widgets: one colour per method everywhere (Okabe–Ito palette,
//! readable by colour-blind students and on a washed-out projector), large text, key bindings.

use egui::Color32;

/// Labels and checkboxes of the exact solution: a grey readable on light and dark slides.
/// Exact curves themselves are drawn in [`ink`], the theme's strongest text colour.
pub const EXACT: Color32 = Color32::from_gray(140);
pub const EULER: Color32 = Color32::from_rgb(213, 94, 0);
pub const MIDPOINT: Color32 = Color32::from_rgb(0, 114, 178);
pub const RK4: Color32 = Color32::from_rgb(0, 158, 115);
pub const HEUN: Color32 = Color32::from_rgb(204, 121, 167);
pub const RK4_TYPO: Color32 = Color32::from_rgb(230, 159, 0);
pub const DOPRI: Color32 = Color32::from_rgb(86, 180, 233);
pub const FIELD: Color32 = Color32::from_rgb(150, 150, 160);
pub const DIVERGED: Color32 = Color32::from_rgb(200, 0, 0);
/// Symplectic Euler (rigid body only): a violet, distinct from the palette's method colours
/// and readable on light and dark slides.
pub const SYMPLECTIC_EULER: Color32 = Color32::from_rgb(150, 110, 220);

/// Colours of deck tableaux other than the notes' RK4 typo (which always gets [`RK4_TYPO`]),
/// in order.
pub const EXTRA_COLORS: [Color32; 3] = [HEUN, DOPRI, SYMPLECTIC_EULER];

/// The colour of a built-in method by its key (`euler`, `midpoint`, `heun`, `rk4`, `exact`).
pub fn method_color(key: &str) -> Color32 {
    match key {
        "euler" => EULER,
        "midpoint" => MIDPOINT,
        "heun" => HEUN,
        "rk4" => RK4,
        "rk4-typo" => RK4_TYPO,
        _ => EXACT,
    }
}

/// The colour of a rigid-body integrator: the same as its tableau's everywhere else.
pub fn integrator_color(m: crate::rigid::Integrator) -> Color32 {
    use crate::rigid::Integrator;
    match m {
        Integrator::Euler => EULER,
        Integrator::Midpoint => MIDPOINT,
        Integrator::Rk4 => RK4,
        Integrator::SymplecticEuler => SYMPLECTIC_EULER,
    }
}

/// Line width of solution paths, in points.
pub const PATH_WIDTH: f32 = 3.0;

/// The theme's strongest text colour: exact solutions, start points, markers.
pub fn ink(ui: &egui::Ui) -> Color32 {
    ui.visuals().strong_text_color()
}

/// Makes text in `ui` at least large enough for the back row (applies to this ui and its
/// children). Never shrinks: the slide renderer scales text with the canvas (large on a 4K
/// projector), and that must win.
pub fn projector_text(ui: &mut egui::Ui) {
    use egui::TextStyle;
    // Inside a slide the renderer has already sized text to the canvas (app::theme::CANVAS_STYLE
    // marks it), so a 4K projector and a laptop window show the same proportions: keep that.
    if crate::app::theme::is_canvas_style(ui.style()) {
        return;
    }
    let s = ui.style_mut();
    for (style, min) in [
        (TextStyle::Body, 20.0),
        (TextStyle::Button, 20.0),
        (TextStyle::Small, 16.0),
        (TextStyle::Monospace, 18.0),
    ] {
        if let Some(font) = s.text_styles.get_mut(&style) {
            font.size = font.size.max(min);
        }
    }
    s.spacing.slider_width = s.spacing.slider_width.max(220.0);
}

/// The widget keys, documented in docs/slides.md: `-`/`+` step size, `[`/`]` step through,
/// so they never clash with the app's slide navigation (arrows, space, page keys).
pub struct Keys {
    pub h_down: bool,
    pub h_up: bool,
    pub back: bool,
    pub forward: bool,
}

pub fn keys(ui: &egui::Ui) -> Keys {
    // The presenter typing an equation: `-`, `+`, `[`, `]` are text, not widget keys.
    if ui.ctx().text_edit_focused() {
        return Keys {
            h_down: false,
            h_up: false,
            back: false,
            forward: false,
        };
    }
    ui.input(|i| Keys {
        h_down: i.key_pressed(egui::Key::Minus),
        h_up: i.key_pressed(egui::Key::Plus) || i.key_pressed(egui::Key::Equals),
        back: i.key_pressed(egui::Key::OpenBracket),
        forward: i.key_pressed(egui::Key::CloseBracket),
    })
}

/// One key press scales h by this factor (four presses double it).
pub const H_KEY_FACTOR: f64 = 1.189_207_115_002_721; // 2^(1/4)

impl Keys {
    /// Applies `-`/`+` to a step size (a quarter octave each) and clamps it to `range`.
    pub fn step_h(&self, h: &mut f64, range: (f64, f64)) {
        if self.h_up {
            *h *= H_KEY_FACTOR;
        }
        if self.h_down {
            *h /= H_KEY_FACTOR;
        }
        *h = h.clamp(range.0, range.1);
    }
}

/// The logarithmic step-size slider of the path widgets.
pub fn h_slider(ui: &mut egui::Ui, h: &mut f64, range: (f64, f64)) {
    ui.add(
        egui::Slider::new(h, range.0..=range.1)
            .logarithmic(true)
            .text("h"),
    );
}

/// A readable number for labels: 3 significant digits, scientific outside 1e-3..1e4.
pub fn fmt_num(x: f64) -> String {
    if !x.is_finite() {
        return "∞".into();
    }
    let a = x.abs();
    if a != 0.0 && !(1e-3..1e4).contains(&a) {
        format!("{x:.2e}")
    } else {
        format!("{x:.3}")
    }
}

/// What keeps a widget from drawing all it should (its equation did not load, a tableau file
/// is missing), one line each.
pub fn problem_lines(load_error: Option<&str>, method_errors: &[String]) -> Vec<String> {
    load_error
        .map(str::to_owned)
        .into_iter()
        .chain(method_errors.iter().cloned())
        .collect()
}

/// Those lines in red above the plot: the slide still shows what could be drawn (the last good
/// equation, the methods that loaded).
pub fn problems_ui(ui: &mut egui::Ui, load_error: Option<&str>, method_errors: &[String]) {
    for line in problem_lines(load_error, method_errors) {
        ui.colored_label(DIVERGED, egui::RichText::new(line).small());
    }
}
