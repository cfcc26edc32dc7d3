//! Decks: the slide model as written in `slides/*.ron`, loading with file positions, and
//! navigation state.

pub mod broken;
pub mod files;
pub mod ink;
mod ink_file;
mod load;
pub mod markup;
mod model;
pub mod nav;
mod prose;
mod session;
pub mod widgets;
pub mod write_back;

pub use ink_file::InkFile;
pub use load::{load_deck, parse_deck, parse_deck_file};
pub use model::{
    Aspect, Block, BookmarkDecl, Controls, Deck, IMAGE_WIDTH_RANGE, Layout, Slide, Theme,
    WidgetProblem, block_tree_path,
};
pub use nav::Nav;
pub use prose::{BulletList, Prose};
pub use session::DeckSession;
