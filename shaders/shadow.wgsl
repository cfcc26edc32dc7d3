// shadow.wgsl — the sun's shadow map: depth-only rendering of the casters (rocks, floating
// bodies; fish use `vs_shadow` in fish.wgsl) through the light's orthographic projection
// (Williams 1978, "Casting Curved Shadows on Curved Surfaces"). Acne is fought by the
// pipeline's slope-scaled depth bias (depth += constant + slope · max|∂z/∂x|, ∂z/∂y|) and
// a small normal offset at lookup; lookup with PCF (Reeves, Salesin, Cook 1987) is
// `sun_visibility` in common.wgsl.
//!include common.wgsl
//!include encoding.wgsl

// `ObjectGpu` in src/render/pbr.rs
struct Object {
    world_from_object: mat4x4f,
    world_uv: f32,
    ambient_occlusion: f32,
    _pad: vec2f,
}

@group(1) @binding(0) var<uniform> object: Object;

@vertex
fn vs_main(@location(0) position: vec3f) -> @builtin(position) vec4f {
    return g.light_clip_from_world * object.world_from_object * vec4f(position, 1.0);
}
