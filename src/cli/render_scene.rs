//! `lectern render-scene`: Render the water scene to PNG frames, headless.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::{Context, Result};

use crate::render::frame::RenderSettings;
use crate::render::{DebugView, Headless, SHADER_DIR};
use crate::scene::{self, DEFAULT_SCENE};

/// Render the water scene to PNG frames, headless.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Scene file (default: scenes/water.ron)
    pub scene: Option<PathBuf>,
    /// Output folder for frame-0000.png, frame-0001.png, …
    #[arg(long, default_value = "out/scene")]
    pub out: PathBuf,
    /// Number of frames
    #[arg(long, default_value_t = 1)]
    pub frames: u32,
    /// Image size, WxH
    #[arg(long, default_value = "1280x720", value_parser = parse_size)]
    pub size: (u32, u32),
    /// Simulation time of the first frame, seconds
    #[arg(long, default_value_t = 0.0)]
    pub time: f64,
    /// Frames per second of simulated time between frames
    #[arg(long, default_value_t = 30.0)]
    pub fps: f64,
    /// Debug view: none, shadow-map, normals, env-cube, caustics-map
    #[arg(long, default_value = "none", value_parser = parse_view)]
    pub view: DebugView,
    /// Folder of the WGSL shaders
    #[arg(long, default_value = SHADER_DIR)]
    pub shaders: PathBuf,
    /// Draw the scene at this fraction of --size and scale it up (dynamic resolution), 0.25–1
    /// [default: 1, or the scene file's fixed quality]
    #[arg(long)]
    pub render_scale: Option<f32>,
    /// Fish level of detail, 0–4 (1 = default distances, 0 = coarsest mesh everywhere)
    /// [default: 1, or the scene file's fixed quality]
    #[arg(long)]
    pub fish_detail: Option<f32>,
    /// Draw and simulate as step K of the automatic quality's ladder does (1 = full quality,
    /// 9 = the coarsest; the presenter panel shows the step in use): render scale, fish detail,
    /// shadow filter, grids, water normals and school stepping; with --render-scale, the
    /// rung at that scale instead of its own
    #[arg(long, value_name = "K", conflicts_with_all = ["fish_detail"])]
    pub rung: Option<usize>,
    /// Techniques to leave out, comma-separated (to see or time what each adds): env-map,
    /// normal-maps, shadows, fish-shadows, brdf, fresnel, caustics, fxaa
    #[arg(long, value_delimiter = ',', value_parser = parse_technique)]
    pub off: Vec<Technique>,
}

/// A technique `--off` can leave out.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Technique {
    EnvMap,
    NormalMaps,
    Shadows,
    FishShadows,
    Brdf,
    Fresnel,
    Caustics,
    Fxaa,
}

pub fn parse_technique(s: &str) -> Result<Technique, String> {
    Ok(match s.trim() {
        "env-map" => Technique::EnvMap,
        "normal-maps" => Technique::NormalMaps,
        "shadows" => Technique::Shadows,
        "fish-shadows" => Technique::FishShadows,
        "brdf" => Technique::Brdf,
        "fresnel" => Technique::Fresnel,
        "caustics" => Technique::Caustics,
        "fxaa" => Technique::Fxaa,
        _ => {
            return Err(format!(
                "unknown technique {s:?}: env-map, normal-maps, shadows, fish-shadows, brdf, \
                 fresnel, caustics, fxaa"
            ));
        }
    })
}

/// Switches `t` off in `settings`.
fn switch_off(settings: &mut RenderSettings, t: Technique) {
    match t {
        Technique::EnvMap => settings.env_map = false,
        Technique::NormalMaps => settings.normal_maps = false,
        Technique::Shadows => settings.shadows = false,
        Technique::FishShadows => settings.fish_shadows = false,
        Technique::Brdf => settings.brdf = false,
        Technique::Fresnel => settings.fresnel = false,
        Technique::Caustics => settings.caustics = false,
        Technique::Fxaa => settings.fxaa = false,
    }
}

pub fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("size {s:?} must be WxH, e.g. 1280x720"))?;
    let w: u32 = w
        .trim()
        .parse()
        .map_err(|_| format!("bad width in {s:?}"))?;
    let h: u32 = h
        .trim()
        .parse()
        .map_err(|_| format!("bad height in {s:?}"))?;
    if !(1..=8192).contains(&w) || !(1..=8192).contains(&h) {
        return Err(format!("size {w}x{h}: each side must be 1..=8192"));
    }
    Ok((w, h))
}

