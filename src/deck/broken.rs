//! One broken slide never takes the deck down: when the deck does not parse as a whole but its
//! RON is well formed, each slide is parsed on its own; a slide that fails is replaced by an
//! error slide (its title, `file:line:col` and the message) and every other slide loads.
//! `lectern check` still reports the fault, and `lectern export` exits non-zero for it unless
//! `--keep-going`.

use std::path::Path;

use super::{Block, Slide};
use crate::diag::Diagnostic;
use crate::ron_tree::{self, Node};

/// RON options the deck is read with.
pub fn ron_options() -> ron::Options {
    ron::Options::default().with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME)
}

/// A slide that did not load: its index and why, at the deck's line and column.
#[derive(Debug, Clone, PartialEq)]
pub struct BrokenSlide {
    pub slide: usize,
    pub diagnostic: Diagnostic,
}

/// The deck `text` with every slide that does not parse on its own blanked out (replaced by a
/// minimal slide padded to the same bytes and lines, so every other value keeps its line,
/// column and byte offset), and why each failed. `None` when no single slide is at fault (the
/// text is not well-formed RON, or every slide parses: the fault is in a deck-level field).
pub fn blank_broken_slides(text: &str, file: &Path) -> Option<(String, Vec<BrokenSlide>)> {
    let tree = ron_tree::parse(text).ok()?;
    let slides = tree.field("slides")?.items();
    let mut out = text.to_owned();
    let mut broken = Vec::new();
    for (i, node) in slides.iter().enumerate() {
        let src = &text[node.span.clone()];
        let Err(e) = ron_options().from_str::<Slide>(src) else {
            continue;
        };
        let placeholder = "(title:\"\")";
        if src.len() < placeholder.len() {
            return None;
        }
        let (line0, col0) = ron_tree::line_col(text, node.span.start);
        let mut d = super::load::at_token(src, Diagnostic::from_ron(file, &e));
        // the error's position is in the slide's own text: move it into the deck's
        if d.line == 1 {
            d.col += col0 - 1;
        }
        if d.line > 0 {
            d.line += line0 - 1;
        }
        d.message = format!("slide {} does not load: {}", i + 1, d.message);
        broken.push(BrokenSlide {
            slide: i,
            diagnostic: d,
        });
        let mut blank = String::from(placeholder);
        for c in src[placeholder.len()..].chars() {
            if c == '\n' {
                blank.push('\n');
            } else {
                blank.extend(std::iter::repeat_n(' ', c.len_utf8()));
            }
        }
        out.replace_range(node.span.clone(), &blank);
    }
    (!broken.is_empty()).then_some((out, broken))
}

/// The slide shown in place of a broken one: the title and id it was written with (when they
/// can be read), and the problem as text, so the room and the presenter see what is wrong.
pub fn error_slide(node: Option<&Node>, broken: &BrokenSlide) -> Slide {
    let string = |name: &str| {
        node.and_then(|n| n.field(name))
            .map(Node::without_some)
            .and_then(Node::as_str)
            .map(str::to_owned)
    };
    let title = string("title").unwrap_or_else(|| format!("Slide {}", broken.slide + 1));
    Slide {
        id: string("id"),
        title: format!("⚠ {title}"),
        layout: Default::default(),
        body: vec![
            Block::Text("This slide does not load; every other slide does.".into()),
            Block::Text(broken.diagnostic.to_string().into()),
        ],
        notes: format!("Fix the file and save: {}", broken.diagnostic),
        handout: String::new(),
        seconds: None,
        skip: false,
    }
}
