//! Typing the equation live, on the presenter's side only: for each ODE widget of the current
//! slide, one text field per right-hand side (and per component of the exact solution, if the
//! problem has one). What is typed is a draft: the room keeps seeing the last equation shown
//! until Enter (so a half-typed `-2` never reaches the projector), and Esc puts the fields back.
//! While drafts compile, a preview copy of the widget under the fields follows every keystroke;
//! while they do not, the error shows under its field with a caret at its column. Ctrl+S writes
//! the shown equation back (see [`super::tweaks::write_back`]).

use egui::{Color32, RichText};

use super::slide_state::SlideState;
use crate::widgets::{ExprSlot, LiveOde};

/// Error text on the presenter's dark panel.
const ERROR: Color32 = Color32::from_rgb(0xff, 0x9c, 0x8f);

/// The editors of every ODE widget on the slide (nothing if it has none).
pub fn ode_editor_ui(ui: &mut egui::Ui, state: &mut SlideState) {
    let paths: Vec<(Vec<usize>, &'static str)> =
        (state.odes().into_iter()).map(|(p, k, _)| (p, k)).collect();
    for (path, kind) in paths {
        ui.push_id(("ode-editor", &path), |ui| {
            if let Some(ode) = state.widget_at(&path).and_then(|w| w.ode()) {
                equation_ui(ui, kind, ode);
            }
            if let Some(preview) = state.preview_widget(&path) {
                preview_ui(ui, preview);
            }
        });
        ui.add_space(6.0);
    }
}

/// The least height of the presenter's preview of a typed equation, in points; it takes the
/// rest of the visible control area when that is more.
const PREVIEW_MIN_HEIGHT: f32 = 180.0;

/// The preview copy of a widget, drawing the drafts' equation (the room does not see it): its
/// plot and values only (the sliders are the presenter's, above), as tall as the control area
/// leaves, so a typed equation's plot is readable at 1280×720.
fn preview_ui(ui: &mut egui::Ui, widget: &mut dyn crate::widgets::SlideWidget) {
    ui.label(RichText::new("preview (Enter shows it to the room, Esc reverts):").italics());
    let width = ui.available_width();
    let height = (ui.clip_rect().bottom() - ui.cursor().top()).max(PREVIEW_MIN_HEIGHT);
    let shown = ui.allocate_ui(egui::vec2(width, height), |ui| {
        ui.set_max_height(height);
        ui.style_mut().text_styles.insert(
            egui::TextStyle::Name(crate::widgets::style::NO_CONTROLS_STYLE.into()),
            egui::FontId::proportional(1.0),
        );
        ui.push_id("preview", |ui| widget.ui(ui));
    });
    // named, so its size can be asked for (screen readers, the UI tests)
    (shown.response)
        .widget_info(|| egui::WidgetInfo::labeled(egui::Role::Group, true, "equation preview"));
}

/// The text fields of one widget's equation.
pub fn equation_ui(ui: &mut egui::Ui, kind: &str, ode: &mut LiveOde) {
    let Some(def) = ode.def().cloned() else {
        if let Some(e) = ode.load_error() {
            ui.label(RichText::new(format!("{kind}: {e}")).color(ERROR));
        }
        return;
    };
    let name = if def.name.is_empty() {
        kind.to_string()
    } else {
        format!("{kind}: {}", def.name)
    };
    ui.label(RichText::new(format!("{name} (type, then Enter to show it; Esc reverts)")).strong());
    if let Some(e) = ode.load_error() {
        ui.label(RichText::new(e).color(ERROR));
    }
    if let Some(note) = ode.dropped_exact() {
        ui.label(RichText::new(note).italics());
    }
    let (rhs, exact) = ode.fields();
    let rows: Vec<(ExprSlot, String, String)> = rhs
        .iter()
        .enumerate()
        .map(|(k, f)| {
            let var = def.vars.get(k).cloned().unwrap_or_default();
            (ExprSlot::Rhs(k), format!("d{var}/dt ="), f.text.clone())
        })
        .chain(exact.iter().enumerate().map(|(k, f)| {
            let var = def.vars.get(k).cloned().unwrap_or_default();
            (
                ExprSlot::Exact(k),
                format!("exact {var}(t) ="),
                f.text.clone(),
            )
        }))
        .collect();
    let mono = egui::TextStyle::Monospace;
    for (slot, label, mut text) in rows {
        let id = ui.scope_id().with(("field", format!("{slot:?}")));
        ui.horizontal(|ui| {
            let name = ui.label(RichText::new(label).family(egui::FontFamily::Monospace));
            let edit = egui::TextEdit::singleline(&mut text)
                .id(id)
                .font(mono.clone())
                .char_limit(crate::ode::problem::MAX_EXPR_CHARS)
                // the field keeps Esc (egui would drop the focus before the field saw it):
                // here Esc means "revert", then the field lets go
                .event_filter(egui::EventFilter {
                    horizontal_arrows: true,
                    vertical_arrows: true,
                    escape: true,
                    ..Default::default()
                })
                .desired_width(ui.available_width());
            // named by its label, for screen readers (and the UI tests' queries)
            let field = ui.add(edit).labelled_by(name.id);
            if field.changed() {
                ode.set_draft(slot, &text);
            }
            // a single-line field gives up the keyboard on Enter
            if field.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter)) {
                ode.commit();
            }
            if field.has_focus() && ui.input(|i| i.key_pressed(egui::Key::Escape)) {
                ode.revert();
                field.surrender_focus();
            }
        });
        // the error of the text as it is now (set_expr may just have changed it)
        let now = match slot {
            ExprSlot::Rhs(k) => ode.fields().0.get(k).and_then(|f| f.error.clone()),
            ExprSlot::Exact(k) => ode.fields().1.get(k).and_then(|f| f.error.clone()),
        };
        if let Some((msg, col)) = now {
            error_ui(ui, &text, &msg, col);
        }
    }
    // (a draft that compiles says so above its preview instead)
    if ode.has_draft() && ode.draft_problem().is_none() {
        ui.label(RichText::new("not shown to the room yet: Enter shows it, Esc reverts").italics());
    }
}

/// Under the field: the text again with a caret under the faulty column, and the message. The
/// plot still draws the last good equation.
fn error_ui(ui: &mut egui::Ui, text: &str, msg: &str, col: usize) {
    let shown: String = text.chars().take(120).collect();
    let caret = if col > 0 && col <= 121 {
        format!("\n{}^", " ".repeat(col - 1))
    } else {
        String::new()
    };
    ui.label(
        RichText::new(format!(
            "{shown}{caret}\ncolumn {col}: {msg} (the room keeps the equation shown)"
        ))
        // a family, not a text style: the presenter panel overrides text styles, and the caret
        // must line up under the character
        .family(egui::FontFamily::Monospace)
        .color(ERROR),
    );
}
