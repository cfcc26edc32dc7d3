//! The embedded Typst fonts, offered to egui as fallbacks: egui's default fonts lack glyphs the
//! slides use in plain labels (ẋ, ω, λ, √, ≈, ⁻¹, ▶ …). The same files that typeset the maths,
//! so labels and formulas agree and nothing depends on the system's fonts.

use typst::text::{FontInfo, FontWeight};

/// Family names (as the font files name themselves) installed as fallbacks, in order.
const FALLBACKS: [&str; 3] = [
    "DejaVu Sans Mono",
    "New Computer Modern Math",
    "Libertinus Serif",
];

/// Adds the fallback fonts to `ctx` (idempotent; call once at start-up, before drawing slides).
pub fn install_egui_fallback_fonts(ctx: &egui::Context) {
    for want in FALLBACKS {
        let found = typst_assets::fonts().find(|data| {
            FontInfo::new(data, 0).is_some_and(|i| {
                i.family == want
                    && i.variant.weight == FontWeight::REGULAR
                    && i.variant.style == typst::text::FontStyle::Normal
            })
        });
        let Some(data) = found else { continue };
        ctx.add_font(egui::epaint::text::FontInsert::new(
            &format!("lectern-{want}"),
            egui::FontData::from_static(data),
            vec![
                egui::epaint::text::InsertFontFamily {
                    family: egui::FontFamily::Proportional,
                    priority: egui::epaint::text::FontPriority::Lowest,
                },
                egui::epaint::text::InsertFontFamily {
                    family: egui::FontFamily::Monospace,
                    priority: egui::epaint::text::FontPriority::Lowest,
                },
            ],
        ));
    }
}
