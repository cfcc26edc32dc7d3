// brdf.wgsl — Cook–Torrance microfacet BRDF and image-based lighting, shared by the opaque
// shaders. References:
//   D_GGX: Walter, Marschner, Li, Torrance 2007, "Microfacet Models for Refraction through
//          Rough Surfaces" (the GGX / Trowbridge–Reitz distribution).
//   V_SmithGGXCorrelated: Heitz 2014, "Understanding the Masking-Shadowing Function in
//          Microfacet-Based BRDFs" (height-correlated Smith), in Filament's form.
//   F_Schlick: Schlick 1994, "An Inexpensive BRDF Model for Physically-based Rendering".
//   Split-sum environment lighting with the analytic DFG fit: Karis 2013 (UE4 course notes),
//          Lazarov 2013 / Karis "mobile" approximation.
// Needs common.wgsl included before it.

// `MaterialGpu` in src/render/pbr.rs
struct MaterialParams {
    base_color: vec4f,
    metallic: f32,
    roughness: f32,             // perceptual; GGX alpha = roughness²
    reflectance: f32,           // F0 = 0.16 reflectance² for dielectrics (Filament)
    normal_strength: f32,       // scales the normal map's tangent-plane tilt
    uv_scale: f32,              // repeats per metre (terrain) or per unit uv
    _pad0: f32,
    _pad1: f32,
    _pad2: f32,
}

fn D_GGX(n_dot_h: f32, alpha: f32) -> f32 {
    let a2 = alpha * alpha;
    let f = (n_dot_h * a2 - n_dot_h) * n_dot_h + 1.0;
    return a2 / (PI * f * f);
}

fn V_SmithGGXCorrelated(n_dot_v: f32, n_dot_l: f32, alpha: f32) -> f32 {
    let a2 = alpha * alpha;
    let ggx_l = n_dot_v * sqrt((-n_dot_l * a2 + n_dot_l) * n_dot_l + a2);
    let ggx_v = n_dot_l * sqrt((-n_dot_v * a2 + n_dot_v) * n_dot_v + a2);
    return 0.5 / max(ggx_v + ggx_l, 1e-5);
}

fn F_Schlick(f0: vec3f, v_dot_h: f32) -> vec3f {
    if (!on(g.fresnel_on)) {
        return f0;
    }
    let f = pow(1.0 - v_dot_h, 5.0);
    return f0 + (vec3f(1.0) - f0) * f;
}

// Karis' analytic approximation of the pre-integrated DFG term (scale, bias) for the split sum.
fn env_brdf_approx(f0: vec3f, roughness: f32, n_dot_v: f32) -> vec3f {
    if (!on(g.fresnel_on)) {
        return f0;
    }
    let c0 = vec4f(-1.0, -0.0275, -0.572, 0.022);
    let c1 = vec4f(1.0, 0.0425, 1.04, -0.04);
    let r = roughness * c0 + c1;
    let a004 = min(r.x * r.x, exp2(-9.28 * n_dot_v)) * r.x + r.y;
    let ab = vec2f(-1.04, 1.04) * a004 + r.zw;
    return f0 * ab.x + ab.y;
}

fn env_radiance(dir: vec3f, roughness: f32) -> vec3f {
    let mips = g.env_mip_count;
    return hdr_load(textureSampleLevel(env_cube, env_sampler, dir, roughness * (mips - 1.0)).rgb);
}

// Outgoing radiance towards v from a surface lit by the sun and the sky cube map.
fn shade(base: vec3f, metallic: f32, roughness_in: f32, reflectance: f32,
         n: vec3f, v: vec3f, world_pos: vec3f, ao: f32) -> vec3f {
    let roughness = clamp(roughness_in, 0.045, 1.0);
    // specular anti-aliasing (Kaplanyan, Hill, Patney & Lefohn 2016, "Filtering distributions
    // of normals for shading antialiasing"): the normal's variance over the pixel, from its
    // screen derivatives, widens the GGX lobe, so small shiny curves (fish, ripples) do not
    // sparkle from frame to frame
    let dn = fwidth(n);
    let variance = min(2.0 * dot(dn, dn), 0.18);
    let alpha = sqrt(min(roughness * roughness * roughness * roughness + variance, 1.0));
    let l = g.sun_dir;
    let h = normalize(v + l);
    let n_dot_v = max(dot(n, v), 1e-4);
    let n_dot_l = clamp(dot(n, l), 0.0, 1.0);
    let n_dot_h = clamp(dot(n, h), 0.0, 1.0);
    let v_dot_h = clamp(dot(v, h), 0.0, 1.0);

    let f0 = mix(vec3f(0.16 * reflectance * reflectance), base, metallic);
    let diffuse_color = base * (1.0 - metallic);

    var direct: vec3f;
    if (on(g.cook_torrance_on)) {
        let d = D_GGX(n_dot_h, alpha);
        let vis = V_SmithGGXCorrelated(n_dot_v, n_dot_l, alpha);
        let f = F_Schlick(f0, v_dot_h);
        let specular = d * vis * f;
        let diffuse = (vec3f(1.0) - f) * diffuse_color / PI;
        direct = (diffuse + specular) * n_dot_l;
    } else {
        // Lambert only: what the lecture's "before" picture looks like
        direct = base / PI * n_dot_l;
    }
    let sun = g.sun_color * g.sun_intensity;
    let lit = direct * sun * sun_visibility(world_pos, n) * sun_transmittance(world_pos)
        * caustics_light(world_pos);

    // ambient: irradiance from the roughest mip, specular from the roughness-matched mip
    var ambient: vec3f;
    let under = sun_transmittance(world_pos);
    if (on(g.env_map_on)) {
        let irradiance = env_radiance(n, 1.0);
        if (on(g.cook_torrance_on)) {
            let r = reflect(-v, n);
            let spec = env_radiance(r, roughness) * env_brdf_approx(f0, roughness, n_dot_v);
            ambient = diffuse_color * irradiance + spec;
        } else {
            ambient = base * irradiance;
        }
    } else {
        ambient = base * vec3f(0.25, 0.3, 0.35);
    }
    return lit + ambient * ao * under;
}
