//! Where the presenter is in the deck: a small, pure state machine (no UI types), so every
//! edge — first, last, a jump past the end, a reload that inserts slides — is testable.

use super::Deck;

#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Nav {
    index: usize,
    len: usize,
    /// The key of the slide on screen ([`super::Slide::key`]), to find it again after a reload.
    key: String,
}

impl Nav {
    /// Starts on the first slide.
    pub fn new(deck: &Deck) -> Self {
        let mut nav = Self {
            index: 0,
            len: deck.slides.len(),
            key: String::new(),
        };
        nav.remember(deck);
        nav
    }

    /// 0-based index of the current slide.
    pub fn index(&self) -> usize {
        self.index
    }

    pub fn len(&self) -> usize {
        self.len
    }

    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    pub fn is_first(&self) -> bool {
        self.index == 0
    }

    pub fn is_last(&self) -> bool {
        self.index + 1 >= self.len
    }

    /// Moves forward to the next slide that is not marked `skip`; at the end it stays.
    /// Returns whether it moved.
    pub fn next(&mut self, deck: &Deck) -> bool {
        match (self.index + 1..deck.slides.len()).find(|&i| !deck.slides[i].skip) {
            Some(i) => self.go(deck, i),
            None => false,
        }
    }

    /// Moves back to the previous slide that is not marked `skip`; at the start it stays.
    /// Returns whether it moved.
    pub fn prev(&mut self, deck: &Deck) -> bool {
        let upto = self.index.min(deck.slides.len());
        match (0..upto).rev().find(|&i| !deck.slides[i].skip) {
            Some(i) => self.go(deck, i),
            None => false,
        }
    }

    /// The first slide that is not skipped (the first slide if all are).
    pub fn first(&mut self, deck: &Deck) -> bool {
        let i = deck.slides.iter().position(|s| !s.skip).unwrap_or(0);
        self.go(deck, i)
    }

    /// The last slide that is not skipped (the last slide if all are).
    pub fn last(&mut self, deck: &Deck) -> bool {
        let i = deck
            .slides
            .iter()
            .rposition(|s| !s.skip)
            .unwrap_or(deck.slides.len().saturating_sub(1));
        self.go(deck, i)
    }

    /// Jumps to 0-based `index`, clamped into the deck. Returns whether it moved.
    pub fn go(&mut self, deck: &Deck, index: usize) -> bool {
        self.len = deck.slides.len();
        let target = index.min(self.len.saturating_sub(1));
        let moved = target != self.index;
        self.index = target;
        self.remember(deck);
        moved
    }

    /// Jumps to the slide the audience calls `number` (1-based, as shown in the corner).
    /// Numbers outside the deck are refused with a message and leave the position alone.
    pub fn goto_number(&mut self, deck: &Deck, number: usize) -> Result<(), String> {
        if number == 0 || number > deck.slides.len() {
            return Err(format!(
                "no slide {number}: the deck has {} slides",
                deck.slides.len()
            ));
        }
        self.go(deck, number - 1);
        Ok(())
    }

    /// Follows a reloaded deck: the same slide (by id, else title) if it still exists, so
    /// inserting or deleting slides before it does not move the presenter; else the same
    /// index, clamped.
    pub fn on_reload(&mut self, new_deck: &Deck) {
        self.len = new_deck.slides.len();
        self.index = new_deck
            .find(&self.key)
            .unwrap_or_else(|| self.index.min(self.len.saturating_sub(1)));
        self.remember(new_deck);
    }

    fn remember(&mut self, deck: &Deck) {
        self.key = deck
            .slides
            .get(self.index)
            .map(|s| s.key().to_owned())
            .unwrap_or_default();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::deck::parse_deck;
    use std::path::Path;

    /// A deck of slides with these ids; an id ending in `?` is a `skip: true` slide.
    fn deck(keys: &[&str]) -> Deck {
        let slides: Vec<String> = keys
            .iter()
            .map(|k| match k.strip_suffix('?') {
                Some(k) => format!("(id: \"{k}\", title: \"Slide {k}\", skip: true, seconds: 60)"),
                None => format!("(id: \"{k}\", title: \"Slide {k}\", seconds: 10)"),
            })
            .collect();
        parse_deck(
            &format!("(title: \"t\", slides: [{}])", slides.join(",")),
            Path::new("t.ron"),
        )
        .unwrap()
    }

    #[test]
    fn stays_inside_the_deck() {
        let d = deck(&["a", "b", "c"]);
        let mut nav = Nav::new(&d);
        assert!(!nav.prev(&d));
        assert_eq!(nav.index(), 0);
        assert!(nav.next(&d) && nav.next(&d));
        assert!(!nav.next(&d));
        assert_eq!(nav.index(), 2);
        assert!(nav.is_last());
    }

    #[test]
    fn paging_passes_over_skipped_slides_but_jumps_reach_them() {
        let d = deck(&["a?", "b", "c?", "d?", "e", "f?"]);
        assert_eq!(d.planned_secs(), 20.0, "skipped slides are not in the plan");
        let mut nav = Nav::new(&d);
        assert!(nav.first(&d));
        assert_eq!(nav.index(), 1);
        assert!(nav.next(&d));
        assert_eq!(nav.index(), 4, "c and d are passed over");
        assert!(!nav.next(&d), "f is skipped: e is the end when paging");
        assert!(nav.prev(&d));
        assert_eq!(nav.index(), 1);
        assert!(!nav.prev(&d));
        // a jump reaches a skipped slide, and paging continues from there
        nav.goto_number(&d, 3).unwrap();
        assert_eq!(nav.index(), 2);
        assert!(nav.next(&d));
        assert_eq!(nav.index(), 4);
        nav.first(&d);
        assert!(nav.last(&d));
        assert_eq!(nav.index(), 4);
    }
}
