// common.wgsl — the per-frame uniforms and bindings every scene pass shares, and the
// Gerstner wave sum (GPU Gems 1, ch. 1, "Effective Water Simulation from Physical Models",
// Finch 2004, eq. 9 and 12). Included by other shaders with `//!include common.wgsl`.
// The CPU twin of `gerstner` is `crate::waves::WaveSum` (and `src/scene/surface.rs`): keep
// them the same formula: θ = k D·p0 − ω t, horizontal amplitude Q A = steepness / (k N).

const MAX_WAVES: u32 = 32u;
const PI: f32 = 3.14159265;
// Snell's ratio from air into water, n_air / n_water = 1 / 1.33
const ETA_AIR_OVER_WATER: f32 = 0.7518797;

// what the background and the water's reflection show with the environment map off
const ENV_OFF_RADIANCE: vec3f = vec3f(0.22, 0.22, 0.23);

const DEBUG_NONE: u32 = 0u;
const DEBUG_SHADOW_MAP: u32 = 1u;
const DEBUG_NORMALS: u32 = 2u;
const DEBUG_ENV_CUBE: u32 = 3u;
const DEBUG_CAUSTICS_MAP: u32 = 4u;

// One Gerstner wave (`WaveGpu` in src/render/frame.rs).
struct Wave {
    direction: vec2f,           // unit, xz
    wavenumber_per_m: f32,      // k = 2π / wavelength
    amplitude_m: f32,
    angular_freq_per_sec: f32,  // ω = k · speed
    steepness_qka: f32,         // Q k A = steepness / N (dimensionless)
    _pad: vec2f,
}

// The per-frame uniforms (`Globals` in src/render/frame.rs; a test compares the layouts).
struct Globals {
    clip_from_world: mat4x4f,
    world_from_clip: mat4x4f,
    light_clip_from_world: mat4x4f,
    eye_m: vec3f,
    time_secs: f32,
    sun_dir: vec3f,             // unit, towards the sun
    sun_intensity: f32,         // irradiance scale
    sun_color: vec3f,           // linear RGB
    exposure: f32,
    absorption_per_m: vec3f,    // Beer–Lambert, per RGB channel
    far_m: f32,                 // camera far plane
    scatter_color: vec3f,       // deep-water in-scattering, linear RGB
    near_m: f32,                // camera near plane
    water_level_m: f32,
    wave_count: u32,
    env_mip_count: f32,
    debug_view: u32,            // DEBUG_*
    viewport_size_px: vec2f,    // the HDR target being drawn
    // technique toggles, 1 = on
    env_map_on: u32,
    normal_maps_on: u32,
    shadows_on: u32,
    cook_torrance_on: u32,      // 0 = Lambert only
    fresnel_on: u32,
    caustics_on: u32,
    caustics_half_extent_m: f32, // the caustics map covers |x|, |z| ≤ this
    caustics_depth_m: f32,      // below the water level: the floor the map is focused on
    rad_per_px: f32,            // the angle one pixel of the HDR target subtends, radians
    wave_reach_m: f32,          // Σ amplitudes: no crest or trough is farther from the level
    sun_disc_radiance: vec3f,   // linear RGB at the disc's centre (drawn by sky.wgsl's background)
    sun_cos_radius: f32,        // cos of the disc's angular radius
    waves: array<Wave, MAX_WAVES>,
}

@group(0) @binding(0) var<uniform> g: Globals;
@group(0) @binding(1) var env_cube: texture_cube<f32>;
@group(0) @binding(2) var env_sampler: sampler;
@group(0) @binding(3) var shadow_map: texture_depth_2d;
@group(0) @binding(4) var shadow_sampler: sampler_comparison;
// made each frame by caustics.wgsl (not bound in that pass itself)
@group(0) @binding(5) var caustics_map: texture_2d<f32>;
@group(0) @binding(6) var caustics_sampler: sampler;

fn on(flag: u32) -> bool {
    return flag != 0u;
}

struct Surface {
    position: vec3f,
    normal: vec3f,
    tangent: vec3f,
}

// The Gerstner sum at rest position (x, z): displaced position and analytic frame.
fn gerstner(xz: vec2f, t: f32) -> Surface {
    return gerstner_faded(xz, t, 0.0);
}

// As `gerstner`, where one pixel covers `footprint_m` metres of water: each wave shorter than
// six pixels there fades out (gone at two), so the far sea does not alias into noise and
// sparkle; the waves under the floating bodies (≫ 6 px each) are the CPU twin's, unfaded.
fn gerstner_faded(xz: vec2f, t: f32, footprint_m: f32) -> Surface {
    return surface_of(xz, gerstner_terms(xz, t, footprint_m, 0u, MAX_WAVES));
}

