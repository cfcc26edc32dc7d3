// caustics.wgsl — water caustics: sunlight focused by the wave surface onto the seabed, rocks
// and fish, after Juan Guardado and Daniel Sánchez-Crespo, "Rendering Water Caustics", GPU
// Gems 1, ch. 2 (2004). As in the chapter, each point below the water looks up along the
// (refracted) sun direction to the wave surface, takes the surface normal there and refracts
// the sun ray through it (Snell, n = 1.33), for the same Gerstner sum the water pass draws
// (`gerstner` in common.wgsl, the one definition).
//
// Where the chapter turns the refracted ray's angle into brightness with a light texture, this
// pass measures how refraction focuses the light instead: the brightness on the floor is the
// area ratio (Jacobian) of the map from the surface to the floor, |det ∂entry/∂p| /
// |det ∂landing/∂p|, for a patch p of the surface at rest (entry: where the sun's rays cross
// it, projected along the sun; landing: where the refracted rays hit the plane `caustics_depth_m`
// below the water). Over flat water both maps are shifts and the ratio is 1, so the pattern
// keeps the sunlight's mean and needs no tuning constant; where rays converge it rises, along
// folds (the bright caustic lines) up to `MAX_INTENSITY`.
//
// Drawn once per frame with the full-screen triangle (fullscreen.wgsl) into a small texture
// (`CAUSTICS_MAP_SIZE`² in src/render/caustics.rs) that covers the swim box in x and z; the lit
// shaders read it with `caustics_light` (common.wgsl). Each texel is a floor point: it finds
// the rest point whose refracted ray lands on it by a fixed number of fixed-point steps (a
// constant loop bound: lavapipe compiles a variant per uniform-bound loop, see
// docs/benchmarks/scene.md), then takes the Jacobian by forward differences.
//!include common.wgsl
//!include encoding.wgsl
//!include fullscreen.wgsl

// fixed-point steps from the flat-water guess to the rest point whose ray lands on the texel
const GATHER_STEPS: u32 = 2u;
// forward-difference step, metres: well under the shortest wavelength the scene allows
const JACOBIAN_STEP_M: f32 = 0.04;
// a fold (det → 0) would be infinitely bright; the cap also bounds the HDR values
const MAX_INTENSITY: f32 = 6.0;

// Where the sun's ray through the surface point of rest position `rest_xz` crosses it
// (projected along the sun onto the mean level: xy) and where its refracted ray hits the
// plane y = `floor_y` (zw).
// Waves shorter than a few texels of the map fade out (`gerstner_faded`): their focusing
// would alias into noise whose mean is not flat water's.
fn entry_and_landing(rest_xz: vec2f, floor_y: f32, texel_m: f32) -> vec4f {
    let s = gerstner_faded(rest_xz, g.time_secs, texel_m);
    let sun = g.sun_dir;
    let entry = s.position.xz - sun.xz * (s.position.y - g.water_level_m) / max(sun.y, 0.05);
    let ray = refract(-sun, s.normal, ETA_AIR_OVER_WATER);
    let landing = s.position.xz + ray.xz * (s.position.y - floor_y) / max(-ray.y, 0.05);
    return vec4f(entry, landing);
}

fn cross2(a: vec2f, b: vec2f) -> f32 {
    return a.x * b.y - a.y * b.x;
}

@fragment
fn fs_caustics(in: FullscreenOut) -> @location(0) vec4f {
    // texture u → world x, v → world z (caustics_light reads it the same way)
    let floor_xz = (in.uv * 2.0 - 1.0) * g.caustics_half_extent_m;
    let floor_y = g.water_level_m - g.caustics_depth_m;
    let texel_m = 2.0 * g.caustics_half_extent_m * fwidth(in.uv.x);
    // over flat water the ray arriving here left the surface this far back along the
    // refracted sun
    let flat_ray = refract(-g.sun_dir, vec3f(0.0, 1.0, 0.0), ETA_AIR_OVER_WATER);
    var rest = floor_xz - flat_ray.xz * g.caustics_depth_m / max(-flat_ray.y, 0.05);
    for (var i = 0u; i < GATHER_STEPS; i++) {
        rest += floor_xz - entry_and_landing(rest, floor_y, texel_m).zw;
    }
    let e = JACOBIAN_STEP_M;
    let a = entry_and_landing(rest, floor_y, texel_m);
    let dx = entry_and_landing(rest + vec2f(e, 0.0), floor_y, texel_m) - a;
    let dz = entry_and_landing(rest + vec2f(0.0, e), floor_y, texel_m) - a;
    let entry_area = abs(cross2(dx.xy, dz.xy));
    let landing_area = max(abs(cross2(dx.zw, dz.zw)), entry_area / MAX_INTENSITY);
    return vec4f(caustics_store(entry_area / landing_area), 0.0, 0.0, 1.0);
}
