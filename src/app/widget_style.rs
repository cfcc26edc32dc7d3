//! The egui style a slide's widgets are drawn in: the theme's palette and every size scaled
//! from canvas units.

use super::theme::{self, Look, size};
use crate::deck::Theme;

/// The style widgets see inside a slide: egui's dark or light visuals recoloured to the
/// palette, and every size scaled from canvas units, so a slider on a 4K projector is as large
/// (relative to the slide) as in a laptop window.
pub(crate) fn widget_style(base: &egui::Style, look: &Look, theme: Theme) -> egui::Style {
    use egui::{FontFamily, FontId, TextStyle};
    let mut style = base.clone();
    let p = look.palette;
    style.visuals = match theme {
        Theme::Dark => egui::Visuals::dark(),
        Theme::Light => egui::Visuals::light(),
    };
    style.visuals.extreme_bg_color = p.panel;
    style.visuals.panel_fill = p.background;
    style.visuals.window_fill = p.panel;
    style.visuals.widgets.noninteractive.fg_stroke.color = p.text;
    style.visuals.selection.bg_fill = p.accent.gamma_multiply(0.6);
    style.interaction.selectable_labels = false;
    // The canvas scale puts rects on fractional points by design; egui's debug-build marker for
    // that would otherwise show up in snapshots. (The field exists only in debug builds.)
    #[cfg(debug_assertions)]
    {
        style.debug.show_unaligned = false;
    }

    let text = |units: f32, family: FontFamily| FontId::new(look.scaled(units), family);
    // The slide's body face for every widget text, readouts included: one face with the body
    // text and the typeset maths beside it (Libertinus), not a sans for controls and a mono
    // for numbers. Nothing smaller than the widget size: the back row reads it all.
    let serif = FontFamily::Name(theme::SERIF.into());
    style.text_styles = [
        (TextStyle::Small, text(size::WIDGET_TEXT, serif.clone())),
        (TextStyle::Body, text(size::WIDGET_TEXT, serif.clone())),
        (TextStyle::Button, text(size::WIDGET_TEXT, serif.clone())),
        (
            TextStyle::Heading,
            text(size::WIDGET_TEXT * 1.4, serif.clone()),
        ),
        (TextStyle::Monospace, text(size::WIDGET_TEXT, serif.clone())),
    ]
    .into();
    style.text_styles.insert(
        TextStyle::Name(theme::CANVAS_STYLE.into()),
        text(size::WIDGET_TEXT, serif),
    );

    // egui's default spacing is made for 12.5-point body text; scale it with ours.
    let k = look.scaled(size::WIDGET_TEXT) / 12.5;
    let s = &mut style.spacing;
    s.item_spacing *= k;
    s.button_padding *= k;
    s.interact_size *= k;
    s.slider_width *= k;
    s.slider_rail_height *= k;
    s.icon_width *= k;
    s.icon_width_inner *= k;
    s.icon_spacing *= k;
    s.combo_width *= k;
    s.text_edit_width *= k;
    s.indent *= k;
    s.menu_width *= k;
    s.tooltip_width *= k;
    let thick = (0.6 * k).max(1.0);
    for w in [
        &mut style.visuals.widgets.noninteractive,
        &mut style.visuals.widgets.inactive,
        &mut style.visuals.widgets.hovered,
        &mut style.visuals.widgets.active,
        &mut style.visuals.widgets.open,
    ] {
        w.fg_stroke.width *= thick;
        w.bg_stroke.width *= thick;
    }
    style
}
