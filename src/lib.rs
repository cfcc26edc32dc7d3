//! lectern: a live-reloading lecture tool for physically based animation.
//!
//! Data flows one way: files on disk → [`reload`] → parsed models ([`deck`], [`scene`],
//! [`ode::problem`]) → simulation ([`ode`], [`rigid`], [`school`], [`waves`]) → draw data →
//! egui / wgpu ([`app`], [`widgets`], [`render`]). The simulation modules know nothing of
//! egui or wgpu, so they are usable and testable with no window.

pub mod bundled;
pub mod diag;
pub mod image_file;
pub mod paths;
pub mod project_files;
pub mod ron_tree;
pub mod web_bundle;
pub mod z85;

// numerics and simulation: no GPU or UI types below this line
pub mod ode;
pub mod rigid;
pub mod school;
pub mod waves;

// models loaded from files
pub mod deck;
pub mod reload;
pub mod scene;

// drawing
pub mod app;
pub mod math;
pub mod render;
pub mod widgets;

// the command line: native only (it typesets, spawns workers, writes files)
#[cfg(not(target_arch = "wasm32"))]
pub mod cli;

// the web player: eframe's WebRunner on a canvas, the deck from the page's bundle
#[cfg(target_arch = "wasm32")]
pub mod web;
