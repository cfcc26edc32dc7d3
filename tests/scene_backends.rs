//! The scene within WebGL2's rules, without a browser: a device made with
//! `wgpu::Limits::downlevel_webgl2_defaults()` and no optional features, with the formats a
//! WebGL2 context without `EXT_color_buffer_float` gets (`RenderCaps::webgl2_like`: 8-bit
//! targets and their encodings), renders the scene with no wgpu validation error, and its
//! picture is close to the float targets' one.

use std::path::Path;

use lectern::render::Headless;
use lectern::render::caps::RenderCaps;
use lectern::render::gpu::{Gpu, GpuRequest};
use lectern::scene;

const SIZE: (u32, u32) = (640, 360);

fn scene_at(t: f64) -> Headless {
    let gpu = Gpu::new(&GpuRequest {
        limits: Some(wgpu::Limits::downlevel_webgl2_defaults()),
        optional_features: false,
        ..Default::default()
    })
    .unwrap();
    assert!(gpu.device.features().is_empty(), "no optional features");
    let s = scene::load_scene(Path::new(scene::DEFAULT_SCENE)).unwrap();
    let mut h = Headless::with_gpu(gpu, RenderCaps::webgl2_like(), s, Path::new("shaders"))
        .expect("every pipeline builds within WebGL2's limits");
    h.sim.set_time(t);
    h
}

fn mean_rgb(img: &image::RgbaImage, rows: std::ops::Range<u32>) -> [f64; 3] {
    let mut sum = [0.0; 3];
    let mut n = 0.0;
    for y in rows {
        for x in 0..img.width() {
            let p = img.get_pixel(x, y);
            for c in 0..3 {
                sum[c] += f64::from(p[c]);
            }
            n += 1.0;
        }
    }
    sum.map(|s| s / n)
}

/// Renders, with any validation error (in an error scope around the frame, or uncaptured)
/// failing the test.
fn render_checked(h: &mut Headless) -> image::RgbaImage {
    let scope = h.gpu.device.push_error_scope(wgpu::ErrorFilter::Validation);
    let img = h.render(SIZE).expect("no uncaptured wgpu error");
    let error = pollster::block_on(scope.pop());
    assert!(error.is_none(), "wgpu validation: {error:?}");
    img
}

#[test]
fn webgl2_limits_and_eight_bit_targets_render_sky_and_water() {
    let mut h = scene_at(2.5);
    assert!(h.renderer.caps().eight_bit_hdr());
    let img = render_checked(&mut h);
    // the default camera: sky in the top rows (blue, not dark), water below (blue-green)
    let sky = mean_rgb(&img, 0..20);
    let water = mean_rgb(&img, SIZE.1 - 60..SIZE.1);
    assert!(sky[2] > 130.0 && sky[2] > sky[0] + 20.0, "sky {sky:?}");
    assert!(
        water[2] > water[0] + 30.0 && water[1] > water[0] + 30.0,
        "water {water:?}"
    );
    // every debug view builds and draws too
    for view in lectern::render::DebugView::ALL {
        h.settings.debug_view = view;
        let v = render_checked(&mut h);
        assert!(
            mean_rgb(&v, 0..SIZE.1).iter().any(|&c| c > 20.0),
            "{view:?} not black"
        );
    }
}

