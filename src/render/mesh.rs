//! Meshes as vertex + index buffers with an explicit vertex layout (the "VAO" of the lecture):
//! position, normal, tangent (xyz + handedness w), uv. Generated in code: terrain, rocks,
//! boxes, spheres and capsules (the fish body is in `fish_mesh`).

use bytemuck::{Pod, Zeroable};
use glam::{Vec2, Vec3};
use wgpu::util::DeviceExt;

#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
pub struct Vertex {
    pub position: [f32; 3],
    pub normal: [f32; 3],
    pub tangent: [f32; 4],
    pub uv: [f32; 2],
}

impl Vertex {
    pub const ATTRIBUTES: [wgpu::VertexAttribute; 4] = wgpu::vertex_attr_array![
        0 => Float32x3, 1 => Float32x3, 2 => Float32x4, 3 => Float32x2
    ];

    pub fn layout() -> wgpu::VertexBufferLayout<'static> {
        wgpu::VertexBufferLayout {
            array_stride: std::mem::size_of::<Vertex>() as u64,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes: &Self::ATTRIBUTES,
        }
    }
}

/// CPU mesh data.
#[derive(Debug, Clone, Default)]
pub struct MeshData {
    pub positions: Vec<Vec3>,
    pub normals: Vec<Vec3>,
    pub uvs: Vec<Vec2>,
    pub indices: Vec<u32>,
    /// grids only: the same surface over fewer of its vertices (see [`grid_indices`])
    pub coarse_indices: Option<Vec<u32>>,
}

impl MeshData {
    /// Smooth normals from area-weighted face normals (when the generator gave none).
    pub fn compute_normals(&mut self) {
        let mut n = vec![Vec3::ZERO; self.positions.len()];
        for t in self.indices.chunks_exact(3) {
            let [a, b, c] = [t[0] as usize, t[1] as usize, t[2] as usize];
            let f = (self.positions[b] - self.positions[a])
                .cross(self.positions[c] - self.positions[a]);
            n[a] += f;
            n[b] += f;
            n[c] += f;
        }
        self.normals = n.into_iter().map(|v| v.normalize_or(Vec3::Y)).collect();
    }

    /// Per-vertex tangents from uv derivatives (Lengyel 2001), Gram–Schmidt orthogonalised,
    /// with the bitangent's handedness in w.
    pub fn vertices(&self) -> Vec<Vertex> {
        let count = self.positions.len();
        let mut tan = vec![Vec3::ZERO; count];
        let mut bit = vec![Vec3::ZERO; count];
        for t in self.indices.chunks_exact(3) {
            let [a, b, c] = [t[0] as usize, t[1] as usize, t[2] as usize];
            let (e1, e2) = (
                self.positions[b] - self.positions[a],
                self.positions[c] - self.positions[a],
            );
            let (d1, d2) = (self.uvs[b] - self.uvs[a], self.uvs[c] - self.uvs[a]);
            let det = d1.x * d2.y - d2.x * d1.y;
            if det.abs() < 1e-12 {
                continue;
            }
            let r = 1.0 / det;
            let sdir = (e1 * d2.y - e2 * d1.y) * r;
            let tdir = (e2 * d1.x - e1 * d2.x) * r;
            for i in [a, b, c] {
                tan[i] += sdir;
                bit[i] += tdir;
            }
        }
        (0..count)
            .map(|i| {
                let n = self.normals[i];
                let mut t = tan[i] - n * n.dot(tan[i]);
                if t.length_squared() < 1e-12 {
                    t = n.any_orthonormal_vector();
                }
                let t = t.normalize();
                let w = if n.cross(t).dot(bit[i]) < 0.0 {
                    -1.0
                } else {
                    1.0
                };
                Vertex {
                    position: self.positions[i].to_array(),
                    normal: n.to_array(),
                    tangent: [t.x, t.y, t.z, w],
                    uv: self.uvs[i].to_array(),
                }
            })
            .collect()
    }
}

/// A mesh on the GPU.
pub struct GpuMesh {
    pub vertex_buffer: wgpu::Buffer,
    pub index_buffer: wgpu::Buffer,
    pub index_count: u32,
    /// the coarse index list of a grid, and its length
    pub coarse: Option<(wgpu::Buffer, u32)>,
}

