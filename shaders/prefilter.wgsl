// prefilter.wgsl — roughness-blurred environment mips for glossy reflections: each mip m of
// the environment cube holds the sky convolved with the GGX lobe of roughness m/(M−1), by
// importance sampling the GGX normal distribution with a Hammersley set and the N = V = R
// assumption (Karis 2013, "Real Shading in Unreal Engine 4", split-sum approximation).

//!include fullscreen.wgsl
//!include cube_face.wgsl
//!include encoding.wgsl

// `PrefilterParams` in src/render/sky.rs
struct Params {
    roughness: f32,     // perceptual roughness of this mip
    face: u32,          // cube face being rendered, WebGPU order
    _pad: vec2u,
}

// GGX samples per texel. A constant, not a uniform, and no branch on the roughness (at 0 every
// sample is the mirror direction): lavapipe compiles a variant per value of a uniform that
// decides a loop or branch (see pbr.wgsl).
const SAMPLE_COUNT: u32 = 64u;

@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var src_cube: texture_cube<f32>;
@group(0) @binding(2) var src_sampler: sampler;

const PI: f32 = 3.14159265;

fn radical_inverse(bits_in: u32) -> f32 {
    var bits = bits_in;
    bits = (bits << 16u) | (bits >> 16u);
    bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
    bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
    bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
    bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
    return f32(bits) * 2.3283064365386963e-10;
}

fn importance_sample_ggx(xi: vec2f, alpha: f32, n: vec3f) -> vec3f {
    let phi = 2.0 * PI * xi.x;
    let cos_theta = sqrt((1.0 - xi.y) / (1.0 + (alpha * alpha - 1.0) * xi.y));
    let sin_theta = sqrt(1.0 - cos_theta * cos_theta);
    let h = vec3f(sin_theta * cos(phi), sin_theta * sin(phi), cos_theta);
    var up = vec3f(0.0, 0.0, 1.0);
    if (abs(n.z) > 0.999) {
        up = vec3f(1.0, 0.0, 0.0);
    }
    let tx = normalize(cross(up, n));
    let ty = cross(n, tx);
    return normalize(tx * h.x + ty * h.y + n * h.z);
}

@fragment
fn fs_main(in: FullscreenOut) -> @location(0) vec4f {
    let n = face_dir(params.face, in.ndc);
    let roughness = params.roughness;
    let alpha = roughness * roughness;
    let count = SAMPLE_COUNT;
    // clamp the HDR sun so a few samples hitting it do not sparkle; the sharp mip keeps it
    let limit = select(vec3f(8.0), vec3f(1e9), roughness < 0.01);
    var sum = vec3f(0.0);
    var weight = 0.0;
    for (var i = 0u; i < count; i++) {
        let xi = vec2f(f32(i) / f32(count), radical_inverse(i));
        let h = importance_sample_ggx(xi, alpha, n);
        let l = normalize(2.0 * dot(n, h) * h - n);
        let n_dot_l = dot(n, l);
        if (n_dot_l > 0.0) {
            sum += min(hdr_load(textureSampleLevel(src_cube, src_sampler, l, 0.0).rgb), limit) * n_dot_l;
            weight += n_dot_l;
        }
    }
    return vec4f(hdr_store(sum / max(weight, 1e-4)), 1.0);
}
