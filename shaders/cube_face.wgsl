// cube_face.wgsl — cube-map face directions (cube maps: Greene 1986, "Environment Mapping and
// Other Applications of World Projections"), shared by the passes that render into the six
// faces of a cube map with the full-screen triangle of fullscreen.wgsl: the procedural sky and
// its roughness-blurred mips. Include with `//!include cube_face.wgsl`.

// Direction through a cube face texel, WebGPU face order +x −x +y −y +z −z: per face the
// world axes that screen x, screen y (down) and the face normal map to. A table, not a chain
// of `if`s on the face uniform: lavapipe compiles a shader variant for every value of a
// uniform that decides a branch (see pbr.wgsl).
fn face_dir(face: u32, ndc: vec2f) -> vec3f {
    var axes = array<mat3x3f, 6>(
        mat3x3f(vec3f(0.0, 0.0, -1.0), vec3f(0.0, -1.0, 0.0), vec3f(1.0, 0.0, 0.0)),
        mat3x3f(vec3f(0.0, 0.0, 1.0), vec3f(0.0, -1.0, 0.0), vec3f(-1.0, 0.0, 0.0)),
        mat3x3f(vec3f(1.0, 0.0, 0.0), vec3f(0.0, 0.0, 1.0), vec3f(0.0, 1.0, 0.0)),
        mat3x3f(vec3f(1.0, 0.0, 0.0), vec3f(0.0, 0.0, -1.0), vec3f(0.0, -1.0, 0.0)),
        mat3x3f(vec3f(1.0, 0.0, 0.0), vec3f(0.0, -1.0, 0.0), vec3f(0.0, 0.0, 1.0)),
        mat3x3f(vec3f(-1.0, 0.0, 0.0), vec3f(0.0, -1.0, 0.0), vec3f(0.0, 0.0, -1.0)),
    );
    return normalize(axes[min(face, 5u)] * vec3f(ndc.x, -ndc.y, 1.0));
}
