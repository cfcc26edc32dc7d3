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
//!include encoding.wgsl

// the opaque colour, its alpha the distance from the eye (`opaque_out`), and a sampler
@group(1) @binding(0) var scene_color: texture_2d<f32>;
@group(1) @binding(1) var screen_sampler: sampler;

struct VertexOut {
    @builtin(position) clip: vec4f,
    @location(0) world_pos: vec3f,
    @location(1) rest_xz: vec2f,
    // the long waves' tangent terms (`WATER_VERTEX_WAVES`), summed per vertex: smooth over a
    // grid cell, so interpolating them loses nothing the eye sees
    @location(2) long_d_dx: vec3f,
    @location(3) long_d_dz: vec3f,
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
    let footprint = footprint_m(rest_xz);
    let long = gerstner_terms(rest_xz, g.time_secs, footprint, 0u, WATER_VERTEX_WAVES);
    let short = gerstner_terms(rest_xz, g.time_secs, footprint, WATER_VERTEX_WAVES, MAX_WAVES);
    let p = vec3f(rest_xz.x, g.water_level_m, rest_xz.y) + long.offset + short.offset;
    var out: VertexOut;
    out.clip = g.clip_from_world * vec4f(p, 1.0);
    out.world_pos = p;
    out.rest_xz = rest_xz;
    out.long_d_dx = long.d_dx;
    out.long_d_dz = long.d_dz;
    return out;
}

// The opaque scene at a screen position: colour, and its distance from the eye.
fn below_at(uv: vec2f) -> vec4f {
    let size = vec2f(textureDimensions(scene_color));
    let texel = vec2i(clamp(uv * size, vec2f(0.0), size - 1.0));
    let dist = dist_load(textureLoad(scene_color, texel, 0).a, g.near_m, g.far_m);
    return vec4f(hdr_load(textureSampleLevel(scene_color, screen_sampler, uv, 0.0).rgb), dist);
}

// Screen uv of a world point.
fn uv_of(p: vec3f) -> vec2f {
    let c = g.clip_from_world * vec4f(p, 1.0);
    let ndc = c.xy / max(c.w, 1e-4);
    return vec2f(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5);
}

fn sky_along(dir: vec3f) -> vec3f {
    let sky = min(hdr_load(textureSampleLevel(env_cube, env_sampler, dir, 0.0).rgb), vec3f(20.0));
    return mix(ENV_OFF_RADIANCE, sky, f32(g.env_map_on));
}

// The normals view: a light tint of the water's own normal over the normals of what lies below
// (`below`: the opaque pass wrote them as colours), so it shows the geometry, not a sheet. Mixed
// in by a factor at the end, like every toggle here: an `if` on the uniforms makes lavapipe
// (Mesa 22.3) compile and keep a variant of this shader every frame (+1.5 MB a frame;
// benchmarks/scene.md).
fn with_normals_view(color: vec3f, n: vec3f, below: vec3f) -> vec4f {
    let normals = mix(below, n * 0.5 + 0.5, 0.3);
    return vec4f(hdr_store(mix(color, normals, f32(g.debug_view == DEBUG_NORMALS))), 1.0);
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
    // per-pixel analytic normal: the short waves evaluated again at this fragment's rest
    // position (all of them at full quality), the long ones' terms interpolated
    var terms = gerstner_terms(in.rest_xz, g.time_secs, footprint_m(in.rest_xz),
                               WATER_VERTEX_WAVES, MAX_WAVES);
    terms.d_dx += in.long_d_dx;
    terms.d_dz += in.long_d_dz;
    let n_up = surface_of(in.rest_xz, terms).normal;
    let from_below = g.eye_m.y < in.world_pos.y;
    let dn = fwidth(n_up);
    let variance = min(2.0 * dot(dn, dn), 0.18);
    let v = normalize(g.eye_m - in.world_pos);
    let n = select(n_up, -n_up, from_below);
    let uv0 = in.clip.xy / g.viewport_size_px;
    let n_dot_v = clamp(dot(n, v), 1e-4, 1.0);
    let straight = below_at(uv0);

    // Both sides are computed and one selected (a software rasteriser runs both sides of a
    // branch anyway), sharing their texture fetches: one sky lookup (reflected from above,
    // through Snell's window from below) and the straight look at the opaque image.
    // from below, into the air (n_water / n_air); outside Snell's window (48.8° from the
    // normal) the surface is a mirror of the water below
    let t_up = refract(-v, n, 1.0 / ETA_AIR_OVER_WATER);
    let window = f32(dot(t_up, t_up) > 1e-6);
    let sky = sky_along(select(reflect(-v, n), t_up, from_below));

    // ---- from below: Schlick with the angle on the thin side of the interface
    let fresnel_up = mix(1.0, 0.02 + 0.98 * pow(1.0 - clamp(dot(t_up, -n), 0.0, 1.0), 5.0), window);
    let eye_depth = g.water_level_m - g.eye_m.y;
    let deep = water_path(1e4, eye_depth, 0.0).inscatter;
    let surface = deep * fresnel_up + sky * (1.0 - fresnel_up) * window;
    let w_up = water_path(water_dist, eye_depth, v.y);
    let seen_from_below = surface * w_up.transmittance + w_up.inscatter;

    // ---- from above: Fresnel weight between reflection and refraction
    let fresnel = mix(0.25, 0.02 + 0.98 * pow(1.0 - n_dot_v, 5.0), f32(g.fresnel_on));
    // refraction: follow the refracted ray as far as the straight view ray reaches the scene
    // behind, look the scene up there, and fall back to the straight lookup when that picks up
    // something in front of the surface (a floating body) or lands off the screen (the image
    // has no texels there: clamping to its edge smeared the border's pixels into streaks)
    let t = refract(-v, n, ETA_AIR_OVER_WATER);
    let guess_m = clamp(straight.a - water_dist, 0.0, 20.0);
    let uv_refracted = uv_of(in.world_pos + t * guess_m);
    let on_screen = all(uv_refracted >= vec2f(0.0)) && all(uv_refracted <= vec2f(1.0));
    var seen = below_at(uv_refracted);
    seen = select(seen, straight, seen.a < water_dist || !on_screen);
    let path = max(seen.a - water_dist, 0.0);
    let w = water_path(path, 0.0, max(-t.y, 0.0));
    let refracted = seen.rgb * w.transmittance + w.inscatter;
    let glint = sun_glint(n, v, fresnel, variance, in.world_pos);
    let seen_from_above = mix(refracted, sky, fresnel) + glint;

    let color = select(seen_from_above, seen_from_below, from_below);
    return with_normals_view(color, n, straight.rgb);
}
