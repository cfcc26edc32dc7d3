//! The one last-good holder, for everything the app loads from a file and keeps while it is
//! edited (decks, scenes, problem files, ink, shader techniques): the newest valid version, the
//! errors of the newest attempt if it failed, and a generation. The app keeps using `value()`
//! while `errors()` are shown (each at its `file:line:col`).
//!
//! Something that may never have loaded (a deck whose first read failed) is a
//! `LastGood<Option<T>>`; something that must have loaded to exist at all (a technique's first
//! pipelines) is a `LastGood<T>`.

use crate::diag::Diagnostic;

#[derive(Debug, Clone)]
pub struct LastGood<T> {
    value: T,
    /// The problems of the newest attempt; empty when it succeeded.
    errors: Vec<Diagnostic>,
    /// Bumped on every successful update, so views can tell a reload happened.
    generation: u64,
}

impl<T: Default> Default for LastGood<T> {
    fn default() -> Self {
        Self::new(T::default())
    }
}

impl<T> LastGood<T> {
    /// Holds `value` with no error, at generation 0.
    pub fn new(value: T) -> Self {
        Self {
            value,
            errors: Vec::new(),
            generation: 0,
        }
    }

    /// Takes a load result: success replaces the value and clears the errors; failure keeps
    /// the value and records the error.
    pub fn update(&mut self, result: Result<T, Diagnostic>) {
        self.update_all(result.map_err(|d| vec![d]));
    }

    /// [`Self::update`] for an attempt that can find several problems at once (a shader's).
    pub fn update_all(&mut self, result: Result<T, Vec<Diagnostic>>) {
        match result {
            Ok(v) => {
                self.value = v;
                self.errors.clear();
                self.generation += 1;
            }
            Err(ds) => self.errors = ds,
        }
    }

    /// The last good value.
    pub fn value(&self) -> &T {
        &self.value
    }

    pub fn value_mut(&mut self) -> &mut T {
        &mut self.value
    }

    /// The first error of the newest attempt, if it failed.
    pub fn error(&self) -> Option<&Diagnostic> {
        self.errors.first()
    }

    /// Every error of the newest attempt (empty when it succeeded).
    pub fn errors(&self) -> &[Diagnostic] {
        &self.errors
    }

    pub fn generation(&self) -> u64 {
        self.generation
    }
}

impl<T> LastGood<Option<T>> {
    /// [`Self::update`] for a holder that may never have loaded.
    pub fn update_some(&mut self, result: Result<T, Diagnostic>) {
        self.update(result.map(Some));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn failure_keeps_value_and_success_clears_error() {
        let mut h = LastGood::new(1);
        h.update(Err(Diagnostic::new("a.ron", 2, 3, "bad")));
        assert_eq!(h.value(), &1);
        assert_eq!(h.error().map(|d| (d.line, d.col)), Some((2, 3)));
        assert_eq!(h.generation(), 0);
        h.update(Ok(2));
        assert_eq!(h.value(), &2);
        assert!(h.error().is_none());
        assert_eq!(h.generation(), 1);
    }

    #[test]
    fn several_errors_are_kept_together_and_replaced_by_the_next_attempt() {
        let mut h: LastGood<Option<&str>> = LastGood::default();
        h.update_all(Err(vec![
            Diagnostic::new("w.wgsl", 4, 1, "one"),
            Diagnostic::new("common.wgsl", 9, 2, "two"),
        ]));
        assert_eq!(h.value(), &None);
        assert_eq!(h.errors().len(), 2);
        h.update(Err(Diagnostic::new("w.wgsl", 5, 1, "three")));
        assert_eq!(h.errors().len(), 1);
        assert_eq!(h.error().map(|d| d.line), Some(5));
        h.update_some(Ok("good"));
        assert_eq!(
            (h.value(), h.errors().len(), h.generation()),
            (&Some("good"), 0, 1)
        );
    }
}
