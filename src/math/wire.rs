//! The typesetting worker's pipe protocol: length-prefixed little-endian frames, one request
//! in and one answer out at a time. Small and hand-written so the child needs nothing but std.
//!
//! ```text
//! request:  u32 len | u8 syntax | u8 style | f32 size_px | [u8; 4] rgba | utf-8 source (rest)
//! answer:   u32 len | u8 tag (0 formula, 1 error, 2 ready) | body
//!   formula: u32 width | u32 height | u32 baseline | rgba bytes (rest)
//!   error:   u32 column + 1 (0: none) | utf-8 message (rest)
//!   ready:   utf-8 protocol version (rest)
//! ```

use std::io::{self, Read, Write};

use super::typeset::{MathError, MathStyle, MathSyntax, RenderedFormula, render_math};

/// Bumped when a frame's layout changes: a stale worker binary is then refused at start.
pub const VERSION: &str = "lectern-typeset-2";

/// Largest frame accepted, either way: a 64 MB formula source or picture is not a formula.
const MAX_FRAME: usize = 64 << 20;

pub use super::formula::Request;

impl Request {
    /// Typesets it here, in this process (the worker's job, or the pool's in-process fallback).
    pub fn render(&self) -> Result<RenderedFormula, MathError> {
        render_math(&self.src, self.syntax, self.style, self.size_px, self.rgba)
    }
}

/// What comes back from a worker.
#[derive(Debug, Clone, PartialEq)]
pub enum Answer {
    Ready(String),
    Done(Result<RenderedFormula, MathError>),
}

fn put_u32(out: &mut Vec<u8>, v: u32) {
    out.extend(v.to_le_bytes());
}

fn frame(w: &mut impl Write, body: &[u8]) -> io::Result<()> {
    if body.len() > MAX_FRAME {
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            "frame too large",
        ));
    }
    w.write_all(&(body.len() as u32).to_le_bytes())?;
    w.write_all(body)?;
    w.flush()
}

/// Reads one frame's body; `Ok(None)` at a clean end of stream (the other side closed).
fn read_frame(r: &mut impl Read) -> io::Result<Option<Vec<u8>>> {
    let mut len = [0u8; 4];
    match r.read_exact(&mut len) {
        Ok(()) => {}
        Err(e) if e.kind() == io::ErrorKind::UnexpectedEof => return Ok(None),
        Err(e) => return Err(e),
    }
    let len = u32::from_le_bytes(len) as usize;
    if len > MAX_FRAME {
        return Err(bad("frame too large"));
    }
    let mut body = vec![0u8; len];
    r.read_exact(&mut body)?;
    Ok(Some(body))
}

fn bad(what: &str) -> io::Error {
    io::Error::new(
        io::ErrorKind::InvalidData,
        format!("typeset worker: {what}"),
    )
}

fn u32_at(b: &[u8], at: usize) -> io::Result<u32> {
    b.get(at..at + 4)
        .map(|s| u32::from_le_bytes([s[0], s[1], s[2], s[3]]))
        .ok_or_else(|| bad("short frame"))
}

fn text(b: &[u8]) -> io::Result<String> {
    String::from_utf8(b.to_vec()).map_err(|_| bad("text is not UTF-8"))
}

pub fn write_request(w: &mut impl Write, req: &Request) -> io::Result<()> {
    let mut body = Vec::with_capacity(10 + req.src.len());
    body.push(match req.syntax {
        MathSyntax::Typst => 0,
        MathSyntax::Latex => 1,
    });
    body.push(match req.style {
        MathStyle::Display => 0,
        MathStyle::Inline => 1,
    });
    body.extend(req.size_px.to_le_bytes());
    body.extend(req.rgba);
    body.extend(req.src.as_bytes());
    frame(w, &body)
}

pub fn read_request(r: &mut impl Read) -> io::Result<Option<Request>> {
    let Some(b) = read_frame(r)? else {
        return Ok(None);
    };
    if b.len() < 10 {
        return Err(bad("short request"));
    }
    let syntax = match b[0] {
        0 => MathSyntax::Typst,
        1 => MathSyntax::Latex,
        _ => return Err(bad("unknown syntax")),
    };
    let style = match b[1] {
        0 => MathStyle::Display,
        1 => MathStyle::Inline,
        _ => return Err(bad("unknown style")),
    };
    Ok(Some(Request {
        syntax,
        style,
        size_px: f32::from_bits(u32_at(&b, 2)?),
        rgba: [b[6], b[7], b[8], b[9]],
        src: text(&b[10..])?,
    }))
}

