//! The students' handout (`lectern export --pdf FILE --handout`): A4 portrait, 2 or 3 slides a
//! page, each in the light theme with its widgets drawn without their controls, and under it
//! the slide's `handout:` text (never its speaker notes). This module sizes the pictures and
//! writes the Typst for the pages; [`super::export_pdf`] compiles it into the PDF.
//!
//! Sizes are chosen for print, not the screen: each picture is rendered at 160–180 dpi of its
//! printed width (2 a page: 1120 px; 3 a page: 800 px) and embedded as JPEG, a fifth of the
//! PNG's bytes for these light slides (figures in `docs/benchmarks/check-export.md`).

/// The slides on one page when `--per-page` is not given: 2, so plot labels print at the
/// size of small text (3 a page prints them at 3–4 pt; still fine for revising).
pub const DEFAULT_PER_PAGE: u8 = 2;

/// The layouts `--per-page` offers.
pub const PER_PAGE: std::ops::RangeInclusive<u8> = 2..=3;

/// A4 portrait, in millimetres.
const PAGE_MM: [f64; 2] = [210.0, 297.0];
const MARGIN_X_MM: f64 = 15.0;
/// Top and bottom margins: the deck's title and the page number sit in them.
const MARGIN_Y_MM: f64 = 18.0;
/// Below each picture: room for about five lines of 10 pt text at 2 a page, four at 3.
fn text_room_mm(per_page: u8) -> f64 {
    if per_page <= 2 { 28.0 } else { 22.0 }
}

/// Print resolution of the pictures: about 170 dpi keeps small plot labels readable on paper;
/// more costs bytes (the bundled lecture's 29 pictures stay well under 3 MB together).
const PRINT_DPI: f64 = 170.0;

/// The handout text that fits under a slide, in characters (about the lines of
/// [`text_room_mm`]): longer text would run into the next slide, so `export` warns.
pub fn text_budget_chars(per_page: u8) -> usize {
    if per_page <= 2 { 520 } else { 400 }
}

/// The deck as the handout draws it: the light theme whatever the deck says (paper is white).
/// Warns of `handout:` texts longer than fit under their slide.
pub fn prepare(deck: &mut crate::deck::Deck, per_page: u8) -> Vec<String> {
    deck.theme = crate::deck::Theme::Light;
    let budget = text_budget_chars(per_page);
    (deck.slides.iter().enumerate())
        .filter_map(|(index, slide)| {
            let len = slide.handout.chars().count();
            (len > budget).then(|| {
                format!(
                    "slide {} ({:?}): its handout text has {len} characters; about {budget} \
                     fit under a slide at {per_page} a page",
                    index + 1,
                    slide.key()
                )
            })
        })
        .collect()
}

/// Height of one slide's share of the page, in millimetres.
fn slot_height_mm(per_page: u8) -> f64 {
    (PAGE_MM[1] - 2.0 * MARGIN_Y_MM) / f64::from(per_page.max(1))
}

/// Printed width of a slide of `aspect` (width over height), in millimetres: as wide as the
/// text column, or narrower so the picture and its text fit the slide's share of the page.
fn picture_width_mm(aspect: f64, per_page: u8) -> f64 {
    let column = PAGE_MM[0] - 2.0 * MARGIN_X_MM;
    let height = slot_height_mm(per_page) - text_room_mm(per_page) - 2.0;
    column.min(height * aspect.max(0.1))
}

/// The pixel size to render a slide of `aspect` at for `per_page` slides a page: about
/// [`PRINT_DPI`], as a whole number of eighths of the slides' layout width (a simple scale of
/// the layout every export shows).
pub fn picture_size_px(aspect: f32, per_page: u8) -> [u32; 2] {
    let layout_pt = f64::from(crate::app::offscreen::SLIDE_LAYOUT_WIDTH_PT);
    let width_mm = picture_width_mm(f64::from(aspect), per_page);
    let px = width_mm / 25.4 * PRINT_DPI;
    let eighths = (px / layout_pt * 8.0).round().max(1.0);
    let w = (layout_pt * eighths / 8.0).round();
    let h = (w / f64::from(aspect.max(0.1))).round();
    [w as u32, h as u32].map(|v| v.clamp(16, 8192))
}

