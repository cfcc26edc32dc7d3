//! The school as instanced draws (fish.wgsl): one instance buffer of per-fish data (position,
//! scale, orientation, tail phase) with step mode Instance, and the fish mesh at four levels
//! of detail (`fish_mesh`). Each frame the fish are sorted into ranges of that buffer: those
//! seen large get the full mesh, smaller ones coarser meshes, fish outside the view are left
//! out of the main pass; the shadow pass draws every fish with the coarsest mesh. Back faces
//! are culled in both passes: on a software rasteriser the fish cost per triangle set up, not
//! per pixel (level of detail: Clark 1976,
//! "Hierarchical Geometric Models for Visible Surface Algorithms"; frustum planes from the
//! projection matrix: Gribb & Hartmann 2001).

use std::ops::Range;

use glam::{Mat4, Quat, Vec4};

use crate::school::FishInstance;

use super::fish_mesh;
use super::mesh::{GpuMesh, MeshData, Vertex};
use super::pipeline::{Ctx, OPAQUE_DEPTH, PerShadowFilter, PipelineDesc, Technique};
use super::shadow::SHADOW_BIAS;

/// Per-instance fish data: position + scale, orientation quaternion (x, y, z, w), tail phase.
#[repr(C)]
#[derive(Debug, Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
pub struct FishInstanceGpu {
    pub position_scale: [f32; 4],
    pub rotation: [f32; 4],
    pub tail_phase: f32,
}

impl FishInstanceGpu {
    pub const ATTRIBUTES: [wgpu::VertexAttribute; 3] =
        wgpu::vertex_attr_array![4 => Float32x4, 5 => Float32x4, 6 => Float32];

    pub fn layout() -> wgpu::VertexBufferLayout<'static> {
        wgpu::VertexBufferLayout {
            array_stride: std::mem::size_of::<Self>() as u64,
            step_mode: wgpu::VertexStepMode::Instance,
            attributes: &Self::ATTRIBUTES,
        }
    }

    fn from(f: &FishInstance) -> Self {
        let q: Quat = f.orientation.normalize();
        Self {
            position_scale: [f.position.x, f.position.y, f.position.z, f.scale],
            rotation: q.to_array(),
            tail_phase: f.tail_phase,
        }
    }
}

/// The fish pipelines: lit (main pass) and depth only (shadow pass).
pub struct FishPipelines {
    pub main: PerShadowFilter<wgpu::RenderPipeline>,
    pub shadow: wgpu::RenderPipeline,
}

impl Technique for FishPipelines {
    const SHADER: &'static str = "fish.wgsl";

    fn build(ctx: &Ctx, m: &wgpu::ShaderModule) -> Self {
        let l = ctx.layouts;
        let buffers = [Some(Vertex::layout()), Some(FishInstanceGpu::layout())];
        Self {
            main: ctx.lit_pipelines(
                m,
                PipelineDesc {
                    label: "fish",
                    groups: &[&l.frame, &l.material],
                    vs: "vs_main",
                    fs: Some("fs_main"),
                    buffers: &buffers,
                    color: Some(ctx.caps.hdr_format),
                    depth: OPAQUE_DEPTH,
                    cull: Some(wgpu::Face::Back), // the fin is two one-sided copies
                },
            ),
            shadow: ctx.pipeline(
                m,
                PipelineDesc {
                    label: "fish.shadow",
                    groups: &[&l.shadow_frame],
                    vs: "vs_shadow",
                    fs: None,
                    buffers: &buffers,
                    color: None,
                    depth: Some((true, wgpu::CompareFunction::Less, SHADOW_BIAS)),
                    cull: Some(wgpu::Face::Back),
                },
            ),
        }
    }
}

/// Levels of detail, finest first; the last is the shadow pass's.
pub const LEVELS: usize = 4;
pub const FAR_LEVEL: usize = LEVELS - 1;

/// The mesh of each level, finest first: 644, 88, 22 and 10 triangles.
pub fn level_meshes() -> [MeshData; LEVELS] {
    [
        fish_mesh::fish(),
        fish_mesh::fish_lod(7, 6),
        fish_mesh::fish_lod(3, 3),
        fish_mesh::fish_far(),
    ]
}

/// Fish drawn at least this many pixels long get the full mesh, at least `MEDIUM_PX` the middle
/// one, at least `COARSE_PX` the coarse one, shorter ones the far one (at `fish_detail` 1;
/// lower detail divides these lengths up).
pub const FULL_PX: f32 = 40.0;
pub const MEDIUM_PX: f32 = 12.0;
pub const COARSE_PX: f32 = 4.0;

/// The fish meshes, finest first.
pub struct FishMeshes {
    pub lods: [GpuMesh; LEVELS],
}

impl FishMeshes {
    pub fn new(device: &wgpu::Device) -> Self {
        Self {
            lods: level_meshes().map(|m| GpuMesh::upload(device, "fish", &m)),
        }
    }
}

/// Where each level's fish lie in the instance buffer this frame.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct LodRanges {
    /// per level, finest first: the visible fish drawn with that mesh
    pub visible: [Range<u32>; LEVELS],
    /// every fish (visible or not), for the shadow pass
    pub all: Range<u32>,
}

impl LodRanges {
    pub fn visible_count(&self) -> u32 {
        self.visible.iter().map(|r| r.len() as u32).sum()
    }
}

