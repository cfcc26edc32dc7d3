//! Shared look of the plot widgets: one colour per method everywhere (Okabe–Ito palette,
//! readable by colour-blind students and on a washed-out projector), large text, key bindings.

use egui::Color32;

use super::colors;

/// Labels and checkboxes of the exact solution: a grey readable on light and dark slides.
/// Exact curves themselves are drawn in [`ink`], the theme's strongest text colour.
pub const EXACT: Color32 = Color32::from_gray(140);
// The methods' colours come from the deck's one colour map, [`colors`]; these names are kept
// for the widgets that draw one fixed method.
pub const EULER: Color32 = colors::VERMILLION.color;
pub const MIDPOINT: Color32 = colors::BLUE.color;
pub const RK4: Color32 = colors::BLUISH_GREEN.color;
pub const HEUN: Color32 = colors::WINE.color;
pub const RK4_TYPO: Color32 = colors::PINK.color;
/// Dormand–Prince's fifth-order formula at a fixed step ("RK5").
pub const RK5: Color32 = colors::ORCHID.color;
pub const FIELD: Color32 = Color32::from_rgb(150, 150, 160);
pub const DIVERGED: Color32 = Color32::from_rgb(200, 0, 0);
pub const SYMPLECTIC_EULER: Color32 = colors::RASPBERRY.color;

/// Colours of deck tableaux other than the notes' RK4 typo (which always gets [`RK4_TYPO`]),
/// in order.
pub const EXTRA_COLORS: [Color32; 3] = [
    colors::TABLEAU_HUES[0].color,
    colors::TABLEAU_HUES[1].color,
    colors::TABLEAU_HUES[2].color,
];

/// The colour of a built-in method, the same in every widget ([`colors::method_hue`]).
pub fn method_color(m: crate::ode::Method) -> Color32 {
    colors::method_hue(m).color
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

// Sizes in slide units: points on the 1920-wide canvas (see `app::theme`), turned into screen
// points by [`unit`], so a thumbnail is the slide scaled down, markers and lines included.
/// Line width of solution paths.
pub const PATH_WIDTH: f32 = 3.0;
/// The width of path `i` of `n` drawn in order: the first widest, the last [`PATH_WIDTH`], so
/// two methods that agree (midpoint under RK4) both show, the earlier as a rim around the later.
pub fn stacked_width(i: usize, n: usize) -> f32 {
    PATH_WIDTH * (1.0 + 0.4 * n.saturating_sub(i + 1) as f32)
}

/// Exact solutions and other reference curves.
pub const REFERENCE_WIDTH: f32 = 2.0;
/// A computed point on a path (a step's end).
pub const MARKER_RADIUS: f32 = 5.0;
/// A point the slide is about (the start, the step's end, a λ marker).
pub const KEY_MARKER_RADIUS: f32 = 7.0;

/// Screen points per slide unit where `ui` draws: the slide's scale inside a slide canvas
/// (read back from the canvas text style that `app::widget_style` sizes), 1 elsewhere.
pub fn unit(ui: &egui::Ui) -> f32 {
    unit_of(ui.style())
}

/// [`unit`] of a style.
pub fn unit_of(style: &egui::Style) -> f32 {
    style
        .text_styles
        .get(&egui::TextStyle::Name(
            crate::app::theme::CANVAS_STYLE.into(),
        ))
        .map_or(1.0, |f| f.size / crate::app::theme::size::WIDGET_TEXT)
}

/// The plot every widget draws in: sizes in slide units (grid and tick-label spacing, so a
/// thumbnail shows the same ticks as the slide), tick labels at full strength in the theme's
/// text colour (egui_plot fades them towards the background), no hover crosshair (it drew
/// unlabelled grid lines), no pan or zoom (a slide shows the view its author chose). The x
/// axis is named below it; the y axis's name goes above the plot, upright ([`y_name_ui`]).
pub fn plot<'a>(ui: &egui::Ui, id: impl egui::AsIdSalt, x_name: &str) -> egui_plot::Plot<'a> {
    use egui_plot::AxisHints;
    let u = unit(ui);
    let ticks = ui.visuals().text_color();
    let x_axis = x_axis(ui, x_name, 80.0);
    let y_axis = AxisHints::new_y()
        .tick_label_color(ticks)
        .label_spacing(egui::Rangef::new(40.0 * u, 41.0 * u))
        .min_thickness(14.0 * u);
    egui_plot::Plot::new(id)
        .allow_drag(false)
        .allow_zoom(false)
        .allow_scroll(false)
        .allow_boxed_zoom(false)
        .allow_double_click_reset(false)
        .show_x(false)
        .show_y(false)
        .show_crosshair(false)
        .grid_spacing(egui::Rangef::new(8.0 * u, 300.0 * u))
        // egui_plot draws grid lines one point wide: below one point per slide unit, fade them
        // as a thinner line would cover less (a thumbnail's grid as light as the slide's)
        .grid_color(thin(ui.visuals().text_color(), u))
        .custom_x_axes(vec![x_axis])
        .custom_y_axes(vec![y_axis])
}

/// The x axis [`plot`] draws, named `x_name`, its tick labels at least `spacing` slide units
/// apart (80 by default; a narrow plot, such as an equal-aspect complex plane, takes 40).
pub fn x_axis(ui: &egui::Ui, x_name: &str, spacing: f32) -> egui_plot::AxisHints<'static> {
    let u = unit(ui);
    let x_axis = egui_plot::AxisHints::new_x()
        .tick_label_color(ui.visuals().text_color())
        .label_spacing(egui::Rangef::new(spacing * u, (spacing + 1.0) * u))
        .min_thickness(14.0 * u);
    if x_name.is_empty() {
        x_axis
    } else {
        x_axis.label(x_name.to_owned())
    }
}