/// The page set-up: A4, the deck's title at the top right, "page n of N" at the foot; the
/// maths font before the monospace one for what the text face lacks (subscript digits: k₁).
pub fn preamble() -> String {
    format!(
        "#set page(paper: \"a4\", margin: (x: {MARGIN_X_MM}mm, y: {MARGIN_Y_MM}mm),\n\
         \x20 header: align(right, text(size: 8pt, fill: luma(40%), read(\"/title.txt\"))),\n\
         \x20 footer: context align(center, text(size: 8pt, fill: luma(40%),\n\
         \x20   counter(page).display(\"1 of 1\", both: true))))\n\
         #set text(font: (\"New Computer Modern\", \"New Computer Modern Math\", \"DejaVu Sans Mono\"), size: 10pt)\n\
         #set par(justify: false, leading: 0.55em, spacing: 0.8em)\n"
    )
}

/// Slide `k` (1-based): its picture `image` (a file of the world) with a thin frame, then its
/// number and `handout-k.txt`, in a block of the slide's share of the page; a page break
/// before each page's first slide.
pub fn slot(k: usize, image: &str, size_px: [u32; 2], per_page: u8) -> String {
    let per_page = per_page.max(1);
    let [w, h] = size_px.map(|v| f64::from(v.max(1)));
    let width_mm = picture_width_mm(w / h, per_page);
    let slot_mm = slot_height_mm(per_page);
    let brk = if k > 1 && (k - 1) % usize::from(per_page) == 0 {
        "#pagebreak()\n"
    } else {
        ""
    };
    // a fixed share of the page: every page holds exactly `per_page` slides
    format!(
        "{brk}#block(width: 100%, height: {slot_mm:.2}mm, breakable: false, spacing: 0pt)[\n\
         \x20 #block(stroke: 0.4pt + luma(70%), image(\"/{image}\", width: {width_mm:.2}mm))\n\
         \x20 #v(1.5mm)\n\
         \x20 #text(weight: \"bold\")[{k}.] #h(0.4em) #read(\"/handout-{k}.txt\")\n\
         ]\n"
    )
}

/// The picture as JPEG (opaque RGB, as the slides are). `image`'s encoder keeps full chroma
/// (4:4:4) and standard Huffman tables; quality 75 shows no ringing around text and plot lines
/// at print size.
pub fn jpeg(image: &image::RgbaImage) -> Result<Vec<u8>, String> {
    let rgb = image::DynamicImage::ImageRgba8(image.clone()).into_rgb8();
    let mut out = Vec::new();
    image::codecs::jpeg::JpegEncoder::new_with_quality(&mut out, JPEG_QUALITY)
        .encode_image(&rgb)
        .map_err(|e| format!("encoding a slide: {e}"))?;
    Ok(out)
}

const JPEG_QUALITY: u8 = 75;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pictures_fit_their_share_of_the_page() {
        for per_page in PER_PAGE {
            let aspect = 16.0 / 9.0;
            let w = picture_width_mm(aspect, per_page);
            let h = w / aspect;
            let room = slot_height_mm(per_page) - text_room_mm(per_page);
            assert!(
                h <= room && w <= 180.0,
                "{per_page}: {w} x {h} mm in {room}"
            );
            // no narrower than needed: either the column's width or the slot's height is used
            assert!(w > 179.0 || h > room - 3.0, "{per_page}: {w} x {h} mm");
        }
        assert_eq!(picture_size_px(16.0 / 9.0, 2), [1120, 630]);
        assert_eq!(picture_size_px(16.0 / 9.0, 3), [800, 450]);
        // 4:3 slides are narrower at 3 a page (the slot's height limits them)
        let [w, h] = picture_size_px(4.0 / 3.0, 3);
        assert!(w < 800 && h > 450, "{w}x{h}");
    }

    #[test]
    fn the_handout_deck_is_light_and_long_texts_are_named() {
        let mut deck: crate::deck::Deck = ron::from_str(&format!(
            r#"(title: "T", theme: Dark, slides: [
                (title: "short", handout: "fits"),
                (title: "Long", handout: "{}"),
            ])"#,
            "word ".repeat(100)
        ))
        .unwrap();
        assert!(
            prepare(&mut deck, 2).is_empty(),
            "500 characters fit at 2 a page"
        );
        let warnings = prepare(&mut deck, 3);
        assert_eq!(deck.theme, crate::deck::Theme::Light);
        assert_eq!(warnings.len(), 1, "{warnings:?}");
        assert!(
            warnings[0].starts_with("slide 2 (\"Long\")"),
            "{warnings:?}"
        );
    }

    #[test]
    fn a_page_break_before_each_pages_first_slide() {
        let breaks = |per_page| {
            (1..=7)
                .filter(|&k| slot(k, "s.jpg", [16, 9], per_page).starts_with("#pagebreak"))
                .collect::<Vec<_>>()
        };
        assert_eq!(breaks(2), [3, 5, 7]);
        assert_eq!(breaks(3), [4, 7]);
    }
}