/// What decides a fish's level: the camera, the target's height and the detail setting.
pub struct LodView {
    pub clip_from_world: Mat4,
    /// pixels per metre at one metre from the camera: target height / (2 tan(fov / 2))
    pub px_per_m_at_1m: f32,
    pub eye: glam::Vec3,
    /// 1 = full detail; smaller values give coarser meshes sooner; 0 = the far mesh everywhere
    pub detail: f32,
}

/// The six frustum planes (a, b, c, d with a x + b y + c z + d ≥ 0 inside) of a wgpu
/// (0..1 depth) projection.
fn frustum_planes(m: Mat4) -> [Vec4; 6] {
    let r = [m.row(0), m.row(1), m.row(2), m.row(3)];
    [
        r[3] + r[0],
        r[3] - r[0],
        r[3] + r[1],
        r[3] - r[1],
        r[2],
        r[3] - r[2],
    ]
    .map(|p| p / p.truncate().length().max(1e-12))
}

/// The level for a fish `length_px` long on screen (None: leave it out).
pub fn level_for(length_px: f32, detail: f32) -> usize {
    let d = detail.clamp(0.0, 4.0);
    if d > 0.0 && length_px * d >= FULL_PX {
        0
    } else if d > 0.0 && length_px * d >= MEDIUM_PX {
        1
    } else if d > 0.0 && length_px * d >= COARSE_PX {
        2
    } else {
        FAR_LEVEL
    }
}

/// Sorts the fish into ranges by level each frame; its buffers are kept from frame to frame.
#[derive(Default)]
pub struct LodSorter {
    levels: [Vec<FishInstanceGpu>; LEVELS + 1],
    /// the instances in draw order: [full | medium | coarse | far | out of view]
    pub sorted: Vec<FishInstanceGpu>,
}

impl LodSorter {
    /// Orders `fish` into [`Self::sorted`] and says where each range is.
    pub fn sort(&mut self, fish: &[FishInstance], view: &LodView) -> LodRanges {
        let planes = frustum_planes(view.clip_from_world);
        for l in &mut self.levels {
            l.clear();
        }
        for f in fish {
            // the mesh spans about ±0.55 of its scale from its centre
            let radius = 0.6 * f.scale;
            let p = f.position.extend(1.0);
            let inside = planes.iter().all(|pl| pl.dot(p) >= -radius);
            let level = if inside {
                let dist = (f.position - view.eye).length().max(1e-3);
                let length_px = 1.1 * f.scale * view.px_per_m_at_1m / dist;
                level_for(length_px, view.detail)
            } else {
                LEVELS
            };
            self.levels[level].push(FishInstanceGpu::from(f));
        }
        self.sorted.clear();
        let mut starts = [0u32; LEVELS + 2];
        for (i, l) in self.levels.iter().enumerate() {
            self.sorted.extend_from_slice(l);
            starts[i + 1] = self.sorted.len() as u32;
        }
        LodRanges {
            visible: std::array::from_fn(|i| starts[i]..starts[i + 1]),
            all: 0..starts[LEVELS + 1],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    fn fish_at(x: f32, z: f32) -> FishInstance {
        FishInstance {
            position: Vec3::new(x, 0.0, z),
            orientation: Quat::IDENTITY,
            scale: 0.3,
            tail_phase: 0.0,
        }
    }

    #[test]
    fn near_fish_get_the_full_mesh_far_ones_coarser_ones_and_unseen_ones_only_shadows() {
        let eye = Vec3::new(0.0, 0.0, 5.0);
        let view_from_world = glam::camera::rh::view::look_at_mat4(eye, Vec3::ZERO, Vec3::Y);
        let clip_from_view =
            glam::camera::rh::proj::directx::perspective(1.0, 16.0 / 9.0, 0.05, 300.0);
        let view = LodView {
            clip_from_world: clip_from_view * view_from_world,
            px_per_m_at_1m: 720.0 / (2.0 * 0.5f32.tan()),
            eye,
            detail: 1.0,
        };
        // 1 m away (≈ 218 px long), 20 m away (≈ 11 px), 100 m away (≈ 2 px), and behind the camera
        let fish = [
            fish_at(0.0, 4.0),
            fish_at(0.0, -15.0),
            fish_at(0.0, -95.0),
            fish_at(0.0, 10.0),
        ];
        let mut sorter = LodSorter::default();
        let r = sorter.sort(&fish, &view);
        let out = &sorter.sorted;
        assert_eq!(r.visible, [0..1, 1..1, 1..2, 2..3]);
        assert_eq!(r.all, 0..4);
        assert_eq!(out[0].position_scale[2], 4.0);
        assert_eq!(
            out[3].position_scale[2], 10.0,
            "the unseen fish is last, for shadows"
        );
        // less detail: the near fish drops a level
        let coarse = LodView {
            detail: 0.15,
            ..view
        };
        let r = sorter.sort(&fish, &coarse);
        assert_eq!(r.visible[0], 0..0);
        assert_eq!(r.visible_count(), 3);
    }

    #[test]
    fn levels_are_coarser_and_the_finest_is_the_full_fish() {
        let tris = level_meshes().map(|m| m.indices.len() / 3);
        assert_eq!(tris[0], fish_mesh::fish().indices.len() / 3);
        assert!(tris.windows(2).all(|w| w[0] > w[1]), "{tris:?}");
        assert!(tris[0] > 50 * tris[FAR_LEVEL], "{tris:?}");
    }
}
