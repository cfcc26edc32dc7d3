//! The water scene on a slide (`Widget(Scene(..))`): the widget's pixels equal
//! `lectern render-scene`'s (`render::Headless`) with the same camera, toggles, time and size,
//! within the scene goldens' tolerance; the toggles and the view reach the picture; a snapshot of
//! the widget in a kittest harness; a missing scene file is reported, not panicked on.
//!
//! Record the snapshot with `UPDATE_SNAPSHOTS=1 cargo test --test suite scene_slide::` (then look).

use std::path::{Path, PathBuf};

use egui_kittest::{Harness, SnapshotOptions};
use lectern::app::OffscreenRenderer;
use lectern::deck::widgets::scene::{SceneCameraSpec, SceneSpec, SceneToggles, SceneView};
use lectern::render::Headless;
use lectern::widgets::SlideWidget;
use lectern::widgets::scene::{SceneGpu, SceneWidget, render_settings};

use crate::common;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Whether `b` passes for `a` by the scene goldens' comparison, and how many pixels failed.
fn within_tolerance(a: &image::RgbaImage, b: &image::RgbaImage) -> (bool, usize) {
    let n = common::scene_failing_pixels(a, b);
    (n <= common::scene_max_failed_pixels(a), n)
}

fn spec() -> SceneSpec {
    SceneSpec {
        view: SceneView::Final,
        toggles: SceneToggles {
            normal_maps: Some(false),
            ..Default::default()
        },
        camera: SceneCameraSpec {
            yaw_deg: Some(20.0),
            pitch_deg: Some(35.0),
            distance: Some(10.0),
            target: None,
        },
        time_s: 0.5,
        ..Default::default()
    }
}

/// What `lectern render-scene --time T` draws with the spec's settings and camera.
fn headless_frame(spec: &SceneSpec, size: (u32, u32)) -> image::RgbaImage {
    let scene = lectern::scene::load_scene(&root().join("scenes/water.ron")).unwrap();
    let mut h = Headless::new(scene, &root().join("shaders")).unwrap();
    h.settings = render_settings(spec, 1.0);
    h.sim.camera.yaw_deg = spec.camera.yaw_deg.unwrap() as f32;
    h.sim.camera.pitch_deg = spec.camera.pitch_deg.unwrap() as f32;
    h.sim.camera.distance = spec.camera.distance.unwrap() as f32;
    h.sim.set_time(spec.time_s);
    h.render(size).unwrap()
}

/// The widget drawn alone, filling a 640×360 image at one pixel per point, through the same
/// offscreen path as `lectern export`.
fn widget_frame(spec: &SceneSpec, size: (u32, u32)) -> image::RgbaImage {
    widget_frame_on(OffscreenRenderer::software_first().unwrap(), spec, size)
}

fn widget_frame_on(
    mut off: OffscreenRenderer,
    spec: &SceneSpec,
    size: (u32, u32),
) -> image::RgbaImage {
    let mut w = SceneWidget::new_in(spec.clone(), Some(&root().join("slides")));
    let img = off
        .render([size.0, size.1], 1.0, |ui| {
            egui::CentralPanel::default()
                .frame(egui::Frame::NONE)
                .show(ui, |ui| w.ui(ui));
        })
        .unwrap();
    assert!(w.problems().is_empty(), "{:?}", w.problems());
    let t = w.sim().unwrap().time_secs();
    assert!((t - spec.time_s).abs() < 1e-3, "the widget shows t = {t}");
    img
}

#[test]
fn the_slide_shows_the_same_pixels_as_render_scene() {
    let size = (640, 360);
    let s = spec();
    let got = widget_frame(&s, size);
    let want = headless_frame(&s, size);
    let (ok, failing) = within_tolerance(&got, &want);
    if !ok {
        got.save("target/scene-slide-widget.png").unwrap();
        want.save("target/scene-slide-headless.png").unwrap();
    }
    assert!(ok, "{failing} pixels fail (target/scene-slide-*.png)");
    // … and the comparison sees a toggle: the headless frame with normal maps on differs
    let mut on = s.clone();
    on.toggles.normal_maps = Some(true);
    let (same, failing) = within_tolerance(&got, &headless_frame(&on, size));
    assert!(!same, "normal maps on must differ: {failing} pixels fail");
}

