// srgb.wgsl — writing display colours to the output target, shared by the passes that draw
// into it (tone mapping, the debug views). A `…Srgb` target encodes on store; a plain one —
// the window's own framebuffer, which scene mode draws into directly — gets the sRGB transfer
// function here (IEC 61966-2-1:1999, the piecewise curve). Include with
// `//!include srgb.wgsl`.

// Set per pipeline from the target's format (src/render/pipeline.rs): a constant for the
// shader compiler, not a uniform, so each pipeline compiles one branch-free variant.
override TARGET_IS_SRGB: bool = true;

fn srgb_from_linear(c: vec3f) -> vec3f {
    let x = clamp(c, vec3f(0.0), vec3f(1.0));
    return select(1.055 * pow(x, vec3f(1.0 / 2.4)) - 0.055, 12.92 * x, x <= vec3f(0.0031308));
}

// The value to write for a linear display colour `c`.
fn to_target(c: vec3f) -> vec4f {
    if (TARGET_IS_SRGB) {
        return vec4f(c, 1.0);
    }
    return vec4f(srgb_from_linear(c), 1.0);
}
