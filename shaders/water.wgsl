// water.wgsl — the sea surface: a flat grid displaced in the vertex shader by a sum of
// Gerstner waves with analytic normals (Finch 2004, GPU Gems 1 ch. 1; Tessendorf 2001),
// shaded with Schlick's Fresnel (Schlick 1994, F0 = 0.02 for water) between the reflected
// sky cube map and the refracted scene below, which is absorbed along its path through the
// water (Beer–Lambert) and mixed with in-scattered deep-water colour. The sun glint is a GGX
// lobe (Walter et al. 2007).
//!include common.wgsl

@group(1) @binding(0) var scene_color: texture_2d<f32>;
@group(1) @binding(1) var scene_depth: texture_depth_2d;
@group(1) @binding(2) var screen_sampler: sampler;

struct VertexOut {
    @builtin(position) clip: vec4f,
    @location(0) world_pos: vec3f,
    @location(1) rest_xz: vec2f,
}

@vertex
fn vs_main(@location(0) rest_xz: vec2f) -> VertexOut {
    let s = gerstner(rest_xz, g.time_secs);
    var out: VertexOut;
    out.clip = g.clip_from_world * vec4f(s.position, 1.0);
    out.world_pos = s.position;
    out.rest_xz = rest_xz;
    return out;
}

// Distance along the view axis from a 0..1 depth value (wgpu's perspective).
fn linear_depth(d: f32) -> f32 {
    let near = g.near_m;
    let far = g.far_m;
    return near * far / (far - d * (far - near));
}

fn load_depth(uv: vec2f) -> f32 {
    let size = vec2f(textureDimensions(scene_depth));
    let texel = vec2i(clamp(uv * size, vec2f(0.0), size - 1.0));
    return textureLoad(scene_depth, texel, 0);
}

@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4f {
    // per-pixel analytic normal: the sum evaluated again at this fragment's rest position
    var n = gerstner(in.rest_xz, g.time_secs).normal;
    let v = normalize(g.eye_m - in.world_pos);
    if (dot(n, v) < 0.0) {
        n = -n; // seen from below
    }
    if (g.debug_view == DEBUG_NORMALS) {
        return vec4f(n * 0.5 + 0.5, 1.0);
    }
    let n_dot_v = clamp(dot(n, v), 1e-4, 1.0);

    // Fresnel weight between reflection and refraction
    var fresnel = 0.25;
    if (on(g.fresnel_on)) {
        fresnel = 0.02 + 0.98 * pow(1.0 - n_dot_v, 5.0);
    }

    // reflection of the sky
    let r = reflect(-v, n);
    var reflected: vec3f;
    if (on(g.env_map_on)) {
        reflected = textureSampleLevel(env_cube, env_sampler, r, 0.0).rgb;
    } else {
        reflected = vec3f(0.45, 0.55, 0.7);
    }
    reflected = min(reflected, vec3f(20.0));

    // refraction: offset the screen lookup by the normal's tilt, fall back when that picks up
    // something in front of the surface
    let screen = g.viewport_size_px;
    let uv0 = in.clip.xy / screen;
    let water_dist = linear_depth(in.clip.z);
    var uv = uv0 + n.xz * 0.04 / max(water_dist * 0.15, 1.0);
    var scene_dist = linear_depth(load_depth(uv));
    if (scene_dist < water_dist) {
        uv = uv0;
        scene_dist = linear_depth(load_depth(uv));
    }
    let below = textureSampleLevel(scene_color, screen_sampler, uv, 0.0).rgb;
    // path length through the water, approximated along the view axis
    let path = max(scene_dist - water_dist, 0.0);
    let transmittance = exp(-g.absorption_per_m * path);
    let sun = g.sun_color * g.sun_intensity;
    let inscatter = g.scatter_color * (sun * 0.5 + vec3f(0.5));
    let refracted = below * transmittance + inscatter * (vec3f(1.0) - transmittance);

    // sun glint: a sharp GGX lobe, shadowed by the floating bodies
    let l = g.sun_dir;
    let h = normalize(v + l);
    let n_dot_l = max(dot(n, l), 0.0);
    let alpha = 0.15 * 0.15;
    let a2 = alpha * alpha;
    let ndh = max(dot(n, h), 0.0);
    let dd = (ndh * a2 - ndh) * ndh + 1.0;
    let d = a2 / (PI * dd * dd);
    let glint = min(d * 0.25 * fresnel * n_dot_l, 50.0) * sun * sun_visibility(in.world_pos, n);

    let color = mix(refracted, reflected, fresnel) + glint;
    return vec4f(color, 1.0);
}
