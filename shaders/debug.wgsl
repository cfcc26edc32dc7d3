// debug.wgsl — teaching views, each filling its panel: the sun's shadow map as grey levels
// (near = dark), zoomed to its casters with their depth range stretched, and the
// environment cube unfolded as a horizontal cross (+y above, −y below; −x +z +x −z across),
// each face showing its roughness-blurred mip chain from left (sharp) to right in a strip, and
// the caustics map seen from above (+x right, +z down; 1 = flat water's light, mid grey),
// cropped to the panel's aspect.
// Shadow maps: Williams 1978; cube maps: Greene 1986; caustics: GPU Gems 1 ch. 2.
//!include fullscreen.wgsl
//!include aces.wgsl
//!include srgb.wgsl
//!include encoding.wgsl

// `PostParams` in src/render/tonemap.rs
struct Post {
    exposure: f32,
    debug_view: u32,            // 1 shadow map, 3 env cube, 4 caustics map
    env_mip_count: f32,
    _pad: f32,
    viewport_size_px: vec2f,    // the display target
    _pad2: vec2f,
}

@group(0) @binding(0) var<uniform> post: Post;
// the shadow map's depths read as plain floats: GLSL (WebGL2, GL) has no `textureLoad` of a
// depth texture, and its shadow samplers only compare (wgpu #4524)
@group(0) @binding(1) var shadow_map: texture_2d<f32>;
@group(0) @binding(2) var env_cube: texture_cube<f32>;
@group(0) @binding(3) var env_sampler: sampler;
@group(0) @binding(4) var caustics_map: texture_2d<f32>;

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
    let size_px = post.viewport_size_px;
    // pixel position in the viewport (not the framebuffer: scene mode draws into a part of
    // the window)
    let px = in.uv * size_px;
    // the two maps fill the panel: each shows a window of its map with the panel's aspect
    // (width over height), so no band of the panel is left empty
    let p = px / size_px;
    let aspect = size_px.x / max(size_px.y, 1.0);
    if (post.debug_view == 4u) {
        // the caustics map covers the swim box: its middle, as wide as the panel allows
        let window = select(vec2f(1.0, 1.0 / aspect), vec2f(aspect, 1.0), aspect < 1.0);
        let uv = 0.5 + (p - 0.5) * window;
        // focusing factor: 1 (flat water) mid grey, the bright folds white
        let focus = caustics_load(textureSampleLevel(caustics_map, env_sampler, uv, 0.0).r);
        return to_target(aces(vec3f(0.2 * focus)));
    }
    if (post.debug_view == 1u) {
        let size = vec2f(textureDimensions(shadow_map));
        // a 16×16 survey of the map: the casters' depth range (empty texels hold the cleared
        // 1.0 and stay out) and the rectangle around them, so the view fills its panel with the
        // casters and stretches their depths over the grey ramp (near the sun dark, far light)
        var lo = 1.0;
        var hi = 0.0;
        var uv_lo = vec2f(1.0);
        var uv_hi = vec2f(0.0);
        for (var j = 0; j < 16; j++) {
            for (var i = 0; i < 16; i++) {
                let uv = (vec2f(f32(i), f32(j)) + 0.5) / 16.0;
                let s = textureLoad(shadow_map, vec2i(uv * size), 0).r;
                if (s < 0.9999) {
                    lo = min(lo, s);
                    hi = max(hi, s);
                    uv_lo = min(uv_lo, uv);
                    uv_hi = max(uv_hi, uv);
                }
            }
        }
        // the window: the casters' rectangle plus a survey cell on each side, grown along one
        // axis to the panel's aspect, centred on them and kept on the map where it fits
        var centre = vec2f(0.5);
        var extent = vec2f(1.0);
        if (hi > 0.0) {
            centre = 0.5 * (uv_lo + uv_hi);
            extent = uv_hi - uv_lo + 2.0 / 16.0;
        }
        let width = max(extent.x, extent.y * aspect);
        let window = vec2f(width, width / aspect);
        let window_lo = select(clamp(centre - 0.5 * window, vec2f(0.0), 1.0 - window),
                               centre - 0.5 * window, window > vec2f(1.0));
        let uv = window_lo + p * window;
        let on_map = all(uv >= vec2f(0.0)) && all(uv <= vec2f(1.0));
        let d = textureLoad(shadow_map, vec2i(clamp(uv, vec2f(0.0), vec2f(1.0)) * (size - 1.0)), 0).r;
        if (d >= 0.9999 || !on_map) {
            // nothing casts here: a deep blue, off the grey ramp, so the casters stand out
            // against it (a pale one left the view a near-uniform sheet)
            return to_target(vec3f(0.02, 0.04, 0.12));
        }
        let t = clamp((d - lo) / max(hi - lo, 1e-4), 0.0, 1.0);
        return to_target(vec3f(mix(0.12, 0.95, t)));
    }
    // env cube cross: 4 × 3 cells, top half of the screen; mips in a strip below
    let cell_px = min(size_px.x / 4.0, size_px.y / 3.6);
    let origin = vec2f(0.5 * (size_px.x - 4.0 * cell_px), 0.0);
    let c = (px - origin) / cell_px;
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
        return to_target(aces(hdr_load(textureSampleLevel(env_cube, env_sampler, d, 0.0).rgb)));
    }
    // the mip strip: the +x…−z equator seen at increasing roughness, one band per mip
    let mips = post.env_mip_count;
    let strip_top = 3.0 * cell_px;
    if (px.y > strip_top && ci.x >= 0 && c.x < 4.0) {
        let t = (px.y - strip_top) / (size_px.y - strip_top);
        let mip = floor(t * mips);
        let yaw = c.x / 4.0 * 6.2831853;
        let d = vec3f(cos(yaw), 0.15, sin(yaw));
        return to_target(aces(hdr_load(textureSampleLevel(env_cube, env_sampler, d, mip).rgb)));
    }
    return to_target(vec3f(0.05));
}
