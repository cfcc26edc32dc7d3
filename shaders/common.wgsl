// common.wgsl — the per-frame uniforms and bindings every scene pass shares, and the
// Gerstner wave sum (GPU Gems 1, ch. 1, "Effective Water Simulation from Physical Models",
// Finch 2004, eq. 9 and 12). Included by other shaders with `//!include common.wgsl`.
// The CPU twin of `gerstner` is `crate::waves::WaveSum` (and `src/scene/surface.rs`): keep
// them the same formula: θ = k D·p0 − ω t, horizontal amplitude Q A = steepness / (k N).

const MAX_WAVES: u32 = 8u;
const PI: f32 = 3.14159265;

const DEBUG_NONE: u32 = 0u;
const DEBUG_SHADOW_MAP: u32 = 1u;
const DEBUG_NORMALS: u32 = 2u;
const DEBUG_ENV_CUBE: u32 = 3u;

struct Wave {
    // direction (unit, xz), wavenumber k = 2π/L (1/m), amplitude (m)
    dir_k_amp: vec4f,
    // angular frequency ω = k·speed (rad/s), Q·k·A = steepness / N (dimensionless)
    omega_qka: vec4f,
}

struct Globals {
    clip_from_world: mat4x4f,
    world_from_clip: mat4x4f,
    light_clip_from_world: mat4x4f,
    camera_pos_time: vec4f,     // xyz eye (m), w time (s)
    sun_dir_intensity: vec4f,   // xyz towards the sun, w irradiance scale
    sun_color: vec4f,
    water: vec4f,               // x level (m), y wave count, z env mip count, w exposure
    absorption: vec4f,          // per metre
    scatter: vec4f,
    // toggles, 1.0 = on: x env map, y normal maps, z shadows, w Cook–Torrance (0 = Lambert)
    toggles: vec4f,
    // x Fresnel on, y debug view (DEBUG_*), z/w viewport size (px)
    toggles2: vec4f,
    waves: array<Wave, MAX_WAVES>,
}

@group(0) @binding(0) var<uniform> g: Globals;
@group(0) @binding(1) var env_cube: texture_cube<f32>;
@group(0) @binding(2) var env_sampler: sampler;
@group(0) @binding(3) var shadow_map: texture_depth_2d;
@group(0) @binding(4) var shadow_sampler: sampler_comparison;

fn toggle(v: f32) -> bool {
    return v > 0.5;
}

fn debug_view() -> u32 {
    return u32(g.toggles2.y + 0.5);
}

struct Surface {
    position: vec3f,
    normal: vec3f,
    tangent: vec3f,
}

// The Gerstner sum at rest position (x, z): displaced position and analytic frame.
fn gerstner(xz: vec2f, t: f32) -> Surface {
    var p = vec3f(xz.x, g.water.x, xz.y);
    // tangents ∂P/∂x and ∂P/∂z; the normal is their exact cross product (keeps the cross terms
    // GPU Gems eq. 12 drops, as src/waves.rs does)
    var tg = vec3f(1.0, 0.0, 0.0);
    var bt = vec3f(0.0, 0.0, 1.0);
    let count = min(u32(g.water.y + 0.5), MAX_WAVES);
    for (var i = 0u; i < count; i++) {
        let w = g.waves[i];
        let d = w.dir_k_amp.xy;
        let k = w.dir_k_amp.z;
        let a = w.dir_k_amp.w;
        let qka = w.omega_qka.y;
        let phase = k * dot(d, xz) - w.omega_qka.x * t;
        let s = sin(phase);
        let c = cos(phase);
        // horizontal: Q·A·D·cos, with Q·A = qka / k
        p += vec3f(d.x * qka / k * c, a * s, d.y * qka / k * c);
        tg -= vec3f(qka * d.x * d.x * s, -d.x * k * a * c, qka * d.x * d.y * s);
        bt -= vec3f(qka * d.x * d.y * s, -d.y * k * a * c, qka * d.y * d.y * s);
    }
    return Surface(p, normalize(cross(bt, tg)), normalize(tg));
}

// Directional shadow: PCF over 3×3 comparison taps (each a bilinear 2×2 in hardware).
fn sun_visibility(world_pos: vec3f, normal: vec3f) -> f32 {
    if (!toggle(g.toggles.z)) {
        return 1.0;
    }
    // a small normal offset complements the pipeline's slope-scaled depth bias
    let p = g.light_clip_from_world * vec4f(world_pos + normal * 0.02, 1.0);
    let ndc = p.xyz / p.w;
    let uv = vec2f(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5);
    if (any(uv < vec2f(0.0)) || any(uv > vec2f(1.0)) || ndc.z > 1.0) {
        return 1.0;
    }
    let texel = 1.0 / vec2f(textureDimensions(shadow_map));
    var sum = 0.0;
    for (var y = -1; y <= 1; y++) {
        for (var x = -1; x <= 1; x++) {
            sum += textureSampleCompareLevel(shadow_map, shadow_sampler, uv + vec2f(f32(x), f32(y)) * texel, ndc.z);
        }
    }
    return sum / 9.0;
}

// Sunlight reaching a point under water is absorbed along its (unrefracted) path: Beer–Lambert.
fn sun_transmittance(world_pos: vec3f) -> vec3f {
    let depth = max(g.water.x - world_pos.y, 0.0);
    let path = depth / max(g.sun_dir_intensity.y, 0.1);
    return exp(-g.absorption.xyz * path);
}