/// The 8-bit path against the float path on the same adapter: mean channel difference at
/// most 3 levels of 255, and at most 3 % of pixels off by more than 16 levels (measured: 2.05
/// and 2.3 %). The sRGB-encoded 8-bit HDR target steps mid tones by a few per cent; the
/// distance in 8 bits (~0.2 m at 10 m) shifts the water's refracted lookups and absorption,
/// mostly in the glints and the fine ripples.
#[test]
fn the_eight_bit_fallback_is_close_to_the_float_targets() {
    let mut eight = scene_at(2.5);
    let got = render_checked(&mut eight);
    let s = scene::load_scene(Path::new(scene::DEFAULT_SCENE)).unwrap();
    let gpu = Gpu::headless().unwrap();
    let mut float =
        Headless::with_gpu(gpu, RenderCaps::float_targets(), s, Path::new("shaders")).unwrap();
    float.sim.set_time(2.5);
    let want = float.render(SIZE).unwrap();
    let mut sum = 0u64;
    let mut far_off = 0usize;
    for (p, q) in got.pixels().zip(want.pixels()) {
        let d: Vec<u8> = (0..3).map(|c| p[c].abs_diff(q[c])).collect();
        sum += d.iter().map(|&x| u64::from(x)).sum::<u64>();
        far_off += usize::from(d.iter().any(|&x| x > 16));
    }
    let n = (SIZE.0 * SIZE.1) as f64;
    let mean = sum as f64 / (3.0 * n);
    let far_fraction = far_off as f64 / n;
    if mean > 3.0 || far_fraction > 0.03 {
        got.save("target/eight-bit.png").unwrap();
        want.save("target/float.png").unwrap();
    }
    eprintln!(
        "8-bit vs float: mean {mean:.2} levels, {:.2} % of pixels > 16",
        100.0 * far_fraction
    );
    assert!(
        mean <= 3.0,
        "mean difference {mean:.2} (target/eight-bit.png, float.png)"
    );
    assert!(
        far_fraction <= 0.03,
        "{:.2} % of pixels off by > 16",
        100.0 * far_fraction
    );
    // and the comparison is not blind: without the shadows the float picture differs more
    float.settings.shadows = false;
    let unshadowed = float.render(SIZE).unwrap();
    let changed = unshadowed
        .pixels()
        .zip(want.pixels())
        .filter(|(p, q)| (0..3).any(|c| p[c].abs_diff(q[c]) > 16))
        .count();
    assert!(
        changed as f64 / n > far_fraction,
        "shadows off changes {changed} pixels"
    );
}

#[test]
fn the_webgl2_like_caps_are_what_a_browser_without_float_targets_reports() {
    let c = RenderCaps::webgl2_like();
    assert_eq!(c.hdr_format, wgpu::TextureFormat::Rgba8UnormSrgb);
    assert_eq!(
        c.max_texture_side_px,
        wgpu::Limits::downlevel_webgl2_defaults().max_texture_dimension_2d
    );
}

/// With no Vulkan driver to be found (the loader pointed at a file that is not there, as on a
/// lecture-room PC or VM with only OpenGL) and no `WGPU_BACKEND`, `lectern render-scene` falls
/// back to GL, says so in its summary line, and draws the scene (sky above, water below).
#[test]
fn without_a_vulkan_driver_render_scene_falls_back_to_gl_and_names_it() {
    let out_dir = tempfile::tempdir().unwrap();
    let run = |hide_vulkan: bool| {
        let mut c = std::process::Command::new(env!("CARGO_BIN_EXE_lectern"));
        c.current_dir(env!("CARGO_MANIFEST_DIR"))
            .args([
                "render-scene",
                "--size",
                "320x180",
                "--time",
                "2.5",
                "--out",
            ])
            .arg(out_dir.path())
            .env_remove("WGPU_BACKEND")
            .env_remove("WGPU_ADAPTER_NAME");
        if hide_vulkan {
            // the old and the new name of the loader's list of drivers
            c.env("VK_ICD_FILENAMES", "/nonexistent/icd.json")
                .env("VK_DRIVER_FILES", "/nonexistent/icd.json");
        }
        let out = c.output().unwrap();
        let said = String::from_utf8_lossy(&out.stderr).into_owned();
        assert!(out.status.success(), "render-scene failed:\n{said}");
        said
    };
    let said = run(true);
    assert!(
        said.contains("(Gl)"),
        "no Vulkan driver: the summary line must name GL:\n{said}"
    );
    let img = image::open(out_dir.path().join("frame-0000.png"))
        .unwrap()
        .into_rgba8();
    assert_eq!(img.dimensions(), (320, 180));
    let sky = mean_rgb(&img, 0..20);
    let water = mean_rgb(&img, 160..180);
    assert!(sky[2] > 60.0, "no sky: mean {sky:?}");
    assert!(
        (0..3).any(|c| (sky[c] - water[c]).abs() > 8.0),
        "sky and water alike ({sky:?} vs {water:?}): no scene drawn"
    );
    // … and the hiding is what made the difference: with the driver list left alone the
    // same machine's default is Vulkan (lavapipe), where one is installed
    let default = run(false);
    if !default.contains("(Gl)") {
        assert!(default.contains("(Vulkan)"), "{default}");
    }
}
