//! How slides look: the logical canvas, type sizes, colours and fonts. All sizes here are in
//! canvas units (the canvas is 1920 units wide whatever the window), so a laptop window and a
//! 4K projector show the same slide; [`Look::scaled`] turns them into screen points.

use egui::{Color32, FontFamily, FontId};

use crate::deck::Theme;

/// Width of the logical canvas in canvas units; its height follows the deck's aspect ratio.
pub const CANVAS_WIDTH: f32 = 1920.0;

/// Font families lectern installs next to egui's (see [`install_fonts`]).
pub const SERIF: &str = "lectern-serif";
pub const SERIF_BOLD: &str = "lectern-serif-bold";
pub const SERIF_ITALIC: &str = "lectern-serif-italic";
pub const MONO: &str = "lectern-mono";

/// Colours of one theme.
#[derive(Debug, Clone, Copy)]
pub struct Palette {
    /// The slide itself.
    pub background: Color32,
    /// Around the slide when the window's shape differs from the canvas.
    pub letterbox: Color32,
    pub title: Color32,
    pub text: Color32,
    /// Footer, captions: present but quiet.
    pub dim: Color32,
    /// The rule under titles, bullets.
    pub accent: Color32,
    /// Behind plots and code, one step off the background.
    pub panel: Color32,
}

impl Palette {
    pub fn of(theme: Theme) -> Self {
        match theme {
            Theme::Dark => Self {
                background: Color32::from_rgb(0x16, 0x19, 0x21),
                letterbox: Color32::from_rgb(0x05, 0x06, 0x08),
                title: Color32::from_rgb(0xf4, 0xf1, 0xea),
                text: Color32::from_rgb(0xd9, 0xd6, 0xcf),
                dim: Color32::from_rgb(0x85, 0x8b, 0x98),
                accent: Color32::from_rgb(0xe8, 0xa8, 0x4f),
                panel: Color32::from_rgb(0x1e, 0x22, 0x2c),
            },
            Theme::Light => Self {
                background: Color32::from_rgb(0xfb, 0xf9, 0xf4),
                letterbox: Color32::from_rgb(0x20, 0x22, 0x26),
                title: Color32::from_rgb(0x17, 0x1a, 0x21),
                text: Color32::from_rgb(0x2a, 0x2d, 0x34),
                dim: Color32::from_rgb(0x68, 0x6b, 0x73),
                accent: Color32::from_rgb(0xb4, 0x5f, 0x06),
                panel: Color32::from_rgb(0xf1, 0xee, 0xe6),
            },
        }
    }
}

/// Type sizes and spacing in canvas units.
pub mod size {
    pub const MARGIN_X: f32 = 120.0;
    pub const MARGIN_TOP: f32 = 84.0;
    pub const MARGIN_BOTTOM: f32 = 84.0;
    pub const TITLE: f32 = 72.0;
    pub const TITLE_SLIDE: f32 = 112.0;
    /// Gap between the title's rule and the first block.
    pub const AFTER_TITLE: f32 = 48.0;
    pub const BODY: f32 = 46.0;
    pub const BLOCK_GAP: f32 = 34.0;
    pub const BULLET_GAP: f32 = 18.0;
    pub const MATH: f32 = 40.0;
    pub const FOOTER: f32 = 24.0;
    /// Text inside widgets (labels, readouts, tick labels, legends, in-plot labels): two thirds
    /// of the body size (30 px on a 1080p slide), so it scales with the slide's type scale and
    /// stays readable from the back row (at least 28 px at 1080p, tested).
    pub const WIDGET_TEXT: f32 = BODY * 0.65;
}

/// A [`Palette`] and the factor from canvas units to screen points for one drawn slide.
#[derive(Debug, Clone, Copy)]
pub struct Look {
    pub palette: Palette,
    /// Screen points per canvas unit.
    pub scale: f32,
}

impl Look {
    /// Canvas units → points.
    pub fn scaled(&self, canvas_units: f32) -> f32 {
        canvas_units * self.scale
    }

    pub fn font(&self, family: &str, canvas_units: f32, ctx: &egui::Context) -> FontId {
        FontId::new(self.scaled(canvas_units), family_or_default(ctx, family))
    }
}

/// The logical canvas of a deck with aspect `ratio` (width / height), in canvas units.
pub fn canvas_size(ratio: f32) -> egui::Vec2 {
    egui::vec2(CANVAS_WIDTH, CANVAS_WIDTH / ratio)
}

