//! The water scene: its model as written in `scenes/*.ron`, the per-frame simulation step, and
//! the immutable per-frame snapshot the renderer reads.
