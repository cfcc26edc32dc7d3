//! The water surface as a sum of Gerstner waves (GPU Gems 1, ch. 1), evaluated on the CPU for
//! buoyancy. Its WGSL twin lives in `shaders/water.wgsl`; both must stay the same formula.

use serde::{Deserialize, Serialize};

/// One Gerstner wave. `direction` is in the xz plane (normalised on use).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GerstnerWave {
    pub direction: [f32; 2],
    /// metres
    pub wavelength: f32,
    /// metres
    pub amplitude: f32,
    /// 0 = sine wave, 1 = sharpest crest without loops (Q in GPU Gems)
    pub steepness: f32,
    /// metres per second (phase speed)
    pub speed: f32,
}
