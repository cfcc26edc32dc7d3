//! The sun's shadow map (shadow.wgsl): depth-only rendering of the casters — rocks and floating
//! bodies here, the fish with `vs_shadow` in fish.wgsl at their coarsest level — through an
//! orthographic light camera fitted to the box where things cast shadows (the fish's swim box
//! and everything in it), with a slope-scaled depth bias (Williams 1978, "Casting Curved
//! Shadows on Curved Surfaces"; lookup with PCF in common.wgsl, Reeves, Salesin & Cook 1987).

use glam::{Mat4, Vec3};

use crate::scene::{Object, Scene};

use super::caps::RenderCaps;
use super::mesh::Vertex;
use super::pipeline::{Ctx, PipelineDesc, Technique};

/// Texels per side of the shadow map.
pub use super::caps::SHADOW_MAP_SIZE;

/// Slope-scaled depth bias of the shadow casters (in depth-format units and per unit slope).
pub const SHADOW_BIAS: wgpu::DepthBiasState = wgpu::DepthBiasState {
    constant: 2,
    slope_scale: 2.5,
    clamp: 0.0,
};

/// The depth-only pipeline of the rocks and floating bodies.
pub struct ShadowPipeline {
    pub pipeline: wgpu::RenderPipeline,
}

impl Technique for ShadowPipeline {
    const SHADER: &'static str = "shadow.wgsl";

    fn build(ctx: &Ctx, m: &wgpu::ShaderModule) -> Self {
        let l = ctx.layouts;
        Self {
            pipeline: ctx.pipeline(
                m,
                PipelineDesc {
                    label: "shadow",
                    groups: &[&l.shadow_frame, &l.object],
                    vs: "vs_main",
                    fs: None,
                    buffers: &[Some(Vertex::layout())],
                    color: None,
                    depth: Some((true, wgpu::CompareFunction::Less, SHADOW_BIAS)),
                    cull: None,
                },
            ),
        }
    }
}

/// The shadow map's depth texture (its view is bound by the lit passes and the debug view).
pub fn shadow_map(device: &wgpu::Device, caps: &RenderCaps) -> wgpu::TextureView {
    device
        .create_texture(&wgpu::TextureDescriptor {
            label: Some("shadow map"),
            size: wgpu::Extent3d {
                width: caps.shadow_map_size_px,
                height: caps.shadow_map_size_px,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: caps.depth_format,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        })
        .create_view(&Default::default())
}

/// The world box whose contents cast shadows: the fish's swim box (widened by a fish length),
/// from the seabed up to above the waves where the floating bodies ride, and every rock and
/// body in it.
pub fn caster_box(scene: &Scene) -> (Vec3, Vec3) {
    let w = scene.simulation.school_half_width + scene.school.fish_scale;
    let mut lo = Vec3::new(-w, scene.water.level - scene.seabed_depth(), -w);
    let mut hi = Vec3::new(w, scene.water.level + 1.0, w);
    for o in &scene.objects {
        match o {
            Object::Rock {
                position, radius, ..
            } => {
                let p = Vec3::from(*position);
                lo = lo.min(p - Vec3::splat(*radius));
                hi = hi.max(p + Vec3::splat(*radius));
            }
            Object::Floating { position, .. } => {
                let p = Vec3::new(position[0], scene.water.level, position[1]);
                lo = lo.min(p - Vec3::splat(1.5));
                hi = hi.max(p + Vec3::splat(1.5));
            }
            Object::Seabed { .. } => {}
        }
    }
    (lo, hi)
}

/// The sun's orthographic camera, fitted around [`caster_box`] as the sun sees it.
pub fn light_clip_from_world(scene: &Scene) -> Mat4 {
    let sun = Vec3::from(scene.sun.direction).normalize_or(Vec3::Y);
    let (lo, hi) = caster_box(scene);
    let centre = 0.5 * (lo + hi);
    let radius = 0.5 * (hi - lo).length();
    let eye = centre + sun * (radius + 1.0);
    // the map's "up" along a horizontal edge of the box, so the box's square top lies along
    // the map's axes rather than as a diamond that leaves its corners unused
    let up = if sun.z.abs() > 0.99 { Vec3::X } else { Vec3::Z };
    let view = glam::camera::rh::view::look_at_mat4(eye, centre, up);
    let mut min = Vec3::splat(f32::MAX);
    let mut max = Vec3::splat(f32::MIN);
    for i in 0..8 {
        let corner = Vec3::new(
            if i & 1 == 0 { lo.x } else { hi.x },
            if i & 2 == 0 { lo.y } else { hi.y },
            if i & 4 == 0 { lo.z } else { hi.z },
        );
        let p = view.transform_point3(corner);
        min = min.min(p);
        max = max.max(p);
    }
    // right-handed view space looks down −z: near and far are distances along it
    glam::camera::rh::proj::directx::orthographic(
        min.x,
        max.x,
        min.y,
        max.y,
        (-max.z - 0.5).max(0.01),
        -min.z + 0.5,
    ) * view
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_light_camera_sees_the_whole_swim_box() {
        let text = std::fs::read_to_string("scenes/water.ron").unwrap();
        let scene = crate::scene::parse_scene(&text, std::path::Path::new("water.ron")).unwrap();
        let m = light_clip_from_world(&scene);
        let w = scene.simulation.school_half_width;
        assert!(w >= 5.0, "the shipped swim box is at least ±5 m: {w}");
        let level = scene.water.level;
        let floor = level - scene.seabed_depth();
        for x in [-w, w] {
            for z in [-w, w] {
                for y in [floor, level] {
                    let c = m.project_point3(Vec3::new(x, y, z));
                    assert!(
                        c.x.abs() <= 1.0 && c.y.abs() <= 1.0 && (0.0..=1.0).contains(&c.z),
                        "corner ({x}, {y}, {z}) is outside the shadow map: {c}"
                    );
                }
            }
        }
        // and the map is not wasted: the box fills most of it across
        let a = m.project_point3(Vec3::new(-w, floor, -w));
        let b = m.project_point3(Vec3::new(w, level, w));
        let c = m.project_point3(Vec3::new(w, floor, -w));
        let d = m.project_point3(Vec3::new(-w, level, w));
        let span_x = [a.x, b.x, c.x, d.x]
            .iter()
            .fold(0.0f32, |s, v| s.max(v.abs()));
        assert!(span_x > 0.7, "{span_x}");
    }
}
