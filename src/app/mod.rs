//! The eframe app: modes, keys, overlays, presenter view — and the one slide renderer that the
//! window, `lectern export` and the snapshot tests share.

mod actions;
mod block_ctx;
mod block_problems;
mod blocks;
mod files;
mod formula_view;
pub mod frame_stats;
mod images;
pub mod ink;
pub mod ink_draw;
mod inline_text;
pub mod keys;
mod lectern_app;
mod ode_editor;
pub mod offscreen;
pub mod overlays;
pub mod pacing;
pub mod plot_data;
pub mod presenter;
pub mod scene_mode;
mod scene_panel;
mod scene_probe;
pub mod screens;
pub mod slide_state;
pub mod slide_view;
mod table_view;
pub mod theme;
pub mod tweak_file;
pub mod tweaks;
mod widget_style;
mod windows;

pub use lectern_app::{LecternApp, Mode, Overlay};
pub use ode_editor::first_field_rect;
pub use offscreen::{OffscreenError, OffscreenRenderer, render_slide_png};
pub use scene_mode::SceneMode;
pub use slide_state::{
    DeckState, DrawnWidget, SlideResponse, SlideState, TweakSnapshot, drawn_widgets,
};
pub use slide_view::{ShowControls, SlideOptions, slide_ui, slide_ui_with};