pub fn parse_view(s: &str) -> Result<DebugView, String> {
    match s {
        "none" | "final" => Ok(DebugView::None),
        "shadow-map" | "shadow" => Ok(DebugView::ShadowMap),
        "normals" => Ok(DebugView::Normals),
        "env-cube" | "env" => Ok(DebugView::EnvCube),
        "caustics-map" | "caustics" => Ok(DebugView::CausticsMap),
        _ => Err(format!(
            "unknown view {s:?}: none, shadow-map, normals, env-cube, caustics-map"
        )),
    }
}

pub fn run(args: Args) -> Result<()> {
    anyhow::ensure!(
        args.frames <= 100_000,
        "--frames {} is too many (at most 100000)",
        args.frames
    );
    anyhow::ensure!(
        args.fps.is_finite() && args.fps > 0.0,
        "--fps must be positive"
    );
    anyhow::ensure!(
        args.time.is_finite() && args.time >= 0.0,
        "--time must be a non-negative number of seconds"
    );
    let path = args.scene.unwrap_or_else(|| PathBuf::from(DEFAULT_SCENE));
    let scene = scene::load_scene(&path)?;
    let t0 = Instant::now();
    let mut h = Headless::new(scene, &args.shaders)?;
    h.settings.debug_view = args.view;
    for &t in &args.off {
        switch_off(&mut h.settings, t);
    }
    if let Some(k) = args.rung {
        let ladder = &scene::quality::LADDER;
        let rung = k
            .checked_sub(1)
            .and_then(|i| ladder.get(i))
            .with_context(|| format!("--rung {k}: the ladder has steps 1 to {}", ladder.len()))?;
        h.settings.apply_rung(rung);
        h.sim.set_school_every(rung.school_every);
    }
    // after the rung: a rung at another scale (to time what its scale alone costs)
    if let Some(s) = args.render_scale {
        anyhow::ensure!(
            (0.25..=1.0).contains(&s),
            "--render-scale must be in 0.25..=1"
        );
        h.settings.render_scale = s;
    }
    if let Some(d) = args.fish_detail {
        anyhow::ensure!((0.0..=4.0).contains(&d), "--fish-detail must be in 0..=4");
        h.settings.fish_detail = d;
    }
    let setup = t0.elapsed();
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("creating {}", args.out.display()))?;
    let t1 = Instant::now();
    let mut render_ms = Vec::with_capacity(args.frames as usize);
    // per fixed simulation step, from the frames that stepped
    let mut step_ms = Vec::with_capacity(args.frames as usize);
    for i in 0..args.frames {
        let (steps_before, t) = (h.sim.steps(), Instant::now());
        h.sim.set_time(args.time + i as f64 / args.fps);
        let stepped = h.sim.steps().saturating_sub(steps_before);
        if i > 0 && stepped > 0 {
            step_ms.push(t.elapsed().as_secs_f64() * 1e3 / stepped as f64);
        }
        let t = Instant::now();
        let img = h.render(args.size)?;
        render_ms.push(t.elapsed().as_secs_f64() * 1e3);
        let file = args.out.join(format!("frame-{i:04}.png"));
        img.save(&file)
            .with_context(|| format!("writing {}", file.display()))?;
    }
    let info = &h.gpu.adapter_info;
    eprintln!(
        "rendered {} frame(s) {}x{} on {} ({:?}) in {:.2} s (+{:.2} s setup) to {}",
        args.frames,
        args.size.0,
        args.size.1,
        info.name,
        info.backend,
        t1.elapsed().as_secs_f64(),
        setup.as_secs_f64(),
        args.out.display()
    );
    render_ms.sort_by(f64::total_cmp);
    step_ms.sort_by(f64::total_cmp);
    if let Some(ms) = step_ms.get(step_ms.len() / 2) {
        eprintln!(
            "simulation: median {ms:.2} ms per fixed step of {:.4} s ({} fish)",
            h.sim.dt_secs(),
            h.sim.fish_count()
        );
    }
    let fi = h.renderer.frame_info();
    if render_ms.is_empty() {
        return Ok(());
    }
    eprintln!(
        "render (GPU work and read-back, no simulation or PNG): median {:.1} ms, min {:.1} ms; \
         drawn at {}x{}, fish full/medium/coarse/far {}/{}/{}/{}",
        render_ms[render_ms.len() / 2],
        render_ms[0],
        fi.render_size.0,
        fi.render_size.1,
        fi.fish_per_lod[0],
        fi.fish_per_lod[1],
        fi.fish_per_lod[2],
        fi.fish_per_lod[3]
    );
    Ok(())
}
