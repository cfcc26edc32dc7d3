// water.wgsl — the sea surface to the horizon: a projected grid (Johanson 2004, "Real-time
// water rendering: introducing the projected grid concept", Lund University), each vertex a
// screen position whose view ray is met with the water plane, then displaced by the Gerstner
// sum (Finch 2004, GPU Gems 1 ch. 1) with every wave faded out where it is shorter than a few
// pixels (`gerstner_faded`, common.wgsl). Shaded with Schlick's Fresnel (Schlick 1994, F0 = 0.02)
// between the reflected sky cube and the scene below, refracted through the surface normal
// (Snell) by a screen-space lookup (Sousa 2005, GPU Gems 2 ch. 19), absorbed and in-scattered
// along its path through the water (Beer–Lambert, `water_path`). From below, the sky shows only
// through Snell's window (total internal reflection outside it). The sun glint is a GGX lobe
// (Walter et al. 2007) widened by the normal's variance over the pixel (Kaplanyan et al. 2016,
// "Stable specular highlights"), so it does not sparkle.
//!include common.wgsl

// the opaque colour, its alpha the distance from the eye (`opaque_out`), and a sampler
@group(1) @binding(0) var scene_color: texture_2d<f32>;
@group(1) @binding(1) var screen_sampler: sampler;

struct VertexOut {
    @builtin(position) clip: vec4f,
    @location(0) world_pos: vec3f,
    @location(1) rest_xz: vec2f,
}

// Where the view ray through the screen point `ndc` meets the still water plane, as a rest
// position; rays that miss it, or meet it beyond the far plane, end at the far plane's
// distance on the horizon (so the grid's last rows collapse onto the horizon line).
fn project_to_water(ndc: vec2f) -> vec2f {
    let far = g.world_from_clip * vec4f(ndc, 1.0, 1.0);
    let dir = normalize(far.xyz / far.w - g.eye_m);
    let horizontal = length(dir.xz);
    let across = dir.xz / max(horizontal, 1e-6);
    let height = g.eye_m.y - g.water_level_m;
    let reach = 0.95 * g.far_m;
    var dist = reach;
    if (height * dir.y < 0.0) {
        dist = min(abs(height) * horizontal / abs(dir.y), reach);
    }
    return g.eye_m.xz + across * dist;
}

// How many metres of water one pixel covers at the rest point `xz`, along the view (the long
// axis of its footprint: stretched by 1 / sin of the grazing angle towards the horizon).
fn footprint_m(xz: vec2f) -> f32 {
    let height = max(abs(g.eye_m.y - g.water_level_m), 0.05);
    let across = distance(xz, g.eye_m.xz);
    let dist = sqrt(across * across + height * height);
    return dist * g.rad_per_px * dist / height;
}

@vertex
fn vs_main(@location(0) grid_ndc: vec2f) -> VertexOut {
    let rest_xz = project_to_water(grid_ndc);
    let s = gerstner_faded(rest_xz, g.time_secs, footprint_m(rest_xz));
    var out: VertexOut;
    out.clip = g.clip_from_world * vec4f(s.position, 1.0);
    out.world_pos = s.position;
    out.rest_xz = rest_xz;
    return out;
}

// The opaque scene at a screen position: colour, and its distance from the eye.
fn below_at(uv: vec2f) -> vec4f {
    let size = vec2f(textureDimensions(scene_color));
    let texel = vec2i(clamp(uv * size, vec2f(0.0), size - 1.0));
    let dist = textureLoad(scene_color, texel, 0).a;
    return vec4f(textureSampleLevel(scene_color, screen_sampler, uv, 0.0).rgb, dist);
}

// Screen uv of a world point.
fn uv_of(p: vec3f) -> vec2f {
    let c = g.clip_from_world * vec4f(p, 1.0);
    let ndc = c.xy / max(c.w, 1e-4);
    return vec2f(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5);
}

fn sky_along(dir: vec3f) -> vec3f {
    let sky = min(textureSampleLevel(env_cube, env_sampler, dir, 0.0).rgb, vec3f(20.0));
    return mix(ENV_OFF_RADIANCE, sky, f32(g.env_map_on));
}

