//! The key to a debug view, drawn over its panel (on a slide and in scene mode): what its
//! colours mean, so the map reads without the lecturer's words.

use crate::render::DebugView;

/// What each colour of a debug view stands for; None for the final image. ASCII arrows and
/// signs: the slide font (Ubuntu Light) has no U+2192 or U+2212.
pub fn legend_text(view: DebugView) -> Option<&'static str> {
    match view {
        DebugView::None => None,
        DebugView::ShadowMap => Some(
            "depth from the sun, stretched to the casters' range: near dark -> far light | blue: nothing casts",
        ),
        DebugView::Normals => Some("world-space normal as colour: x->R y->G z->B (up is green)"),
        DebugView::EnvCube => Some(
            "sky cube: -x +z +x -z across, +y above, -y below | strip: mips, rougher to the right",
        ),
        DebugView::CausticsMap => Some(
            "light the waves focus on the floor, seen from above: grey = flat water, white = focused",
        ),
    }
}

/// The legend along the bottom of `rect`, light text on a dark band (legible over any map).
pub fn legend_ui(ui: &egui::Ui, rect: egui::Rect, view: DebugView) {
    let Some(text) = legend_text(view) else {
        return;
    };
    let painter = ui.painter_at(rect);
    let size_pt = (rect.height() / 22.0).clamp(10.0, 18.0);
    let galley = painter.layout(
        text.to_owned(),
        egui::FontId::proportional(size_pt),
        egui::Color32::WHITE,
        rect.width() - 16.0,
    );
    let band = egui::Rect::from_min_max(
        egui::pos2(rect.left(), rect.bottom() - galley.size().y - 8.0),
        rect.right_bottom(),
    );
    painter.rect_filled(band, 0.0, egui::Color32::from_black_alpha(170));
    painter.galley(
        band.min + egui::vec2(8.0, 4.0),
        galley,
        egui::Color32::WHITE,
    );
}
