//! A RON syntax tree with byte spans, so that an error found *after* serde has parsed a file
//! (a bad expression inside a string, a missing image, a value out of range) can point at the
//! value's own line and column, and so that a write-back can replace exactly that value's bytes.
//!
//! serde and `ron` give values without positions; this reads the same text a second time into
//! [`Node`]s that keep where each value, field name and string content sits. It is only used on
//! text `ron` has already accepted, so it is lenient and small: no type checking, numbers kept
//! as their text.
//!
//! ```text
//! let tree = ron_tree::parse(text)?;
//! let rhs0 = tree.at("slides[3].body[1].ode.rhs[0]");   // through Widget(..), Inline(..), Some(..)
//! let (line, col) = ron_tree::line_col(text, rhs0.unwrap().str_offset(text, 7).unwrap());
//! ```

use std::ops::Range;

/// One value and the bytes it spans (from its first to its last character, names included).
#[derive(Debug, Clone, PartialEq)]
pub struct Node {
    pub span: Range<usize>,
    pub value: Value,
}

#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    /// A bare identifier: `true`, `None`, `Euler`, `inf`, a unit enum variant.
    Ident(String),
    /// A number, as written (`-0.5`, `1e-3`, `0x1F`).
    Number(String),
    /// A string literal; `content` is the span between the quotes.
    Str {
        value: String,
        content: Range<usize>,
        raw: bool,
    },
    /// A character literal, as written between the quotes.
    Char(String),
    /// `Name(a, b)` or `(a, b)`: tuples, tuple structs, newtype and tuple enum variants, `Some(x)`.
    Seq {
        name: Option<String>,
        items: Vec<Node>,
    },
    /// `Name(key: value, …)` or `(key: value, …)`: structs and struct enum variants.
    Struct {
        name: Option<String>,
        fields: Vec<Field>,
    },
    /// `[a, b]`
    List(Vec<Node>),
    /// `{k: v}`
    Map(Vec<(Node, Node)>),
}

#[derive(Debug, Clone, PartialEq)]
pub struct Field {
    pub name: String,
    pub name_span: Range<usize>,
    pub value: Node,
}

/// Where parsing stopped and why (the text was not RON this reader understands).
#[derive(Debug, Clone, PartialEq)]
pub struct ParseError {
    pub offset: usize,
    pub message: String,
}

/// Parses RON text into a tree. Leading `#![enable(...)]` attributes are skipped.
pub fn parse(text: &str) -> Result<Node, ParseError> {
    let mut p = Parser {
        s: text,
        b: text.as_bytes(),
        i: 0,
    };
    p.skip_trivia();
    while p.b[p.i..].starts_with(b"#!") {
        p.skip_balanced_attribute()?;
        p.skip_trivia();
    }
    let node = p.value()?;
    p.skip_trivia();
    if p.i < p.b.len() {
        return Err(p.err("unexpected text after the value"));
    }
    Ok(node)
}

/// 1-based line and column (in characters) of byte `offset` in `text`.
pub fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, col)
}

/// One step of a path: a field name or an index into a list or tuple.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Seg<'a> {
    Field(&'a str),
    Index(usize),
}

/// Splits `a.b[2].c.1` into segments (a numeric segment after a dot is an index).
pub fn path_segments(path: &str) -> Option<Vec<Seg<'_>>> {
    let mut out = Vec::new();
    for part in path.split('.').filter(|p| !p.is_empty()) {
        let (head, mut rest) = match part.find('[') {
            Some(k) => (&part[..k], &part[k..]),
            None => (part, ""),
        };
        if !head.is_empty() {
            match head.parse::<usize>() {
                Ok(i) => out.push(Seg::Index(i)),
                Err(_) => out.push(Seg::Field(head)),
            }
        }
        while let Some(stripped) = rest.strip_prefix('[') {
            let end = stripped.find(']')?;
            out.push(Seg::Index(stripped[..end].trim().parse().ok()?));
            rest = &stripped[end + 1..];
        }
        if !rest.is_empty() {
            return None;
        }
    }
    Some(out)
}

