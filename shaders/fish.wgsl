// fish.wgsl — the school as one instanced draw: per-vertex data from the fish mesh's vertex
// buffer, per-instance data (position, orientation quaternion, scale, tail phase) from an
// instance buffer with step mode Instance. The body bends with a travelling wave that grows
// towards the tail (carangiform swimming; Lighthill 1960 elongated-body theory). Shaded with
// the Cook–Torrance BRDF and a procedural scale normal map.
//!include common.wgsl
//!include encoding.wgsl
//!include brdf.wgsl

@group(1) @binding(0) var<uniform> material: MaterialParams;
@group(1) @binding(1) var normal_map: texture_2d<f32>;
@group(1) @binding(2) var material_sampler: sampler;

struct VertexIn {
    @location(0) position: vec3f,
    @location(1) normal: vec3f,
    @location(2) tangent: vec4f,
    @location(3) uv: vec2f,
    // per instance
    @location(4) inst_pos_scale: vec4f,
    @location(5) inst_rotation: vec4f,
    @location(6) inst_phase: f32,
}

struct VertexOut {
    @builtin(position) clip: vec4f,
    @location(0) world_pos: vec3f,
    @location(1) normal: vec3f,
    @location(2) tangent: vec4f,
    @location(3) uv: vec2f,
}

fn quat_rotate(q: vec4f, v: vec3f) -> vec3f {
    let t = 2.0 * cross(q.xyz, v);
    return v + q.w * t + cross(q.xyz, t);
}

// Fish space: nose at +x, back at +y. Lateral (z) wave, amplitude growing tail-wards.
fn swim(p: vec3f, phase: f32) -> vec3f {
    let s = clamp(0.5 - p.x, 0.0, 1.2); // 0 at the nose, ~1 at the tail
    let bend = 0.18 * s * s * sin(phase - 4.0 * s);
    return vec3f(p.x, p.y, p.z + bend);
}

// Body wave slope d(bend)/dx, to rotate the normal with the bend.
fn swim_slope(p: vec3f, phase: f32) -> f32 {
    let s = clamp(0.5 - p.x, 0.0, 1.2);
    let ds = -1.0;
    return 0.18 * (2.0 * s * sin(phase - 4.0 * s) - 4.0 * s * s * cos(phase - 4.0 * s)) * ds;
}

fn fish_world(in: VertexIn) -> vec3f {
    let p = swim(in.position, in.inst_phase);
    return quat_rotate(in.inst_rotation, p * in.inst_pos_scale.w) + in.inst_pos_scale.xyz;
}

fn bend_dir(v: vec3f, slope: f32) -> vec3f {
    // shear x→z by the slope: normals transform with the inverse transpose (z→x by -slope)
    return normalize(vec3f(v.x - slope * v.z, v.y, v.z));
}

@vertex
fn vs_main(in: VertexIn) -> VertexOut {
    let slope = swim_slope(in.position, in.inst_phase);
    let world = fish_world(in);
    var out: VertexOut;
    out.clip = g.clip_from_world * vec4f(world, 1.0);
    out.world_pos = world;
    out.normal = quat_rotate(in.inst_rotation, bend_dir(in.normal, slope));
    out.tangent = vec4f(quat_rotate(in.inst_rotation, in.tangent.xyz), in.tangent.w);
    out.uv = in.uv * material.uv_scale;
    return out;
}

@vertex
fn vs_shadow(in: VertexIn) -> @builtin(position) vec4f {
    return g.light_clip_from_world * vec4f(fish_world(in), 1.0);
}

@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4f {
    var n = normalize(in.normal);
    if (on(g.normal_maps_on)) {
        let t = normalize(in.tangent.xyz - n * dot(n, in.tangent.xyz));
        let b = cross(n, t) * in.tangent.w;
        var tn = textureSample(normal_map, material_sampler, in.uv).xyz * 2.0 - 1.0;
        tn = vec3f(tn.xy * material.normal_strength, tn.z);
        n = normalize(mat3x3f(t, b, n) * tn);
    }
    if (g.debug_view == DEBUG_NORMALS) {
        return opaque_out(n * 0.5 + 0.5, in.world_pos);
    }
    // countershading: dark back, silver belly (uv.y runs belly 0 → back 1)
    let back = smoothstep(0.45, 0.8, in.uv.y);
    let base = mix(material.base_color.rgb, vec3f(0.08, 0.16, 0.22), back);
    let v = normalize(g.eye_m - in.world_pos);
    let color = shade(base, material.metallic * (1.0 - back), material.roughness,
                      material.reflectance, n, v, in.world_pos, 1.0);
    return opaque_out(color, in.world_pos);
}
