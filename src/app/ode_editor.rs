//! Typing the equation live, on the presenter's side only: for each ODE widget of the current
//! slide, one text field per right-hand side (and per component of the exact solution, if the
//! problem has one). A keystroke that compiles replaces the equation for the next frame; one
//! that does not keeps the last good equation and shows the error under the field, with a caret
//! at its column. Ctrl+S writes the typed text back (see [`super::tweaks::write_back`]).

use egui::{Color32, RichText};

use super::slide_state::SlideState;
use crate::widgets::{ExprSlot, LiveOde};

/// Error text on the presenter's dark panel.
const ERROR: Color32 = Color32::from_rgb(0xff, 0x9c, 0x8f);

/// The editors of every ODE widget on the slide (nothing if it has none).
pub fn ode_editor_ui(ui: &mut egui::Ui, state: &mut SlideState) {
    for (path, kind, ode) in state.odes() {
        ui.push_id(("ode-editor", &path), |ui| equation_ui(ui, kind, ode));
        ui.add_space(6.0);
    }
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
    ui.label(RichText::new(format!("{name} (type to change the equation)")).strong());
    if let Some(e) = ode.load_error() {
        ui.label(RichText::new(e).color(ERROR));
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
                .desired_width(ui.available_width());
            // named by its label, for screen readers (and the UI tests' queries)
            if ui.add(edit).labelled_by(name.id).changed() {
                ode.set_expr(slot, &text);
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
            "{shown}{caret}\ncolumn {col}: {msg} (the last good equation stays)"
        ))
        // a family, not a text style: the presenter panel overrides text styles, and the caret
        // must line up under the character
        .family(egui::FontFamily::Monospace)
        .color(ERROR),
    );
}
