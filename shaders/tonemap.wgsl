// tonemap.wgsl — HDR to display: exposure, then the ACES filmic curve in Narkowicz's fit
// (Narkowicz 2015, "ACES Filmic Tone Mapping Curve"); the sRGB encoding is done by the
// *Srgb target format. The normals debug view is already display-ready and passes through.

struct Params {
    // x exposure, y debug view
    v: vec4f,
}

@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var hdr: texture_2d<f32>;

struct FullscreenOut {
    @builtin(position) clip: vec4f,
    @location(0) uv: vec2f,
}

@vertex
fn vs_fullscreen(@builtin(vertex_index) i: u32) -> FullscreenOut {
    let uv = vec2f(f32((i << 1u) & 2u), f32(i & 2u));
    return FullscreenOut(vec4f(uv * 2.0 - 1.0, 0.0, 1.0), vec2f(uv.x, 1.0 - uv.y));
}

fn aces(x: vec3f) -> vec3f {
    return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), vec3f(0.0), vec3f(1.0));
}

@fragment
fn fs_main(in: FullscreenOut) -> @location(0) vec4f {
    let texel = vec2i(in.clip.xy);
    let c = textureLoad(hdr, texel, 0).rgb;
    if (u32(params.v.y + 0.5) == 2u) {
        // normals are encoded 0..1 in sRGB-ish display space; undo the target's encoding
        return vec4f(pow(c, vec3f(2.2)), 1.0);
    }
    return vec4f(aces(c * params.v.x), 1.0);
}
