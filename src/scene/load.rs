//! Reading a scene file: RON parse errors keep their `line:col`; range checks name the field and
//! the bad value, and point at the value itself (found again in a [`crate::ron_tree`]).

use std::path::Path;

use crate::diag::Diagnostic;

use super::model::{MAX_FISH, MAX_OBJECTS, MAX_WAVES, Object, Scene, Shape, WATER_DENSITY};

/// Parses and validates scene text; `file` only names the source in diagnostics.
pub fn parse_scene(text: &str, file: &Path) -> Result<Scene, Diagnostic> {
    let scene: Scene = ron::from_str(text).map_err(|e| Diagnostic::from_ron(file, &e))?;
    validate(&scene).map_err(|(at, msg)| {
        let tree = crate::ron_tree::parse(text).ok();
        Diagnostic::at_value(tree.as_ref(), text, file, &at, msg)
    })?;
    Ok(scene)
}

/// Reads, parses and validates a scene file.
pub fn load_scene(path: &Path) -> Result<Scene, Diagnostic> {
    let text = crate::project_files::read_to_string(path)
        .map_err(|e| Diagnostic::whole_file(path, format!("cannot read scene: {e}")))?;
    parse_scene(&text, path)
}

/// For `lectern check`: every problem of one scene file (at most one: parsing stops at the first).
pub fn check_file(path: &Path) -> Vec<Diagnostic> {
    load_scene(path).err().into_iter().collect()
}

/// The path of the value at fault (`water.waves[2].speed`) and the message.
type Invalid = (String, String);

fn check(ok: bool, at: impl Into<String>, msg: impl FnOnce() -> String) -> Result<(), Invalid> {
    if ok { Ok(()) } else { Err((at.into(), msg())) }
}

/// The path of the first of `fields` (under `parent`) whose values fail `ok`, else the first.
fn first_bad(parent: &str, fields: &[(&str, &[f32])], ok: impl Fn(f32) -> bool) -> String {
    let name = fields
        .iter()
        .find(|(_, v)| !v.iter().all(|&x| ok(x)))
        .or(fields.first())
        .map_or("", |(n, _)| n);
    format!("{parent}.{name}")
}

fn finite(v: &[f32]) -> bool {
    v.iter().all(|x| x.is_finite())
}

fn in_range(v: f32, lo: f32, hi: f32) -> bool {
    v.is_finite() && v >= lo && v <= hi
}

