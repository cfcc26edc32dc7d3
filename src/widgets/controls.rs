//! Where a slide's widgets drew their controls (sliders, checkboxes, buttons, choices): each
//! goes through [`control`], which notes its rect in the slide's list. The slide renderer starts
//! the list afresh for every slide it draws ([`begin_controls`]); `lectern export --handout`
//! fails a picture whose list is not empty, and the tests compare the list with egui's
//! accessibility tree. Whether controls are drawn at all is [`super::style::controls_shown`].

/// Where the slide drawn last put its controls, in points: every slider, checkbox, button and
/// choice a widget draws goes through [`control`], which notes its rect here. Cleared when a
/// slide starts drawing ([`begin_controls`]); `lectern export --handout` and the tests read it
/// (empty when the slide was drawn without controls).
#[derive(Debug, Clone, Default)]
pub struct ControlRects(pub Vec<egui::Rect>);

fn control_rects_id() -> egui::Id {
    egui::Id::unique("lectern-control-rects")
}

/// Starts a slide's list of control rects afresh.
pub fn begin_controls(ctx: &egui::Context) {
    ctx.data_mut(|d| d.insert_temp(control_rects_id(), ControlRects::default()));
}

/// The control rects of the slide drawn last (see [`ControlRects`]).
pub fn control_rects(ctx: &egui::Context) -> Vec<egui::Rect> {
    ctx.data(|d| d.get_temp::<ControlRects>(control_rects_id()))
        .unwrap_or_default()
        .0
}

/// Draws a control with `add` and notes where it went; the one way widgets draw controls on a
/// slide. Call it only where [`super::style::controls_shown`].
pub fn control(
    ui: &mut egui::Ui,
    add: impl FnOnce(&mut egui::Ui) -> egui::Response,
) -> egui::Response {
    let response = add(ui);
    let rect = response.rect;
    ui.ctx().data_mut(|d| {
        d.get_temp_mut_or_default::<ControlRects>(control_rects_id())
            .0
            .push(rect)
    });
    response
}