impl GpuMesh {
    pub fn upload(device: &wgpu::Device, label: &str, mesh: &MeshData) -> Self {
        let vertices = mesh.vertices();
        Self {
            vertex_buffer: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents: bytemuck::cast_slice(&vertices),
                usage: wgpu::BufferUsages::VERTEX,
            }),
            index_buffer: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents: bytemuck::cast_slice(&mesh.indices),
                usage: wgpu::BufferUsages::INDEX,
            }),
            index_count: mesh.indices.len() as u32,
            coarse: mesh.coarse_indices.as_ref().map(|idx| {
                let buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some(label),
                    contents: bytemuck::cast_slice(idx),
                    usage: wgpu::BufferUsages::INDEX,
                });
                (buffer, idx.len() as u32)
            }),
        }
    }

    /// One instance, with the coarse index list when asked and there is one.
    pub fn draw_detail(&self, pass: &mut wgpu::RenderPass<'_>, coarse: bool) {
        match (&self.coarse, coarse) {
            (Some((indices, count)), true) => {
                pass.set_vertex_buffer(0, self.vertex_buffer.slice(..));
                pass.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint32);
                pass.draw_indexed(0..*count, 0, 0..1);
            }
            _ => self.draw(pass, 1),
        }
    }

    pub fn draw(&self, pass: &mut wgpu::RenderPass<'_>, instances: u32) {
        self.draw_instances(pass, 0..instances);
    }

    /// Draws the instances `range` of the instance buffer bound at slot 1 (if any).
    pub fn draw_instances(&self, pass: &mut wgpu::RenderPass<'_>, range: std::ops::Range<u32>) {
        if range.is_empty() {
            return;
        }
        pass.set_vertex_buffer(0, self.vertex_buffer.slice(..));
        pass.set_index_buffer(self.index_buffer.slice(..), wgpu::IndexFormat::Uint32);
        pass.draw_indexed(0..self.index_count, 0, range);
    }

    pub fn triangle_count(&self) -> u32 {
        self.index_count / 3
    }
}

/// Indices of a (cols+1)×(rows+1) vertex grid, counter-clockwise seen from +normal when u runs
/// along +x and v along −z (or, for surfaces, with the generator's orientation), over every
/// `step`-th row and column of vertices (and the last, so the same area is covered): `step` 2
/// is a level of detail with a quarter of the triangles that needs no vertices of its own.
pub(super) fn grid_indices(cols: u32, rows: u32, step: u32) -> Vec<u32> {
    let lines = |n: u32| -> Vec<u32> {
        let mut v: Vec<u32> = (0..n).step_by(step.max(1) as usize).collect();
        v.push(n);
        v
    };
    let (cs, rs) = (lines(cols), lines(rows));
    let mut idx = Vec::with_capacity(cs.len() * rs.len() * 6);
    for r in rs.windows(2) {
        for c in cs.windows(2) {
            let i0 = r[0] * (cols + 1) + c[0];
            let i1 = r[0] * (cols + 1) + c[1];
            let i2 = r[1] * (cols + 1) + c[0];
            let i3 = r[1] * (cols + 1) + c[1];
            idx.extend_from_slice(&[i0, i2, i1, i1, i2, i3]);
        }
    }
    idx
}

/// The step of the coarse index lists over the water and seabed grids.
pub const COARSE_GRID_STEP: u32 = 2;

/// Seabed dunes: height above the floor level at (x, z), metres per unit `relief`.
pub fn dunes(x: f32, z: f32) -> f32 {
    0.5 * (0.23 * x + 0.4 * (0.11 * z).sin()).sin()
        + 0.3 * (0.37 * z - 0.21 * x).sin()
        + 0.15 * (0.9 * x + 0.7 * z).sin() * (0.5 * z).cos()
}

/// A square height field centred on the origin; y = floor + relief · dunes, rising towards
/// the edges so the lagoon's floor meets the horizon less abruptly.
pub fn terrain(size: f32, resolution: u32, floor_y: f32, relief: f32) -> MeshData {
    let n = resolution.max(2);
    let mut m = MeshData::default();
    let h = |x: f32, z: f32| {
        let r = (x * x + z * z).sqrt() / (0.5 * size);
        floor_y + relief * dunes(x, z) + 1.5 * (r - 0.35).max(0.0).powi(2)
    };
    for j in 0..=n {
        for i in 0..=n {
            let x = (i as f32 / n as f32 - 0.5) * size;
            let z = (j as f32 / n as f32 - 0.5) * size;
            m.positions.push(Vec3::new(x, h(x, z), z));
            let e = 0.05;
            let dx = (h(x + e, z) - h(x - e, z)) / (2.0 * e);
            let dz = (h(x, z + e) - h(x, z - e)) / (2.0 * e);
            m.normals.push(Vec3::new(-dx, 1.0, -dz).normalize());
            m.uvs.push(Vec2::new(x, z));
        }
    }
    m.indices = grid_indices(n, n, 1);
    m.coarse_indices = Some(grid_indices(n, n, COARSE_GRID_STEP));
    m
}

