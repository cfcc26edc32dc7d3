//! The text of `Text` and `Bullets` blocks, written plain (`Text("where $h$ is the step")`,
//! `Bullets(["a", "b"])`) or with its fields (`Text((src: "where $\\alpha$ …", latex: true))`,
//! `Bullets((items: [..], latex: true))`) when its `$…$` are LaTeX rather than Typst.
//!
//! The field form has the double parentheses of every newtype-of-struct in a deck (widgets are
//! `SlopeField((..))`): `ron` reads a variant either as a newtype or as a struct variant, never
//! both, and its `unwrap_variant_newtypes` extension, which would allow `Text(src: ..)`, would
//! break `SlopeField((..))`. A single-parenthesis `Text(src: ..)` gets an error saying so.

use serde::de::{self, Deserializer, MapAccess, SeqAccess, Visitor};
use serde::{Deserialize, Serialize, Serializer};

/// A paragraph: its source with inline markup, and how its `$…$` are written.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Prose {
    pub src: String,
    /// `$…$` are LaTeX (converted like a `Math` block's with `latex: true`), not Typst.
    #[serde(default)]
    pub latex: bool,
    /// Written `Text((src: ..))` rather than `Text("..")` (where its string is in the file).
    #[serde(skip)]
    pub with_fields: bool,
}

/// A bulleted list: its items (each with inline markup), and how their `$…$` are written.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BulletList {
    pub items: Vec<String>,
    #[serde(default)]
    pub latex: bool,
    /// Written `Bullets((items: ..))` rather than `Bullets([..])`.
    #[serde(skip)]
    pub with_fields: bool,
}

impl Prose {
    /// The [`crate::ron_tree`] path of its string below the block's: `.0` for `Text("..")`,
    /// `.src` for `Text((src: ..))`.
    pub fn tree_suffix(&self) -> &'static str {
        if self.with_fields { ".src" } else { ".0" }
    }
}

impl BulletList {
    /// The path of item `k` below the block's: `[k]`, or `.items[k]` in the field form.
    pub fn item_tree_suffix(&self, k: usize) -> String {
        if self.with_fields {
            format!(".items[{k}]")
        } else {
            format!("[{k}]")
        }
    }
}

impl From<&str> for Prose {
    fn from(src: &str) -> Self {
        src.to_owned().into()
    }
}

impl From<String> for Prose {
    fn from(src: String) -> Self {
        Self {
            src,
            ..Self::default()
        }
    }
}

impl From<Vec<String>> for BulletList {
    fn from(items: Vec<String>) -> Self {
        Self {
            items,
            ..Self::default()
        }
    }
}

const SINGLE_PARENS: &str = "the field form needs double parentheses, like a widget's: \
     `Text((src: \"…\", latex: true))`, `Bullets((items: [\"…\"], latex: true))`";

/// Reads `Text(..)`'s payload: a string or `(src: .., latex: ..)`.
pub fn deserialize_prose<'de, D: Deserializer<'de>>(d: D) -> Result<Prose, D::Error> {
    struct V;
    impl<'de> Visitor<'de> for V {
        type Value = Prose;
        fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
            f.write_str("a string or (src: \"…\", latex: true)")
        }
        fn visit_str<E: de::Error>(self, s: &str) -> Result<Prose, E> {
            Ok(s.into())
        }
        fn visit_string<E: de::Error>(self, s: String) -> Result<Prose, E> {
            Ok(s.into())
        }
        fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<Prose, A::Error> {
            let p = Prose::deserialize(de::value::MapAccessDeserializer::new(map))?;
            Ok(Prose {
                with_fields: true,
                ..p
            })
        }
        fn visit_unit<E: de::Error>(self) -> Result<Prose, E> {
            Err(E::custom(SINGLE_PARENS))
        }
    }
    d.deserialize_any(V)
}

/// Reads `Bullets(..)`'s payload: a list of strings or `(items: [..], latex: ..)`.
pub fn deserialize_bullets<'de, D: Deserializer<'de>>(d: D) -> Result<BulletList, D::Error> {
    struct V;
    impl<'de> Visitor<'de> for V {
        type Value = BulletList;
        fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
            f.write_str("a list of strings or (items: [\"…\"], latex: true)")
        }
        fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<BulletList, A::Error> {
            Vec::<String>::deserialize(de::value::SeqAccessDeserializer::new(seq)).map(Into::into)
        }
        fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<BulletList, A::Error> {
            let b = BulletList::deserialize(de::value::MapAccessDeserializer::new(map))?;
            Ok(BulletList {
                with_fields: true,
                ..b
            })
        }
        fn visit_unit<E: de::Error>(self) -> Result<BulletList, E> {
            Err(E::custom(SINGLE_PARENS))
        }
    }
    d.deserialize_any(V)
}

/// Writes the form it was read in (the field form whenever `latex` is set).
pub fn serialize_prose<S: Serializer>(p: &Prose, s: S) -> Result<S::Ok, S::Error> {
    if p.with_fields || p.latex {
        p.serialize(s)
    } else {
        s.serialize_str(&p.src)
    }
}

pub fn serialize_bullets<S: Serializer>(b: &BulletList, s: S) -> Result<S::Ok, S::Error> {
    if b.with_fields || b.latex {
        b.serialize(s)
    } else {
        b.items.serialize(s)
    }
}

#[cfg(test)]
mod tests {
    use crate::deck::Block;

    fn block(text: &str) -> Result<Block, ron::error::SpannedError> {
        ron::from_str(text)
    }

    #[test]
    fn text_and_bullets_read_plain_or_with_their_fields() {
        let Ok(Block::Text(p)) = block(r#"Text("where $h$ is")"#) else {
            panic!()
        };
        assert_eq!((p.src.as_str(), p.latex), ("where $h$ is", false));
        let Ok(Block::Text(p)) = block(r#"Text((src: "$\\alpha$", latex: true))"#) else {
            panic!()
        };
        assert_eq!((p.src.as_str(), p.latex), ("$\\alpha$", true));
        let Ok(Block::Bullets(b)) = block(r#"Bullets(["a", "b"])"#) else {
            panic!()
        };
        assert_eq!((b.items.len(), b.latex), (2, false));
        let Ok(Block::Bullets(b)) = block(r#"Bullets((items: ["$x^2$"], latex: true))"#) else {
            panic!()
        };
        assert_eq!((b.items, b.latex), (vec!["$x^2$".to_string()], true));
        // written back as read
        for text in [
            r#"Text("a")"#,
            r#"Text((src:"a",latex:true))"#,
            r#"Bullets(["a"])"#,
        ] {
            assert_eq!(ron::to_string(&block(text).unwrap()).unwrap(), text);
        }
    }

    #[test]
    fn a_misspelt_field_and_single_parentheses_are_explained() {
        let e = block(r#"Text((src: "a", latx: true))"#).unwrap_err();
        let d = crate::diag::Diagnostic::from_ron(std::path::Path::new("d.ron"), &e);
        assert!(d.message.contains("did you mean `latex`?"), "{d}");
        let e = block(r#"Text(src: "a", latex: true)"#).unwrap_err();
        assert!(e.to_string().contains("double parentheses"), "{e}");
        let e = block(r#"Bullets(items: ["a"])"#).unwrap_err();
        assert!(e.to_string().contains("double parentheses"), "{e}");
    }
}
