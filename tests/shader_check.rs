//! `lectern check`'s shader step on whatever adapter exists (Mesa's software one in CI): the
//! bundled shaders pass; a shader that is valid WGSL but does not fit the renderer — a moved
//! binding, a renamed entry point, a changed vertex input — is reported at the shader's own
//! line; an include-only shader named alone is checked through the shaders that include it and
//! reported at its own line; with no adapter the step is skipped in one line.

use std::path::Path;
use std::process::Command;

use lectern::diag::Diagnostic;
use lectern::render::{check_shader_file, shaders};

fn copy_shaders() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    for f in shaders::list(Path::new("shaders")) {
        std::fs::copy(&f, dir.path().join(f.file_name().unwrap())).unwrap();
    }
    dir
}

/// Replaces `from` (which must occur once) in `file`; the 1-based line it was on.
fn edit(file: &Path, from: &str, to: &str) -> usize {
    let text = std::fs::read_to_string(file).unwrap();
    assert_eq!(
        text.matches(from).count(),
        1,
        "{from:?} in {}",
        file.display()
    );
    let line = text[..text.find(from).unwrap()].matches('\n').count() + 1;
    std::fs::write(file, text.replace(from, to)).unwrap();
    line
}

fn at(ds: &[Diagnostic], file: &Path, line: usize) -> bool {
    ds.iter()
        .any(|d| d.file == file && d.line == line && d.col > 0)
}

#[test]
fn bundled_shaders_pass_naga_and_pipeline_creation() {
    let files = shaders::list(Path::new("shaders"));
    assert!(files.len() >= 10, "{files:?}");
    for f in &files {
        assert_eq!(check_shader_file(f), vec![], "{}", f.display());
    }
    assert_eq!(lectern::render::pipeline_check_skipped(), None);
}

#[test]
fn a_moved_binding_is_reported_at_its_declaration() {
    let dir = copy_shaders();
    let pbr = dir.path().join("pbr.wgsl");
    let line = edit(
        &pbr,
        "@group(1) @binding(1) var normal_map",
        "@group(1) @binding(7) var normal_map",
    );
    let ds = check_shader_file(&pbr);
    assert!(at(&ds, &pbr, line), "{ds:?}");
    assert!(ds[0].message.contains("@binding(7)"), "{}", ds[0].message);
    assert!(
        ds[0].message.contains("has bindings 0, 1, 2"),
        "{}",
        ds[0].message
    );
}

#[test]
fn a_renamed_entry_point_is_reported_at_the_function() {
    let dir = copy_shaders();
    let tonemap = dir.path().join("tonemap.wgsl");
    let line = edit(&tonemap, "fn fs_main(", "fn fs_final(");
    let ds = check_shader_file(&tonemap);
    assert!(at(&ds, &tonemap, line), "{ds:?}");
    let d = &ds[0];
    assert_eq!(d.col, 4, "at the name: {d}");
    assert!(
        d.message.contains("`fs_main`") && d.message.contains("`fs_final`"),
        "{d}"
    );
}

#[test]
fn a_changed_vertex_input_is_reported_at_its_location() {
    let dir = copy_shaders();
    // locations swapped: the tangent (vec4f) now reads the uv attribute (Float32x2)
    let pbr = dir.path().join("pbr.wgsl");
    let line = edit(
        &pbr,
        "@location(2) tangent: vec4f,\n    @location(3) uv: vec2f,\n}\n\nstruct VertexOut",
        "@location(3) tangent: vec4f,\n    @location(2) uv: vec2f,\n}\n\nstruct VertexOut",
    );
    let ds = check_shader_file(&pbr);
    assert!(at(&ds, &pbr, line), "{ds:?}");
    assert!(ds[0].message.contains("Float32x2"), "{}", ds[0].message);
    // a location no vertex buffer has (the water grid only gives location 0)
    let water = dir.path().join("water.wgsl");
    let line = edit(
        &water,
        "fn vs_main(@location(0) grid_ndc: vec2f)",
        "fn vs_main(@location(5) grid_ndc: vec2f)",
    );
    let ds = check_shader_file(&water);
    assert!(at(&ds, &water, line), "{ds:?}");
    assert!(ds[0].message.contains("@location(5)"), "{}", ds[0].message);
}

#[test]
fn an_include_only_shader_named_alone_is_checked_through_its_users_at_its_own_lines() {
    let dir = copy_shaders();
    let brdf = dir.path().join("brdf.wgsl");
    // a syntax error
    let text = std::fs::read_to_string(&brdf).unwrap();
    let line = edit(
        &brdf,
        "return a2 / (PI * f * f);",
        "return a2 / (PI * f * );",
    );
    let ds = check_shader_file(&brdf);
    assert_eq!(ds.len(), 1, "once, though two shaders include it: {ds:?}");
    assert!(at(&ds, &brdf, line), "{ds:?}");
    std::fs::write(&brdf, &text).unwrap();
    assert_eq!(check_shader_file(&brdf), vec![]);
    // valid WGSL that does not fit: the frame's comparison sampler moved
    let common = dir.path().join("common.wgsl");
    let line = edit(
        &common,
        "@group(0) @binding(4) var shadow_sampler",
        "@group(0) @binding(6) var shadow_sampler",
    );
    let ds = check_shader_file(&common);
    assert!(at(&ds, &common, line), "{ds:?}");
    assert!(ds.iter().all(|d| d.file == common), "{ds:?}");
}

#[test]
fn check_on_the_command_line_reports_the_position_and_exits_non_zero() {
    let dir = copy_shaders();
    let fish = dir.path().join("fish.wgsl");
    let line = edit(
        &fish,
        "@group(1) @binding(0) var<uniform> material",
        "@group(2) @binding(0) var<uniform> material",
    );
    let out = Command::new(env!("CARGO_BIN_EXE_lectern"))
        .arg("check")
        .arg(&fish)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(!out.status.success(), "{stdout}");
    let want = format!("{}:{line}:", fish.display());
    assert!(stdout.contains(&want), "{stdout}");
}

#[test]
fn with_no_adapter_the_pipeline_step_is_skipped_in_one_line() {
    // no such backend on this machine: wgpu finds no adapter at all
    let backend = if cfg!(windows) { "metal" } else { "dx12" };
    let out = Command::new(env!("CARGO_BIN_EXE_lectern"))
        .args(["check", "shaders"])
        .env("WGPU_BACKEND", backend)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let skipped: Vec<&str> = stdout
        .lines()
        .filter(|l| l.contains("pipeline step was skipped"))
        .collect();
    assert_eq!(skipped.len(), 1, "{stdout}");
}
