//! Decks: the slide model as written in `slides/*.ron`, loading with file positions, and
//! navigation state.

pub mod files;
mod load;
mod model;
pub mod nav;
mod session;
pub mod widgets;
pub mod write_back;

pub use load::{load_deck, parse_deck, parse_deck_file};
pub use model::{Aspect, Block, BookmarkDecl, Deck, Layout, Slide, Theme};
pub use nav::Nav;
pub use session::DeckSession;