pub fn write_answer(w: &mut impl Write, answer: &Answer) -> io::Result<()> {
    let mut body = Vec::new();
    match answer {
        Answer::Done(Ok(f)) => {
            body.reserve(13 + f.rgba_premultiplied.len());
            body.push(0);
            put_u32(&mut body, f.width);
            put_u32(&mut body, f.height);
            put_u32(&mut body, f.baseline);
            body.extend(&f.rgba_premultiplied);
        }
        Answer::Done(Err(e)) => {
            body.push(1);
            put_u32(&mut body, e.col.map_or(0, |c| c as u32 + 1));
            body.extend(e.message.as_bytes());
        }
        Answer::Ready(version) => {
            body.push(2);
            body.extend(version.as_bytes());
        }
    }
    frame(w, &body)
}

pub fn read_answer(r: &mut impl Read) -> io::Result<Option<Answer>> {
    let Some(b) = read_frame(r)? else {
        return Ok(None);
    };
    let answer = match b.first() {
        Some(0) => {
            let (width, height) = (u32_at(&b, 1)?, u32_at(&b, 5)?);
            let baseline = u32_at(&b, 9)?;
            let rgba = b[13..].to_vec();
            if rgba.len() as u64 != width as u64 * height as u64 * 4 {
                return Err(bad("picture size does not match its bytes"));
            }
            Answer::Done(Ok(RenderedFormula {
                width,
                height,
                baseline,
                rgba_premultiplied: rgba,
            }))
        }
        Some(1) => {
            let col = u32_at(&b, 1)?;
            Answer::Done(Err(MathError {
                message: text(&b[5..])?,
                col: (col > 0).then(|| col as usize - 1),
            }))
        }
        Some(2) => Answer::Ready(text(&b[1..])?),
        _ => return Err(bad("unknown answer")),
    };
    Ok(Some(answer))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_round_trip() {
        let req = Request {
            src: "x^2 + ω".into(),
            syntax: MathSyntax::Latex,
            style: MathStyle::Inline,
            size_px: 41.5,
            rgba: [1, 2, 3, 4],
        };
        let mut buf = Vec::new();
        write_request(&mut buf, &req).unwrap();
        write_request(&mut buf, &req).unwrap();
        let mut r = buf.as_slice();
        assert_eq!(read_request(&mut r).unwrap(), Some(req.clone()));
        assert_eq!(read_request(&mut r).unwrap(), Some(req));
        assert_eq!(read_request(&mut r).unwrap(), None, "clean end");

        for answer in [
            Answer::Ready(VERSION.into()),
            Answer::Done(Ok(RenderedFormula {
                width: 2,
                height: 1,
                baseline: 1,
                rgba_premultiplied: vec![9; 8],
            })),
            Answer::Done(Err(MathError {
                message: "unknown variable: q".into(),
                col: Some(0),
            })),
            Answer::Done(Err(MathError {
                message: "no column".into(),
                col: None,
            })),
        ] {
            let mut buf = Vec::new();
            write_answer(&mut buf, &answer).unwrap();
            assert_eq!(read_answer(&mut buf.as_slice()).unwrap(), Some(answer));
        }
    }

    #[test]
    fn truncated_or_lying_frames_are_errors() {
        let mut buf = Vec::new();
        write_answer(
            &mut buf,
            &Answer::Done(Ok(RenderedFormula {
                width: 3,
                height: 3,
                baseline: 2,
                rgba_premultiplied: vec![0; 36],
            })),
        )
        .unwrap();
        assert!(read_answer(&mut &buf[..buf.len() - 1]).is_err());
        // a picture whose bytes do not match its size
        let mut body = vec![0u8];
        body.extend(100u32.to_le_bytes());
        body.extend(100u32.to_le_bytes());
        body.extend(50u32.to_le_bytes());
        let mut lying = Vec::new();
        frame(&mut lying, &body).unwrap();
        assert!(read_answer(&mut lying.as_slice()).is_err());
        // a length beyond the limit is refused before allocating it
        let huge = (u32::MAX).to_le_bytes();
        assert!(read_request(&mut huge.as_slice()).is_err());
    }
}