impl Node {
    /// The enum variant or struct name written before the parentheses, if any.
    pub fn name(&self) -> Option<&str> {
        match &self.value {
            Value::Seq { name, .. } | Value::Struct { name, .. } => name.as_deref(),
            Value::Ident(s) => Some(s),
            _ => None,
        }
    }

    /// The only item of a one-item `Name(x)` or `(x)`: a newtype variant, `Some(x)`.
    fn newtype_inner(&self) -> Option<&Node> {
        match &self.value {
            Value::Seq { items, .. } if items.len() == 1 => Some(&items[0]),
            _ => None,
        }
    }

    /// The value of field `name`, looking through newtype wrappers (`Some(..)`, `Widget(..)`,
    /// `SlopeField((..))`) until a struct with that field is found. A value written as
    /// `Some(x)` (the deck allows both `id: "a"` and `id: Some("a")`) is returned as `x`.
    pub fn field(&self, name: &str) -> Option<&Node> {
        let found = match &self.value {
            Value::Struct { fields, .. } => {
                fields.iter().find(|f| f.name == name).map(|f| &f.value)
            }
            Value::Map(entries) => entries
                .iter()
                .find(|(k, _)| k.as_str() == Some(name))
                .map(|(_, v)| v),
            _ => return self.newtype_inner()?.field(name),
        };
        found.map(Node::without_some)
    }

    /// `x` for `Some(x)`, else the node itself.
    pub fn without_some(&self) -> &Node {
        match &self.value {
            Value::Seq {
                name: Some(n),
                items,
            } if n == "Some" && items.len() == 1 => items[0].without_some(),
            _ => self,
        }
    }

    /// The field entry itself (for the span of its name).
    pub fn field_entry(&self, name: &str) -> Option<&Field> {
        match &self.value {
            Value::Struct { fields, .. } => fields.iter().find(|f| f.name == name),
            _ => self.newtype_inner()?.field_entry(name),
        }
    }

    /// Item `i` of a list or tuple; through a newtype wrapper around a list or tuple
    /// (`Columns([..])`, `Some([..])`).
    pub fn index(&self, i: usize) -> Option<&Node> {
        match &self.value {
            Value::List(items) => items.get(i),
            Value::Seq { items, .. } if items.len() != 1 => items.get(i),
            Value::Seq { items, .. } => {
                let inner = &items[0];
                match inner.value {
                    Value::List(_) | Value::Seq { name: None, .. } => inner.index(i),
                    _ if i == 0 => Some(inner),
                    _ => None,
                }
            }
            _ => None,
        }
    }

    /// The node at `path` (`slides[3].body[1].ode.rhs[0]`, `start.1`), or `None`.
    pub fn at(&self, path: &str) -> Option<&Node> {
        let mut node = self;
        for seg in path_segments(path)? {
            node = match seg {
                Seg::Field(f) => node.field(f)?,
                Seg::Index(i) => node.index(i)?,
            };
        }
        Some(node)
    }

    /// The string's value if this is a string literal.
    pub fn as_str(&self) -> Option<&str> {
        match &self.value {
            Value::Str { value, .. } => Some(value),
            _ => None,
        }
    }

    /// The items of a list, or of a tuple (looking through one newtype wrapper).
    pub fn items(&self) -> &[Node] {
        match &self.value {
            Value::List(items) => items,
            Value::Seq { items, .. } if items.len() != 1 => items,
            Value::Seq { items, .. } => match &items[0].value {
                Value::List(inner) => inner,
                _ => items,
            },
            _ => &[],
        }
    }

