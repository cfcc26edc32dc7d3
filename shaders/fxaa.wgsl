// fxaa.wgsl — post-process anti-aliasing of geometric edges: FXAA (Timothy Lottes 2009/2011,
// "FXAA", NVIDIA white paper; this is the "console" variant of FXAA 3.11): four diagonal
// half-texel taps estimate the edge's direction from luma, two and four taps along it blend
// across the edge, and the wider blend is kept unless it leaves the local luma range. Shared by
// the tone mapping pass (tonemap.wgsl), which defines `display_at(uv)`: the display colour
// (tone mapped, before the target's encoding) of the HDR image at `uv`. Include with
// `//!include fxaa.wgsl`. Chosen per pipeline (`FXAA_ON`), a constant to the shader compiler.

override FXAA_ON: bool = true;

// less local contrast than this (absolute, or relative to the brightest tap) is not an edge
const FXAA_EDGE_MIN: f32 = 1.0 / 24.0;
const FXAA_EDGE_REL: f32 = 1.0 / 8.0;
// Lottes' defaults: how much the direction is reduced in dark areas, and the longest blend
const FXAA_REDUCE_MIN: f32 = 1.0 / 128.0;
const FXAA_REDUCE_MUL: f32 = 1.0 / 8.0;
const FXAA_SPAN_MAX_TEXELS: f32 = 8.0;

// Perceptual luma of a display-linear colour (Rec. 601 weights, square root for gamma).
fn fxaa_luma(c: vec3f) -> f32 {
    return sqrt(dot(c, vec3f(0.299, 0.587, 0.114)));
}

// The anti-aliased display colour at `uv`, for an image whose texels are `texel` apart in uv.
fn fxaa(uv: vec2f, texel: vec2f) -> vec3f {
    let rgb_m = display_at(uv);
    let m = fxaa_luma(rgb_m);
    let nw = fxaa_luma(display_at(uv + vec2f(-0.5, -0.5) * texel));
    let ne = fxaa_luma(display_at(uv + vec2f(0.5, -0.5) * texel));
    let sw = fxaa_luma(display_at(uv + vec2f(-0.5, 0.5) * texel));
    let se = fxaa_luma(display_at(uv + vec2f(0.5, 0.5) * texel));
    let luma_min = min(m, min(min(nw, ne), min(sw, se)));
    let luma_max = max(m, max(max(nw, ne), max(sw, se)));
    if (luma_max - luma_min < max(FXAA_EDGE_MIN, luma_max * FXAA_EDGE_REL)) {
        return rgb_m;
    }
    // the luma gradient turned by 90°: along the edge
    var dir = vec2f(-((nw + ne) - (sw + se)), (nw + sw) - (ne + se));
    let reduce = max((nw + ne + sw + se) * 0.25 * FXAA_REDUCE_MUL, FXAA_REDUCE_MIN);
    let rcp_dir_min = 1.0 / (min(abs(dir.x), abs(dir.y)) + reduce);
    dir = clamp(dir * rcp_dir_min, vec2f(-FXAA_SPAN_MAX_TEXELS), vec2f(FXAA_SPAN_MAX_TEXELS)) * texel;
    let a = 0.5 * (display_at(uv + dir * (1.0 / 3.0 - 0.5)) + display_at(uv + dir * (2.0 / 3.0 - 0.5)));
    let b = 0.5 * a + 0.25 * (display_at(uv - 0.5 * dir) + display_at(uv + 0.5 * dir));
    let lb = fxaa_luma(b);
    return select(b, a, lb < luma_min || lb > luma_max);
}
