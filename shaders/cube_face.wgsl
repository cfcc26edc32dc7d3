// cube_face.wgsl — shared by the passes that render into the six faces of a cube map (the
// procedural sky, its roughness-blurred mips): a full-screen triangle and the direction through
// a face texel in WebGPU's face order (cube maps: Greene 1986). Included with
// `//!include cube_face.wgsl`.

struct FullscreenOut {
    @builtin(position) clip: vec4f,
    @location(0) ndc: vec2f,
}

// One triangle covering the viewport.
@vertex
fn vs_fullscreen(@builtin(vertex_index) i: u32) -> FullscreenOut {
    let uv = vec2f(f32((i << 1u) & 2u), f32(i & 2u));
    let ndc = uv * 2.0 - 1.0;
    return FullscreenOut(vec4f(ndc, 1.0, 1.0), ndc);
}

// Direction through a cube face texel, WebGPU face order +x −x +y −y +z −z.
fn face_dir(face: u32, ndc: vec2f) -> vec3f {
    let u = ndc.x;
    let v = -ndc.y;
    var d = vec3f(-u, -v, -1.0); // face 5: -z
    if (face == 0u) {
        d = vec3f(1.0, -v, -u);
    } else if (face == 1u) {
        d = vec3f(-1.0, -v, u);
    } else if (face == 2u) {
        d = vec3f(u, 1.0, v);
    } else if (face == 3u) {
        d = vec3f(u, -1.0, -v);
    } else if (face == 4u) {
        d = vec3f(u, -v, 1.0);
    }
    return normalize(d);
}