/// `color` for a line egui_plot draws one point wide whatever we ask (grid lines, slope
/// marks), faded where one slide unit is less than a point so it covers what it would at
/// full size.
pub fn thin(color: Color32, unit: f32) -> Color32 {
    color.gamma_multiply(unit.clamp(0.0, 1.0))
}

/// How far (in data units, x and y) to widen a plot's view of size `span` so a key marker on
/// its edge is drawn whole: the marker's radius plus a little, at the plot's size in `transform`.
pub fn marker_pad(transform: &egui_plot::PlotTransform, span: (f64, f64), u: f32) -> (f64, f64) {
    let frame = transform.frame();
    let r = f64::from((KEY_MARKER_RADIUS + 3.0) * u);
    let w = f64::from(frame.width()).max(1.0);
    let h = f64::from(frame.height()).max(1.0);
    (span.0.abs() * r / w, span.1.abs() * r / h)
}

/// The y axis's name, upright, above the plot's left edge (a rotated "v" read as ">").
pub fn y_name_ui(ui: &mut egui::Ui, name: &str) {
    if !name.is_empty() {
        ui.label(egui::RichText::new(name).italics());
        // the top tick label is centred on the frame's top edge: keep clear of it
        ui.add_space(0.5 * ui.text_style_height(&egui::TextStyle::Body));
    }
}

/// How a plot maps data to the screen ([`crate::deck::widgets::Aspect`]).
pub fn with_aspect<'a>(
    plot: egui_plot::Plot<'a>,
    aspect: crate::deck::widgets::Aspect,
) -> egui_plot::Plot<'a> {
    match aspect {
        crate::deck::widgets::Aspect::Equal => plot.data_aspect(1.0),
        crate::deck::widgets::Aspect::Free => plot,
    }
}

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

