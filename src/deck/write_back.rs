//! Writing live tweaks back into the deck file as its new defaults, changing only the bytes of
//! those values: comments, formatting and every other byte stay as the lecturer wrote them.
//! The new text goes to a temporary file beside the deck, is synced, then renamed over it, so a
//! crash or a full disk never leaves a half-written deck.

use std::io::Write;
use std::path::{Path, PathBuf};

use crate::ron_tree::{self, Node, Value};

/// A new value as it goes into the file.
#[derive(Debug, Clone, PartialEq)]
pub enum NewValue {
    /// RON text as is: `0.5`, `true`, `12`.
    Raw(String),
    /// A string, written as a RON string literal (quotes and backslashes escaped).
    Str(String),
    /// The field at the path goes, with its comma (and its line, if it had one of its own).
    RemoveField,
}

/// One value to write: `param` (a [`ron_tree`] path inside the widget: `h`, `start.1`,
/// `ode.params.k`, `ode.rhs[0]`) of the widget at block path `block` (indices into the body,
/// then into columns) on the slide whose `id` is `slide`.
#[derive(Debug, Clone, PartialEq)]
pub struct ValueEdit {
    pub slide: String,
    pub block: Vec<usize>,
    pub param: String,
    pub value: NewValue,
}

/// The [`ron_tree`] path of `edit`'s value in the deck `tree`: the slide is found by its id in
/// the file as it is now (slides may have moved since it was loaded).
fn deck_path_of(tree: &Node, edit: &ValueEdit) -> Result<String, String> {
    let err = |what: &str| format!("slide \"{}\": {what}", edit.slide);
    let slides = tree
        .field("slides")
        .ok_or_else(|| err("the file has no slides"))?;
    let index = slides
        .items()
        .iter()
        .position(|s| s.field("id").and_then(Node::as_str) == Some(edit.slide.as_str()))
        .ok_or_else(|| err("no slide with this id in the file"))?;
    Ok(format!(
        "{}.{}",
        super::block_tree_path(index, &edit.block),
        edit.param
    ))
}

/// `text` (a deck) with every edit applied, changing only those values' bytes. Fails
/// (changing nothing) if a value cannot be located.
pub fn apply_edits(text: &str, edits: &[ValueEdit]) -> Result<String, String> {
    let tree =
        ron_tree::parse(text).map_err(|e| format!("the file does not parse: {}", e.message))?;
    let at: Vec<(String, NewValue)> = edits
        .iter()
        .map(|e| Ok((deck_path_of(&tree, e)?, e.value.clone())))
        .collect::<Result<_, String>>()?;
    apply_at(text, &at)
}

/// `text` with the value at each [`ron_tree`] path replaced (any RON file: a deck, a problem
/// file), changing only those bytes.
pub fn apply_at(text: &str, edits: &[(String, NewValue)]) -> Result<String, String> {
    let tree =
        ron_tree::parse(text).map_err(|e| format!("the file does not parse: {}", e.message))?;
    let mut spans: Vec<(usize, usize, String)> = Vec::new();
    for (path, value) in edits {
        if *value == NewValue::RemoveField {
            let (a, b) = field_span(text, &tree, path)?;
            spans.push((a, b, String::new()));
            continue;
        }
        let node = tree.at(path).ok_or_else(|| {
            format!(
                "`{path}` is not written in the file (only values in the file can be written back)"
            )
        })?;
        let new = match value {
            NewValue::Raw(v) => {
                if !matches!(node.value, Value::Number(_) | Value::Ident(_)) {
                    return Err(format!("`{path}` has no plain value to replace"));
                }
                v.clone()
            }
            NewValue::Str(v) => {
                if node.as_str().is_none() {
                    return Err(format!("`{path}` is not a string"));
                }
                ron_string(v)
            }
            NewValue::RemoveField => unreachable!("handled above"),
        };
        spans.push((node.span.start, node.span.end, new));
    }
    spans.sort_by_key(|s| s.0);
    let mut out = String::with_capacity(text.len());
    let mut at = 0;
    for (a, b, v) in spans {
        if a < at {
            return Err("two edits touch the same value".into());
        }
        out.push_str(&text[at..a]);
        out.push_str(&v);
        at = b;
    }
    out.push_str(&text[at..]);
    Ok(out)
}

