//! The water surface on the CPU, for placing floating bodies. Same formula as
//! `shaders/water.wgsl` (GPU Gems 1, ch. 1, eq. 9 and 12).

use glam::Vec3;

use super::model::Water;

/// Height and unit normal of the surface above the horizontal point (x, z) at time `t`.
/// The Gerstner sum moves points horizontally; a body at (x, z) uses the displacement of the
/// grid point at (x, z), which is what the vertex shader draws there to first order.
pub fn height_and_normal(water: &Water, x: f32, z: f32, t: f32) -> (f32, Vec3) {
    let n_waves = water.waves.len().max(1) as f32;
    let mut y = water.level;
    let mut normal = Vec3::Y;
    for w in &water.waves {
        let d = glam::Vec2::from(w.direction).normalize_or_zero();
        let k = std::f32::consts::TAU / w.wavelength;
        let phase = k * (d.x * x + d.y * z) - k * w.speed * t;
        let (s, c) = phase.sin_cos();
        let q = w.steepness / n_waves;
        y += w.amplitude * s;
        normal.x -= d.x * k * w.amplitude * c;
        normal.z -= d.y * k * w.amplitude * c;
        normal.y -= q * s;
    }
    (y, normal.normalize_or(Vec3::Y))
}