/// The largest rect of aspect `ratio` centred in `avail`, and its scale in points per canvas unit.
pub fn fit_canvas(avail: egui::Rect, ratio: f32) -> (egui::Rect, f32) {
    let canvas = canvas_size(ratio);
    let scale = (avail.width() / canvas.x)
        .min(avail.height() / canvas.y)
        .max(1e-3);
    let rect = egui::Rect::from_center_size(avail.center(), canvas * scale);
    (rect, scale)
}

/// Our named family if it is installed in `ctx`, else egui's proportional one (the first frame
/// after [`install_fonts`] may still run on the old font set).
pub fn family_or_default(ctx: &egui::Context, name: &str) -> FontFamily {
    let family = FontFamily::Name(name.into());
    if ctx.fonts(|f| f.families().contains(&family)) {
        family
    } else if name == MONO {
        FontFamily::Monospace
    } else {
        FontFamily::Proportional
    }
}

/// Whether [`install_fonts`] has taken effect in `ctx`.
pub fn fonts_installed(ctx: &egui::Context) -> bool {
    let family = FontFamily::Name(SERIF.into());
    ctx.fonts(|f| f.families().contains(&family))
}

/// Installs the slide fonts: Libertinus Serif (the face Typst sets maths beside, so text and
/// formulas match) and DejaVu Sans Mono, all bundled by `typst-assets`, with egui's own fonts as
/// fallbacks for symbols and emoji. Idempotent and cheap after the first call.
pub fn install_fonts(ctx: &egui::Context) {
    if fonts_installed(ctx) {
        return;
    }
    // by name, from typst-assets (or, in the web player, from its bundle)
    let faces: std::collections::HashMap<String, &'static [u8]> =
        crate::math::slide_fonts().into_iter().collect();
    let face = |name: &str| faces.get(name).copied();
    let (Some(serif), Some(serif_italic), Some(serif_bold), Some(math), Some(newcm), Some(mono)) = (
        face("LibertinusSerif-Regular"),
        face("LibertinusSerif-Italic"),
        face("LibertinusSerif-Semibold"),
        face("NewCMMath-Book"),
        face("NewCM10-Regular"),
        face("DejaVuSansMono"),
    ) else {
        tracing::warn!("slide fonts missing; slides use egui's default fonts");
        return;
    };
    let mut defs = egui::FontDefinitions::default();
    // After our face: New Computer Modern (wide coverage of maths symbols, super- and
    // subscripts), then egui's own fonts (emoji, icons).
    defs.font_data.insert(
        "NewCM10-Regular".into(),
        egui::FontData::from_static(newcm).into(),
    );
    defs.font_data.insert(
        "NewCMMath-Book".into(),
        egui::FontData::from_static(math).into(),
    );
    let mut fallbacks = vec!["NewCM10-Regular".to_owned(), "NewCMMath-Book".to_owned()];
    fallbacks.extend(
        defs.families
            .get(&FontFamily::Proportional)
            .cloned()
            .unwrap_or_default(),
    );
    // Widget text (egui's proportional and monospace families) gets the same fallbacks, so a
    // plot label like "ẋ" or "Rᵀ" is drawn, not a box.
    for family in [FontFamily::Proportional, FontFamily::Monospace] {
        if let Some(chain) = defs.families.get_mut(&family) {
            chain.insert(1.min(chain.len()), "NewCMMath-Book".to_owned());
            chain.insert(1.min(chain.len()), "NewCM10-Regular".to_owned());
        }
    }
    let mut add = |name: &str, bytes: &'static [u8], family: &str| {
        defs.font_data
            .insert(name.into(), egui::FontData::from_static(bytes).into());
        let mut chain = vec![name.to_owned()];
        chain.extend(fallbacks.iter().cloned());
        defs.families.insert(FontFamily::Name(family.into()), chain);
    };
    add("LibertinusSerif-Regular", serif, SERIF);
    add("LibertinusSerif-Italic", serif_italic, SERIF_ITALIC);
    add("LibertinusSerif-Semibold", serif_bold, SERIF_BOLD);
    add("DejaVuSansMono", mono, MONO);
    // Last resort in every family: the maths fonts' full coverage (superscript minus, arrows,
    // box drawing), so no label anywhere falls through to a missing glyph.
    crate::math::add_fallback_fonts(&mut defs);
    ctx.set_fonts(defs);
}

/// A text style that only slide canvases define: widgets that set absolute text sizes for use
/// outside a slide check [`is_canvas_style`] and leave the canvas-scaled sizes alone.
pub const CANVAS_STYLE: &str = "lectern-canvas";

pub fn is_canvas_style(style: &egui::Style) -> bool {
    style
        .text_styles
        .contains_key(&egui::TextStyle::Name(CANVAS_STYLE.into()))
}