// What waves `first`..`last` add at rest position `xz`: the displacement, and the terms of
// the tangents ∂P/∂x and ∂P/∂z. Sums are additive, so the water's vertex shader can sum the
// long waves once per vertex and its fragment shader the short ones per pixel
// (`WATER_VERTEX_WAVES`). The slots are filled long to short and end at the last one
// (`waves_gpu` in src/render/frame.rs); unused leading slots are zero and add nothing.
struct WaveTerms {
    offset: vec3f,
    d_dx: vec3f,
    d_dz: vec3f,
}

fn gerstner_terms(xz: vec2f, t: f32, footprint_in_m: f32, first: u32, last: u32) -> WaveTerms {
    var sum = WaveTerms(vec3f(0.0), vec3f(0.0), vec3f(0.0));
    let footprint_m = max(footprint_in_m, 1e-6);
    // constant bounds only (`MAX_WAVES` or a pipeline constant), never `g.wave_count`: a loop
    // bound read from a uniform makes lavapipe (Mesa 22.3) compile and keep a new shader variant
    // every frame (+0.25 MB per frame; see pbr.wgsl and docs/benchmarks/scene.md)
    for (var i = first; i < last; i++) {
        let w = g.waves[i];
        let d = w.direction;
        let k = max(w.wavenumber_per_m, 1e-6); // an unused slot: k = 0
        let fade = smoothstep(2.0, 6.0, 2.0 * PI / (k * footprint_m));
        let a = w.amplitude_m * fade;
        let qka = w.steepness_qka * fade;
        let phase = k * dot(d, xz) - w.angular_freq_per_sec * t;
        let s = sin(phase);
        let c = cos(phase);
        // horizontal: Q·A·D·cos, with Q·A = qka / k
        sum.offset += vec3f(d.x * qka / k * c, a * s, d.y * qka / k * c);
        sum.d_dx -= vec3f(qka * d.x * d.x * s, -d.x * k * a * c, qka * d.x * d.y * s);
        sum.d_dz -= vec3f(qka * d.x * d.y * s, -d.y * k * a * c, qka * d.y * d.y * s);
    }
    return sum;
}

// The surface from the terms of every wave: the normal is the exact cross product of the
// tangents (keeps the cross terms GPU Gems eq. 12 drops, as src/waves.rs does).
fn surface_of(xz: vec2f, terms: WaveTerms) -> Surface {
    let p = vec3f(xz.x, g.water_level_m, xz.y) + terms.offset;
    let tg = vec3f(1.0, 0.0, 0.0) + terms.d_dx;
    let bt = vec3f(0.0, 0.0, 1.0) + terms.d_dz;
    return Surface(p, normalize(cross(bt, tg)), normalize(tg));
}

// How many of the wave slots (the longest, from slot 0) the water sums per vertex only, its
// fragment shader adding the rest per pixel: 0 at full quality, more on the lower rungs of the
// automatic quality (`WaterNormals` in src/render/frame.rs), a constant to the shader compiler.
override WATER_VERTEX_WAVES: u32 = 0u;

// Comparison taps on each side of the centre one in `sun_visibility`: 1 (3×3 PCF) or 0 (one
// bilinear tap, the lowest quality rungs). Set per pipeline (ShadowFilter in src/render/frame.rs):
// a constant to the shader compiler, so the loops below have constant bounds.
override SHADOW_PCF_RADIUS: i32 = 1;

// Directional shadow: percentage-closer filtering (Reeves, Salesin & Cook 1987) over
// (2r + 1)² comparison taps, each a bilinear 2×2 in hardware.
fn sun_visibility(world_pos: vec3f, normal: vec3f) -> f32 {
    // a small normal offset complements the pipeline's slope-scaled depth bias
    let p = g.light_clip_from_world * vec4f(world_pos + normal * 0.02, 1.0);
    let ndc = p.xyz / p.w;
    let uv = vec2f(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5);
    if (any(uv < vec2f(0.0)) || any(uv > vec2f(1.0)) || ndc.z > 1.0) {
        return 1.0;
    }
    let texel = 1.0 / vec2f(textureDimensions(shadow_map));
    var sum = 0.0;
    let r = SHADOW_PCF_RADIUS;
    for (var y = -r; y <= r; y++) {
        for (var x = -r; x <= r; x++) {
            sum += textureSampleCompareLevel(shadow_map, shadow_sampler, uv + vec2f(f32(x), f32(y)) * texel, ndc.z);
        }
    }
    let taps = f32(2 * r + 1);
    return mix(1.0, sum / (taps * taps), f32(g.shadows_on));
}

