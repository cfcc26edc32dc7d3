//! The PDF: one page per slide, from the very pictures `lectern export` renders, laid out by
//! Typst and written by `typst-pdf` (the Typst we already build for the maths, plus its PDF
//! backend). With notes, each page is an A4 sheet for the speaker: the slide on top, its speaker
//! notes below as real text (embedded, subsetted fonts with Unicode mappings, so ẋ, ω, ² can be
//! searched and copied). The students' handout (2 or 3 slides a page with their `handout:`
//! text) is laid out by [`super::export_handout`].
//!
//! The slide images and the texts reach Typst as files of an in-memory world and are read with
//! `image(..)` and `read(..)`: no text from the deck is ever parsed as Typst markup, so notes
//! may hold `#`, `$`, `*` or `]` freely.

use std::collections::HashMap;
use std::sync::LazyLock;

use typst::diag::{FileError, FileResult, Severity};
use typst::foundations::{Bytes, Datetime};
use typst::syntax::{FileId, Source};
use typst::text::{Font, FontBook};
use typst::utils::LazyHash;
use typst::{Library, LibraryExt, World};
use typst_layout::PagedDocument;

/// One slide of the PDF.
pub struct HandoutPage {
    /// The rendered slide, encoded as `image_format` says.
    pub image: Vec<u8>,
    pub image_format: ImageFormat,
    /// Pixel size of the image: the page takes its aspect.
    pub size_px: [u32; 2],
    pub title: String,
    pub notes: String,
    /// The words for students (`handout:`), printed by [`Layout::Handout`] only.
    pub handout: String,
}

/// How a slide picture is embedded.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ImageFormat {
    /// Lossless: the slide PDFs, whose pictures are the PNGs `--out` writes.
    Png,
    /// The students' handout: light slides at print size are a sixth of their PNG (see
    /// `docs/benchmarks/check-export.md`).
    Jpeg,
}

impl ImageFormat {
    /// The file extension Typst reads the format from.
    pub fn extension(self) -> &'static str {
        match self {
            ImageFormat::Png => "png",
            ImageFormat::Jpeg => "jpg",
        }
    }
}

/// Page layout.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Layout {
    /// Each page is the slide, edge to edge, 10 inches wide, as tall as the slide's aspect.
    Slides,
    /// A4 portrait: the slide on top, "Slide n of N: title", then the speaker notes.
    Notes,
    /// A4 portrait for students: `per_page` slides (2 or 3) a page, each with its `handout:`
    /// text below it; the deck's title on top, page numbers at the foot.
    Handout { per_page: u8 },
}

/// Width of a slide page: 10 in (720 pt); a 1920-pixel slide prints at 192 dpi.
const SLIDE_PAGE_WIDTH_PT: f64 = 720.0;

