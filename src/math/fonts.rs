//! The embedded Typst fonts, offered to egui as fallbacks: egui's default fonts lack glyphs the
//! slides use in plain labels (ẋ, ω, λ, √, ≈, ⁻¹, ▶ …). The same files that typeset the maths,
//! so labels and formulas agree and nothing depends on the system's fonts.

use egui::{FontDefinitions, FontFamily};

/// Family names (as the font files name themselves) installed as fallbacks, in order.
#[cfg(not(target_arch = "wasm32"))]
const FALLBACKS: [&str; 3] = [
    "DejaVu Sans Mono",
    "New Computer Modern Math",
    "Libertinus Serif",
];

/// The fallback fonts as (egui font name, bytes), found by family among the embedded fonts
/// (`lectern export --web` puts these bytes in the bundle for the player).
#[cfg(not(target_arch = "wasm32"))]
pub fn fallback_fonts() -> Vec<(String, &'static [u8])> {
    use typst::text::{FontInfo, FontWeight};
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

/// The faces the slides set text in, by the name egui knows them, with their place in
/// typst-assets 0.15's list (a fixed order: the count is checked so a reordering upstream fails
/// loudly in tests, not silently).
const SLIDE_FACES: [(&str, usize); 6] = [
    ("LibertinusSerif-Regular", 0),
    ("LibertinusSerif-Italic", 2),
    ("LibertinusSerif-Semibold", 4),
    ("NewCMMath-Book", 7),
    ("NewCM10-Regular", 9),
    ("DejaVuSansMono", 16),
];

/// The slide faces as (egui font name, bytes), all of [`SLIDE_FACES`] or none (then slides use
/// egui's default fonts).
#[cfg(not(target_arch = "wasm32"))]
pub fn slide_fonts() -> Vec<(String, &'static [u8])> {
    let all: Vec<&'static [u8]> = typst_assets::fonts().collect();
    if all.len() < 17 {
        return Vec::new();
    }
    SLIDE_FACES
        .iter()
        .map(|(name, i)| (name.to_string(), all[*i]))
        .collect()
}

/// The faces `lectern export --web` puts in the page: the slide faces, and the fallbacks that
/// are a slide face (free: the bundle stores bytes once) or of a family no slide face is of. New Computer Modern Math Regular is left out so: the slide face
/// NewCMMath-Book (the same family, placed before it in every chain, `app::theme`) covers all
/// its characters but four unused symbols (U+2612, U+2726, U+1F6D1, U+1F7FF), and 1.3 MB less
/// is a tenth of the page.
#[cfg(not(target_arch = "wasm32"))]
pub fn web_fonts() -> Vec<(String, &'static [u8])> {
    let family = |data: &[u8]| typst::text::FontInfo::new(data, 0).map(|i| i.family);
    let slide = slide_fonts();
    let slide_families: Vec<String> = slide.iter().filter_map(|(_, d)| family(d)).collect();
    let fallbacks = fallback_fonts().into_iter().filter(|(_, d)| {
        slide.iter().any(|(_, s)| s == d) || family(d).is_none_or(|f| !slide_families.contains(&f))
    });
    let kept: Vec<_> = fallbacks.collect();
    slide.into_iter().chain(kept).collect()
}

#[cfg(target_arch = "wasm32")]
static BUNDLED: std::sync::OnceLock<Vec<(String, &'static [u8])>> = std::sync::OnceLock::new();

/// The web player's slide faces: those of the bundle (see [`set_bundled_fonts`]).
#[cfg(target_arch = "wasm32")]
pub fn slide_fonts() -> Vec<(String, &'static [u8])> {
    let have = BUNDLED.get().cloned().unwrap_or_default();
    let faces: Vec<_> = SLIDE_FACES
        .iter()
        .filter_map(|(name, _)| have.iter().find(|(n, _)| n == name).cloned())
        .collect();
    if faces.len() == SLIDE_FACES.len() {
        faces
    } else {
        Vec::new()
    }
}

/// The web player's fallback fonts: those of the bundle (see [`set_bundled_fonts`]).
#[cfg(target_arch = "wasm32")]
pub fn fallback_fonts() -> Vec<(String, &'static [u8])> {
    let have = BUNDLED.get().cloned().unwrap_or_default();
    have.into_iter()
        .filter(|(n, _)| n.starts_with("lectern-"))
        .collect()
}

/// The web player, at start, before drawing: the fonts its bundle carries (those of
/// [`slide_fonts`] and [`fallback_fonts`] at export), as (egui font name, bytes). Once.
#[cfg(target_arch = "wasm32")]
pub fn set_bundled_fonts(fonts: Vec<(String, &'static [u8])>) {
    let _ = BUNDLED.set(fonts);
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
