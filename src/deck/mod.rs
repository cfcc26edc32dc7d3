//! Decks: the slide model as written in `slides/*.ron`, loading with file positions, and
//! navigation state.

mod load;
mod model;

pub use load::{load_deck, parse_deck};
pub use model::{Aspect, Block, Deck, Slide};
