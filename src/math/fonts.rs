//! The embedded Typst fonts, offered to egui as fallbacks: egui's default fonts lack glyphs the
//! slides use in plain labels (ẋ, ω, λ, √, ≈, ⁻¹, ▶ …). The same files that typeset the maths,
//! so labels and formulas agree and nothing depends on the system's fonts.

use egui::{FontDefinitions, FontFamily};
use typst::text::{FontInfo, FontWeight};

/// Family names (as the font files name themselves) installed as fallbacks, in order.
const FALLBACKS: [&str; 3] = [
    "DejaVu Sans Mono",
    "New Computer Modern Math",
    "Libertinus Serif",
];

/// The fallback fonts as (egui font name, bytes), found by family among the embedded fonts.
fn fallback_fonts() -> Vec<(String, &'static [u8])> {
    FALLBACKS
        .iter()
        .filter_map(|want| {
            let data = typst_assets::fonts().find(|data| {
                FontInfo::new(data, 0).is_some_and(|i| {
                    i.family == *want
                        && i.variant.weight == FontWeight::REGULAR
                        && i.variant.style == typst::text::FontStyle::Normal
                })
            })?;
            Some((format!("lectern-{want}"), data))
        })
        .collect()
}

/// Appends the fallback fonts to the end of every family in `defs` (proportional, monospace
/// and every named family), for apps that build their own [`FontDefinitions`]. Idempotent.
pub fn add_fallback_fonts(defs: &mut FontDefinitions) {
    for (name, data) in fallback_fonts() {
        defs.font_data
            .entry(name.clone())
            .or_insert_with(|| egui::FontData::from_static(data).into());
        for chain in defs.families.values_mut() {
            if !chain.contains(&name) {
                chain.push(name.clone());
            }
        }
    }
}

/// Adds the fallback fonts to `ctx` at the lowest priority of the proportional and monospace
/// families (idempotent; call once at start-up, before drawing slides). Apps that replace the
/// font definitions should call [`add_fallback_fonts`] on theirs instead.
pub fn install_egui_fallback_fonts(ctx: &egui::Context) {
    for (name, data) in fallback_fonts() {
        ctx.add_font(egui::epaint::text::FontInsert::new(
            &name,
            egui::FontData::from_static(data),
            [FontFamily::Proportional, FontFamily::Monospace]
                .into_iter()
                .map(|family| egui::epaint::text::InsertFontFamily {
                    family,
                    priority: egui::epaint::text::FontPriority::Lowest,
                })
                .collect(),
        ));
    }
}
