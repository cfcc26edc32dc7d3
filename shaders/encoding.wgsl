// encoding.wgsl — how values are stored in the renderer's own targets when the adapter cannot
// render to float formats (a WebGL2 context without EXT_color_buffer_float; `RenderCaps` in
// src/render/caps.rs decides, once): HDR colour and the environment cube scaled down into an
// 8-bit sRGB target (the sRGB curve keeps the dark tones' steps small), the eye distance as a
// fraction d / (d + 16 m) (see `dist_store`), the caustics factor scaled down. With float
// targets the scales are 1 and nothing is encoded.
// Include with `//!include encoding.wgsl` in every shader that writes or reads those targets.

// Set per pipeline from `RenderCaps::encoding` (src/render/pipeline.rs).
override HDR_STORE_SCALE: f32 = 1.0;
override DIST_ENCODED: bool = false;
override CAUSTICS_STORE_SCALE: f32 = 1.0;

fn hdr_store(c: vec3f) -> vec3f {
    return c * HDR_STORE_SCALE;
}

fn hdr_load(c: vec3f) -> vec3f {
    return c / HDR_STORE_SCALE;
}

// 8 bits of distance as d / (d + DIST_KNEE_M): steps of ~0.2 m at 10 m, where the water's
// paths are measured (differences of two distances), ~4 % of the distance at 100 m, the far
// plane at 0.99 (a log scale over near…far had 0.4 m steps at 10 m).
const DIST_KNEE_M: f32 = 16.0;

fn dist_store(dist_m: f32, near_m: f32, far_m: f32) -> f32 {
    if (DIST_ENCODED) {
        let d = clamp(dist_m, near_m, far_m);
        return d / (d + DIST_KNEE_M);
    }
    return dist_m;
}

fn dist_load(stored: f32, near_m: f32, far_m: f32) -> f32 {
    if (DIST_ENCODED) {
        let u = min(stored, 0.999);
        return clamp(DIST_KNEE_M * u / (1.0 - u), near_m, far_m);
    }
    return stored;
}

fn caustics_store(focus: f32) -> f32 {
    return focus * CAUSTICS_STORE_SCALE;
}

fn caustics_load(stored: f32) -> f32 {
    return stored / CAUSTICS_STORE_SCALE;
}
