//! One error type for everything a file can get wrong: the file, the 1-based line and column,
//! and a message. Every loader (decks, scenes, problems, tableaux, shaders) reports through it,
//! so the app shows and `lectern check` prints them the same way.

use std::fmt;
use std::path::{Path, PathBuf};

#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Diagnostic {
    pub file: PathBuf,
    /// 1-based; 0 when the problem has no position (e.g. the file is missing).
    pub line: usize,
    /// 1-based; 0 when the problem has no position.
    pub col: usize,
    pub message: String,
}

impl Diagnostic {
    pub fn new(
        file: impl Into<PathBuf>,
        line: usize,
        col: usize,
        message: impl Into<String>,
    ) -> Self {
        Self {
            file: file.into(),
            line,
            col,
            message: message.into(),
        }
    }

    /// A problem with the whole file (unreadable, missing, a value out of range with no span).
    pub fn whole_file(file: impl Into<PathBuf>, message: impl Into<String>) -> Self {
        Self::new(file, 0, 0, message)
    }

    /// A problem with the value at `path` (a [`crate::ron_tree`] path such as
    /// `slides[3].seconds`) of the RON `text` parsed into `tree`: at the value's line and
    /// column, or for the whole file when the path is not found.
    pub fn at_value(
        tree: Option<&crate::ron_tree::Node>,
        text: &str,
        file: &Path,
        path: &str,
        message: impl Into<String>,
    ) -> Self {
        match tree.and_then(|t| t.at(path)) {
            Some(node) => {
                let (line, col) = node.line_col(text);
                Self::new(file, line, col, message)
            }
            None => Self::whole_file(file, message),
        }
    }

    /// A problem at byte `offset` of `text`.
    pub fn at_offset(text: &str, file: &Path, offset: usize, message: impl Into<String>) -> Self {
        let (line, col) = crate::ron_tree::line_col(text, offset);
        Self::new(file, line, col, message)
    }

    /// Converts a `ron` parse error, which carries a 1-based position.
    /// An unknown variant or field name (a misspelt widget, a field of another widget) gets a
    /// "did you mean" when one expected name is close.
    pub fn from_ron(file: &Path, err: &ron::error::SpannedError) -> Self {
        use ron::error::Error;
        let mut message = err.code.to_string();
        if let Error::NoSuchEnumVariant {
            expected, found, ..
        }
        | Error::NoSuchStructField {
            expected, found, ..
        } = &err.code
            && let Some(hint) = did_you_mean(found, expected.iter().copied())
        {
            message = format!("{message}; {hint}");
        }
        Self::new(file, err.span.start.line, err.span.start.col, message)
    }
}

/// "did you mean `SlopeField`?" for the candidate closest to `found` (case aside), when it is
/// close enough to be a slip: at most a third of its letters differ (at least one may), or
/// one is the other with a different case or separators.
pub fn did_you_mean<'a>(
    found: &str,
    candidates: impl IntoIterator<Item = &'a str>,
) -> Option<String> {
    let fold = |s: &str| {
        s.chars()
            .filter(|c| *c != '_' && *c != '-')
            .flat_map(char::to_lowercase)
            .collect::<String>()
    };
    let found_folded = fold(found);
    let (best, distance) = candidates
        .into_iter()
        .filter(|c| *c != found)
        .map(|c| (c, strsim::levenshtein(&found_folded, &fold(c))))
        .min_by_key(|(_, d)| *d)?;
    let allowed = (found.chars().count() / 3).max(1);
    (distance <= allowed).then(|| format!("did you mean `{best}`?"))
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.line == 0 {
            write!(f, "{}: {}", self.file.display(), self.message)
        } else {
            write!(
                f,
                "{}:{}:{}: {}",
                self.file.display(),
                self.line,
                self.col,
                self.message
            )
        }
    }
}

impl std::error::Error for Diagnostic {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn did_you_mean_picks_the_close_name_and_nothing_far() {
        let widgets = ["SlopeField", "StepConstruction", "Spiral", "Scene"];
        let hint = |f: &str| did_you_mean(f, widgets.iter().copied());
        assert_eq!(
            hint("SlopeFeild").as_deref(),
            Some("did you mean `SlopeField`?")
        );
        assert_eq!(
            hint("slope_field").as_deref(),
            Some("did you mean `SlopeField`?")
        );
        assert_eq!(hint("Spirl").as_deref(), Some("did you mean `Spiral`?"));
        assert_eq!(hint("Histogram"), None);
        assert_eq!(
            did_you_mean("x", ["y"]).as_deref(),
            Some("did you mean `y`?")
        );
        assert_eq!(
            did_you_mean("beta", ["zeta", "omega"]).as_deref(),
            Some("did you mean `zeta`?")
        );
    }

    #[test]
    fn an_unknown_ron_variant_gets_a_did_you_mean() {
        #[derive(Debug, serde::Deserialize)]
        #[allow(dead_code)]
        enum W {
            SlopeField,
            Spiral,
        }
        let err = ron::from_str::<W>("SlopeFeld").unwrap_err();
        let d = Diagnostic::from_ron(Path::new("deck.ron"), &err);
        assert!(d.message.ends_with("did you mean `SlopeField`?"), "{d}");
    }

    #[test]
    fn ron_error_keeps_line_and_column() {
        let err = ron::from_str::<Vec<u32>>("[1,\n 2,\n x]").unwrap_err();
        let d = Diagnostic::from_ron(Path::new("deck.ron"), &err);
        assert_eq!((d.line, d.col), (3, 2));
        assert!(d.to_string().starts_with("deck.ron:3:2: "), "{d}");
    }
}
