//! The web page's bundle: the deck and every file it names, its formulas typeset at export, and
//! the fonts the slides use, which `lectern export --web` writes (gzipped, as base64 inside a
//! classic script, `bundle.js`, since `file://` pages may not `fetch`) and the player reads at
//! start. No egui, no Typst: both sides share this one definition of the format.
//!
//! Layout (`lectern-web-bundle/2`): one line of JSON (the [`WebBundle`] without its bytes), a
//! newline, then every byte string back to back, raw, each stored once however many names it
//! has (a font that is both a slide face and a fallback travels once). Raw bytes rather than
//! base64 inside the JSON let the page's gzip shrink the fonts as fonts. A formula's pixels are
//! a PNG (straight RGBA as egui uploads it, the premultiplication undone and redone around the
//! codec).

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::math::{MathError, MathStyle, MathSyntax, RenderedFormula};

/// What a page's bundle says it is: a player refuses any other.
pub const FORMAT: &str = "lectern-web-bundle/2";

#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct WebBundle {
    pub format: String,
    /// The deck's path inside the bundle (relative, `/`-separated), e.g. `slides/lecture.ron`.
    pub deck: String,
    /// Every project file the deck's loading and drawing read, by the same relative path.
    pub files: Vec<BundledFile>,
    pub formulas: Vec<BundledFormula>,
    /// The slide and fallback faces, by the name egui knows them.
    pub fonts: Vec<BundledFile>,
    /// The length of each byte string after the JSON line, in order.
    blob_lengths: Vec<usize>,
    #[serde(skip)]
    blobs: Vec<Vec<u8>>,
}

/// A name and the byte string it stands for.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BundledFile {
    pub path: String,
    pub blob: usize,
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
    /// The byte string holding the PNG (straight alpha), and the baseline in pixels from the top.
    Png {
        png_blob: usize,
        baseline: u32,
    },
    Error {
        message: String,
        col: Option<usize>,
    },
}

impl WebBundle {
    pub fn new(deck: impl Into<String>) -> Self {
        Self {
            format: FORMAT.into(),
            deck: deck.into(),
            ..Self::default()
        }
    }

    /// Stores `bytes` once: the index of an equal byte string already in, or of a new one.
    pub fn add_blob(&mut self, bytes: &[u8]) -> usize {
        if let Some(i) = self.blobs.iter().position(|b| b.as_slice() == bytes) {
            return i;
        }
        self.blobs.push(bytes.to_vec());
        self.blob_lengths.push(bytes.len());
        self.blobs.len() - 1
    }

    pub fn add_file(&mut self, path: impl Into<String>, bytes: &[u8]) {
        let blob = self.add_blob(bytes);
        self.files.push(BundledFile {
            path: path.into(),
            blob,
        });
    }

    pub fn add_font(&mut self, name: impl Into<String>, bytes: &[u8]) {
        let blob = self.add_blob(bytes);
        self.fonts.push(BundledFile {
            path: name.into(),
            blob,
        });
    }

    /// Typeset results as the bundle keeps them (a formula's pixels as a PNG byte string).
    pub fn add_formula(
        &mut self,
        src: &str,
        syntax: MathSyntax,
        style: MathStyle,
        rgba: [u8; 4],
        em_px: f32,
        typeset: &Result<RenderedFormula, MathError>,
    ) -> Result<(), String> {
        let result = match typeset {
            Ok(f) => FormulaResult::Png {
                png_blob: self.add_blob(&png_of(f)?),
                baseline: f.baseline,
            },
            Err(e) => FormulaResult::Error {
                message: e.message.clone(),
                col: e.col,
            },
        };
        self.formulas.push(BundledFormula {
            src: src.to_owned(),
            latex: syntax == MathSyntax::Latex,
            inline: style == MathStyle::Inline,
            rgba,
            em_px,
            result,
        });
        Ok(())
    }

    /// The byte strings stored, one per distinct content.
    pub fn blob_count(&self) -> usize {
        self.blobs.len()
    }

    pub fn blob(&self, index: usize) -> Result<&[u8], String> {
        self.blobs.get(index).map(Vec::as_slice).ok_or_else(|| {
            format!("the bundle is damaged: it names byte string {index}, which it lacks")
        })
    }

    pub fn bytes_of(&self, file: &BundledFile) -> Result<&[u8], String> {
        self.blob(file.blob)
            .map_err(|e| format!("{}: {e}", file.path))
    }