/// The values `-`/`+` step h through: 1, 2, 5 × 10ᵏ, so every h a key gives reads round on
/// the slide (0.5, 1, 2), never 0.7071.
pub fn h_ladder_next(h: f64, up: bool) -> f64 {
    // the rung at or just below h (a hair of tolerance so 0.5 counts as on the ladder)
    let decade = 10f64.powf((h * (1.0 + 1e-9)).log10().floor());
    let rungs = [1.0, 2.0, 5.0, 10.0];
    let on = |r: f64| (h / (r * decade) - 1.0).abs() < 1e-6;
    if up {
        rungs
            .iter()
            .map(|r| r * decade)
            .find(|&v| v > h && !on(v / decade))
            .unwrap_or(10.0 * decade)
    } else {
        rungs
            .iter()
            .rev()
            .map(|r| r * decade)
            .find(|&v| v < h && !on(v / decade))
            .unwrap_or(0.5 * decade)
    }
}

impl Keys {
    /// Applies `-`/`+` to a step size (the next value of [`h_ladder_next`]) and clamps it to
    /// `range`.
    pub fn step_h(&self, h: &mut f64, range: (f64, f64)) {
        if self.h_up {
            *h = h_ladder_next(*h, true);
        }
        if self.h_down {
            *h = h_ladder_next(*h, false);
        }
        *h = h.clamp(range.0, range.1);
    }
}

/// The logarithmic step-size slider of the path widgets.
pub fn h_slider(ui: &mut egui::Ui, h: &mut f64, range: (f64, f64)) {
    slider(ui, h, range.0..=range.1, "h", true);
}

/// A text style only slides drawn without controls define (`controls: Presenter`, where the
/// presenter view has them, and the printed handout): widgets then show their values, not
/// their sliders, checkboxes and buttons.
pub const NO_CONTROLS_STYLE: &str = "lectern-no-controls";

/// Whether widgets in `ui` draw their controls (sliders, checkboxes, buttons). With the
/// deck's `controls: Presenter` the audience sees the plot and the values only (and so does
/// the printed handout).
pub fn controls_shown(ui: &egui::Ui) -> bool {
    !ui.style()
        .text_styles
        .contains_key(&egui::TextStyle::Name(NO_CONTROLS_STYLE.into()))
}

/// A button that is on the slide only with its controls; whether it was clicked.
pub fn button(ui: &mut egui::Ui, text: &str) -> bool {
    controls_shown(ui) && super::controls::control(ui, |ui| ui.button(text)).clicked()
}

/// One of a set of choices (a selectable label), or where controls are hidden, its text when
/// it is the chosen one and nothing otherwise; whether it was clicked.
pub fn choice(ui: &mut egui::Ui, selected: bool, text: impl Into<egui::WidgetText>) -> bool {
    if controls_shown(ui) {
        super::controls::control(ui, |ui| ui.selectable_label(selected, text)).clicked()
    } else {
        if selected {
            ui.label(text);
        }
        false
    }
}

/// A slider labelled `label` (a key hint after two spaces, `"stage  [ ]"`, is dropped from
/// the value), or, where controls are the presenter's, the value as text: `h = 0.500`.
pub fn slider<N: egui::emath::Numeric>(
    ui: &mut egui::Ui,
    value: &mut N,
    range: std::ops::RangeInclusive<N>,
    label: &str,
    logarithmic: bool,
) {
    if controls_shown(ui) {
        super::controls::control(ui, |ui| {
            ui.add(
                egui::Slider::new(value, range)
                    .logarithmic(logarithmic)
                    .text(label),
            )
        });
    } else {
        let name = label.split("  ").next().unwrap_or(label);
        let v = value.to_f64();
        let text = if N::INTEGRAL {
            format!("{name} = {v}")
        } else {
            format!("{name} = {}", fmt_num(v))
        };
        ui.label(text);
    }
}