/// The widget on the GL backend (egui's GL device has WebGL2's limits) against render-scene on
/// the default adapter (Vulkan's lavapipe in CI), within the goldens' tolerance.
#[test]
fn on_the_gl_backend_the_slide_shows_the_same_pixels_too() {
    let off = match OffscreenRenderer::software_first_on(wgpu::Backends::GL) {
        Ok(off) => off,
        Err(e) => {
            eprintln!("\n!!!!! scene_slide: SKIPPING THE GL CASE: no GL adapter ({e}) !!!!!\n");
            return;
        }
    };
    assert!(
        off.adapter_name().starts_with("Gl"),
        "{}",
        off.adapter_name()
    );
    let size = (640, 360);
    let s = spec();
    let got = widget_frame_on(off, &s, size);
    let want = headless_frame(&s, size);
    let (ok, failing) = within_tolerance(&got, &want);
    if !ok {
        got.save("target/scene-slide-widget-gl.png").unwrap();
    }
    assert!(
        ok,
        "{failing} pixels fail (target/scene-slide-widget-gl.png)"
    );
}

#[test]
fn view_and_toggles_reach_the_render_settings() {
    let mut s = spec();
    s.view = SceneView::ShadowMap;
    s.toggles.shadows = Some(false);
    let r = render_settings(&s, 0.5);
    assert_eq!(r.debug_view, lectern::render::DebugView::ShadowMap);
    assert!(!r.shadows && !r.normal_maps);
    // unset toggles keep the renderer's default: on
    assert!(r.env_map && r.brdf && r.fresnel);
    assert_eq!(r.render_scale, 0.5);
}

#[test]
fn presenter_toggles_are_params_and_write_back_as_the_spec() {
    let mut w = SceneWidget::new_in(spec(), Some(&root().join("slides")));
    let ids: Vec<String> = w.params().iter().map(|p| p.id.clone()).collect();
    for id in [
        "toggles.env_map",
        "toggles.normal_maps",
        "toggles.shadows",
        "toggles.brdf",
        "toggles.fresnel",
        "camera.yaw_deg",
        "camera.pitch_deg",
        "camera.distance",
        "playing",
    ] {
        assert!(ids.iter().any(|i| i == id), "{id} in {ids:?}");
    }
    for mut p in w.params() {
        if p.id == "toggles.shadows" {
            p.set(lectern::widgets::ParamSnapshot::Bool(false)).unwrap();
        }
    }
    let lectern::widgets::WidgetSpec::Scene(now) = w.spec() else {
        panic!("a Scene spec");
    };
    assert_eq!(now.toggles.shadows, Some(false));
    assert!(!render_settings(&now, 1.0).shadows);
    w.reset();
    let lectern::widgets::WidgetSpec::Scene(back) = w.spec() else {
        panic!("a Scene spec");
    };
    assert_eq!(back.toggles.shadows, None, "R gives the deck's values back");
}

#[test]
fn a_missing_scene_is_a_problem_not_a_panic() {
    let s = SceneSpec {
        scene: "../scenes/nope.ron".into(),
        ..Default::default()
    };
    let w = SceneWidget::new_in(s, Some(&root().join("slides")));
    let p = w.problems();
    assert_eq!(p.len(), 1, "{p:?}");
    assert!(p[0].contains("nope.ron"), "{p:?}");
    let s = SceneSpec {
        scene: "../../../etc/passwd".into(),
        ..Default::default()
    };
    let w = SceneWidget::new_in(s, Some(&root().join("slides")));
    assert!(w.problems()[0].contains("outside the project"));
}