// The normals view: a light tint of the water's own normal over the normals of what lies below
// (the opaque pass wrote them as colours), so it shows the geometry, not a sheet. Mixed in by a
// factor at the end, like every toggle here: an `if` on the uniforms makes lavapipe (Mesa 22.3)
// compile and keep a variant of this shader every frame (+1.5 MB a frame; benchmarks/scene.md).
fn with_normals_view(color: vec3f, n: vec3f, uv: vec2f) -> vec4f {
    let normals = mix(below_at(uv).rgb, n * 0.5 + 0.5, 0.3);
    return vec4f(mix(color, normals, f32(g.debug_view == DEBUG_NORMALS)), 1.0);
}

// GGX glint of the sun off the surface, its roughness widened by the normal's variance over
// the pixel (Kaplanyan 2016: σ² from the screen derivatives of the normal, added to α²).
fn sun_glint(n: vec3f, v: vec3f, fresnel: f32, variance: f32, world_pos: vec3f) -> vec3f {
    let l = g.sun_dir;
    let h = normalize(v + l);
    let n_dot_l = max(dot(n, l), 0.0);
    let alpha = 0.15 * 0.15;
    let a2 = min(alpha * alpha + variance, 1.0);
    let ndh = max(dot(n, h), 0.0);
    let dd = (ndh * a2 - ndh) * ndh + 1.0;
    let d = a2 / (PI * dd * dd);
    let sun = g.sun_color * g.sun_intensity;
    // the glint is the water's microfacet lobe: "Lambert only" has none (a factor, not a branch)
    return min(d * 0.25 * fresnel * n_dot_l, 50.0) * sun * sun_visibility(world_pos, n)
        * f32(g.cook_torrance_on);
}

@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4f {
    let water_dist = distance(g.eye_m, in.world_pos);
    // per-pixel analytic normal: the sum evaluated again at this fragment's rest position
    var n = gerstner_faded(in.rest_xz, g.time_secs, footprint_m(in.rest_xz)).normal;
    let from_below = g.eye_m.y < in.world_pos.y;
    let dn = fwidth(n);
    let variance = min(2.0 * dot(dn, dn), 0.18);
    let v = normalize(g.eye_m - in.world_pos);
    if (from_below) {
        n = -n;
    }
    let uv0 = in.clip.xy / g.viewport_size_px;
    let n_dot_v = clamp(dot(n, v), 1e-4, 1.0);

    if (from_below) {
        // into the air (n_water / n_air); outside Snell's window (48.8° from the normal) the
        // surface is a mirror of the water below
        let t = refract(-v, n, 1.0 / ETA_AIR_OVER_WATER);
        let tir = dot(t, t) < 1e-6;
        var fresnel = 1.0;
        if (!tir) {
            // Schlick with the angle on the thin side of the interface
            fresnel = 0.02 + 0.98 * pow(1.0 - clamp(dot(t, -n), 0.0, 1.0), 5.0);
        }
        let deep = water_path(1e4, g.water_level_m - g.eye_m.y, 0.0).inscatter;
        var surface = deep * fresnel;
        if (!tir) {
            surface += sky_along(t) * (1.0 - fresnel);
        }
        let eye_depth = g.water_level_m - g.eye_m.y;
        let w = water_path(water_dist, eye_depth, -(-v).y);
        return with_normals_view(surface * w.transmittance + w.inscatter, n, uv0);
    }

    // Fresnel weight between reflection and refraction
    let fresnel = mix(0.25, 0.02 + 0.98 * pow(1.0 - n_dot_v, 5.0), f32(g.fresnel_on));
    let reflected = sky_along(reflect(-v, n));

    // refraction: follow the refracted ray as far as the straight view ray reaches the scene
    // behind, look the scene up there, and fall back to the straight lookup when that picks up
    // something in front of the surface (a floating body)
    let straight = below_at(uv0);
    let t = refract(-v, n, ETA_AIR_OVER_WATER);
    let guess_m = clamp(straight.a - water_dist, 0.0, 20.0);
    var seen = below_at(uv_of(in.world_pos + t * guess_m));
    if (seen.a < water_dist) {
        seen = straight;
    }
    let path = max(seen.a - water_dist, 0.0);
    let w = water_path(path, 0.0, max(-t.y, 0.0));
    let refracted = seen.rgb * w.transmittance + w.inscatter;

    let glint = sun_glint(n, v, fresnel, variance, in.world_pos);
    return with_normals_view(mix(refracted, reflected, fresnel) + glint, n, uv0);
}