/// A UV sphere, optionally split into a capsule by `half_length` along x.
pub fn capsule(radius: f32, half_length: f32, rings: u32, segments: u32) -> MeshData {
    let rings = rings.max(2) & !1; // even, so the equator ring exists and can be doubled
    let mut m = MeshData::default();
    for k in 0..=rings + 1 {
        // the equator appears twice: once on each hemisphere, joined by the cylinder
        let (r, shift) = if k <= rings / 2 {
            (k, half_length)
        } else {
            (k - 1, -half_length)
        };
        let theta = std::f32::consts::PI * r as f32 / rings as f32; // from the +x pole
        let (st, ct) = theta.sin_cos();
        for s in 0..=segments {
            let phi = std::f32::consts::TAU * s as f32 / segments as f32;
            let n = Vec3::new(ct, st * phi.cos(), st * phi.sin());
            m.positions.push(n * radius + Vec3::X * shift);
            m.normals.push(n);
            m.uvs.push(Vec2::new(
                s as f32 / segments as f32 * 2.0,
                k as f32 / (rings + 1) as f32,
            ));
        }
    }
    m.indices = grid_indices(segments, rings + 1, 1);
    m
}

/// An axis-aligned box centred on the origin, flat-shaded (4 vertices per face).
pub fn cuboid(size: Vec3) -> MeshData {
    let h = size * 0.5;
    let mut m = MeshData::default();
    // (normal, u axis, v axis)
    let faces = [
        (Vec3::X, Vec3::NEG_Z, Vec3::Y),
        (Vec3::NEG_X, Vec3::Z, Vec3::Y),
        (Vec3::Y, Vec3::X, Vec3::NEG_Z),
        (Vec3::NEG_Y, Vec3::X, Vec3::Z),
        (Vec3::Z, Vec3::X, Vec3::Y),
        (Vec3::NEG_Z, Vec3::NEG_X, Vec3::Y),
    ];
    for (n, u, v) in faces {
        let base = m.positions.len() as u32;
        for (a, b) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
            let p = n * h + u * a * h + v * b * h;
            let p = Vec3::new(
                p.x.clamp(-h.x, h.x),
                p.y.clamp(-h.y, h.y),
                p.z.clamp(-h.z, h.z),
            );
            m.positions.push(p);
            m.normals.push(n);
            let ext = Vec2::new(
                (u * size).abs().max_element(),
                (v * size).abs().max_element(),
            );
            m.uvs
                .push(Vec2::new((a + 1.0) * 0.5 * ext.x, (b + 1.0) * 0.5 * ext.y));
        }
        m.indices
            .extend_from_slice(&[base, base + 1, base + 2, base, base + 2, base + 3]);
    }
    m
}

fn hash01(i: u32, seed: u32) -> f32 {
    let mut x = i.wrapping_mul(0x2c1b_3c6d) ^ seed.wrapping_mul(0x297a_2d39);
    x ^= x >> 12;
    x = x.wrapping_mul(0x9E37_79B9);
    x ^= x >> 15;
    (x & 0xFFFF) as f32 / 65535.0
}

/// A boulder: a sphere pushed in and out by a few seeded lumps, flattened where it rests.
pub fn rock(radius: f32, seed: u32) -> MeshData {
    let mut m = capsule(1.0, 0.0, 24, 32);
    let lumps: Vec<(Vec3, f32)> = (0..7)
        .map(|i| {
            let d = Vec3::new(
                hash01(i, seed) * 2.0 - 1.0,
                hash01(i + 50, seed) * 2.0 - 1.0,
                hash01(i + 99, seed) * 2.0 - 1.0,
            );
            (d.normalize_or(Vec3::X), 0.25 * (hash01(i + 7, seed) - 0.4))
        })
        .collect();
    for p in &mut m.positions {
        let d = p.normalize();
        let mut r = 1.0;
        for (c, a) in &lumps {
            r += a * d.dot(*c).max(0.0).powi(3);
        }
        let mut q = d * r * radius;
        q.y = q.y.max(-0.25 * radius) * 0.8; // squat, and flat at the bottom
        *p = q;
    }
    m.compute_normals();
    m
}