/// The PDF bytes of a handout with `pages`, titled `title`.
pub fn handout_pdf(pages: &[HandoutPage], title: &str, layout: Layout) -> Result<Vec<u8>, String> {
    if pages.is_empty() {
        return Err("a handout needs at least one slide".into());
    }
    let mut files: HashMap<String, Bytes> = HashMap::new();
    files.insert("title.txt".into(), Bytes::new(title.as_bytes().to_vec()));
    let mut main = String::from(
        "#set document(title: read(\"/title.txt\"))\n\
         #set text(font: (\"New Computer Modern\", \"DejaVu Sans Mono\"), size: 11pt)\n",
    );
    match layout {
        Layout::Slides => {}
        Layout::Handout { .. } => main.push_str(&super::export_handout::preamble()),
        Layout::Notes => main.push_str(
            "#set page(paper: \"a4\", margin: (x: 18mm, y: 16mm))\n\
             #set par(justify: false, leading: 0.6em, spacing: 1.0em)\n",
        ),
    }
    let n = pages.len();
    for (i, page) in pages.iter().enumerate() {
        let k = i + 1;
        let image = format!("slide-{k}.{}", page.image_format.extension());
        files.insert(image.clone(), Bytes::new(page.image.clone()));
        files.insert(
            format!("title-{k}.txt"),
            Bytes::new(page.title.as_bytes().to_vec()),
        );
        files.insert(
            format!("notes-{k}.txt"),
            Bytes::new(page.notes.trim().as_bytes().to_vec()),
        );
        files.insert(
            format!("handout-{k}.txt"),
            Bytes::new(page.handout.trim().as_bytes().to_vec()),
        );
        if let Layout::Handout { per_page } = layout {
            main.push_str(&super::export_handout::slot(
                k,
                &image,
                page.size_px,
                per_page,
            ));
            continue;
        }
        if i > 0 {
            main.push_str("#pagebreak()\n");
        }
        match layout {
            Layout::Slides => {
                let [w, h] = page.size_px.map(|v| f64::from(v.max(1)));
                let height_pt = SLIDE_PAGE_WIDTH_PT * h / w;
                main.push_str(&format!(
                    "#set page(width: {SLIDE_PAGE_WIDTH_PT}pt, height: {height_pt:.3}pt, margin: 0pt)\n\
                     #image(\"/{image}\", width: 100%, height: 100%, fit: \"stretch\")\n"
                ));
            }
            Layout::Notes => main.push_str(&format!(
                "#block(stroke: 0.5pt + luma(60%), image(\"/{image}\", width: 100%))\n\
                 #text(size: 9pt, fill: luma(35%))[Slide {k} of {n}: #read(\"/title-{k}.txt\")]\n\n\
                 #read(\"/notes-{k}.txt\")\n"
            )),
            Layout::Handout { .. } => {}
        }
    }
    let world = HandoutWorld {
        source: Source::detached(main),
        files,
    };
    let warned = typst::compile::<PagedDocument>(&world);
    let doc = warned.output.map_err(|errs| {
        let first = errs
            .iter()
            .find(|d| d.severity == Severity::Error)
            .or(errs.first());
        format!(
            "laying out the handout: {}",
            first.map_or("unknown Typst error".into(), |d| d.message.to_string())
        )
    })?;
    typst_pdf::pdf(&doc, &typst_pdf::PdfOptions::default()).map_err(|errs| {
        format!(
            "writing the PDF: {}",
            errs.first()
                .map_or("unknown error".into(), |d| d.message.to_string())
        )
    })
}

/// The standard library and the embedded fonts (`typst-assets`), loaded once.
struct Shared {
    library: LazyHash<Library>,
    book: LazyHash<FontBook>,
    fonts: Vec<Font>,
}

static SHARED: LazyLock<Shared> = LazyLock::new(|| {
    let fonts: Vec<Font> = typst_assets::fonts()
        .flat_map(|data| Font::iter(Bytes::new(data)))
        .collect();
    Shared {
        library: LazyHash::new(Library::default()),
        book: LazyHash::new(FontBook::from_fonts(&fonts)),
        fonts,
    }
});

/// The handout's main file and its in-memory files (slide images, titles, notes).
struct HandoutWorld {
    source: Source,
    files: HashMap<String, Bytes>,
}

impl World for HandoutWorld {
    fn library(&self) -> &LazyHash<Library> {
        &SHARED.library
    }
    fn book(&self) -> &LazyHash<FontBook> {
        &SHARED.book
    }
    fn main(&self) -> FileId {
        self.source.id()
    }
    fn source(&self, id: FileId) -> FileResult<Source> {
        if id == self.source.id() {
            Ok(self.source.clone())
        } else {
            Err(FileError::AccessDenied)
        }
    }
    fn file(&self, id: FileId) -> FileResult<Bytes> {
        let name = id.get().vpath().get_without_slash();
        self.files.get(name).cloned().ok_or(FileError::AccessDenied)
    }
    fn font(&self, index: usize) -> Option<Font> {
        SHARED.fonts.get(index).cloned()
    }
    fn today(&self, _offset: Option<typst::foundations::Duration>) -> Option<Datetime> {
        None
    }
}

/// Collects the slides of an export and writes them as a PDF at the end.
pub struct HandoutWriter {
    pub path: std::path::PathBuf,
    pub layout: Layout,
    pages: Vec<HandoutPage>,
}

impl HandoutWriter {
    pub fn new(path: std::path::PathBuf, layout: Layout) -> Self {
        Self {
            path,
            layout,
            pages: Vec::new(),
        }
    }

