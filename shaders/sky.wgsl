// sky.wgsl — the analytic daylight sky of Preetham, Shirley & Smits 1999, "A Practical Analytic
// Model for Daylight" (SIGGRAPH 99): the Perez et al. 1993 all-weather distribution
// F(θ, γ) = (1 + A e^{B / cos θ})(1 + C e^{D γ} + E cos² γ) for luminance Y and chromaticity
// x, y, its coefficients linear in the turbidity T (the paper's appendix A.2), the zenith
// values Y_z (eq. A.3, kcd/m²) and x_z, y_z (the appendix's cubic in θ_s), then Yxy → XYZ →
// linear sRGB (IEC 61966-2-1). Rendered once into the six faces of a cube map (the sky only),
// then drawn as the background along each pixel's view ray (environment mapping: Blinn &
// Newell 1976; cube maps: Greene 1986). The sun disc (limb-darkened, Neckel & Labs 1994's
// simple two-term fit) is drawn analytically in the background at the pixel's own resolution,
// in the scene light's direction: a cube texel (0.7° at 128²) is coarser than its edge. The
// cube leaves it out, so reflections see the sky and the water's and materials' reflection of
// the sun is their specular lobe from the light alone (nothing counted twice).
//!include common.wgsl
//!include encoding.wgsl
//!include fullscreen.wgsl
//!include cube_face.wgsl

// `SkyParams` in src/render/sky.rs
struct SkyParams {
    sun_dir: vec4f,        // xyz towards the sun, w unused
    ground: vec4f,         // rgb below the horizon (scene radiance), w unused
    turbidity: f32,        // T, 2 (clear) .. 10 (hazy)
    radiance_per_kcd: f32, // scene radiance per kcd/m² of Preetham luminance
    _pad: vec2f,
    face: vec4u,           // x: cube face being rendered
}

@group(1) @binding(0) var<uniform> sky: SkyParams;

struct Perez {
    a: f32,
    b: f32,
    c: f32,
    d: f32,
    e: f32,
}

fn perez(p: Perez, cos_theta: f32, gamma: f32, cos_gamma: f32) -> f32 {
    return (1.0 + p.a * exp(p.b / max(cos_theta, 0.01)))
        * (1.0 + p.c * exp(p.d * gamma) + p.e * cos_gamma * cos_gamma);
}

// Preetham's sky radiance (kcd/m² scaled to scene radiance, linear sRGB) along `d` (unit,
// above the horizon) with the sun towards `s`.
fn preetham(d: vec3f, s: vec3f, t: f32) -> vec3f {
    let theta_s = acos(clamp(s.y, 0.0, 1.0));
    let cos_theta = max(d.y, 0.0);
    let cos_gamma = clamp(dot(d, s), -1.0, 1.0);
    let gamma = acos(cos_gamma);
    let p_big_y = Perez(0.1787 * t - 1.4630, -0.3554 * t + 0.4275, -0.0227 * t + 5.3251,
        0.1206 * t - 2.5771, -0.0670 * t + 0.3703);
    let p_x = Perez(-0.0193 * t - 0.2592, -0.0665 * t + 0.0008, -0.0004 * t + 0.2125,
        -0.0641 * t - 0.8989, -0.0033 * t + 0.0452);
    let p_y = Perez(-0.0167 * t - 0.2608, -0.0950 * t + 0.0092, -0.0079 * t + 0.2102,
        -0.0441 * t - 1.6537, -0.0109 * t + 0.0529);
    let chi = (4.0 / 9.0 - t / 120.0) * (PI - 2.0 * theta_s);
    let zenith_big_y = (4.0453 * t - 4.9710) * tan(chi) - 0.2155 * t + 2.4192;
    let th = vec4f(theta_s * theta_s * theta_s, theta_s * theta_s, theta_s, 1.0);
    let tt = vec3f(t * t, t, 1.0);
    let zenith_x = dot(tt, vec3f(
        dot(vec4f(0.00166, -0.00375, 0.00209, 0.0), th),
        dot(vec4f(-0.02903, 0.06377, -0.03202, 0.00394), th),
        dot(vec4f(0.11693, -0.21196, 0.06052, 0.25886), th)));
    let zenith_y = dot(tt, vec3f(
        dot(vec4f(0.00275, -0.00610, 0.00317, 0.0), th),
        dot(vec4f(-0.04214, 0.08970, -0.04153, 0.00516), th),
        dot(vec4f(0.15346, -0.26756, 0.06670, 0.26688), th)));
    let cos_s = cos(theta_s);
    let big_y = zenith_big_y * perez(p_big_y, cos_theta, gamma, cos_gamma)
        / perez(p_big_y, 1.0, theta_s, cos_s);
    let x = zenith_x * perez(p_x, cos_theta, gamma, cos_gamma) / perez(p_x, 1.0, theta_s, cos_s);
    let y = max(zenith_y * perez(p_y, cos_theta, gamma, cos_gamma) / perez(p_y, 1.0, theta_s, cos_s), 1e-4);
    let xyz = vec3f(x * big_y / y, big_y, (1.0 - x - y) * big_y / y);
    let rgb = mat3x3f(
        vec3f(3.2406, -0.9689, 0.0557),
        vec3f(-1.5372, 1.8758, -0.2040),
        vec3f(-0.4986, 0.0415, 1.0570)) * xyz;
    return max(rgb, vec3f(0.0)) * sky.radiance_per_kcd;
}