    /// The bundle's layout (see the module's doc), before the page's gzip.
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut out = serde_json::to_vec(self).unwrap_or_default();
        out.push(b'\n');
        for b in &self.blobs {
            out.extend_from_slice(b);
        }
        out
    }

    /// Reads a bundle; a damaged one is an error saying where.
    pub fn from_bytes(bytes: &[u8]) -> Result<Self, String> {
        let damaged = "the bundle is damaged";
        let newline = bytes
            .iter()
            .position(|&b| b == b'\n')
            .ok_or_else(|| format!("{damaged}: it has no header line"))?;
        let mut b: WebBundle = serde_json::from_slice(&bytes[..newline])
            .map_err(|e| format!("{damaged} at line {}, column {}: {e}", e.line(), e.column()))?;
        if b.format != FORMAT {
            return Err(format!(
                "the bundle is {:?}, this player reads {FORMAT:?}: export the page again",
                b.format
            ));
        }
        let mut rest = &bytes[newline + 1..];
        for &len in &b.blob_lengths {
            if len > rest.len() {
                return Err(format!("{damaged}: its bytes end early"));
            }
            let (blob, tail) = rest.split_at(len);
            b.blobs.push(blob.to_vec());
            rest = tail;
        }
        if !rest.is_empty() {
            return Err(format!("{damaged}: {} bytes too many", rest.len()));
        }
        Ok(b)
    }

    /// The bundle's files as a [`crate::project_files::Bundle`].
    pub fn project_files(&self) -> Result<crate::project_files::Bundle, String> {
        let mut out = crate::project_files::Bundle::new();
        for f in &self.files {
            out.insert(Path::new(&f.path), self.bytes_of(f)?.to_vec());
        }
        Ok(out)
    }

    pub fn deck_path(&self) -> PathBuf {
        PathBuf::from(&self.deck)
    }

    /// A formula's pixels (or its error) as the typesetter returned them.
    pub fn rendered(
        &self,
        f: &BundledFormula,
    ) -> Result<Result<RenderedFormula, MathError>, String> {
        match &f.result {
            FormulaResult::Error { message, col } => Ok(Err(MathError {
                message: message.clone(),
                col: *col,
            })),
            FormulaResult::Png { png_blob, baseline } => {
                let damaged = |e: &dyn std::fmt::Display| {
                    format!("formula `{}`: damaged in the bundle ({e})", f.src)
                };
                let png = self.blob(*png_blob).map_err(|e| damaged(&e))?;
                let img = image::load_from_memory_with_format(png, image::ImageFormat::Png)
                    .map_err(|e| damaged(&e))?
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

impl BundledFormula {
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
    fn a_formula_comes_back_as_typeset_bytes_are_stored_once_and_a_damaged_bundle_says_so() {
        // a half-transparent edge pixel: premultiplied values survive PNG's straight alpha
        let f = RenderedFormula {
            width: 2,
            height: 1,
            baseline: 1,
            rgba_premultiplied: vec![10, 20, 30, 255, 50, 40, 0, 128],
        };
        let mut b = WebBundle::new("slides/a.ron");
        b.add_file("slides/a.ron", b"(title: \"t\")");
        let face = vec![7u8; 1000];
        b.add_font("Face-Regular", &face);
        b.add_font("lectern-Face", &face);
        b.add_formula(
            "x^2",
            MathSyntax::Typst,
            MathStyle::Inline,
            [1, 2, 3, 255],
            64.0,
            &Ok(f.clone()),
        )
        .unwrap();
        // the deck, one face (named twice), one PNG
        assert_eq!(b.blob_count(), 3);
        let bytes = b.to_bytes();
        assert!(bytes.len() < 2 * face.len(), "{} bytes", bytes.len());
        let back = WebBundle::from_bytes(&bytes).unwrap();
        assert_eq!(back, b);
        assert_eq!(back.bytes_of(&back.fonts[1]).unwrap(), &face[..]);
        let got = back.rendered(&back.formulas[0]).unwrap().unwrap();
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

        let e = WebBundle::from_bytes(&bytes[..bytes.len() - 10]).unwrap_err();
        assert!(e.contains("damaged") && e.contains("end early"), "{e}");
        let header_end = bytes.iter().position(|&c| c == b'\n').unwrap();
        let e = WebBundle::from_bytes(&bytes[..header_end / 2]).unwrap_err();
        assert!(e.contains("damaged"), "{e}");
        let mut cut_header = bytes[..header_end / 2].to_vec();
        cut_header.extend_from_slice(&bytes[header_end..]);
        let e = WebBundle::from_bytes(&cut_header).unwrap_err();
        assert!(e.contains("line 1, column"), "{e}");
        let other = String::from_utf8_lossy(&bytes[..header_end])
            .replace(FORMAT, "lectern-web-bundle/1")
            .into_bytes();
        let e = WebBundle::from_bytes(&[&other[..], &bytes[header_end..]].concat()).unwrap_err();
        assert!(e.contains("export"), "{e}");
    }
}
