// debug.wgsl — teaching views: the sun's shadow map as grey levels (near = dark), and the
// environment cube unfolded as a horizontal cross (+y above, −y below; −x +z +x −z across),
// each face showing its roughness-blurred mip chain from left (sharp) to right in a strip.

struct Params {
    // x view (1 shadow map, 3 env cube), y env mip count, z/w viewport size
    v: vec4f,
}

@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var shadow_map: texture_depth_2d;
@group(0) @binding(2) var env_cube: texture_cube<f32>;
@group(0) @binding(3) var env_sampler: sampler;

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

fn cross_dir(face: i32, f: vec2f) -> vec3f {
    let u = f.x * 2.0 - 1.0;
    let v = f.y * 2.0 - 1.0;
    var d = vec3f(-u, -v, -1.0);
    if (face == 0) {
        d = vec3f(1.0, -v, -u);
    } else if (face == 1) {
        d = vec3f(-1.0, -v, u);
    } else if (face == 2) {
        d = vec3f(u, 1.0, v);
    } else if (face == 3) {
        d = vec3f(u, -1.0, -v);
    } else if (face == 4) {
        d = vec3f(u, -v, 1.0);
    }
    return d;
}

@fragment
fn fs_main(in: FullscreenOut) -> @location(0) vec4f {
    let view = u32(params.v.x + 0.5);
    if (view == 1u) {
        // square, centred
        let side = min(params.v.z, params.v.w);
        let p = (in.clip.xy - 0.5 * (params.v.zw - vec2f(side))) / side;
        if (any(p < vec2f(0.0)) || any(p > vec2f(1.0))) {
            return vec4f(0.05, 0.05, 0.05, 1.0);
        }
        let size = vec2f(textureDimensions(shadow_map));
        let d = textureLoad(shadow_map, vec2i(p * size), 0);
        let grey = pow(clamp(d, 0.0, 1.0), 2.0);
        return vec4f(vec3f(grey), 1.0);
    }
    // env cube cross: 4 × 3 cells, top half of the screen; mips in a strip below
    let cell_px = min(params.v.z / 4.0, params.v.w / 3.6);
    let origin = vec2f(0.5 * (params.v.z - 4.0 * cell_px), 0.0);
    let c = (in.clip.xy - origin) / cell_px;
    var face = -1;
    let ci = vec2i(floor(c));
    if (ci.y == 1 && ci.x >= 0 && ci.x < 4) {
        var across = array<i32, 4>(1, 4, 0, 5);
        face = across[ci.x];
    } else if (ci.x == 1 && ci.y == 0) {
        face = 2;
    } else if (ci.x == 1 && ci.y == 2) {
        face = 3;
    }
    if (face >= 0) {
        let d = normalize(cross_dir(face, fract(c)));
        return vec4f(aces(textureSampleLevel(env_cube, env_sampler, d, 0.0).rgb), 1.0);
    }
    // the mip strip: the +x…−z equator seen at increasing roughness, one band per mip
    let mips = params.v.y;
    let strip_top = 3.0 * cell_px;
    if (in.clip.y > strip_top && ci.x >= 0 && c.x < 4.0) {
        let t = (in.clip.y - strip_top) / (params.v.w - strip_top);
        let mip = floor(t * mips);
        let yaw = c.x / 4.0 * 6.2831853;
        let d = vec3f(cos(yaw), 0.15, sin(yaw));
        return vec4f(aces(textureSampleLevel(env_cube, env_sampler, d, mip).rgb), 1.0);
    }
    return vec4f(0.05, 0.05, 0.05, 1.0);
}