/// A checkbox, or where controls are the presenter's, its label when it is on (a legend
/// entry) and nothing when it is off.
pub fn toggle(ui: &mut egui::Ui, on: &mut bool, text: egui::RichText) {
    if controls_shown(ui) {
        super::controls::control(ui, |ui| ui.checkbox(on, text));
    } else if *on {
        ui.label(text);
    }
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

/// A short number for maths on a slide: up to 3 decimals without trailing zeros, a real minus
/// sign (−5, 0.557, 2.5).
pub fn fmt_signed(x: f64) -> String {
    if !x.is_finite() {
        return "∞".into();
    }
    let s = format!("{:.3}", x.abs());
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if x < 0.0 && s != "0" {
        format!("−{s}")
    } else {
        s.to_string()
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
        ui.colored_label(text_color(ui, DIVERGED), egui::RichText::new(line).small());
    }
}

/// WCAG 2 relative luminance of an sRGB colour (0 black … 1 white).
pub fn relative_luminance(c: Color32) -> f32 {
    let lin = |v: u8| {
        let s = f32::from(v) / 255.0;
        if s <= 0.04045 {
            s / 12.92
        } else {
            ((s + 0.055) / 1.055).powf(2.4)
        }
    };
    0.2126 * lin(c.r()) + 0.7152 * lin(c.g()) + 0.0722 * lin(c.b())
}

/// WCAG 2 contrast ratio of two opaque colours, 1 … 21.
pub fn contrast_ratio(a: Color32, b: Color32) -> f32 {
    let (la, lb) = (relative_luminance(a), relative_luminance(b));
    (la.max(lb) + 0.05) / (la.min(lb) + 0.05)
}

/// The contrast WCAG asks of text (AA, normal size); control labels are held to it.
pub const MIN_TEXT_CONTRAST: f32 = 4.5;

/// `color`, lightened on a dark `background` or darkened on a light one just enough to reach
/// [`MIN_TEXT_CONTRAST`]: a label keeps its method's hue (the legend still matches the line)
/// and stays readable on both themes. Colours that already pass are returned unchanged.
pub fn readable_on(color: Color32, background: Color32) -> Color32 {
    if contrast_ratio(color, background) >= MIN_TEXT_CONTRAST {
        return color;
    }
    let toward = if relative_luminance(background) < 0.18 {
        Color32::WHITE
    } else {
        Color32::BLACK
    };
    let mix = |t: f32| {
        let m = |a: u8, b: u8| (f32::from(a) + (f32::from(b) - f32::from(a)) * t).round() as u8;
        Color32::from_rgb(
            m(color.r(), toward.r()),
            m(color.g(), toward.g()),
            m(color.b(), toward.b()),
        )
    };
    // the ratio grows monotonically with t: bisect for the smallest mix that passes
    let (mut lo, mut hi) = (0.0_f32, 1.0_f32);
    for _ in 0..16 {
        let mid = 0.5 * (lo + hi);
        if contrast_ratio(mix(mid), background) >= MIN_TEXT_CONTRAST {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    mix(hi)
}

/// Text in `color` (a method's colour) on a slide — a control's label, a legend, a readout,
/// a label inside a plot — readable on both surfaces text sits on there: the slide's
/// background and the plots' (egui's `extreme_bg_color`).
pub fn text_color(ui: &egui::Ui, color: Color32) -> Color32 {
    text_color_in(ui.visuals(), color)
}

/// [`text_color`] where the `Ui` is borrowed (inside a plot's closure).
pub fn text_color_in(visuals: &egui::Visuals, color: Color32) -> Color32 {
    readable_on(
        readable_on(color, visuals.panel_fill),
        visuals.extreme_bg_color,
    )
}

/// As [`text_color`], for a selected label: on the selection fill blended over the background.
pub fn selected_label_color(ui: &egui::Ui, color: Color32) -> Color32 {
    let v = ui.visuals();
    readable_on(color, over(v.selection.bg_fill, v.panel_fill))
}

/// `top` (premultiplied, possibly translucent) composited over the opaque `bottom`.
fn over(top: Color32, bottom: Color32) -> Color32 {
    let a = f32::from(top.a()) / 255.0;
    let c = |t: u8, b: u8| (f32::from(t) + f32::from(b) * (1.0 - a)).round().min(255.0) as u8;
    Color32::from_rgb(
        c(top.r(), bottom.r()),
        c(top.g(), bottom.g()),
        c(top.b(), bottom.b()),
    )
}

#[cfg(test)]
mod contrast_tests {
    use super::*;

    #[test]
    fn wcag_ratios_of_known_pairs() {
        assert!((contrast_ratio(Color32::WHITE, Color32::BLACK) - 21.0).abs() < 1e-3);
        assert!((contrast_ratio(Color32::GRAY, Color32::GRAY) - 1.0).abs() < 1e-6);
        // #767676 on white is the classic just-passing grey, 4.54:1
        let g = Color32::from_gray(0x76);
        assert!((contrast_ratio(g, Color32::WHITE) - 4.54).abs() < 0.01);
    }

    #[test]
    fn every_method_colour_is_made_readable_on_both_slide_backgrounds() {
        let backgrounds = [
            Color32::from_rgb(0x16, 0x19, 0x21),
            Color32::from_rgb(0xfb, 0xf9, 0xf4),
        ];
        let colours = [
            EXACT,
            EULER,
            MIDPOINT,
            RK4,
            HEUN,
            RK4_TYPO,
            RK5,
            SYMPLECTIC_EULER,
        ]
        .into_iter()
        .chain(
            colors::all_roles()
                .into_iter()
                .map(|r| colors::hue_of(r).color),
        )
        .collect::<Vec<_>>();
        let mut changed = 0;
        for bg in backgrounds {
            for &c in &colours {
                let r = readable_on(c, bg);
                assert!(
                    contrast_ratio(r, bg) >= MIN_TEXT_CONTRAST,
                    "{c:?} on {bg:?}"
                );
                // no more change than needed: a colour that passes is kept
                if contrast_ratio(c, bg) >= MIN_TEXT_CONTRAST {
                    assert_eq!(r, c);
                } else {
                    changed += 1;
                    // and the hue survives: the dominant channel stays dominant
                    let dominant = |c: Color32| {
                        let v = [c.r(), c.g(), c.b()];
                        (0..3).max_by_key(|&i| v[i]).unwrap()
                    };
                    if c.r().max(c.g()).max(c.b()) - c.r().min(c.g()).min(c.b()) > 60 {
                        assert_eq!(dominant(r), dominant(c), "{c:?} → {r:?}");
                    }
                }
            }
        }
        // Midpoint's blue on the dark slide and the warm colours on the light one do not pass
        assert!(changed >= 3, "{changed}");
    }
}

#[cfg(test)]
mod ladder_tests {
    use super::*;

    #[test]
    fn h_keys_walk_a_ladder_of_round_values() {
        let mut h = 0.3;
        let mut up = Vec::new();
        for _ in 0..6 {
            h = h_ladder_next(h, true);
            up.push(h);
        }
        let want = [0.5, 1.0, 2.0, 5.0, 10.0, 20.0];
        for (g, w) in up.iter().zip(want) {
            assert!((g - w).abs() < 1e-12 * w, "{up:?}");
        }
        let mut down = Vec::new();
        let mut h = 1.0;
        for _ in 0..4 {
            h = h_ladder_next(h, false);
            down.push(h);
        }
        let want = [0.5, 0.2, 0.1, 0.05];
        for (g, w) in down.iter().zip(want) {
            assert!((g - w).abs() < 1e-12 * w, "{down:?}");
        }
        // off the ladder: to the next rung either way
        assert!((h_ladder_next(0.7071, true) - 1.0).abs() < 1e-12);
        assert!((h_ladder_next(0.7071, false) - 0.5).abs() < 1e-12);
        assert!((h_ladder_next(1.5, false) - 1.0).abs() < 1e-12);
    }
}
