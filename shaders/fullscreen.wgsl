// fullscreen.wgsl — one triangle that covers the viewport (three vertices, no vertex buffer:
// positions from the vertex index), shared by every pass that shades each pixel of its target
// once: the sky's cube faces and background, the environment prefilter, tone mapping and the
// debug views. Include with `//!include fullscreen.wgsl`. The technique: "full-screen
// triangle" (Bill Bilodeau, AMD, "Vertex Shader Tricks", GDC 2014) — one triangle instead of a
// quad has no diagonal seam where pixels are shaded twice.

struct FullscreenOut {
    @builtin(position) clip: vec4f,
    // −1…1, y up (clip space of the triangle)
    @location(0) ndc: vec2f,
    // 0…1, y down (texture space)
    @location(1) uv: vec2f,
}

@vertex
fn vs_fullscreen(@builtin(vertex_index) i: u32) -> FullscreenOut {
    let t = vec2f(f32((i << 1u) & 2u), f32(i & 2u));
    let ndc = t * 2.0 - 1.0;
    // depth 1: drawn last with LessEqual, the sky background fills only what nothing covered
    return FullscreenOut(vec4f(ndc, 1.0, 1.0), ndc, vec2f(t.x, 1.0 - t.y));
}