/// How far past the screen's edges the projected water grid reaches (in ndc): the waves
/// displace vertices sideways and up, and the grid must still cover the screen's corners.
pub const WATER_GRID_MARGIN: f32 = 0.15;

/// The projected water grid (Johanson 2004): screen positions in ndc, −1 − margin ..
/// 1 + margin each way (the vertex shader meets each one's view ray with the water plane), its
/// indices and its coarse indices (every [`COARSE_GRID_STEP`]-th row and column).
pub fn water_grid(resolution: u32) -> (Vec<[f32; 2]>, Vec<u32>, Vec<u32>) {
    let n = resolution.max(2);
    let reach = 1.0 + WATER_GRID_MARGIN;
    let mut v = Vec::with_capacity(((n + 1) * (n + 1)) as usize);
    for j in 0..=n {
        for i in 0..=n {
            let at = |t: u32| (t as f32 / n as f32 * 2.0 - 1.0) * reach;
            v.push([at(i), at(j)]);
        }
    }
    (
        v,
        grid_indices(n, n, 1),
        grid_indices(n, n, COARSE_GRID_STEP),
    )
}

#[cfg(test)]
/// Fraction of non-degenerate triangles whose winding faces away from `centre` (the
/// triangles collapsed onto a pole have no orientation and are not counted).
pub(super) fn outward(m: &MeshData, centre: Vec3) -> f32 {
    let (mut ok, mut total) = (0, 0);
    for t in m.indices.chunks_exact(3) {
        let [a, b, c] = [t[0], t[1], t[2]].map(|i| m.positions[i as usize]);
        let n = (b - a).cross(c - a);
        if n.length_squared() < 1e-12 {
            continue;
        }
        total += 1;
        if n.dot((a + b + c) / 3.0 - centre) > 0.0 {
            ok += 1;
        }
    }
    ok as f32 / total as f32
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn closed_meshes_wind_counter_clockwise_outwards() {
        assert_eq!(outward(&cuboid(Vec3::new(1.0, 2.0, 3.0)), Vec3::ZERO), 1.0);
        assert!(outward(&capsule(1.0, 0.5, 12, 16), Vec3::ZERO) > 0.99);
    }

    /// The coarse list covers the same area with a quarter of the triangles (and an odd side
    /// keeps its last row), wound the same way.
    #[test]
    fn coarse_grid_indices_cover_the_same_surface() {
        for n in [8u32, 9, 192] {
            let t = terrain(10.0, n, -3.0, 0.0);
            let area = |idx: &[u32]| -> f64 {
                idx.chunks_exact(3)
                    .map(|tri| {
                        let [a, b, c] = [tri[0], tri[1], tri[2]].map(|i| t.positions[i as usize]);
                        let n = (b - a).cross(c - a);
                        assert!(n.y > 0.0, "faces up");
                        0.5 * f64::from(n.y)
                    })
                    .sum()
            };
            let coarse = t.coarse_indices.as_ref().unwrap();
            let (a_coarse, a_full) = (area(coarse), area(&t.indices));
            assert!(
                (a_coarse - 100.0).abs() < 1e-2 && (a_full - 100.0).abs() < 1e-2,
                "{n}: {a_coarse} {a_full}"
            );
            let cells = n.div_ceil(COARSE_GRID_STEP);
            assert_eq!(coarse.len() as u32, cells * cells * 6);
        }
    }

    #[test]
    fn terrain_faces_up_and_tangents_follow_u() {
        let t = terrain(10.0, 8, -3.0, 0.5);
        for tri in t.indices.chunks_exact(3) {
            let [a, b, c] = [tri[0], tri[1], tri[2]].map(|i| t.positions[i as usize]);
            assert!((b - a).cross(c - a).y > 0.0);
        }
        let v = t.vertices();
        // u = world x, so the tangent points along +x; v = world z, so the bitangent is +z
        let mid = &v[v.len() / 2];
        assert!(mid.tangent[0] > 0.9);
        let n = Vec3::from(mid.normal);
        let b = n.cross(Vec3::new(mid.tangent[0], mid.tangent[1], mid.tangent[2])) * mid.tangent[3];
        assert!(b.z > 0.9, "{b}");
    }
}
