//! A holder for something loaded from a file: the newest valid version, plus the error of the
//! newest invalid one. The app keeps drawing `value()` while `error()` is shown.

use crate::diag::Diagnostic;

#[derive(Debug, Clone)]
pub struct LastGood<T> {
    value: Option<T>,
    error: Option<Diagnostic>,
    /// Bumped on every successful update, so views can tell a reload happened.
    generation: u64,
}

impl<T> Default for LastGood<T> {
    fn default() -> Self {
        Self {
            value: None,
            error: None,
            generation: 0,
        }
    }
}

impl<T> LastGood<T> {
    pub fn new(value: T) -> Self {
        Self {
            value: Some(value),
            error: None,
            generation: 1,
        }
    }

    /// Takes a load result: success replaces the value and clears the error; failure keeps the
    /// value and records the error.
    pub fn update(&mut self, result: Result<T, Diagnostic>) {
        match result {
            Ok(v) => {
                self.value = Some(v);
                self.error = None;
                self.generation += 1;
            }
            Err(e) => self.error = Some(e),
        }
    }

    pub fn value(&self) -> Option<&T> {
        self.value.as_ref()
    }

    pub fn value_mut(&mut self) -> Option<&mut T> {
        self.value.as_mut()
    }

    pub fn error(&self) -> Option<&Diagnostic> {
        self.error.as_ref()
    }

    pub fn generation(&self) -> u64 {
        self.generation
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn failure_keeps_value_and_success_clears_error() {
        let mut h = LastGood::new(1);
        h.update(Err(Diagnostic::new("a.ron", 2, 3, "bad")));
        assert_eq!(h.value(), Some(&1));
        assert_eq!(h.error().unwrap().line, 2);
        h.update(Ok(2));
        assert_eq!(h.value(), Some(&2));
        assert!(h.error().is_none());
        assert_eq!(h.generation(), 2);
    }
}