/// The bytes to remove for the field at `path` (`exact`, `slides[2].body[0].ode.exact`): its
/// name, value and the comma after it, and the whole line when the field had it to itself.
fn field_span(text: &str, tree: &Node, path: &str) -> Result<(usize, usize), String> {
    let (parent, name) = match path.rsplit_once('.') {
        Some((parent, name)) => (tree.at(parent), name),
        None => (Some(tree), path),
    };
    let entry = parent
        .and_then(|p| p.field_entry(name))
        .ok_or_else(|| format!("`{path}` is not written in the file"))?;
    let start = entry.name_span.start;
    let mut end = entry.value.span.end;
    let after = &text[end..];
    let ws = after.len() - after.trim_start_matches([' ', '\t']).len();
    let mut start = start;
    if after[ws..].starts_with(',') {
        end += ws + 1;
    } else {
        // the last field: the comma before it goes instead
        let before = text[..start].trim_end();
        if before.ends_with(',') {
            start = before.len() - 1;
        }
    }
    let line_start = text[..start].rfind('\n').map_or(0, |i| i + 1);
    let rest = &text[end..];
    let line_end = rest.find('\n').map_or(text.len(), |i| end + i + 1);
    let alone = text[line_start..start].trim().is_empty() && text[end..line_end].trim().is_empty();
    if alone {
        return Ok((line_start, line_end));
    }
    let spaces = text[end..].len() - text[end..].trim_start_matches([' ', '\t']).len();
    Ok((start, end + spaces))
}

/// `s` as a RON string literal.
pub fn ron_string(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    out.push('"');
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            other => out.push(other),
        }
    }
    out.push('"');
    out
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn replaces_only_the_value_and_skips_strings_and_comments() {
        let text = "(slides: [\n (id: \"a\", body: [Widget(X((h: 1.0)))]),\n // id: \"b\" h: 9\n (id: \"b\", title: \"h: 3\", body: [Text(\"Widget(\"), Widget(S((h: 0.1, start: (1.0, -2.5)))), Columns([[Text(\"x\")], [Widget(S((h: 2, ode: Inline((rhs: [\"x\"])))))]])]),\n])";
        let edit = |block: Vec<usize>, p: &str, v: NewValue| ValueEdit {
            slide: "b".into(),
            block,
            param: p.into(),
            value: v,
        };
        let raw = |v: &str| NewValue::Raw(v.into());
        let out = apply_edits(
            text,
            &[
                edit(vec![1], "h", raw("0.5")),
                edit(vec![1], "start.1", raw("4.0")),
                edit(vec![2, 1, 0], "h", raw("3")),
                edit(
                    vec![2, 1, 0],
                    "ode.rhs[0]",
                    NewValue::Str("-2*x + \"q\"".into()),
                ),
            ],
        )
        .unwrap();
        assert_eq!(
            out,
            text.replace("h: 0.1", "h: 0.5")
                .replace("-2.5", "4.0")
                .replace("h: 2,", "h: 3,")
                .replace("[\"x\"]", "[\"-2*x + \\\"q\\\"\"]")
        );
        assert!(apply_edits(text, &[edit(vec![1], "turns", raw("1"))]).is_err());
        assert!(apply_edits(text, &[edit(vec![1], "start", raw("1"))]).is_err());
        let other = ValueEdit {
            slide: "zz".into(),
            ..edit(vec![1], "h", raw("1"))
        };
        assert!(
            apply_edits(text, &[other])
                .unwrap_err()
                .contains("no slide")
        );
    }

    #[test]
    fn a_removed_field_takes_its_comma_and_its_own_line() {
        let file = "(\n    vars: [\"x\"],\n    rhs: [\"-x\"],\n    exact: Some([\"exp(-t)\"]),\n    initial: [1.0],\n)\n";
        let out = apply_at(file, &[("exact".into(), NewValue::RemoveField)]).unwrap();
        assert_eq!(out, file.replace("    exact: Some([\"exp(-t)\"]),\n", ""));
        let inline = "(w: S((ode: Inline((rhs: [\"-x\"], exact: [\"exp(-t)\"], initial: [1.0])))))";
        let out = apply_at(inline, &[("w.ode.exact".into(), NewValue::RemoveField)]).unwrap();
        assert_eq!(out, inline.replace("exact: [\"exp(-t)\"], ", ""));
        let last = "(rhs: [\"-x\"], exact: [\"e\"])";
        let out = apply_at(last, &[("exact".into(), NewValue::RemoveField)]).unwrap();
        assert_eq!(out, "(rhs: [\"-x\"])");
        assert!(ron_tree::parse(&out).is_ok(), "{out}");
        assert!(apply_at(last, &[("nope".into(), NewValue::RemoveField)]).is_err());
    }
}
