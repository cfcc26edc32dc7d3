//! Reading a picture a deck names: decoded with limits checked against the file's header
//! before any pixel buffer is allocated, so a PNG that claims 100 000 × 100 000 pixels is
//! refused in microseconds instead of asking for 40 GB. No egui here: the app uploads the
//! result, `lectern check` only asks whether it decodes.

use std::path::Path;

/// Largest side accepted (a 4K slide needs at most 3840; this leaves room for print sources).
pub const MAX_SIDE_PX: u32 = 16_384;
/// Most memory the decoder may allocate for one picture.
pub const MAX_ALLOC_BYTES: u64 = 512 * 1024 * 1024;

fn limits() -> image::Limits {
    let mut limits = image::Limits::default();
    limits.max_image_width = Some(MAX_SIDE_PX);
    limits.max_image_height = Some(MAX_SIDE_PX);
    limits.max_alloc = Some(MAX_ALLOC_BYTES);
    limits
}

/// Decodes the picture at `path` (already resolved through [`crate::paths`]) into RGBA8.
pub fn decode(path: &Path) -> Result<image::RgbaImage, String> {
    let shown = path.display();
    let bytes =
        crate::project_files::read(path).map_err(|e| format!("cannot open image {shown}: {e}"))?;
    let mut reader = image::ImageReader::new(std::io::Cursor::new(bytes))
        .with_guessed_format()
        .map_err(|e| format!("cannot read image {shown}: {e}"))?;
    reader.limits(limits());
    let img = reader.decode().map_err(|e| match e {
        image::ImageError::Limits(_) => format!(
            "image {shown} is too large (more than {MAX_SIDE_PX} pixels on a side or {} MB decoded)",
            MAX_ALLOC_BYTES / (1024 * 1024)
        ),
        e => format!("cannot decode image {shown}: {e}"),
    })?;
    Ok(img.to_rgba8())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A valid PNG header (signature + IHDR with its CRC) claiming `w × h` RGBA pixels, and no
    /// pixel data.
    fn png_header(w: u32, h: u32) -> Vec<u8> {
        let mut ihdr = b"IHDR".to_vec();
        ihdr.extend(w.to_be_bytes());
        ihdr.extend(h.to_be_bytes());
        ihdr.extend([8, 6, 0, 0, 0]);
        let crc = crc32(&ihdr);
        let mut out = b"\x89PNG\r\n\x1a\n".to_vec();
        out.extend(13u32.to_be_bytes());
        out.extend(ihdr);
        out.extend(crc.to_be_bytes());
        out
    }

    fn crc32(bytes: &[u8]) -> u32 {
        let mut c = 0xffff_ffffu32;
        for &b in bytes {
            c ^= b as u32;
            for _ in 0..8 {
                c = if c & 1 != 0 {
                    0xedb8_8320 ^ (c >> 1)
                } else {
                    c >> 1
                };
            }
        }
        !c
    }

    #[test]
    fn a_header_claiming_huge_dimensions_is_refused_before_allocating() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("huge.png");
        std::fs::write(&path, png_header(100_000, 100_000)).unwrap();
        let t = std::time::Instant::now();
        let err = decode(&path).unwrap_err();
        assert!(err.contains("too large"), "{err}");
        // refused from the header: no 40 GB buffer was asked for (that would abort or swap)
        assert!(t.elapsed().as_secs_f64() < 5.0);
    }

    #[test]
    fn a_small_picture_decodes_and_garbage_is_reported() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("ok.png");
        image::RgbaImage::from_pixel(3, 2, image::Rgba([10, 20, 30, 255]))
            .save(&path)
            .unwrap();
        let img = decode(&path).unwrap();
        assert_eq!(img.dimensions(), (3, 2));
        std::fs::write(dir.path().join("bad.png"), b"not a png").unwrap();
        assert!(decode(&dir.path().join("bad.png")).is_err());
        assert!(
            decode(&dir.path().join("missing.png"))
                .unwrap_err()
                .contains("cannot open")
        );
    }
}
