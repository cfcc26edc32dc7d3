//! Writing live tweaks back into the deck file as its new defaults, changing only the bytes of
//! those values: comments, formatting and every other byte stay as the lecturer wrote them.
//! The new text goes to a temporary file beside the deck, is synced, then renamed over it, so a
//! crash or a full disk never leaves a half-written deck.

use std::io::Write;
use std::path::{Path, PathBuf};

/// One value to write: parameter `param` (e.g. `h`, or `start.1` for the second element of the
/// tuple `start`) of the `widget`-th `Widget(...)` (0-based, in file order) on slide `slide`.
#[derive(Debug, Clone, PartialEq)]
pub struct ValueEdit {
    pub slide: String,
    pub widget: usize,
    pub param: String,
    /// The new value as RON text (`0.5`, `true`, `12`).
    pub value: String,
}

/// `text` with every edit applied. Fails (changing nothing) if a value cannot be located.
pub fn apply_edits(text: &str, edits: &[ValueEdit]) -> Result<String, String> {
    let code = code_mask(text);
    let mut spans: Vec<(usize, usize, &str)> = Vec::new();
    for e in edits {
        let (a, b) = locate(text, &code, e)?;
        spans.push((a, b, e.value.as_str()));
    }
    spans.sort_by_key(|s| s.0);
    let mut out = String::with_capacity(text.len());
    let mut at = 0;
    for (a, b, v) in spans {
        if a < at {
            return Err("two edits touch the same value".into());
        }
        out.push_str(&text[at..a]);
        out.push_str(v);
        at = b;
    }
    out.push_str(&text[at..]);
    Ok(out)
}

