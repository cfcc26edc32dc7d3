//! The fish body at each level of detail (fish space: nose at +x, back at +y, unit length; the
//! instance scale sizes it). Every level is closed and wound counter-clockwise seen from
//! outside, with the tail fin as two one-sided copies facing ±z, so the fish pipelines cull
//! back faces: about half of each fish's triangles never reach the rasteriser.

use glam::{Vec2, Vec3};

use super::mesh::{MeshData, grid_indices};

/// Where the body ends and the fin begins, fish space.
const TAIL_ROOT: Vec3 = Vec3::new(-0.35, 0.0, 0.0);
/// Half the fin's thickness: its two sides are this far apart (so neither is culled as the
/// other's back).
const FIN_HALF_THICKNESS: f32 = 0.002;

/// The body's half-height and half-width `s` of the way from the nose (0) to the tail root (1):
/// blunt nose, thickest at a third, thin caudal peduncle.
fn body_radii(s: f32) -> (f32, f32) {
    let t = (s.max(1e-3)).powf(0.45) * (1.0 - s).powf(0.9) * 1.25;
    (0.16 * t + 0.006, 0.065 * t + 0.004)
}

/// The x of the body `s` of the way from the nose to the tail root.
fn body_x(s: f32) -> f32 {
    0.5 - (0.5 - TAIL_ROOT.x) * s
}

/// The body at full detail (20 rings of 16 segments, 644 triangles).
pub fn fish() -> MeshData {
    fish_lod(20, 16)
}

/// The body: an elliptic cross-section lofted along x (nose +0.5, tail root −0.35),
/// laterally compressed, plus a forked tail fin. `rings` along the body and `segments` around
/// it set the level of detail (2 · rings · segments + 4 triangles).
pub fn fish_lod(rings: u32, segments: u32) -> MeshData {
    let rings = rings.max(2);
    let segments = segments.max(3);
    let mut m = MeshData::default();
    for r in 0..=rings {
        let s = r as f32 / rings as f32; // 0 nose … 1 tail root
        let (ry, rz) = body_radii(s);
        for k in 0..=segments {
            let phi = std::f32::consts::TAU * k as f32 / segments as f32;
            let (sp, cp) = phi.sin_cos();
            m.positions.push(Vec3::new(body_x(s), ry * cp, rz * sp));
            m.uvs.push(Vec2::new(s * 3.0, cp * 0.5 + 0.5));
        }
    }
    m.indices = grid_indices(segments, rings, 1);
    // the fork: top tip, the notch, bottom tip
    tail_fin(
        &mut m,
        &[
            Vec3::new(-0.55, 0.14, 0.0),
            Vec3::new(-0.47, 0.0, 0.0),
            Vec3::new(-0.55, -0.14, 0.0),
        ],
    );
    m.compute_normals();
    m
}

/// The farthest level, for fish a few pixels long and for the shadow map: a double cone of
/// four sides from the nose through the thickest cross-section to the tail root, and a
/// one-triangle fin on each side (10 triangles, 5 facing any viewer). Its silhouette from the
/// side and from above is the lofted body's to within a few per cent of its length.
pub fn fish_far() -> MeshData {
    let mut m = MeshData::default();
    let s_mid = 0.3;
    let (ry, rz) = body_radii(s_mid);
    let x_mid = body_x(s_mid);
    // nose, the thickest ring (top, one side, bottom, other side), tail root
    let ring = [
        (Vec3::new(x_mid, ry, 0.0), 1.0),
        (Vec3::new(x_mid, 0.0, rz), 0.5),
        (Vec3::new(x_mid, -ry, 0.0), 0.0),
        (Vec3::new(x_mid, 0.0, -rz), 0.5),
    ];
    m.positions.push(Vec3::new(0.5, 0.0, 0.0));
    m.uvs.push(Vec2::new(0.0, 0.5));
    for (p, v) in ring {
        m.positions.push(p);
        m.uvs.push(Vec2::new(s_mid * 3.0, v));
    }
    m.positions.push(TAIL_ROOT);
    m.uvs.push(Vec2::new(3.0, 0.5));
    let (nose, tail) = (0u32, 5u32);
    for k in 0..4u32 {
        let (a, b) = (1 + k, 1 + (k + 1) % 4);
        // around +x the ring runs top → +z → bottom → −z
        m.indices.extend_from_slice(&[nose, a, b, b, a, tail]);
    }
    tail_fin(
        &mut m,
        &[Vec3::new(-0.55, 0.14, 0.0), Vec3::new(-0.55, -0.14, 0.0)],
    );
    m.compute_normals();
    m
}

