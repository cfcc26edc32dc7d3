//! The light inline markup of slide text (`Text`, `Bullets`): `*emphasis*` and `` `code` ``.
//! Part of the deck model: what a paragraph says, not how it is drawn.

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Inline {
    Plain,
    Emphasis,
    Code,
}

/// Splits `*emphasis*` and `` `code` `` out of a paragraph. An unmatched marker is kept as
/// literal text, so a lone `*` (as in "a * b") never swallows the rest of the line.
pub fn inline_spans(text: &str) -> Vec<(&str, Inline)> {
    let mut out = Vec::new();
    let mut rest = text;
    while !rest.is_empty() {
        let next = rest.find(['*', '`']);
        let Some(start) = next else {
            out.push((rest, Inline::Plain));
            break;
        };
        let marker = rest.as_bytes()[start] as char;
        let after = &rest[start + 1..];
        match after.find(marker) {
            Some(len) if len > 0 => {
                if start > 0 {
                    out.push((&rest[..start], Inline::Plain));
                }
                let kind = if marker == '*' {
                    Inline::Emphasis
                } else {
                    Inline::Code
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
}