    /// Adds the rendered `image` of `slide` as the next page (the students' handout embeds it
    /// as JPEG, the other layouts as PNG).
    pub fn push(
        &mut self,
        image: &image::RgbaImage,
        slide: &crate::deck::Slide,
    ) -> Result<(), String> {
        let (bytes, image_format) = match self.layout {
            Layout::Handout { .. } => (super::export_handout::jpeg(image)?, ImageFormat::Jpeg),
            Layout::Slides | Layout::Notes => (png_rgb(image)?, ImageFormat::Png),
        };
        self.pages.push(HandoutPage {
            image: bytes,
            image_format,
            size_px: [image.width(), image.height()],
            title: slide.title.clone(),
            notes: slide.notes.clone(),
            handout: slide.handout.clone(),
        });
        Ok(())
    }

    /// Lays out and writes the PDF (temp file + rename, so a reader never sees half a file);
    /// its number of pages.
    pub fn finish(self, title: &str) -> Result<usize, String> {
        let bytes = handout_pdf(&self.pages, title, self.layout)?;
        let name = self
            .path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        let tmp = self.path.with_file_name(format!(".{name}.lectern-tmp"));
        std::fs::write(&tmp, &bytes)
            .and_then(|()| std::fs::rename(&tmp, &self.path))
            .map_err(|e| {
                let _ = std::fs::remove_file(&tmp);
                format!("cannot write {}: {e}", self.path.display())
            })?;
        Ok(match self.layout {
            Layout::Handout { per_page } => self.pages.len().div_ceil(usize::from(per_page.max(1))),
            Layout::Slides | Layout::Notes => self.pages.len(),
        })
    }
}

/// An opaque RGB PNG of `image` (slides are opaque; RGB keeps the PDF free of soft masks).
pub fn png_rgb(image: &image::RgbaImage) -> Result<Vec<u8>, String> {
    let rgb = image::DynamicImage::ImageRgba8(image.clone()).into_rgb8();
    let mut out = std::io::Cursor::new(Vec::new());
    rgb.write_to(&mut out, image::ImageFormat::Png)
        .map_err(|e| format!("encoding a slide: {e}"))?;
    Ok(out.into_inner())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn page(colour: [u8; 4], notes: &str) -> HandoutPage {
        let img = image::RgbaImage::from_pixel(64, 36, image::Rgba(colour));
        HandoutPage {
            image: png_rgb(&img).unwrap(),
            image_format: ImageFormat::Png,
            size_px: [64, 36],
            title: "A #title with $ and ]".into(),
            notes: notes.into(),
            handout: format!("for students: {notes}"),
        }
    }

    fn count(haystack: &[u8], needle: &[u8]) -> usize {
        haystack
            .windows(needle.len())
            .filter(|w| *w == needle)
            .count()
    }

    #[test]
    fn one_page_per_slide_and_markup_in_notes_is_text() {
        let pages = [
            page([200, 0, 0, 255], "ẋ = ω² x; #let x = 1 $ *not bold* ]"),
            page([0, 200, 0, 255], ""),
            page([0, 0, 200, 255], "third"),
        ];
        for layout in [Layout::Slides, Layout::Notes] {
            let pdf = handout_pdf(&pages, "Handout", layout).unwrap();
            assert!(pdf.starts_with(b"%PDF-"), "{layout:?}");
            assert_eq!(count(&pdf, b"/Type/Pages/Count 3/"), 1, "{layout:?}");
        }
        // 2 a page: 3 slides on 2 pages; 3 a page: on 1; 4 slides at 3 a page: on 2
        let four: Vec<HandoutPage> = (0..4).map(|_| page([90, 90, 90, 255], "n")).collect();
        for (pages, per_page, want) in [(&pages[..], 2, 2), (&pages[..], 3, 1), (&four[..], 3, 2)] {
            let pdf = handout_pdf(pages, "Handout", Layout::Handout { per_page }).unwrap();
            let want = format!("/Type/Pages/Count {want}/");
            assert_eq!(count(&pdf, want.as_bytes()), 1, "{per_page} a page");
        }
    }

    #[test]
    fn no_pages_is_an_error() {
        assert!(handout_pdf(&[], "x", Layout::Slides).is_err());
    }
}
