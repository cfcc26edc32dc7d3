// tonemap.wgsl — HDR to display (tone mapping): exposure, then the ACES filmic curve in
// Narkowicz's fit (Narkowicz 2015, "ACES Filmic Tone Mapping Curve", aces.wgsl); the sRGB
// encoding is done by a *Srgb target format or by `to_target` (srgb.wgsl). The HDR image may be
// smaller than the display (dynamic resolution): it is sampled bilinearly, which scales it up.
// The normals debug view is already display-ready and passes through.
//!include fullscreen.wgsl
//!include aces.wgsl
//!include srgb.wgsl

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
@group(0) @binding(1) var hdr: texture_2d<f32>;
@group(0) @binding(2) var hdr_sampler: sampler;

@fragment
fn fs_main(in: FullscreenOut) -> @location(0) vec4f {
    let c = textureSampleLevel(hdr, hdr_sampler, in.uv, 0.0).rgb;
    if (post.debug_view == 2u) {
        // normals are encoded 0..1 in sRGB-ish display space; undo the target's encoding
        return to_target(pow(c, vec3f(2.2)));
    }
    return to_target(aces(c * post.exposure));
}
