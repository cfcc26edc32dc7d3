//! Procedural tangent-space normal maps: a tileable height field per pattern, turned into
//! normals by central differences and stored as RGBA8 *linear* (`Rgba8Unorm`, not `Srgb`:
//! these are vectors, not colours; gamma-decoding them would bend every normal).

use crate::scene::NormalPattern;

pub const SIZE: u32 = 256;

fn hash(x: i32, y: i32, seed: u32) -> f32 {
    let mut h = (x as u32).wrapping_mul(0x8da6_b343)
        ^ (y as u32).wrapping_mul(0xd816_3841)
        ^ seed.wrapping_mul(0xcb1a_b31f);
    h ^= h >> 13;
    h = h.wrapping_mul(0x5bd1_e995);
    h ^= h >> 15;
    (h & 0xFFFF) as f32 / 65535.0
}

/// Value noise with period `p` cells, so textures tile.
fn noise(u: f32, v: f32, p: i32, seed: u32) -> f32 {
    let (x, y) = (u * p as f32, v * p as f32);
    let (xi, yi) = (x.floor() as i32, y.floor() as i32);
    let (fx, fy) = (x - xi as f32, y - yi as f32);
    let s = |t: f32| t * t * (3.0 - 2.0 * t);
    let h = |a: i32, b: i32| hash(a.rem_euclid(p), b.rem_euclid(p), seed);
    let a = h(xi, yi) + (h(xi + 1, yi) - h(xi, yi)) * s(fx);
    let b = h(xi, yi + 1) + (h(xi + 1, yi + 1) - h(xi, yi + 1)) * s(fx);
    a + (b - a) * s(fy)
}

fn fbm(u: f32, v: f32, base: i32, octaves: u32, seed: u32) -> f32 {
    let mut sum = 0.0;
    let mut amp = 0.5;
    let mut p = base;
    for o in 0..octaves {
        sum += amp * noise(u, v, p, seed + o);
        amp *= 0.5;
        p *= 2;
    }
    sum
}

/// Height in texel units of "bump", u and v in [0, 1).
fn height(pattern: NormalPattern, u: f32, v: f32) -> f32 {
    use std::f32::consts::TAU;
    match pattern {
        NormalPattern::Flat => 0.0,
        NormalPattern::Ripples => {
            let warp = 0.08 * (TAU * 2.0 * v).sin() + 0.05 * fbm(u, v, 4, 2, 11);
            let crest = (TAU * (6.0 * (u + warp))).sin();
            // asymmetric ripples: gentle upwind slope, steep lee
            4.0 * (crest + 0.3 * (2.0 * TAU * 6.0 * (u + warp)).sin()) + 3.0 * fbm(u, v, 16, 3, 3)
        }
        NormalPattern::Bumps => 96.0 * fbm(u, v, 4, 5, 21),
        NormalPattern::Planks => {
            let plank = (v * 4.0).fract();
            let groove = if !(0.03..=0.97).contains(&plank) {
                -3.0
            } else {
                0.0
            };
            let row = (v * 4.0).floor() as u32;
            groove
                + 2.0 * fbm(u, v * 0.25 + row as f32 * 0.37, 2, 2, 40 + row)
                + 0.8 * noise(u, v, 64, 5) * (TAU * (v * 64.0 + 3.0 * fbm(u, v, 2, 2, 9))).sin()
        }
        NormalPattern::Brushed => {
            // streaks along u: noise with 128 cells across v and only 2 along u
            let rows = 128.0;
            let r = (v * rows).floor() as i32;
            0.6 * noise(u, r as f32 / rows, 2, 77) + 0.4 * hash(r, 0, 78)
        }
        NormalPattern::Scales => {
            // overlapping scales on an offset grid; each scale a dome, the next row on top
            let rows = 8.0;
            let cols = 8.0;
            let y = v * rows;
            let row = y.floor();
            let x = u * cols + 0.5 * (row as i32 % 2) as f32;
            let fx = x.fract() - 0.5;
            let fy = y.fract();
            let d = (fx * fx + (fy - 0.1) * (fy - 0.1) * 0.6).sqrt();
            3.0 * (1.0 - d * 1.6).max(0.0) + fy
        }
    }
}

/// RGBA8 texels, row-major, `SIZE`², tangent-space normals (x right = +u, y up = +v).
pub fn generate(pattern: NormalPattern) -> Vec<u8> {
    let n = SIZE as usize;
    let mut h = vec![0.0f32; n * n];
    for y in 0..n {
        for x in 0..n {
            h[y * n + x] = height(pattern, x as f32 / n as f32, y as f32 / n as f32);
        }
    }
    let at = |x: isize, y: isize| {
        h[(y.rem_euclid(n as isize) as usize) * n + x.rem_euclid(n as isize) as usize]
    };
    let mut out = Vec::with_capacity(n * n * 4);
    for y in 0..n as isize {
        for x in 0..n as isize {
            let dx = (at(x + 1, y) - at(x - 1, y)) * 0.5;
            let dy = (at(x, y + 1) - at(x, y - 1)) * 0.5;
            let v = glam::Vec3::new(-dx, -dy, 8.0).normalize();
            out.extend_from_slice(&[
                ((v.x * 0.5 + 0.5) * 255.0).round() as u8,
                ((v.y * 0.5 + 0.5) * 255.0).round() as u8,
                ((v.z * 0.5 + 0.5) * 255.0).round() as u8,
                255,
            ]);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flat_map_points_straight_out_and_bumps_do_not() {
        let flat = generate(NormalPattern::Flat);
        assert!(flat.chunks(4).all(|t| t == [128, 128, 255, 255]));
        let bumps = generate(NormalPattern::Bumps);
        let tilted = bumps.chunks(4).filter(|t| t[0].abs_diff(128) > 4).count();
        assert!(tilted > bumps.len() / 40, "only {tilted} tilted texels");
    }

    #[test]
    fn maps_tile_seamlessly() {
        for p in [
            NormalPattern::Ripples,
            NormalPattern::Bumps,
            NormalPattern::Scales,
        ] {
            let a = height(p, 0.0, 0.3);
            let b = height(p, 1.0, 0.3);
            assert!((a - b).abs() < 1e-3, "{p:?}: {a} vs {b}");
        }
    }
}