    /// Byte offset in the file of character `char_offset` of a string's value (escapes in a
    /// normal string are walked, so `"a\"b"` maps value char 2 to the `b`). For a non-string,
    /// the start of the node.
    pub fn str_offset(&self, text: &str, char_offset: usize) -> Option<usize> {
        let Value::Str { content, raw, .. } = &self.value else {
            return Some(self.span.start);
        };
        let src = text.get(content.clone())?;
        if *raw {
            let at = src
                .char_indices()
                .nth(char_offset)
                .map_or(src.len(), |(i, _)| i);
            return Some(content.start + at);
        }
        let mut produced = 0;
        let mut it = src.char_indices().peekable();
        while let Some((i, c)) = it.next() {
            if produced == char_offset {
                return Some(content.start + i);
            }
            if c == '\\' {
                match it.next() {
                    Some((_, 'u')) => {
                        // \u{XXXX}: one character
                        for (_, c) in it.by_ref() {
                            if c == '}' {
                                break;
                            }
                        }
                    }
                    Some((_, 'x')) => {
                        it.next();
                        it.next();
                    }
                    _ => {}
                }
            }
            produced += 1;
        }
        Some(content.end)
    }

    /// 1-based (line, column) where this node starts.
    pub fn line_col(&self, text: &str) -> (usize, usize) {
        line_col(text, self.span.start)
    }
}

struct Parser<'a> {
    s: &'a str,
    b: &'a [u8],
    i: usize,
}