/// The widget in a kittest harness (as tests/slides.rs draws the deck): a shadow-map debug view
/// beside nothing else, at 640×360.
#[test]
fn scene_widget_snapshot() {
    let rs = egui_kittest::wgpu::create_render_state(
        egui_kittest::wgpu::default_wgpu_setup(),
        egui_wgpu::RendererOptions::PREDICTABLE,
    );
    let gpu_state = rs.clone();
    let mut w = SceneWidget::new_in(
        SceneSpec {
            view: SceneView::ShadowMap,
            ..spec()
        },
        Some(Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/slides"))),
    );
    let mut h = Harness::builder()
        .with_size(egui::vec2(640.0, 360.0))
        .renderer(egui_kittest::wgpu::WgpuTestRenderer::from_render_state(rs))
        .with_context_setup(move |ctx| SceneGpu::install(ctx, gpu_state, 1.0, false))
        .build_ui(move |ui| {
            egui::CentralPanel::default()
                .frame(egui::Frame::NONE)
                .show(ui, |ui| w.ui(ui));
        });
    h.run_steps(2);
    h.snapshot_options(
        "widget-scene-shadow-map",
        &SnapshotOptions::new().threshold(0.6).max_failed_pixels(8),
    );
}

/// A frame is rendered only when the picture changes, and slides without a Scene widget never
/// make a scene renderer; every Scene widget on every slide shares one.
#[test]
fn renders_only_on_change_and_costs_nothing_on_other_slides() {
    let mut off = OffscreenRenderer::software_first().unwrap();
    let gpu = SceneGpu::get(off.egui_ctx()).expect("offscreen installs the scene device");
    let deck = lectern::deck::load_deck(&root().join("slides/lecture.ron")).unwrap();
    let index = |id: &str| {
        deck.slides
            .iter()
            .position(|s| s.id.as_deref() == Some(id))
            .unwrap()
    };
    let mut state = lectern::app::SlideState::default();
    off.render_slide(&deck, index("euler"), &mut state, [640, 360])
        .unwrap();
    assert_eq!(gpu.renderer_count(), 0, "a slide without a scene");
    for id in ["project-env-map", "project-shadow-map"] {
        let mut state = lectern::app::SlideState::default();
        off.render_slide(&deck, index(id), &mut state, [640, 360])
            .unwrap();
    }
    assert_eq!(gpu.renderer_count(), 1, "four widgets, one renderer");

    let mut w = SceneWidget::new_in(spec(), Some(&root().join("slides")));
    let mut draw = |w: &mut SceneWidget| {
        off.render([320, 180], 1.0, |ui| {
            egui::CentralPanel::default()
                .frame(egui::Frame::NONE)
                .show(ui, |ui| w.ui(ui));
        })
        .unwrap()
    };
    draw(&mut w);
    assert_eq!(w.frames_rendered(), 1, "three egui passes, one scene frame");
    draw(&mut w);
    assert_eq!(w.frames_rendered(), 1, "nothing changed");
    w.spec.toggles.shadows = Some(false);
    draw(&mut w);
    assert_eq!(w.frames_rendered(), 2, "a toggle renders again");
    w.spec.camera.yaw_deg = Some(21.0);
    draw(&mut w);
    assert_eq!(w.frames_rendered(), 3, "so does the camera");
}

/// Ctrl+S writes a presenter's toggle and camera tweaks back into the deck, changing only those
/// values' bytes.
#[test]
fn toggles_and_camera_write_back_to_the_deck() {
    use lectern::app::tweaks::write_back;
    use lectern::widgets::ParamSnapshot;
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir_all(dir.path().join("slides")).unwrap();
    let path = dir.path().join("slides/deck.ron");
    let original = "(\n  title: \"t\",\n  slides: [\n    (id: \"s\", title: \"s\", body: [\n      Widget(Scene((toggles: (shadows: true), camera: (yaw_deg: 20.0, pitch_deg: 35.0)))),\n    ]),\n  ],\n)\n";
    std::fs::write(&path, original).unwrap();
    let deck = lectern::deck::load_deck(&path).unwrap();
    let slide = deck.slides[0].clone();
    let mut state = lectern::app::SlideState::default();
    state.ensure_widgets(&slide);
    state.set_param(&[0], "toggles.shadows", ParamSnapshot::Bool(false));
    state.set_param(&[0], "camera.yaw_deg", ParamSnapshot::F64(45.0));
    assert_eq!(write_back(&path, &slide, &mut state), Ok(2));
    assert_eq!(
        std::fs::read_to_string(&path).unwrap(),
        original
            .replace("shadows: true", "shadows: false")
            .replace("yaw_deg: 20.0", "yaw_deg: 45.0")
    );
}

/// Scene mode shows the same picture too (one renderer type, two targets): its whole window
/// frame equals `render-scene`'s at t = 0 within the golden tolerance — so no frame-time
/// readout is painted over the audience's picture (switched on, as the controls can, the
/// same comparison fails).
/// Scene mode draws into egui's own pass over a plain (non-sRGB) target, as in the window, and
/// encodes sRGB in the tone mapping shader; `render-scene` draws into an sRGB texture that
/// encodes on store — both paths are compared here.
#[test]
fn scene_mode_shows_the_same_pixels_as_render_scene() {
    let size = (640, 360);
    let mut off = OffscreenRenderer::software_first().unwrap();
    let rs = off.render_state().clone();
    assert!(!rs.target_format.is_srgb(), "{:?}", rs.target_format);
    let mut mode =
        lectern::app::SceneMode::new(&rs, &root().join("scenes/water.ron"), || {}).unwrap();
    mode.paused = true;
    mode.controls_button = false;
    let got = off
        .render([size.0, size.1], 1.0, |ui| {
            egui::CentralPanel::default()
                .frame(egui::Frame::NONE)
                .show(ui, |ui| mode.ui(ui, &rs));
        })
        .unwrap();
    let mut spec = SceneSpec::default();
    let scene = lectern::scene::load_scene(&root().join("scenes/water.ron")).unwrap();
    spec.camera = SceneCameraSpec {
        yaw_deg: Some(scene.camera.yaw_deg as f64),
        pitch_deg: Some(scene.camera.pitch_deg as f64),
        distance: Some(scene.camera.distance as f64),
        target: None,
    };
    let want = headless_frame(&spec, size);
    let (ok, failing) = within_tolerance(&got, &want);
    assert!(ok, "{failing} pixels fail");
    mode.show_frame_time = true;
    let with_readout = off
        .render([size.0, size.1], 1.0, |ui| {
            egui::CentralPanel::default()
                .frame(egui::Frame::NONE)
                .show(ui, |ui| mode.ui(ui, &rs));
        })
        .unwrap();
    let (ok, failing) = within_tolerance(&with_readout, &want);
    assert!(
        !ok,
        "the readout, when on, is visible ({failing} pixels fail)"
    );
}

/// In the window the slides' scene reloads like scene mode: a saved shader redraws the picture,
/// one that does not build keeps the last good pipelines and is named at its line on the
/// presenter side, a saved scene file replaces the scene and one that does not parse keeps the
/// last good scene.
#[test]
fn saved_shaders_and_scene_files_reach_the_slides() {
    use std::cell::RefCell;
    use std::rc::Rc;
    use std::time::{Duration, Instant};
    let dir = tempfile::tempdir().unwrap();
    for sub in ["scenes", "shaders"] {
        std::fs::create_dir_all(dir.path().join(sub)).unwrap();
        for entry in std::fs::read_dir(root().join(sub)).unwrap() {
            let from = entry.unwrap().path();
            std::fs::copy(&from, dir.path().join(sub).join(from.file_name().unwrap())).unwrap();
        }
    }
    std::fs::create_dir_all(dir.path().join("slides")).unwrap();
    let rs = egui_kittest::wgpu::create_render_state(
        egui_kittest::wgpu::default_wgpu_setup(),
        egui_wgpu::RendererOptions::PREDICTABLE,
    );
    let gpu_state = rs.clone();
    let w = Rc::new(RefCell::new(SceneWidget::new_in(
        spec(),
        Some(&dir.path().join("slides")),
    )));
    let shown = w.clone();
    let mut h = Harness::builder()
        .with_size(egui::vec2(320.0, 180.0))
        .renderer(egui_kittest::wgpu::WgpuTestRenderer::from_render_state(rs))
        // animate = the window: the files are watched
        .with_context_setup(move |ctx| SceneGpu::install(ctx, gpu_state, 1.0, true))
        .build_ui(move |ui| {
            egui::CentralPanel::default()
                .frame(egui::Frame::NONE)
                .show(ui, |ui| shown.borrow_mut().ui(ui));
        });
    h.run_steps(2);
    assert_eq!(w.borrow().frames_rendered(), 1);
    let mut wait_for = |what: &str, done: &dyn Fn(&SceneWidget) -> bool| {
        let start = Instant::now();
        while !done(&w.borrow()) {
            assert!(start.elapsed() < Duration::from_secs(10), "{what}");
            std::thread::sleep(Duration::from_millis(50));
            h.run_steps(1);
        }
    };
    let water = dir.path().join("shaders/water.wgsl");
    let good = std::fs::read_to_string(&water).unwrap();
    std::fs::write(&water, format!("{good}\n// saved in class\n")).unwrap();
    wait_for("a saved shader redraws", &|w| w.frames_rendered() == 2);
    assert!(
        w.borrow().problems().is_empty(),
        "{:?}",
        w.borrow().problems()
    );

    std::fs::write(&water, format!("{good}\nfn broken( {{\n")).unwrap();
    wait_for("a broken shader is named", &|w| {
        w.problems().iter().any(|p| p.contains("water.wgsl:"))
    });

    let scene_file = dir.path().join("scenes/water.ron");
    let text = std::fs::read_to_string(&scene_file).unwrap();
    let moved = text.replace("sun_size_deg: 1.2", "sun_size_deg: 2.5");
    assert_ne!(moved, text);
    std::fs::write(&water, &good).unwrap();
    std::fs::write(&scene_file, &moved).unwrap();
    wait_for("a saved scene replaces the scene", &|w| {
        w.sim().is_some_and(|s| s.scene.sky.sun_size_deg == 2.5)
    });
    let frames = w.borrow().frames_rendered();
    std::fs::write(&scene_file, "(sky: ").unwrap();
    wait_for("a broken scene is named at its line and column", &|w| {
        w.problems().iter().any(|p| p.contains("water.ron:1:"))
    });
    let w = w.borrow();
    assert!(w.frames_rendered() > frames);
    assert_eq!(
        w.sim().unwrap().scene.sky.sun_size_deg,
        2.5,
        "the last good scene stays"
    );
}

/// The Scene widgets of deck slide `id`, in reading order.
fn slide_scenes(id: &str) -> Vec<SceneSpec> {
    use lectern::deck::Block;
    use lectern::deck::widgets::WidgetSpec;
    fn walk(b: &Block, out: &mut Vec<SceneSpec>) {
        match b {
            Block::Widget(WidgetSpec::Scene(s)) => out.push(s.clone()),
            Block::Columns(cols) => cols.iter().flatten().for_each(|b| walk(b, out)),
            _ => {}
        }
    }
    let deck = lectern::deck::load_deck(&root().join("slides/lecture.ron")).unwrap();
    let slide = deck.slides.iter().find(|s| s.id.as_deref() == Some(id));
    let mut out = Vec::new();
    slide
        .unwrap_or_else(|| panic!("no slide {id}"))
        .body
        .iter()
        .for_each(|b| walk(b, &mut out));
    out
}

/// What render-scene draws for a slide's Scene widget, its camera target included.
fn headless_slide_frame(spec: &SceneSpec, size: (u32, u32)) -> image::RgbaImage {
    let scene = lectern::scene::load_scene(&root().join("scenes/water.ron")).unwrap();
    let mut h = Headless::new(scene, &root().join("shaders")).unwrap();
    h.settings = render_settings(spec, 1.0);
    let c = &mut h.sim.camera;
    if let Some(t) = spec.camera.target {
        c.target = glam::DVec3::from(t).as_vec3();
    }
    c.yaw_deg = spec.camera.yaw_deg.unwrap_or(c.yaw_deg as f64) as f32;
    c.pitch_deg = spec.camera.pitch_deg.unwrap_or(c.pitch_deg as f64) as f32;
    c.distance = spec.camera.distance.unwrap_or(c.distance as f64) as f32;
    h.sim.set_time(spec.time_s);
    h.render(size).unwrap()
}

fn mean_abs_luma_diff(a: &image::RgbaImage, b: &image::RgbaImage) -> f64 {
    let luma =
        |p: &image::Rgba<u8>| 0.2126 * p[0] as f64 + 0.7152 * p[1] as f64 + 0.0722 * p[2] as f64;
    let sum: f64 = a
        .pixels()
        .zip(b.pixels())
        .map(|(p, q)| (luma(p) - luma(q)).abs())
        .sum();
    sum / (a.width() * a.height()) as f64
}

/// The normal-map slide's pair differs at a glance: over the whole picture the mean luma
/// differs by more than 4/255 between maps on and off (measured 5.4 with the camera close to a
/// rock lit from the side; the earlier framing, 3 m from the rock with the sun behind the
/// camera, differed by 2.5 and failed this).
#[test]
fn the_normal_map_pair_differs_at_a_glance() {
    let scenes = slide_scenes("project-normal-map");
    let [on, off] = scenes.as_slice() else {
        panic!("the slide shows an on/off pair: {} scenes", scenes.len())
    };
    assert_eq!(
        (on.toggles.normal_maps, off.toggles.normal_maps),
        (Some(true), Some(false))
    );
    let size = (480, 360);
    let d = mean_abs_luma_diff(
        &headless_slide_frame(on, size),
        &headless_slide_frame(off, size),
    );
    eprintln!("normal maps on vs off: mean |luma difference| {d:.2}/255");
    assert!(d > 4.0, "the pair differs by only {d:.2}/255 of luma");
}
