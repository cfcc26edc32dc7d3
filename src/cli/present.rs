//! `lectern present`: present a deck in a window.

use std::path::PathBuf;
use std::sync::{Arc, Mutex};

use anyhow::Context as _;

use crate::app::LecternApp;
use crate::app::keys;
use crate::app::screens::{MonitorRect, ScreenChoice, ScreenPlan, plan_screens};
use crate::deck::DeckSession;
use winit::application::ApplicationHandler;
use winit::event::{DeviceEvent, DeviceId, StartCause, WindowEvent};
use winit::event_loop::ActiveEventLoop;
use winit::window::WindowId;

/// Present a deck in a window (the default command).
#[derive(Debug, Default, clap::Args)]
pub struct Args {
    /// The deck to present [default: slides/lecture.ron]
    pub deck: Option<PathBuf>,
    /// Start on this slide (1-based).
    #[arg(long, value_name = "N")]
    pub slide: Option<usize>,
    /// Start fullscreen.
    #[arg(long)]
    pub fullscreen: bool,
    /// Open the presenter window (notes, timer, next slide, controls) even on one monitor.
    /// With a second monitor this is automatic: the slides go full-screen on it and the
    /// presenter window stays on the primary (laptop) screen.
    #[arg(long, conflicts_with = "single_screen")]
    pub presenter: bool,
    /// One window only, whatever monitors are connected (P toggles the presenter overlay).
    #[arg(long)]
    pub single_screen: bool,
    /// Rehearsal: record the actual time per slide in DECK.timings.ron beside the deck.
    #[arg(long)]
    pub rehearse: bool,
    /// Append `mode,frame_ms` to FILE for every drawn frame (`slides` or `scene`; wall
    /// milliseconds since the previous drawn frame), to measure the live app.
    #[arg(long, value_name = "FILE")]
    pub frame_stats: Option<PathBuf>,
}

/// The bundled lecture: `slides/lecture.ron` under the current folder, else in the source tree
/// this binary was built from (so `cargo run` works from anywhere inside the project).
pub fn default_deck() -> PathBuf {
    let local = PathBuf::from("slides/lecture.ron");
    if local.exists() {
        return local;
    }
    let built = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/slides/lecture.ron"));
    if built.exists() { built } else { local }
}

pub fn run(args: Args) -> anyhow::Result<()> {
    let path = args.deck.unwrap_or_else(default_deck);
    let mut session = DeckSession::open(&path).map_err(|d| anyhow::anyhow!("{d}"))?;
    if let Some(n) = args.slide {
        session
            .navigate(|nav, deck| nav.goto_number(deck, n))
            .map_err(|m| anyhow::anyhow!(m))?;
    }
    let title = format!("lectern — {}", session.deck().title);
    let rehearsal = args.rehearse.then(|| path.with_extension("timings.ron"));
    let frame_stats = args.frame_stats;
    let choice = if args.single_screen {
        ScreenChoice::Single
    } else if args.presenter {
        ScreenChoice::Presenter
    } else {
        ScreenChoice::Auto
    };
    let viewport = egui::ViewportBuilder::default()
        .with_title(&title)
        .with_app_id("lectern")
        .with_inner_size([1280.0, 720.0])
        .with_min_inner_size([320.0, 180.0])
        .with_fullscreen(args.fullscreen);
    // Vulkan (Metal, DX12) where the machine has it, else GL (`WGPU_BACKEND` still narrows it)
    let mut setup = egui_wgpu::WgpuSetupCreateNew::without_display_handle();
    setup.native_adapter_selector = Some(std::sync::Arc::new(|adapters, surface| {
        adapters
            .iter()
            .filter(|a| a.get_info().backend != wgpu::Backend::Noop)
            .filter(|a| surface.is_none_or(|s| a.is_surface_supported(s)))
            .min_by_key(|a| crate::app::offscreen::adapter_rank(&a.get_info(), false))
            .cloned()
            .ok_or_else(|| "no adapter can draw into the window".to_owned())
    }));
    let options = eframe::NativeOptions {
        viewport,
        renderer: eframe::Renderer::Wgpu,
        wgpu_options: egui_wgpu::WgpuConfiguration {
            wgpu_setup: egui_wgpu::WgpuSetup::CreateNew(setup),
            ..Default::default()
        },
        ..Default::default()
    };
    let open_error = "cannot open the window (no display? set DISPLAY or WAYLAND_DISPLAY, \
         or use `lectern export` headless)";
    // Our own event loop, so the monitors can be read (winit lists them only on a running
    // loop) before eframe creates the app.
    let event_loop = winit::event_loop::EventLoop::<eframe::UserEvent>::with_user_event()
        .build()
        .context(open_error)?;
    let monitors: Arc<Mutex<Vec<MonitorRect>>> = Arc::default();
    let seen = monitors.clone();
    let app = eframe::create_native(
        &title,
        options,
        Box::new(move |cc| {
            let monitors = seen.lock().map(|m| m.clone()).unwrap_or_default();
            let plan = plan_screens(&monitors, choice);
            eprintln!("lectern: {}", describe(&monitors, &plan));
            let mut app = LecternApp::new(session);
            app.render_state = cc.wgpu_render_state.clone();
            app.watch(&cc.egui_ctx);
            // The live window never waits for a formula (export and tests do).
            crate::math::never_wait(&cc.egui_ctx);
            app.set_screens(monitors, plan);
            app.rehearsal_file = rehearsal;
            if let Some(file) = &frame_stats {
                app.set_frame_stats(file)
                    .map_err(|e| format!("cannot write {}: {e}", file.display()))?;
            }
            Ok(Box::new(app))
        }),
        &event_loop,
    );
    let mut probe = MonitorProbe {
        inner: app,
        monitors,
        probed: false,
    };
    event_loop.run_app(&mut probe).context(open_error)
}