impl Parser<'_> {
    fn err(&self, message: &str) -> ParseError {
        ParseError {
            offset: self.i,
            message: message.into(),
        }
    }

    fn peek(&self) -> Option<u8> {
        self.b.get(self.i).copied()
    }

    fn skip_trivia(&mut self) {
        loop {
            while self.peek().is_some_and(|c| c.is_ascii_whitespace()) {
                self.i += 1;
            }
            if self.b[self.i..].starts_with(b"//") {
                while self.peek().is_some_and(|c| c != b'\n') {
                    self.i += 1;
                }
            } else if self.b[self.i..].starts_with(b"/*") {
                // block comments nest in RON
                let mut depth = 0;
                while self.i < self.b.len() {
                    if self.b[self.i..].starts_with(b"/*") {
                        depth += 1;
                        self.i += 2;
                    } else if self.b[self.i..].starts_with(b"*/") {
                        depth -= 1;
                        self.i += 2;
                        if depth == 0 {
                            break;
                        }
                    } else {
                        self.i += 1;
                    }
                }
            } else {
                return;
            }
        }
    }

    fn skip_balanced_attribute(&mut self) -> Result<(), ParseError> {
        self.i += 2;
        if self.peek() != Some(b'[') {
            return Err(self.err("expected `[` after `#!`"));
        }
        let mut depth = 0;
        while let Some(c) = self.peek() {
            self.i += 1;
            match c {
                b'[' => depth += 1,
                b']' => {
                    depth -= 1;
                    if depth == 0 {
                        return Ok(());
                    }
                }
                _ => {}
            }
        }
        Err(self.err("unclosed attribute"))
    }

    fn ident(&mut self) -> Option<String> {
        let start = self.i;
        if self.b[self.i..].starts_with(b"r#") {
            self.i += 2;
        }
        let body = self.i;
        while self
            .peek()
            .is_some_and(|c| c.is_ascii_alphanumeric() || c == b'_' || c >= 0x80)
        {
            // identifiers may be Unicode (XID); take whole UTF-8 sequences
            self.i += 1;
        }
        while !self.s.is_char_boundary(self.i) {
            self.i += 1;
        }
        if self.i == body {
            self.i = start;
            return None;
        }
        Some(self.s[body..self.i].to_string())
    }

    fn value(&mut self) -> Result<Node, ParseError> {
        self.skip_trivia();
        let start = self.i;
        let c = self.peek().ok_or_else(|| self.err("expected a value"))?;
        let value = match c {
            b'"' => self.string(false)?,
            b'r' if matches!(self.b.get(self.i + 1), Some(b'"') | Some(b'#'))
                && self.raw_string_ahead() =>
            {
                self.string(true)?
            }
            b'b' if self.b.get(self.i + 1) == Some(&b'"') => {
                self.i += 1;
                self.string(false)?
            }
            b'\'' => self.char_lit()?,
            b'[' => {
                self.i += 1;
                Value::List(self.items(b']')?)
            }
            b'{' => self.map()?,
            b'(' => self.parens(None)?,
            b'0'..=b'9' | b'-' | b'+' | b'.' => self.number(),
            _ => {
                let name = self.ident().ok_or_else(|| self.err("expected a value"))?;
                self.skip_trivia();
                if self.peek() == Some(b'(') {
                    self.parens(Some(name))?
                } else if matches!(name.as_str(), "inf" | "NaN") {
                    Value::Number(name)
                } else {
                    Value::Ident(name)
                }
            }
        };
        Ok(Node {
            span: start..self.i,
            value,
        })
    }

    /// `r"…"` or `r#"…"#` starts here (as opposed to an identifier such as `rk4` or `r#type`).
    fn raw_string_ahead(&self) -> bool {
        let mut j = self.i + 1;
        while self.b.get(j) == Some(&b'#') {
            j += 1;
        }
        self.b.get(j) == Some(&b'"')
    }

    fn string(&mut self, raw: bool) -> Result<Value, ParseError> {
        if raw {
            self.i += 1;
            let mut hashes = 0;
            while self.peek() == Some(b'#') {
                hashes += 1;
                self.i += 1;
            }
            self.i += 1; // the quote
            let content_start = self.i;
            let close: Vec<u8> = std::iter::once(b'"')
                .chain(std::iter::repeat_n(b'#', hashes))
                .collect();
            while self.i < self.b.len() && !self.b[self.i..].starts_with(&close) {
                self.i += 1;
            }
            if self.i >= self.b.len() {
                return Err(self.err("unclosed raw string"));
            }
            let content = content_start..self.i;
            self.i += close.len();
            return Ok(Value::Str {
                value: self.s[content.clone()].to_string(),
                content,
                raw: true,
            });
        }
        self.i += 1;
        let content_start = self.i;
        let mut value = String::new();
        loop {
            let rest = &self.s[self.i..];
            let mut chars = rest.chars();
            let c = chars.next().ok_or_else(|| self.err("unclosed string"))?;
            match c {
                '"' => break,
                '\\' => {
                    let e = chars.next().ok_or_else(|| self.err("unclosed string"))?;
                    self.i += 1 + e.len_utf8();
                    match e {
                        'n' => value.push('\n'),
                        't' => value.push('\t'),
                        'r' => value.push('\r'),
                        '0' => value.push('\0'),
                        'u' => {
                            let body = &self.s[self.i..];
                            let end = body.find('}').ok_or_else(|| self.err("bad \\u escape"))?;
                            let hex = body[..end].trim_start_matches('{');
                            let ch = u32::from_str_radix(hex, 16)
                                .ok()
                                .and_then(char::from_u32)
                                .unwrap_or('\u{fffd}');
                            value.push(ch);
                            self.i += end + 1;
                        }
                        'x' => {
                            let hex = self.s.get(self.i..self.i + 2).unwrap_or("");
                            value.push(u8::from_str_radix(hex, 16).map_or('\u{fffd}', char::from));
                            self.i += 2;
                        }
                        '\n' => {
                            // line continuation: skip the next line's leading whitespace
                            while self.peek().is_some_and(|c| c.is_ascii_whitespace()) {
                                self.i += 1;
                            }
                        }
                        other => value.push(other),
                    }
                }
                c => {
                    value.push(c);
                    self.i += c.len_utf8();
                }
            }
        }
        let content = content_start..self.i;
        self.i += 1;
        Ok(Value::Str {
            value,
            content,
            raw: false,
        })
    }

    fn char_lit(&mut self) -> Result<Value, ParseError> {
        self.i += 1;
        let start = self.i;
        while let Some(c) = self.peek() {
            if c == b'\\' {
                self.i += 2;
                continue;
            }
            if c == b'\'' {
                let v = self.s[start..self.i].to_string();
                self.i += 1;
                return Ok(Value::Char(v));
            }
            self.i += 1;
        }
        Err(self.err("unclosed character literal"))
    }

    fn number(&mut self) -> Value {
        let start = self.i;
        if matches!(self.peek(), Some(b'-') | Some(b'+')) {
            self.i += 1;
        }
        if self.s[self.i..].starts_with("inf") || self.s[self.i..].starts_with("NaN") {
            self.i += 3;
            return Value::Number(self.s[start..self.i].to_string());
        }
        while let Some(c) = self.peek() {
            let exp_sign = matches!(c, b'-' | b'+')
                && matches!(self.b.get(self.i - 1), Some(b'e') | Some(b'E'))
                && !self.s[start..self.i].starts_with("0x");
            if c.is_ascii_alphanumeric() || c == b'_' || c == b'.' || exp_sign {
                self.i += 1;
            } else {
                break;
            }
        }
        Value::Number(self.s[start..self.i].to_string())
    }

    /// Comma-separated values up to `close` (trailing comma allowed).
    fn items(&mut self, close: u8) -> Result<Vec<Node>, ParseError> {
        let mut items = Vec::new();
        loop {
            self.skip_trivia();
            if self.peek() == Some(close) {
                self.i += 1;
                return Ok(items);
            }
            items.push(self.value()?);
            self.skip_trivia();
            match self.peek() {
                Some(b',') => self.i += 1,
                Some(c) if c == close => {}
                _ => return Err(self.err("expected `,` or a closing bracket")),
            }
        }
    }

    fn map(&mut self) -> Result<Value, ParseError> {
        self.i += 1;
        let mut entries = Vec::new();
        loop {
            self.skip_trivia();
            if self.peek() == Some(b'}') {
                self.i += 1;
                return Ok(Value::Map(entries));
            }
            let key = self.value()?;
            self.skip_trivia();
            if self.peek() != Some(b':') {
                return Err(self.err("expected `:` in a map"));
            }
            self.i += 1;
            let value = self.value()?;
            entries.push((key, value));
            self.skip_trivia();
            match self.peek() {
                Some(b',') => self.i += 1,
                Some(b'}') => {}
                _ => return Err(self.err("expected `,` or `}` in a map")),
            }
        }
    }

    /// After an optional name, at `(`: a struct if the first thing inside is `ident:`.
    fn parens(&mut self, name: Option<String>) -> Result<Value, ParseError> {
        self.i += 1;
        self.skip_trivia();
        let save = self.i;
        let is_struct = self.ident().is_some() && {
            self.skip_trivia();
            self.peek() == Some(b':') && self.b.get(self.i + 1) != Some(&b':')
        };
        self.i = save;
        if !is_struct {
            return Ok(Value::Seq {
                name,
                items: self.items(b')')?,
            });
        }
        let mut fields = Vec::new();
        loop {
            self.skip_trivia();
            if self.peek() == Some(b')') {
                self.i += 1;
                return Ok(Value::Struct { name, fields });
            }
            let name_start = self.i;
            let fname = self
                .ident()
                .ok_or_else(|| self.err("expected a field name"))?;
            let name_span = name_start..self.i;
            self.skip_trivia();
            if self.peek() != Some(b':') {
                return Err(self.err("expected `:` after a field name"));
            }
            self.i += 1;
            let value = self.value()?;
            fields.push(Field {
                name: fname,
                name_span,
                value,
            });
            self.skip_trivia();
            match self.peek() {
                Some(b',') => self.i += 1,
                Some(b')') => {}
                _ => return Err(self.err("expected `,` or `)` after a field")),
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const DECK: &str = r##"#![enable(implicit_some)]
// a comment with "quotes" and (parens
(
    title: "Deck /* not a comment */",
    slides: [
        (id: "a", title: "One", body: [Text("x"), Columns([[Math(src: r#"dot(x) = "f""#)], []])]),
        (
            id: Some("b"),
            title: "Two",
            /* nested /* block */ comment */
            body: [
                Widget(SlopeField((
                    ode: Inline((vars: ["x"], rhs: ["x*sin(t) - \"q\" + y"], params: {"k": 1.3})),
                    start: (0.0, -1.5e-3),
                    h: 0.5,
                ))),
            ],
        ),
    ],
)
"##;

    #[test]
    fn finds_values_through_newtype_wrappers() {
        let tree = parse(DECK).unwrap();
        assert_eq!(
            tree.at("title").unwrap().as_str(),
            Some("Deck /* not a comment */")
        );
        assert_eq!(tree.at("slides[1].id").unwrap().as_str(), Some("b"));
        let math = tree.at("slides[0].body[1][0][0].src").unwrap();
        assert_eq!(math.as_str(), Some(r#"dot(x) = "f""#));
        let h = tree.at("slides[1].body[0].h").unwrap();
        assert_eq!(&DECK[h.span.clone()], "0.5");
        let y0 = tree.at("slides[1].body[0].start.1").unwrap();
        assert_eq!(&DECK[y0.span.clone()], "-1.5e-3");
        let k = tree.at("slides[1].body[0].ode.params.k").unwrap();
        assert_eq!(&DECK[k.span.clone()], "1.3");
        assert_eq!(
            tree.at("slides[1].body[0].ode").unwrap().name(),
            Some("Inline")
        );
        assert!(tree.at("slides[2]").is_none());
        assert!(tree.at("slides[1].body[0].nope").is_none());
    }

    #[test]
    fn string_offsets_walk_escapes_and_raw_strings() {
        let tree = parse(DECK).unwrap();
        let rhs = tree.at("slides[1].body[0].ode.rhs[0]").unwrap();
        assert_eq!(rhs.as_str(), Some("x*sin(t) - \"q\" + y"));
        // char 17 of the value is `y`, after two escaped quotes
        let at = rhs.str_offset(DECK, 17).unwrap();
        assert_eq!(&DECK[at..at + 1], "y");
        let (line, col) = line_col(DECK, at);
        let src_line = DECK.lines().nth(line - 1).unwrap();
        assert_eq!(src_line.chars().nth(col - 1), Some('y'));
        let math = tree.at("slides[0].body[1][0][0].src").unwrap();
        let at = math.str_offset(DECK, 9).unwrap();
        assert_eq!(&DECK[at..at + 3], "\"f\"");
    }

    #[test]
    fn line_col_counts_characters() {
        assert_eq!(line_col("ab\ncé d", 7), (2, 4));
        assert_eq!(line_col("x", 99), (1, 2));
    }

    #[test]
    fn rejects_what_is_not_ron() {
        assert!(parse("(a: 1,").is_err());
        assert!(parse("[1, 2] x").is_err());
        assert!(parse("\"open").is_err());
    }

    #[test]
    fn path_syntax() {
        assert_eq!(
            path_segments("a.b[2].c.1").unwrap(),
            vec![
                Seg::Field("a"),
                Seg::Field("b"),
                Seg::Index(2),
                Seg::Field("c"),
                Seg::Index(1)
            ]
        );
        assert!(path_segments("a[x]").is_none());
    }

    #[test]
    fn the_bundled_files_parse() {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
        for dir in ["slides", "slides/problems", "slides/tableaux", "scenes"] {
            for entry in std::fs::read_dir(root.join(dir)).unwrap() {
                let path = entry.unwrap().path();
                if path.extension().is_some_and(|e| e == "ron") {
                    let text = std::fs::read_to_string(&path).unwrap();
                    parse(&text).unwrap_or_else(|e| panic!("{}: {e:?}", path.display()));
                }
            }
        }
    }
}
