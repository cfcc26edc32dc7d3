//! The web page's bundle: the deck and every file it names, its formulas typeset at export, and
//! the fonts the slides use, as one JSON document that `lectern export --web` writes (inside a
//! classic script, `bundle.js`, since `file://` pages may not `fetch`) and the player reads at
//! start. No egui, no Typst: both sides share this one definition of the format.
//!
//! Bytes travel as base64; a formula's pixels as PNG (straight RGBA as egui uploads it, the
//! premultiplication undone and redone around the codec).

use std::path::{Path, PathBuf};

use base64::Engine as _;
use serde::{Deserialize, Serialize};

use crate::math::{MathError, MathStyle, MathSyntax, RenderedFormula};

/// What a page's bundle says it is: a player refuses any other.
pub const FORMAT: &str = "lectern-web-bundle/1";

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct WebBundle {
    pub format: String,
    /// The deck's path inside the bundle (relative, `/`-separated), e.g. `slides/lecture.ron`.
    pub deck: String,
    /// Every project file the deck's loading and drawing read, by the same relative path.
    pub files: Vec<BundledFile>,
    pub formulas: Vec<BundledFormula>,
    /// The slide and fallback faces, by the name egui knows them.
    pub fonts: Vec<BundledFile>,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BundledFile {
    pub path: String,
    pub base64: String,
}

/// One formula as the export's Typst typeset it, at twice its layout size.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BundledFormula {
    pub src: String,
    pub latex: bool,
    pub inline: bool,
    pub rgba: [u8; 4],
    /// Pixels per em it was typeset at.
    pub em_px: f32,
    #[serde(flatten)]
    pub result: FormulaResult,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FormulaResult {
    /// PNG (straight alpha) as base64, and the baseline in pixels from the top.
    Png {
        png_base64: String,
        baseline: u32,
    },
    Error {
        message: String,
        col: Option<usize>,
    },
}

impl BundledFile {
    pub fn new(path: impl Into<String>, bytes: &[u8]) -> Self {
        Self {
            path: path.into(),
            base64: base64::engine::general_purpose::STANDARD.encode(bytes),
        }
    }

    pub fn bytes(&self) -> Result<Vec<u8>, String> {
        base64::engine::general_purpose::STANDARD
            .decode(&self.base64)
            .map_err(|e| format!("{}: damaged in the bundle ({e})", self.path))
    }
}

impl BundledFormula {
    pub fn new(
        src: &str,
        syntax: MathSyntax,
        style: MathStyle,
        rgba: [u8; 4],
        em_px: f32,
        result: &Result<RenderedFormula, MathError>,
    ) -> Result<Self, String> {
        let result = match result {
            Ok(f) => FormulaResult::Png {
                png_base64: base64::engine::general_purpose::STANDARD.encode(png_of(f)?),
                baseline: f.baseline,
            },
            Err(e) => FormulaResult::Error {
                message: e.message.clone(),
                col: e.col,
            },
        };
        Ok(Self {
            src: src.to_owned(),
            latex: syntax == MathSyntax::Latex,
            inline: style == MathStyle::Inline,
            rgba,
            em_px,
            result,
        })
    }

    pub fn syntax(&self) -> MathSyntax {
        if self.latex {
            MathSyntax::Latex
        } else {
            MathSyntax::Typst
        }
    }

    pub fn style(&self) -> MathStyle {
        if self.inline {
            MathStyle::Inline
        } else {
            MathStyle::Display
        }
    }

    /// The formula's pixels (or its error) as the typesetter returned them.
    pub fn rendered(&self) -> Result<Result<RenderedFormula, MathError>, String> {
        match &self.result {
            FormulaResult::Error { message, col } => Ok(Err(MathError {
                message: message.clone(),
                col: *col,
            })),
            FormulaResult::Png {
                png_base64,
                baseline,
            } => {
                let png = base64::engine::general_purpose::STANDARD
                    .decode(png_base64)
                    .map_err(|e| format!("formula `{}`: damaged in the bundle ({e})", self.src))?;
                let img = image::load_from_memory_with_format(&png, image::ImageFormat::Png)
                    .map_err(|e| format!("formula `{}`: damaged in the bundle ({e})", self.src))?
                    .into_rgba8();
                let (width, height) = img.dimensions();
                let mut rgba = img.into_raw();
                premultiply(&mut rgba);
                Ok(Ok(RenderedFormula {
                    width,
                    height,
                    baseline: *baseline,
                    rgba_premultiplied: rgba,
                }))
            }
        }
    }
}

/// A PNG of `f` (PNG holds straight alpha).
fn png_of(f: &RenderedFormula) -> Result<Vec<u8>, String> {
    let mut rgba = f.rgba_premultiplied.clone();
    for px in rgba.chunks_exact_mut(4) {
        let a = px[3] as u32;
        if a > 0 && a < 255 {
            for c in &mut px[..3] {
                *c = ((*c as u32 * 255 + a / 2) / a).min(255) as u8;
            }
        }
    }
    let img = image::RgbaImage::from_raw(f.width, f.height, rgba)
        .ok_or("a formula's pixels do not match its size")?;
    let mut out = std::io::Cursor::new(Vec::new());
    img.write_to(&mut out, image::ImageFormat::Png)
        .map_err(|e| e.to_string())?;
    Ok(out.into_inner())
}

fn premultiply(rgba: &mut [u8]) {
    for px in rgba.chunks_exact_mut(4) {
        let a = px[3] as u32;
        if a < 255 {
            for c in &mut px[..3] {
                *c = ((*c as u32 * a + 127) / 255) as u8;
            }
        }
    }
}

impl WebBundle {
    pub fn to_json(&self) -> String {
        serde_json::to_string(self).unwrap_or_default()
    }

    /// Reads a bundle; a damaged one is an error with its line and column.
    pub fn from_json(text: &str) -> Result<Self, String> {
        let b: WebBundle = serde_json::from_str(text).map_err(|e| {
            format!(
                "the bundle is damaged at line {}, column {}: {e}",
                e.line(),
                e.column()
            )
        })?;
        if b.format != FORMAT {
            return Err(format!(
                "the bundle is {:?}, this player reads {FORMAT:?}: export the page again",
                b.format
            ));
        }
        Ok(b)
    }

    /// The bundle's files as a [`crate::project_files::Bundle`].
    pub fn project_files(&self) -> Result<crate::project_files::Bundle, String> {
        let mut out = crate::project_files::Bundle::new();
        for f in &self.files {
            out.insert(Path::new(&f.path), f.bytes()?);
        }
        Ok(out)
    }

    pub fn deck_path(&self) -> PathBuf {
        PathBuf::from(&self.deck)
    }
}

/// `path` relative to `root`, `/`-separated, as the bundle stores it; `None` outside `root`.
pub fn bundle_path(root: &Path, path: &Path) -> Option<String> {
    let rel = path.strip_prefix(root).ok()?;
    let parts: Vec<String> = rel
        .components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect();
    (!parts.is_empty()).then(|| parts.join("/"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_formula_comes_back_as_typeset_and_a_damaged_bundle_says_where() {
        // a half-transparent edge pixel: premultiplied values survive PNG's straight alpha
        let f = RenderedFormula {
            width: 2,
            height: 1,
            baseline: 1,
            rgba_premultiplied: vec![10, 20, 30, 255, 50, 40, 0, 128],
        };
        let bf = BundledFormula::new(
            "x^2",
            MathSyntax::Typst,
            MathStyle::Inline,
            [1, 2, 3, 255],
            64.0,
            &Ok(f.clone()),
        )
        .unwrap();
        let b = WebBundle {
            format: FORMAT.into(),
            deck: "slides/a.ron".into(),
            files: vec![BundledFile::new("slides/a.ron", b"(title: \"t\")")],
            formulas: vec![bf],
            fonts: vec![],
        };
        let json = b.to_json();
        let back = WebBundle::from_json(&json).unwrap();
        assert_eq!(back, b);
        let got = back.formulas[0].rendered().unwrap().unwrap();
        assert_eq!((got.width, got.height, got.baseline), (2, 1, 1));
        for (g, w) in got.rgba_premultiplied.iter().zip(&f.rgba_premultiplied) {
            assert!(g.abs_diff(*w) <= 1, "{got:?} vs {f:?}");
        }
        assert_eq!(back.formulas[0].style(), MathStyle::Inline);
        let files = back.project_files().unwrap();
        use crate::project_files::FileSource as _;
        assert_eq!(
            files.read(Path::new("slides/a.ron")).unwrap(),
            b"(title: \"t\")"
        );

        let cut = &json[..json.len() / 2];
        let e = WebBundle::from_json(cut).unwrap_err();
        assert!(e.contains("line 1, column"), "{e}");
        let other = json.replace(FORMAT, "lectern-web-bundle/0");
        assert!(WebBundle::from_json(&other).unwrap_err().contains("export"));
    }
}
