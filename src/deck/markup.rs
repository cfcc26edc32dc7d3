//! The light inline markup of slide text (`Text`, `Bullets`): `*emphasis*`, `` `code` `` and
//! `$maths$` (typeset inline, like a `Math` block's source); `\$` is a literal dollar.
//! Part of the deck model: what a paragraph says, not how it is drawn.

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Inline {
    Plain,
    Emphasis,
    Code,
    /// Maths source between `$…$` (without the dollars).
    Math,
}

/// Splits `*emphasis*`, `` `code` `` and `$maths$` out of a paragraph. Every span is a slice of
/// `text` (so a formula's place in the string is known). An unmatched marker is kept as
/// literal text, so a lone `*` (as in "a * b") or `$` ("costs $5") never swallows the rest of
/// the line; `\$` is a dollar that never opens maths (inside maths it is Typst's own `\$`).
pub fn inline_spans(text: &str) -> Vec<(&str, Inline)> {
    let mut out = Vec::new();
    let mut rest = text;
    while !rest.is_empty() {
        let Some(start) = rest.find(['*', '`', '$']) else {
            out.push((rest, Inline::Plain));
            break;
        };
        let marker = rest.as_bytes()[start] as char;
        if marker == '$' && rest[..start].ends_with('\\') {
            // `\$`: the text before the backslash, then the dollar as plain text
            if start > 1 {
                out.push((&rest[..start - 1], Inline::Plain));
            }
            out.push((&rest[start..=start], Inline::Plain));
            rest = &rest[start + 1..];
            continue;
        }
        let after = &rest[start + 1..];
        let end = if marker == '$' {
            closing_dollar(after)
        } else {
            after.find(marker)
        };
        match end {
            Some(len) if len > 0 => {
                if start > 0 {
                    out.push((&rest[..start], Inline::Plain));
                }
                let kind = match marker {
                    '*' => Inline::Emphasis,
                    '`' => Inline::Code,
                    _ => Inline::Math,
                };
                out.push((&after[..len], kind));
                rest = &after[len + 1..];
            }
            _ => {
                out.push((&rest[..=start], Inline::Plain));
                rest = after;
            }
        }
    }
    out
}

/// The byte index of the `$` closing maths in `s` (the text after the opening one), skipping
/// escaped `\$`.
fn closing_dollar(s: &str) -> Option<usize> {
    let mut escaped = false;
    for (i, c) in s.char_indices() {
        match c {
            '$' if !escaped => return Some(i),
            '\\' => escaped = !escaped,
            _ => escaped = false,
        }
    }
    None
}

/// Whether `text` holds inline maths (then it is laid out run by run, not as one galley).
pub fn has_inline_math(text: &str) -> bool {
    text.contains('$') && inline_spans(text).iter().any(|(_, k)| *k == Inline::Math)
}

/// The inline formulas of `text`: each source with its 0-based character offset in `text`.
pub fn inline_formulas(text: &str) -> Vec<(&str, usize)> {
    inline_spans(text)
        .into_iter()
        .filter(|(_, k)| *k == Inline::Math)
        .map(|(src, _)| {
            let byte = src.as_ptr() as usize - text.as_ptr() as usize;
            (src, text[..byte].chars().count())
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inline_markup_splits_and_keeps_lone_markers() {
        use Inline::*;
        assert_eq!(
            inline_spans("a *b* `c` d"),
            vec![
                ("a ", Plain),
                ("b", Emphasis),
                (" ", Plain),
                ("c", Code),
                (" d", Plain)
            ]
        );
        assert_eq!(inline_spans("x * y"), vec![("x *", Plain), (" y", Plain)]);
    }

    #[test]
    fn dollars_open_maths_unless_escaped_or_alone() {
        use Inline::*;
        assert_eq!(
            inline_spans("where $h$ is the step, $x_0 = 1$."),
            vec![
                ("where ", Plain),
                ("h", Math),
                (" is the step, ", Plain),
                ("x_0 = 1", Math),
                (".", Plain)
            ]
        );
        assert_eq!(
            inline_spans(r"costs \$5 or $a \$ b$"),
            vec![
                ("costs ", Plain),
                ("$", Plain),
                ("5 or ", Plain),
                (r"a \$ b", Math)
            ]
        );
        assert_eq!(
            inline_spans("costs $5"),
            vec![("costs $", Plain), ("5", Plain)]
        );
        assert_eq!(inline_spans("`$x$`"), vec![("$x$", Code)]);
        assert!(!has_inline_math("costs $5") && has_inline_math("a $b$"));
        let text = "ω: $omega$ and $h^2$";
        assert_eq!(inline_formulas(text), vec![("omega", 4), ("h^2", 16)]);
    }
}