/// Writes `text` to `path` atomically: temp file beside it, synced, renamed over. `write` does
/// the temp-file write (tests inject failures); on any failure the temp file is removed and the
/// original is untouched.
pub fn write_atomic_with(
    path: &Path,
    text: &str,
    write: impl FnOnce(&Path, &[u8]) -> std::io::Result<()>,
) -> std::io::Result<()> {
    let tmp = temp_path(path);
    let result = write(&tmp, text.as_bytes()).and_then(|()| std::fs::rename(&tmp, path));
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

/// [`write_atomic_with`] with a real, synced write.
pub fn write_atomic(path: &Path, text: &str) -> std::io::Result<()> {
    write_atomic_with(path, text, |tmp, bytes| {
        let mut f = std::fs::File::create(tmp)?;
        f.write_all(bytes)?;
        f.sync_all()
    })
}

fn temp_path(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    path.with_file_name(format!(".{name}.lectern-tmp"))
}

/// For each byte: is it code (not inside a string or comment)?
fn code_mask(text: &str) -> Vec<bool> {
    let b = text.as_bytes();
    let mut mask = vec![true; b.len()];
    let mut i = 0;
    while i < b.len() {
        let start = i;
        if b[i] == b'/' && b.get(i + 1) == Some(&b'/') {
            while i < b.len() && b[i] != b'\n' {
                i += 1;
            }
        } else if b[i] == b'/' && b.get(i + 1) == Some(&b'*') {
            i += 2;
            while i + 1 < b.len() && !(b[i] == b'*' && b[i + 1] == b'/') {
                i += 1;
            }
            i = (i + 2).min(b.len());
        } else if b[i] == b'r' && matches!(b.get(i + 1), Some(b'#') | Some(b'"')) {
            let mut hashes = 0;
            let mut j = i + 1;
            while b.get(j) == Some(&b'#') {
                hashes += 1;
                j += 1;
            }
            if b.get(j) != Some(&b'"') {
                i += 1;
                continue;
            }
            j += 1;
            let close: Vec<u8> = std::iter::once(b'"')
                .chain(std::iter::repeat_n(b'#', hashes))
                .collect();
            while j < b.len() && !b[j..].starts_with(&close) {
                j += 1;
            }
            i = (j + close.len()).min(b.len());
        } else if b[i] == b'"' {
            i += 1;
            while i < b.len() && b[i] != b'"' {
                if b[i] == b'\\' {
                    i += 1;
                }
                i += 1;
            }
            i = (i + 1).min(b.len());
        } else {
            i += 1;
            continue;
        }
        mask[start..i].iter_mut().for_each(|m| *m = false);
    }
    mask
}

/// Byte offset of the bracket closing the one at `open`, skipping non-code.
fn matching(text: &[u8], code: &[bool], open: usize) -> Option<usize> {
    let mut depth = 0i32;
    for i in open..text.len() {
        if !code[i] {
            continue;
        }
        match text[i] {
            b'(' | b'[' | b'{' => depth += 1,
            b')' | b']' | b'}' => {
                depth -= 1;
                if depth == 0 {
                    return Some(i);
                }
            }
            _ => {}
        }
    }
    None
}

fn is_ident(c: u8) -> bool {
    c.is_ascii_alphanumeric() || c == b'_'
}

/// Code positions in `lo..hi` where the identifier `word` starts (whole word).
fn find_word(text: &[u8], code: &[bool], word: &str, lo: usize, hi: usize) -> Vec<usize> {
    let w = word.as_bytes();
    (lo..hi.saturating_sub(w.len() - 1))
        .filter(|&i| {
            code[i]
                && text[i..].starts_with(w)
                && (i == 0 || !is_ident(text[i - 1]))
                && text.get(i + w.len()).is_none_or(|c| !is_ident(*c))
        })
        .collect()
}

fn skip_ws(text: &[u8], mut i: usize) -> usize {
    while i < text.len() && text[i].is_ascii_whitespace() {
        i += 1;
    }
    i
}

/// The span of the scalar value of `edit` in the file.
fn locate(text: &str, code: &[bool], edit: &ValueEdit) -> Result<(usize, usize), String> {
    let b = text.as_bytes();
    let err = |what: &str| format!("slide \"{}\": {what}", edit.slide);
    // The slide: the tuple around `id: "<slide>"`.
    let quoted = format!("\"{}\"", edit.slide);
    let id_at = find_word(b, code, "id", 0, b.len())
        .into_iter()
        .find(|&i| {
            let j = skip_ws(b, i + 2);
            b.get(j) == Some(&b':') && {
                let k = skip_ws(b, j + 1);
                let k = if text[k..].starts_with("Some(") {
                    k + 5
                } else {
                    k
                };
                text[k..].starts_with(&quoted)
            }
        })
        .ok_or_else(|| err("no slide with this id in the file"))?;
    let mut depth = 0i32;
    let open = (0..id_at)
        .rev()
        .find(|&i| {
            if !code[i] {
                return false;
            }
            match b[i] {
                b')' | b']' | b'}' => depth += 1,
                b'(' | b'[' | b'{' => {
                    if depth == 0 {
                        return true;
                    }
                    depth -= 1;
                }
                _ => {}
            }
            false
        })
        .ok_or_else(|| err("cannot find where the slide starts"))?;
    let close = matching(b, code, open).ok_or_else(|| err("unbalanced brackets"))?;
    // The widget: the n-th `Widget(` in the slide.
    let w = find_word(b, code, "Widget", open, close)
        .into_iter()
        .filter(|&i| b.get(skip_ws(b, i + 6)) == Some(&b'('))
        .nth(edit.widget)
        .ok_or_else(|| err(&format!("no widget number {}", edit.widget + 1)))?;
    let w_open = skip_ws(b, w + 6);
    let w_close = matching(b, code, w_open).ok_or_else(|| err("unbalanced widget"))?;
    // The field, then the tuple element if the id has one (`start.1`).
    let mut parts = edit.param.split('.');
    let field = parts.next().unwrap_or_default();
    let f = find_word(b, code, field, w_open, w_close)
        .into_iter()
        .find(|&i| b.get(skip_ws(b, i + field.len())) == Some(&b':'))
        .ok_or_else(|| {
            err(&format!(
                "`{field}` is not written in the widget (only values in the file can be written back)"
            ))
        })?;
    let mut v = skip_ws(b, skip_ws(b, f + field.len()) + 1);
    for idx in parts {
        let idx: usize = idx
            .parse()
            .map_err(|_| err(&format!("bad parameter id {}", edit.param)))?;
        if b.get(v) != Some(&b'(') && b.get(v) != Some(&b'[') {
            return Err(err(&format!("`{field}` is not a tuple")));
        }
        let end = matching(b, code, v).ok_or_else(|| err("unbalanced tuple"))?;
        let mut depth = 0;
        let mut element = 0;
        let mut start = v + 1;
        for i in v + 1..end {
            if !code[i] {
                continue;
            }
            match b[i] {
                b'(' | b'[' | b'{' => depth += 1,
                b')' | b']' | b'}' => depth -= 1,
                b',' if depth == 0 => {
                    if element == idx {
                        break;
                    }
                    element += 1;
                    start = i + 1;
                }
                _ => {}
            }
        }
        if element != idx {
            return Err(err(&format!("`{field}` has no element {idx}")));
        }
        v = skip_ws(b, start);
    }
    let mut end = v;
    while end < b.len() && (is_ident(b[end]) || matches!(b[end], b'.' | b'-' | b'+')) {
        end += 1;
    }
    if end == v {
        return Err(err(&format!(
            "`{}` has no plain value to replace",
            edit.param
        )));
    }
    Ok((v, end))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn replaces_only_the_value_and_skips_strings_and_comments() {
        let text = "(slides: [\n (id: \"a\", body: [Widget(X((h: 1.0)))]),\n // id: \"b\" h: 9\n (id: \"b\", title: \"h: 3\", body: [Text(\"Widget(\"), Widget(S((h: 0.1, start: (1.0, -2.5)))), Widget(S((h: 2)))]),\n])";
        let edit = |w, p: &str, v: &str| ValueEdit {
            slide: "b".into(),
            widget: w,
            param: p.into(),
            value: v.into(),
        };
        let out = apply_edits(
            text,
            &[
                edit(0, "h", "0.5"),
                edit(0, "start.1", "4.0"),
                edit(1, "h", "3"),
            ],
        )
        .unwrap();
        assert_eq!(
            out,
            text.replace("h: 0.1", "h: 0.5")
                .replace("-2.5", "4.0")
                .replace("h: 2)", "h: 3)")
        );
        assert!(apply_edits(text, &[edit(0, "turns", "1")]).is_err());
    }
}