/// One line for the terminal: what monitors were seen and where the windows go.
fn describe(monitors: &[MonitorRect], plan: &ScreenPlan) -> String {
    let list: Vec<String> = monitors
        .iter()
        .map(|m| {
            format!(
                "{} {}x{}+{}+{}{}",
                m.name,
                m.size_px[0],
                m.size_px[1],
                m.pos_px[0],
                m.pos_px[1],
                if m.primary { " (primary)" } else { "" }
            )
        })
        .collect();
    let name = |i: Option<usize>| {
        i.and_then(|i| monitors.get(i))
            .map_or("where the system puts it".to_owned(), |m| m.name.clone())
    };
    let plan = match plan {
        ScreenPlan::Single => "one window (P: presenter overlay)".to_owned(),
        ScreenPlan::Dual {
            audience,
            presenter,
        } => format!(
            "audience window on {}, presenter window on {}",
            name(*audience),
            name(*presenter)
        ),
    };
    format!("monitors: [{}]; {plan}", list.join(", "))
}

/// The egui key for the keys whose release the window may drop (the slide keys).
fn egui_key(key: &winit::keyboard::Key) -> Option<egui::Key> {
    use winit::keyboard::{Key, NamedKey};
    let Key::Named(named) = key else {
        return None;
    };
    Some(match named {
        NamedKey::ArrowLeft => egui::Key::ArrowLeft,
        NamedKey::ArrowRight => egui::Key::ArrowRight,
        NamedKey::ArrowUp => egui::Key::ArrowUp,
        NamedKey::ArrowDown => egui::Key::ArrowDown,
        NamedKey::PageUp => egui::Key::PageUp,
        NamedKey::PageDown => egui::Key::PageDown,
        NamedKey::Home => egui::Key::Home,
        NamedKey::End => egui::Key::End,
        NamedKey::Space => egui::Key::Space,
        NamedKey::Tab => egui::Key::Tab,
        _ => return None,
    })
}

/// Forwards everything to eframe; on the first `resumed` it first records the monitors.
/// Releases of the slide keys are dropped on the way (see [`egui_key`]).
struct MonitorProbe<'a> {
    inner: eframe::EframeWinitApplication<'a>,
    monitors: Arc<Mutex<Vec<MonitorRect>>>,
    probed: bool,
}

impl ApplicationHandler<eframe::UserEvent> for MonitorProbe<'_> {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if !self.probed {
            self.probed = true;
            let primary = event_loop.primary_monitor();
            let list: Vec<MonitorRect> = event_loop
                .available_monitors()
                .map(|m| {
                    let pos = m.position();
                    let size = m.size();
                    MonitorRect {
                        pos_px: [pos.x, pos.y],
                        size_px: [size.width, size.height],
                        scale: m.scale_factor(),
                        primary: primary.as_ref() == Some(&m),
                        name: m.name().unwrap_or_else(|| "monitor".to_owned()),
                    }
                })
                .collect();
            if let Ok(mut m) = self.monitors.lock() {
                *m = list;
            }
        }
        self.inner.resumed(event_loop);
    }

    fn window_event(&mut self, el: &ActiveEventLoop, id: WindowId, event: WindowEvent) {
        if let WindowEvent::KeyboardInput { event: key, .. } = &event
            && key.state == winit::event::ElementState::Released
            && egui_key(&key.logical_key).is_some_and(keys::release_is_ignored)
        {
            // Each event egui sees costs two more frames; a slide key's release changes
            // nothing (see `keys::release_is_ignored`).
            return;
        }
        self.inner.window_event(el, id, event);
    }

    fn new_events(&mut self, el: &ActiveEventLoop, cause: StartCause) {
        self.inner.new_events(el, cause);
    }

    fn user_event(&mut self, el: &ActiveEventLoop, event: eframe::UserEvent) {
        self.inner.user_event(el, event);
    }

    fn device_event(&mut self, el: &ActiveEventLoop, id: DeviceId, event: DeviceEvent) {
        self.inner.device_event(el, id, event);
    }

    fn about_to_wait(&mut self, el: &ActiveEventLoop) {
        self.inner.about_to_wait(el);
    }

    fn suspended(&mut self, el: &ActiveEventLoop) {
        self.inner.suspended(el);
    }

    fn exiting(&mut self, el: &ActiveEventLoop) {
        self.inner.exiting(el);
    }

    fn memory_warning(&mut self, el: &ActiveEventLoop) {
        self.inner.memory_warning(el);
    }
}