/// Range checks; returns the path of the value at fault and the message.
fn validate(s: &Scene) -> Result<(), Invalid> {
    let c = &s.camera;
    check(
        finite(&c.target) && in_range(c.distance, 0.1, 1e4),
        if finite(&c.target) {
            "camera.distance"
        } else {
            "camera.target"
        },
        || format!("camera.distance = {} must be in 0.1..=10000 m", c.distance),
    )?;
    check(in_range(c.fov_deg, 5.0, 150.0), "camera.fov_deg", || {
        format!("camera.fov_deg = {} must be in 5..=150 degrees", c.fov_deg)
    })?;
    check(
        in_range(c.pitch_deg, -89.0, 89.0),
        "camera.pitch_deg",
        || {
            format!(
                "camera.pitch_deg = {} must be in -89..=89 degrees",
                c.pitch_deg
            )
        },
    )?;
    check(c.yaw_deg.is_finite(), "camera.yaw_deg", || {
        "camera.yaw_deg must be finite".into()
    })?;

    let d = s.sun.direction;
    check(
        finite(&d) && d[0] * d[0] + d[1] * d[1] + d[2] * d[2] > 1e-8 && d[1] > 0.0,
        "sun.direction",
        || format!("sun.direction = {d:?} must be a non-zero vector pointing above the horizon"),
    )?;
    check(
        finite(&s.sun.color) && s.sun.color.iter().all(|&x| x >= 0.0),
        "sun.color",
        || "sun.color must be finite and non-negative".into(),
    )?;
    check(in_range(s.sun.intensity, 0.0, 1e3), "sun.intensity", || {
        format!("sun.intensity = {} must be in 0..=1000", s.sun.intensity)
    })?;

    let k = &s.sky;
    check(
        k.cube_size.is_power_of_two() && (16..=1024).contains(&k.cube_size),
        "sky.cube_size",
        || {
            format!(
                "sky.cube_size = {} must be a power of two in 16..=1024",
                k.cube_size
            )
        },
    )?;
    check(
        in_range(k.sun_size_deg, 0.05, 20.0),
        "sky.sun_size_deg",
        || format!("sky.sun_size_deg = {} must be in 0.05..=20", k.sun_size_deg),
    )?;
    check(in_range(k.turbidity, 1.7, 10.0), "sky.turbidity", || {
        format!(
            "sky.turbidity = {} must be in 1.7..=10 (Preetham's model)",
            k.turbidity
        )
    })?;
    check(
        in_range(k.radiance_per_kcd, 0.0, 100.0),
        "sky.radiance_per_kcd",
        || {
            format!(
                "sky.radiance_per_kcd = {} must be in 0..=100",
                k.radiance_per_kcd
            )
        },
    )?;
    check(
        finite(&k.ground_color) && k.ground_color.iter().all(|&x| x >= 0.0),
        "sky.ground_color",
        || "sky.ground_color must be finite and non-negative".into(),
    )?;

    let w = &s.water;
    check(
        (2..=1024).contains(&w.resolution),
        "water.resolution",
        || format!("water.resolution = {} must be in 2..=1024", w.resolution),
    )?;
    check(
        w.absorption.iter().all(|&a| in_range(a, 0.0, 100.0)),
        "water.absorption",
        || {
            format!(
                "water.absorption = {:?} must be in 0..=100 per metre",
                w.absorption
            )
        },
    )?;
    if let Some(sp) = &w.spectrum {
        check(
            (1..=MAX_WAVES as u32).contains(&sp.count),
            "water.spectrum.count",
            || {
                format!(
                    "water.spectrum.count = {} must be in 1..={MAX_WAVES}",
                    sp.count
                )
            },
        )?;
        check(
            in_range(sp.peak_wavelength, 0.1, 1e3),
            "water.spectrum.peak_wavelength",
            || {
                format!(
                    "water.spectrum.peak_wavelength = {} must be in 0.1..=1000 m",
                    sp.peak_wavelength
                )
            },
        )?;
        check(
            in_range(sp.significant_height, 0.0, 20.0),
            "water.spectrum.significant_height",
            || {
                format!(
                    "water.spectrum.significant_height = {} must be in 0..=20 m",
                    sp.significant_height
                )
            },
        )?;
        let dl = sp.wind_direction[0].hypot(sp.wind_direction[1]);
        check(
            dl.is_finite() && dl > 1e-6,
            "water.spectrum.wind_direction",
            || "water.spectrum.wind_direction must be a non-zero 2D vector".into(),
        )?;
        check(
            in_range(sp.spread_deg, 0.0, 180.0),
            "water.spectrum.spread_deg",
            || {
                format!(
                    "water.spectrum.spread_deg = {} must be in 0..=180",
                    sp.spread_deg
                )
            },
        )?;
        check(
            in_range(sp.peak_enhancement, 1.0, 10.0),
            "water.spectrum.peak_enhancement",
            || {
                format!(
                    "water.spectrum.peak_enhancement = {} must be in 1..=10",
                    sp.peak_enhancement
                )
            },
        )?;
        check(
            in_range(sp.steepness, 0.0, 1.0),
            "water.spectrum.steepness",
            || {
                format!(
                    "water.spectrum.steepness = {} must be in 0..=1",
                    sp.steepness
                )
            },
        )?;
    }
    let total_waves = w.waves.len() + w.spectrum.as_ref().map_or(0, |s| s.count as usize);
    check(total_waves <= MAX_WAVES, "water.waves", || {
        format!(
            "water.waves and water.spectrum.count make {total_waves} waves; at most {MAX_WAVES} are supported"
        )
    })?;
    for (i, wave) in w.waves.iter().enumerate() {
        let dl = wave.direction[0].hypot(wave.direction[1]);
        check(
            dl.is_finite() && dl > 1e-6,
            format!("water.waves[{i}].direction"),
            || format!("water.waves[{i}].direction must be a non-zero 2D vector"),
        )?;
        check(
            in_range(wave.wavelength, 0.01, 1e4),
            format!("water.waves[{i}].wavelength"),
            || {
                format!(
                    "water.waves[{i}].wavelength = {} must be in 0.01..=10000 m",
                    wave.wavelength
                )
            },
        )?;
        check(
            in_range(wave.amplitude, 0.0, 100.0),
            format!("water.waves[{i}].amplitude"),
            || {
                format!(
                    "water.waves[{i}].amplitude = {} must be in 0..=100 m",
                    wave.amplitude
                )
            },
        )?;
        check(
            in_range(wave.steepness, 0.0, 1.0),
            format!("water.waves[{i}].steepness"),
            || {
                format!(
                    "water.waves[{i}].steepness = {} must be in 0..=1",
                    wave.steepness
                )
            },
        )?;
        check(
            in_range(wave.speed, -1e3, 1e3),
            format!("water.waves[{i}].speed"),
            || {
                format!(
                    "water.waves[{i}].speed = {} must be finite and below 1000 m/s",
                    wave.speed
                )
            },
        )?;
    }

    check(
        !s.materials.is_empty() && s.materials.len() <= 64,
        "materials",
        || format!("scene needs 1..=64 materials, found {}", s.materials.len()),
    )?;
    for (k, m) in s.materials.iter().enumerate() {
        let name = &m.name;
        let at = |field: &str| format!("materials[{k}].{field}");
        check(
            finite(&m.base_color) && m.base_color.iter().all(|&x| (0.0..=1.0).contains(&x)),
            at("base_color"),
            || format!("material {name:?}: base_color must be in 0..=1"),
        )?;
        check(in_range(m.metallic, 0.0, 1.0), at("metallic"), || {
            format!(
                "material {name:?}: metallic = {} must be in 0..=1",
                m.metallic
            )
        })?;
        check(in_range(m.roughness, 0.0, 1.0), at("roughness"), || {
            format!(
                "material {name:?}: roughness = {} must be in 0..=1",
                m.roughness
            )
        })?;
        check(in_range(m.reflectance, 0.0, 1.0), at("reflectance"), || {
            format!(
                "material {name:?}: reflectance = {} must be in 0..=1",
                m.reflectance
            )
        })?;
        check(
            in_range(m.normal_strength, 0.0, 10.0),
            at("normal_strength"),
            || {
                format!(
                    "material {name:?}: normal_strength = {} must be in 0..=10",
                    m.normal_strength
                )
            },
        )?;
        check(in_range(m.uv_scale, 1e-3, 1e3), at("uv_scale"), || {
            format!(
                "material {name:?}: uv_scale = {} must be in 0.001..=1000",
                m.uv_scale
            )
        })?;
    }

    check(s.objects.len() <= MAX_OBJECTS, "objects", || {
        format!(
            "scene has {} objects; at most {MAX_OBJECTS}",
            s.objects.len()
        )
    })?;
    for (k, o) in s.objects.iter().enumerate() {
        let at = |field: &str| format!("objects[{k}].{field}");
        check(
            s.material_index(o.material()).is_some(),
            at("material"),
            || {
                format!(
                    "material = {:?}: unknown material (no material has that name)",
                    o.material()
                )
            },
        )?;
        match o {
            Object::Seabed {
                size,
                depth,
                resolution,
                relief,
                ..
            } => {
                check(in_range(*size, 1.0, 1e4), at("size"), || {
                    format!("Seabed.size = {size} must be in 1..=10000 m")
                })?;
                check(in_range(*depth, 0.1, 1e3), at("depth"), || {
                    format!("Seabed.depth = {depth} must be in 0.1..=1000 m")
                })?;
                check((2..=1024).contains(resolution), at("resolution"), || {
                    format!("Seabed.resolution = {resolution} must be in 2..=1024")
                })?;
                check(in_range(*relief, 0.0, 100.0), at("relief"), || {
                    format!("Seabed.relief = {relief} must be in 0..=100 m")
                })?;
            }
            Object::Rock {
                position, radius, ..
            } => {
                check(
                    finite(position) && in_range(*radius, 0.01, 100.0),
                    at(if finite(position) {
                        "radius"
                    } else {
                        "position"
                    }),
                    || format!("Rock.radius = {radius} must be in 0.01..=100 m"),
                )?;
            }
            Object::Floating {
                shape,
                position,
                density,
                tilt_deg,
                ..
            } => {
                check(
                    finite(position) && tilt_deg.is_finite(),
                    at(if finite(position) {
                        "tilt_deg"
                    } else {
                        "position"
                    }),
                    || "Floating position and tilt_deg must be finite".into(),
                )?;
                check(
                    in_range(*density, 1.0, WATER_DENSITY - 1.0),
                    at("density"),
                    || {
                        format!(
                            "Floating density = {density} kg/m³ must be in 1..{WATER_DENSITY} \
                         (denser than water, it would sink)"
                        )
                    },
                )?;
                let dims: Vec<f32> = match shape {
                    Shape::Box { size } => size.to_vec(),
                    Shape::Sphere { radius } => vec![*radius],
                    Shape::Capsule { radius, length } => vec![*radius, *length],
                };
                check(
                    dims.iter().all(|&x| in_range(x, 0.01, 100.0)),
                    at("shape"),
                    || format!("Floating shape {shape:?}: sizes must be in 0.01..=100 m"),
                )?;
            }
        }
    }

    match s.quality {
        super::model::Quality::Auto { budget_ms } => {
            check(in_range(budget_ms, 1.0, 1000.0), "budget_ms", || {
                format!("quality.budget_ms = {budget_ms} must be in 1..=1000 ms")
            })?;
        }
        super::model::Quality::Fixed {
            render_scale,
            fish_detail,
        } => {
            check(in_range(render_scale, 0.25, 1.0), "render_scale", || {
                format!("quality.render_scale = {render_scale} must be in 0.25..=1")
            })?;
            check(in_range(fish_detail, 0.0, 4.0), "fish_detail", || {
                format!("quality.fish_detail = {fish_detail} must be in 0..=4")
            })?;
        }
    }

    let f = &s.school;
    check(f.count <= MAX_FISH, "school.count", || {
        format!(
            "school.count = {} is too many fish: at most {MAX_FISH}",
            f.count
        )
    })?;
    check(
        in_range(f.min_speed, 0.0, 100.0)
            && in_range(f.max_speed, 0.0, 100.0)
            && f.min_speed <= f.max_speed,
        if in_range(f.min_speed, 0.0, 100.0) {
            "school.max_speed"
        } else {
            "school.min_speed"
        },
        || {
            format!(
                "school speeds must satisfy 0 <= min_speed ({}) <= max_speed ({}) <= 100",
                f.min_speed, f.max_speed
            )
        },
    )?;
    check(
        in_range(f.fish_scale, 0.001, 10.0),
        "school.fish_scale",
        || {
            format!(
                "school.fish_scale = {} must be in 0.001..=10 m",
                f.fish_scale
            )
        },
    )?;
    check(
        (1..=crate::school::MAX_SCHOOLS).contains(&f.schools),
        "school.schools",
        || {
            format!(
                "school.schools = {} must be in 1..={}",
                f.schools,
                crate::school::MAX_SCHOOLS
            )
        },
    )?;
    check(
        in_range(f.goal_weight, 0.0, 100.0),
        "school.goal_weight",
        || {
            format!(
                "school.goal_weight = {} must be in 0..=100 per s²",
                f.goal_weight
            )
        },
    )?;
    check(
        in_range(f.spawn_radius, 0.0, 1e3),
        "school.spawn_radius",
        || {
            format!(
                "school.spawn_radius = {} must be in 0..=1000 m",
                f.spawn_radius
            )
        },
    )?;
    let radii = [f.separation_radius, f.neighbour_radius, f.flee_radius];
    check(
        radii.iter().all(|&r| in_range(r, 0.0, 1e3)),
        first_bad(
            "school",
            &[
                ("separation_radius", &[f.separation_radius]),
                ("neighbour_radius", &[f.neighbour_radius]),
                ("flee_radius", &[f.flee_radius]),
            ],
            |r| in_range(r, 0.0, 1e3),
        ),
        || "school radii must be in 0..=1000 m".into(),
    )?;
    let weights = [
        f.separation_weight,
        f.alignment_weight,
        f.cohesion_weight,
        f.bounds_weight,
        f.flee_weight,
    ];
    check(
        weights.iter().all(|&w| in_range(w, -1e3, 1e3)),
        first_bad(
            "school",
            &[
                ("separation_weight", &[f.separation_weight]),
                ("alignment_weight", &[f.alignment_weight]),
                ("cohesion_weight", &[f.cohesion_weight]),
                ("bounds_weight", &[f.bounds_weight]),
                ("flee_weight", &[f.flee_weight]),
            ],
            |w| in_range(w, -1e3, 1e3),
        ),
        || "school weights must be finite".into(),
    )?;

    let m = &s.simulation;
    check(in_range(m.dt_secs, 1e-4, 0.1), "simulation.dt_secs", || {
        format!(
            "simulation.dt_secs = {} must be in 0.0001..=0.1 s",
            m.dt_secs
        )
    })?;
    check(
        in_range(m.body_h_secs, 1e-3, 0.5),
        "simulation.body_h_secs",
        || {
            format!(
                "simulation.body_h_secs = {} must be in 0.001..=0.5 s",
                m.body_h_secs
            )
        },
    )?;
    check(
        in_range(m.linear_drag_per_sec, 0.0, 100.0) && in_range(m.angular_drag_per_sec, 0.0, 100.0),
        if in_range(m.linear_drag_per_sec, 0.0, 100.0) {
            "simulation.angular_drag_per_sec"
        } else {
            "simulation.linear_drag_per_sec"
        },
        || "simulation drags must be in 0..=100 per second".into(),
    )?;
    check(
        in_range(m.school_half_width, 0.5, 1e3),
        "simulation.school_half_width",
        || {
            format!(
                "simulation.school_half_width = {} must be in 0.5..=1000 m",
                m.school_half_width
            )
        },
    )?;
    Ok(())
}