/// The tail fin: a fan from the tail root through `edge` (top to bottom), once facing +z and
/// once −z.
fn tail_fin(m: &mut MeshData, edge: &[Vec3]) {
    for side in [1.0f32, -1.0] {
        let base = m.positions.len() as u32;
        for p in std::iter::once(TAIL_ROOT).chain(edge.iter().copied()) {
            m.positions.push(p + Vec3::Z * FIN_HALF_THICKNESS * side);
            m.uvs
                .push(Vec2::new(3.0 + (TAIL_ROOT.x - p.x) * 4.0, p.y * 2.0 + 0.5));
        }
        for i in 1..edge.len() as u32 {
            let (a, b) = (base + i, base + i + 1);
            if side > 0.0 {
                m.indices.extend_from_slice(&[base, a, b]);
            } else {
                m.indices.extend_from_slice(&[base, b, a]);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every triangle with an area faces away from the body's axis (the fin's: away from its
    /// other side), so culling back faces never removes a visible one.
    fn every_triangle_faces_out(m: &MeshData) {
        for t in m.indices.chunks_exact(3) {
            let [a, b, c] = [t[0], t[1], t[2]].map(|i| m.positions[i as usize]);
            let n = (b - a).cross(c - a);
            if n.length() < 1e-7 {
                continue;
            }
            let centre = (a + b + c) / 3.0;
            let out = if centre.x < TAIL_ROOT.x + 1e-4 && centre.z.abs() <= FIN_HALF_THICKNESS {
                Vec3::Z * centre.z.signum()
            } else {
                Vec3::new(0.0, centre.y, centre.z)
            };
            assert!(n.dot(out) > 0.0, "{a} {b} {c}: normal {n}, outward {out}");
        }
    }

    #[test]
    fn every_level_is_wound_outwards_for_back_face_culling() {
        for (r, s) in [(20, 16), (7, 6), (3, 3)] {
            every_triangle_faces_out(&fish_lod(r, s));
        }
        every_triangle_faces_out(&fish_far());
        assert!(super::super::mesh::outward(&fish(), Vec3::ZERO) > 0.9);
    }

    #[test]
    fn the_far_level_has_the_bodys_extent_in_ten_triangles() {
        let far = fish_far();
        let full = fish();
        assert_eq!(far.indices.len() / 3, 10);
        // the body (in front of the tail root) and the whole mesh, fin included
        let extent = |m: &MeshData, body_only: bool| {
            m.positions
                .iter()
                .filter(|p| !body_only || p.x > TAIL_ROOT.x + 1e-4)
                .fold((Vec3::MAX, Vec3::MIN), |(lo, hi), p| {
                    (lo.min(*p), hi.max(*p))
                })
        };
        let ((flo, fhi), (olo, ohi)) = (extent(&far, false), extent(&full, false));
        // same length and fin span
        assert!((flo.x - olo.x).abs() < 1e-6 && (fhi.x - ohi.x).abs() < 1e-6);
        assert!((flo.y - olo.y).abs() < 1e-6 && (fhi.y - ohi.y).abs() < 1e-6);
        // the body's height and width within 10 % of the lofted body's
        let ((_, fb), (_, ob)) = (extent(&far, true), extent(&full, true));
        assert!((fb.y - ob.y).abs() < 0.1 * ob.y, "{fb} vs {ob}");
        assert!((fb.z - ob.z).abs() < 0.1 * ob.z, "{fb} vs {ob}");
        // the back is dark and the belly light: uv.y runs belly 0 → back 1 on both
        let top = far
            .positions
            .iter()
            .position(|p| p.x > TAIL_ROOT.x && p.y == fb.y)
            .unwrap();
        assert_eq!(far.uvs[top].y, 1.0);
    }
}
