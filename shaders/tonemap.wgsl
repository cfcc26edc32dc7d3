// tonemap.wgsl — HDR to display (tone mapping): exposure, then the ACES filmic curve in
// Narkowicz's fit (Narkowicz 2015, "ACES Filmic Tone Mapping Curve", aces.wgsl), after a white
// balance (`WHITE_BALANCE` below); the sRGB
// encoding is done by a *Srgb target format or by `to_target` (srgb.wgsl). `fs_main` draws the
// display image at the HDR image's size, anti-aliasing geometric edges with FXAA (Lottes 2011,
// fxaa.wgsl) where the pipeline has it on; `fs_upscale` then scales it up to the output
// bilinearly (dynamic resolution draws the scene smaller than the display). The normals debug
// view is already display-ready and passes through.
//!include fullscreen.wgsl
//!include aces.wgsl
//!include srgb.wgsl
//!include fxaa.wgsl
//!include encoding.wgsl

// `PostParams` in src/render/tonemap.rs
struct Post {
    exposure: f32,
    debug_view: u32,            // 2 = normals (pass through)
    env_mip_count: f32,
    _pad: f32,
    viewport_size_px: vec2f,    // the display target
    _pad2: vec2f,
}

@group(0) @binding(0) var<uniform> post: Post;
// the HDR image (`fs_main`), or the display image (`fs_upscale`)
@group(0) @binding(1) var hdr: texture_2d<f32>;
@group(0) @binding(2) var hdr_sampler: sampler;

// White balance: the scene is lit by its sun (colour (1, 0.92, 0.8) in the scene file, about
// 5000 K) and Preetham's sky, which is yellow-pink near the sun and the horizon in absolute
// colour; a camera balanced for that key light maps CIE D50 (x 0.34567, y 0.35850; CIE 15:2004)
// to the display's D65 white, which leaves the sunlit sand neutral and the sky away from the
// sun blue. A von Kries adaptation in the Bradford cone space (Lam 1985; the matrices as in
// Lindbloom, "Chromatic Adaptation", brucelindbloom.com), D50 → D65, for linear sRGB:
// M = RGB_from_XYZ · Bradford⁻¹ · diag(ρβγ_D65 / ρβγ_D50) · Bradford · XYZ_from_RGB (columns).
const WHITE_BALANCE = mat3x3f(
    vec3f(0.93918, 0.00446, 0.00815),
    vec3f(-0.09428, 1.02437, 0.02947),
    vec3f(-0.01747, -0.00652, 1.33199));

// The display colour of the HDR image at `uv` (what fxaa.wgsl blends).
fn display_at(uv: vec2f) -> vec3f {
    let c = hdr_load(textureSampleLevel(hdr, hdr_sampler, uv, 0.0).rgb);
    return aces(max(WHITE_BALANCE * c, vec3f(0.0)) * post.exposure);
}

@fragment
fn fs_main(in: FullscreenOut) -> @location(0) vec4f {
    if (post.debug_view == 2u) {
        // normals are encoded 0..1 in sRGB-ish display space; undo the target's encoding
        let c = hdr_load(textureSampleLevel(hdr, hdr_sampler, in.uv, 0.0).rgb);
        return to_target(pow(c, vec3f(2.2)));
    }
    if (FXAA_ON) {
        return to_target(fxaa(in.uv, 1.0 / vec2f(textureDimensions(hdr))));
    }
    return to_target(display_at(in.uv));
}

@fragment
fn fs_upscale(in: FullscreenOut) -> @location(0) vec4f {
    return to_target(textureSampleLevel(hdr, hdr_sampler, in.uv, 0.0).rgb);
}
