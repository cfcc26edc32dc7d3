// sky.wgsl — a procedural sky (zenith/horizon/ground gradient, a sun disc with a forward-
// scattering glow in the spirit of Henyey–Greenstein 1941) rendered once into the six faces of
// a cube map, then drawn as the background by looking the cube map up along each pixel's view
// ray (environment mapping: Blinn & Newell 1976; cube maps: Greene 1986).
//!include common.wgsl
//!include fullscreen.wgsl
//!include cube_face.wgsl

struct SkyParams {
    zenith: vec4f,
    horizon: vec4f,
    ground: vec4f,
    sun_dir: vec4f,    // xyz towards the sun, w cos(angular radius)
    sun_color: vec4f,  // rgb disc radiance
    face: vec4u,       // x: cube face being rendered
}

@group(1) @binding(0) var<uniform> sky: SkyParams;


fn sky_radiance(d: vec3f) -> vec3f {
    let up = d.y;
    var c: vec3f;
    if (up >= 0.0) {
        c = mix(sky.horizon.rgb, sky.zenith.rgb, pow(up, 0.45));
    } else {
        c = mix(sky.horizon.rgb, sky.ground.rgb, pow(-up, 0.35));
    }
    let s = normalize(sky.sun_dir.xyz);
    let mu = dot(d, s);
    // forward-scattering glow around the sun, and the disc itself
    let glow = pow(max(mu, 0.0), 64.0) * 0.6 + pow(max(mu, 0.0), 8.0) * 0.15;
    c += sky.sun_color.rgb / 60.0 * glow * 2.0;
    let disc = smoothstep(sky.sun_dir.w - 0.00002, sky.sun_dir.w + 0.00002, mu);
    c += sky.sun_color.rgb * disc * step(0.0, up);
    return c;
}

@fragment
fn fs_cube_face(in: FullscreenOut) -> @location(0) vec4f {
    return vec4f(sky_radiance(face_dir(sky.face.x, in.ndc)), 1.0);
}

// Background: the depth test (LessEqual at depth 1) keeps it behind everything.
@fragment
fn fs_background(in: FullscreenOut) -> @location(0) vec4f {
    let far = g.world_from_clip * vec4f(in.ndc, 1.0, 1.0);
    let dir = normalize(far.xyz / far.w - g.eye_m);
    if (g.debug_view == DEBUG_NORMALS) {
        return vec4f(0.0, 0.0, 0.0, 1.0);
    }
    var c: vec3f;
    if (on(g.env_map_on)) {
        c = textureSampleLevel(env_cube, env_sampler, dir, 0.0).rgb;
    } else {
        c = mix(vec3f(0.5, 0.6, 0.7), vec3f(0.25, 0.35, 0.6), clamp(dir.y, 0.0, 1.0));
    }
    return vec4f(c, 1.0);
}