fn sky_radiance(d: vec3f) -> vec3f {
    let s = normalize(sky.sun_dir.xyz);
    let t = sky.turbidity;
    // below the horizon: the horizon's radiance fading into the ground colour (the env cube's
    // lower half, seen only in reflections of steep waves and from under water)
    let horizon = preetham(normalize(vec3f(d.x, 0.0, d.z) + vec3f(0.0, 1e-3, 0.0)), s, t);
    let c = mix(horizon, sky.ground.rgb, smoothstep(0.0, 0.4, -d.y));
    return select(c, preetham(d, s, t), d.y >= 0.0);
}

// The sun disc along the unit direction `d`: limb-darkened, I(μ)/I(1) = 1 − u (1 − μ) with
// μ = √(1 − r²), u ≈ 0.6 (visible light), its edge anti-aliased over `px_rad` (one pixel).
// The angle from the sun's centre is 2 asin(|d − s| / 2): exact for small angles, where
// acos of a dot product loses its digits.
fn sun_disc(d: vec3f, s: vec3f, cos_radius: f32, radiance: vec3f, px_rad: f32) -> vec3f {
    let radius = acos(clamp(cos_radius, -1.0, 1.0));
    let angle = 2.0 * asin(clamp(0.5 * length(d - s), 0.0, 1.0));
    let r2 = min(angle * angle / max(radius * radius, 1e-8), 1.0);
    let limb = 1.0 - 0.6 * (1.0 - sqrt(1.0 - r2));
    let coverage = clamp((radius - angle) / max(px_rad, 1e-6) + 0.5, 0.0, 1.0);
    return radiance * limb * coverage * step(0.0, d.y);
}

@fragment
fn fs_cube_face(in: FullscreenOut) -> @location(0) vec4f {
    return vec4f(hdr_store(sky_radiance(face_dir(sky.face.x, in.ndc))), 1.0);
}

// Background: the depth test (LessEqual at depth 1) keeps it behind everything. Alpha holds the
// distance to what the pixel shows (the far plane here; see `opaque_out` in common.wgsl).
@fragment
fn fs_background(in: FullscreenOut) -> @location(0) vec4f {
    let far = g.world_from_clip * vec4f(in.ndc, 1.0, 1.0);
    let dir = normalize(far.xyz / far.w - g.eye_m);
    if (g.debug_view == DEBUG_NORMALS) {
        return vec4f(0.0, 0.0, 0.0, dist_store(g.far_m, g.near_m, g.far_m));
    }
    var c: vec3f;
    if (on(g.env_map_on)) {
        c = hdr_load(textureSampleLevel(env_cube, env_sampler, dir, 0.0).rgb)
            + sun_disc(dir, g.sun_dir, g.sun_cos_radius, g.sun_disc_radiance, g.rad_per_px);
    } else {
        // no environment: nothing to see or reflect but a flat grey (the "off" picture)
        c = ENV_OFF_RADIANCE;
    }
    return opaque_out(c, g.eye_m + dir * g.far_m);
}
