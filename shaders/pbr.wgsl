// pbr.wgsl — opaque meshes (seabed, rocks, floating bodies): vertex + index buffers with an
// explicit layout (position, normal, tangent with handedness, uv), tangent-space normal mapping
// (Blinn 1978 bump mapping; Mikkelsen 2008 tangent frames) and the Cook–Torrance BRDF of
// brdf.wgsl with sun shadows (Williams 1978 shadow maps; Reeves et al. 1987 PCF).
//!include common.wgsl
//!include encoding.wgsl
//!include brdf.wgsl

// `ObjectGpu` in src/render/pbr.rs
struct Object {
    world_from_object: mat4x4f,
    world_uv: f32,              // 1: world xz as texture coordinates (terrain)
    ambient_occlusion: f32,
    _pad: vec2f,
}

@group(1) @binding(0) var<uniform> material: MaterialParams;
@group(1) @binding(1) var normal_map: texture_2d<f32>;
@group(1) @binding(2) var material_sampler: sampler;
@group(2) @binding(0) var<uniform> object: Object;

struct VertexIn {
    @location(0) position: vec3f,
    @location(1) normal: vec3f,
    @location(2) tangent: vec4f,
    @location(3) uv: vec2f,
}

struct VertexOut {
    @builtin(position) clip: vec4f,
    @location(0) world_pos: vec3f,
    @location(1) normal: vec3f,
    @location(2) tangent: vec4f,
    @location(3) uv: vec2f,
}

@vertex
fn vs_main(in: VertexIn) -> VertexOut {
    let world = object.world_from_object * vec4f(in.position, 1.0);
    // uniform scale only, so the upper 3×3 transforms normals correctly
    let m = mat3x3f(object.world_from_object[0].xyz, object.world_from_object[1].xyz, object.world_from_object[2].xyz);
    var out: VertexOut;
    out.clip = g.clip_from_world * world;
    out.world_pos = world.xyz;
    out.normal = normalize(m * in.normal);
    out.tangent = vec4f(normalize(m * in.tangent.xyz), in.tangent.w);
    // a select, not an `if`: Mesa's lavapipe (22.3) inlines uniforms that decide a branch and
    // compiles a new shader variant on every draw that rebinds them, keeping each one: with an
    // `if` here the app grew by ~0.2 MB per object per frame (docs/benchmarks/scene.md)
    out.uv = select(in.uv, world.xz, object.world_uv > 0.5) * material.uv_scale;
    return out;
}

// Perturbs the interpolated normal with the tangent-space normal map (stored linear, [0,1]).
fn mapped_normal(n_in: vec3f, t_in: vec4f, uv: vec2f, strength: f32) -> vec3f {
    let n = normalize(n_in);
    if (!on(g.normal_maps_on)) {
        return n;
    }
    // Gram–Schmidt: re-orthogonalise the interpolated tangent against the normal
    let t = normalize(t_in.xyz - n * dot(n, t_in.xyz));
    let b = cross(n, t) * t_in.w;
    var tn = textureSample(normal_map, material_sampler, uv).xyz * 2.0 - 1.0;
    tn = vec3f(tn.xy * strength, tn.z);
    return normalize(mat3x3f(t, b, n) * tn);
}

@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4f {
    let n = mapped_normal(in.normal, in.tangent, in.uv, material.normal_strength);
    if (g.debug_view == DEBUG_NORMALS) {
        return opaque_out(n * 0.5 + 0.5, in.world_pos);
    }
    let v = normalize(g.eye_m - in.world_pos);
    // the waterline: a wet band just above the surface where the waves splash, darker (water
    // fills the pores, less light scatters back out) and glossier (a film of water)
    // only within the waves' reach of the mean level (and the band above it): the seabed and
    // rocks cover most pixels, and the sum costs 32 waves a pixel on a software rasteriser (a
    // branch on the position, not on a uniform alone: see the vertex shader)
    var above_m = 1e3;
    if (abs(in.world_pos.y - g.water_level_m) < g.wave_reach_m + 0.2) {
        above_m = in.world_pos.y - gerstner(in.world_pos.xz, g.time_secs).position.y;
    }
    let wet = (1.0 - smoothstep(0.03, 0.18, above_m)) * step(0.0, above_m);
    let base = material.base_color.rgb * mix(1.0, 0.55, wet);
    let roughness = mix(material.roughness, 0.12, wet);
    let color = shade(base, material.metallic, roughness,
                      material.reflectance, n, v, in.world_pos, object.ambient_occlusion);
    return opaque_out(color, in.world_pos);
}
