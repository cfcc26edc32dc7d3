// aces.wgsl — the ACES filmic tone curve in Narkowicz's fit (Krzysztof Narkowicz 2015, "ACES
// Filmic Tone Mapping Curve"), shared by the tone mapping pass and the debug views that show
// HDR images. Include with `//!include aces.wgsl`.

fn aces(x: vec3f) -> vec3f {
    return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), vec3f(0.0), vec3f(1.0));
}
