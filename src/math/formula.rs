//! What a formula is, asked for and answered, whoever typesets it: Typst in this process or a
//! worker natively ([`super::typeset`], [`super::pool`]), or the formulas typeset at export that
//! the web player carries. No Typst here, so the web build shares these types.

/// Which syntax a formula is written in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum MathSyntax {
    /// Typst maths, e.g. `dot(x) = f(x, t)`.
    Typst,
    /// LaTeX maths, e.g. `\dot{x} = f(x, t)`, converted to Typst by `mitex`.
    Latex,
}

/// How a formula sits: on its own line (a `Math` block) or inside a line of text (`$…$` in a
/// paragraph), where it must stand on the text's baseline.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum MathStyle {
    #[default]
    Display,
    Inline,
}

/// A rendered formula: premultiplied RGBA, row-major, `width × height` pixels, with its
/// baseline `baseline` pixels below the top edge (where a line of text must sit).
#[derive(Debug, Clone, PartialEq)]
pub struct RenderedFormula {
    pub width: u32,
    pub height: u32,
    pub baseline: u32,
    pub rgba_premultiplied: Vec<u8>,
}

impl RenderedFormula {
    /// This formula scaled by `scale` (the web player draws formulas typeset at twice their
    /// layout size at the size a screen asks for; premultiplied RGBA filters correctly as it is).
    pub fn resampled(&self, scale: f32) -> RenderedFormula {
        let w = ((self.width as f32 * scale).round() as u32).max(1);
        let h = ((self.height as f32 * scale).round() as u32).max(1);
        if (w, h) == (self.width, self.height) {
            return self.clone();
        }
        let Some(img) =
            image::RgbaImage::from_raw(self.width, self.height, self.rgba_premultiplied.clone())
        else {
            return self.clone();
        };
        let out = image::imageops::resize(&img, w, h, image::imageops::FilterType::CatmullRom);
        RenderedFormula {
            width: w,
            height: h,
            baseline: (self.baseline as f32 * h as f32 / self.height.max(1) as f32).round() as u32,
            rgba_premultiplied: out.into_raw(),
        }
    }
}

/// Why a formula did not render. `col` is a 1-based column (in characters) into the formula as
/// the lecturer wrote it, when Typst could point at the fault.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct MathError {
    pub message: String,
    pub col: Option<usize>,
}

impl std::fmt::Display for MathError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.col {
            Some(c) => write!(f, "column {c}: {}", self.message),
            None => write!(f, "{}", self.message),
        }
    }
}

impl std::error::Error for MathError {}

/// The space around an inline formula's ink, above and below (so antialiased edges are not
/// cut), in ems: a line of text lays the formula out without it (see `app::inline_text`).
pub const INLINE_MARGIN_Y_EM: f32 = 0.15;

/// About how tall `src` will be once typeset, in ems, without typesetting it: for the
/// placeholder a slide draws while the formula is on its way, so the blocks below move little
/// when it arrives. Calibrated on the bundled deck (a line 1.3–1.6 em, a fraction 2.4–2.7, a
/// column vector or matrix ~1.2–1.35 em per row).
pub fn estimated_height_em(src: &str) -> f32 {
    // the most rows in any vec(..) (entries split by commas) or mat(..) (rows split by `;`)
    let mut rows = 1usize;
    for (open, sep) in [("vec(", b','), ("mat(", b';'), ("cases(", b',')] {
        for (start, _) in src.match_indices(open) {
            let mut depth = 0i32;
            let mut n = 1;
            for &b in &src.as_bytes()[start + open.len() - 1..] {
                match b {
                    b'(' | b'[' | b'{' => depth += 1,
                    b')' | b']' | b'}' => {
                        depth -= 1;
                        if depth == 0 {
                            break;
                        }
                    }
                    _ if b == sep && depth == 1 => n += 1,
                    _ => {}
                }
            }
            rows = rows.max(n);
        }
    }
    let rows = rows.max(src.matches("\\\\").count() + 1);
    if rows > 1 {
        return 1.25 * rows as f32 + 0.4;
    }
    // `a/b` is a fraction, `\/` a plain slash
    let fraction = src
        .char_indices()
        .any(|(i, c)| c == '/' && !src[..i].ends_with('\\'))
        || src.contains("frac");
    if fraction {
        2.6
    } else if src.contains('^') || src.contains('_') {
        1.5
    } else {
        1.35
    }
}

/// One formula to typeset.
#[derive(Debug, Clone, PartialEq)]
pub struct Request {
    pub src: String,
    pub syntax: MathSyntax,
    pub style: MathStyle,
    pub size_px: f32,
    pub rgba: [u8; 4],
}

/// A typesetting job's state as seen from outside, the same for both pools (the native one's
/// workers, the web player's table of prerendered formulas, which is always `Done`).
#[derive(Debug, Clone, PartialEq)]
pub enum Poll {
    Pending,
    Done(Result<RenderedFormula, MathError>),
    /// Dropped unstarted: submit it again if it is still wanted.
    Expired,
}

/// Called when a job the caller waits for is done (e.g. to repaint), for both pools.
pub type Notify = std::sync::Arc<dyn Fn() + Send + Sync>;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn resampling_halves_a_master_and_keeps_its_baseline_and_ink() {
        // 8×4 master, a filled 4×2 block in its middle, baseline at row 3
        let mut rgba = vec![0u8; 8 * 4 * 4];
        for y in 1..3 {
            for x in 2..6 {
                rgba[(y * 8 + x) * 4..][..4].copy_from_slice(&[200, 100, 50, 255]);
            }
        }
        let master = RenderedFormula {
            width: 8,
            height: 4,
            baseline: 3,
            rgba_premultiplied: rgba,
        };
        let half = master.resampled(0.5);
        assert_eq!((half.width, half.height, half.baseline), (4, 2, 2));
        assert_eq!(half.rgba_premultiplied.len(), 4 * 2 * 4);
        let ink: u32 = half.rgba_premultiplied.chunks(4).map(|p| p[3] as u32).sum();
        // a quarter of the master's pixels were ink: about a quarter of the half's alpha
        assert!((ink as f32 / (8.0 * 255.0) - 0.25).abs() < 0.15, "{ink}");
        assert_eq!(master.resampled(1.0), master);
    }
}