// Sunlight reaching a point under water is absorbed along its path, refracted at the (flat)
// surface and so steeper than the sun itself: Beer–Lambert.
fn sun_transmittance(world_pos: vec3f) -> vec3f {
    let depth = max(g.water_level_m - world_pos.y, 0.0);
    let path = depth / max(sun_dir_in_water().y, 0.1);
    return exp(-g.absorption_per_m * path);
}

// How much sunlight the waves focus onto a point under water, relative to flat water: the
// caustics map (caustics.wgsl, GPU Gems 1 ch. 2) at the point's xz, shifted along the refracted
// sun by how far the point lies above or below the map's floor. The pattern is faded in with
// depth (none at the surface, where rays have not converged yet, full from the map's depth on)
// and out at the map's edge; caustics off weighs it by 0 (a factor, not a branch).
fn caustics_light(world_pos: vec3f) -> f32 {
    let depth = g.water_level_m - world_pos.y;
    let ray = refract(-g.sun_dir, vec3f(0.0, 1.0, 0.0), ETA_AIR_OVER_WATER);
    let xz = world_pos.xz + ray.xz * (g.caustics_depth_m - depth) / max(-ray.y, 0.05);
    let uv = xz / (2.0 * max(g.caustics_half_extent_m, 1e-3)) + 0.5;
    let focused = caustics_load(textureSampleLevel(caustics_map, caustics_sampler, uv, 0.0).r);
    let edge = max(abs(uv.x * 2.0 - 1.0), abs(uv.y * 2.0 - 1.0));
    let inside = 1.0 - smoothstep(0.85, 1.0, edge);
    let depth_fade = clamp(depth / max(g.caustics_depth_m, 1e-3), 0.0, 1.0);
    return mix(1.0, focused, f32(g.caustics_on) * inside * depth_fade);
}

// The sun's direction under water (refracted at a flat surface), pointing towards the sun.
fn sun_dir_in_water() -> vec3f {
    return -refract(-g.sun_dir, vec3f(0.0, 1.0, 0.0), ETA_AIR_OVER_WATER);
}

// Light along a straight path of `path_m` metres through water that starts `depth0_m` below
// the surface and descends `descent_per_m` per metre (negative: rising). Beer–Lambert per
// channel for what lies behind, and single-scattered sunlight gathered along the way: at path
// length s the sunlight has crossed (depth0 + descent·s) / μ_sun metres of water and the
// scattered light s more, so the in-scatter is the closed form of
// ∫₀ᴸ σ e^{−σ (depth0/μ + s (1 + descent/μ))} ds (Preetham 1999 §6 uses the same single-
// scattering integral for aerial perspective). `scatter_color` is then the radiance of deep
// water seen horizontally just under the surface, per unit of sun-plus-sky light.
struct WaterPath {
    transmittance: vec3f,
    inscatter: vec3f,
}

fn water_path(path_m: f32, depth0_m: f32, descent_per_m: f32) -> WaterPath {
    let sigma = g.absorption_per_m;
    let mu_sun = max(sun_dir_in_water().y, 0.1);
    let k = 1.0 + descent_per_m / mu_sun;
    let len = max(path_m, 0.0);
    let transmittance = exp(-sigma * len);
    // (1 − e^{−σkL}) / k, and its limit σL as k → 0 (a path rising as fast as the light fades)
    let gathered = select((vec3f(1.0) - exp(-sigma * k * len)) / k, sigma * len, abs(k) < 1e-3);
    let light = g.sun_color * g.sun_intensity * 0.5 + vec3f(0.5);
    let above = exp(-sigma * max(depth0_m, 0.0) / mu_sun);
    return WaterPath(transmittance, g.scatter_color * light * above * gathered);
}

// What the opaque passes write: linear colour, and in alpha the distance from the eye (metres;
// both as encoding.wgsl stores them).
// The water pass reads that distance from this colour target, never from the depth attachment
// it tests against (sampling an attached depth texture is not allowed on WebGL2/GLES). With the
// eye under water the path to the point is fogged here, the water surface not being in between.
fn opaque_out(color: vec3f, world_pos: vec3f) -> vec4f {
    let dist = distance(world_pos, g.eye_m);
    let eye_depth = g.water_level_m - g.eye_m.y;
    let dir = (world_pos - g.eye_m) / max(dist, 1e-4);
    let w = water_path(dist, max(eye_depth, 0.0), -dir.y);
    // a factor, not an `if` on the uniforms: lavapipe (Mesa 22.3) compiles and keeps a shader
    // variant per draw for a branch they decide (+1.4 MB a frame here; docs/benchmarks/scene.md)
    let under = f32(eye_depth > 0.0) * f32(g.debug_view != DEBUG_NORMALS);
    let shown = mix(color, color * w.transmittance + w.inscatter, under);
    return vec4f(hdr_store(shown), dist_store(dist, g.near_m, g.far_m));
}
