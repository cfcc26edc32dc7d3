//! The wgpu renderer of scene mode: one module per technique, each beside its WGSL file in
//! `shaders/`.
