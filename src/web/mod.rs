//! The web player (`wasm32` only): the desktop app's [`LecternApp`] — the same slide renderer,
//! widgets, keys and overlays — run by eframe's `WebRunner` on the page's canvas, with the deck,
//! its files, formulas and fonts from the page's bundle ([`crate::web_bundle`], written by
//! `lectern export --web`). What differs from the desktop is cfg-gated where it lives (the
//! pre-typeset formula pool, the fonts, the scene widget's note); this module only starts it,
//! keeps the `#/N` fragment and the slide in step, and answers the test hook
//! ([`hook`]: `window.lectern`).

mod hook;
mod page;

use std::cell::RefCell;
use std::rc::Rc;

use wasm_bindgen::JsCast as _;

use crate::app::LecternApp;
use crate::deck::DeckSession;
use crate::web_bundle::WebBundle;

/// The id of the canvas `index.html` gives the player.
pub const CANVAS_ID: &str = "lectern-canvas";

/// Starts the player (the wasm binary's `main`); a failure shows as text on the page.
pub fn start() {
    page::show_panics();
    wasm_bindgen_futures::spawn_local(async {
        if let Err(e) = run().await {
            page::show_error(&e);
        }
    });
}

async fn run() -> Result<(), String> {
    let window = web_sys::window().ok_or("no browser window")?;
    let bundle = WebBundle::from_bytes(&page::bundle_bytes(&window)?)?;
    install(&bundle)?;
    let mut session = DeckSession::open(bundle.deck_path()).map_err(|d| d.to_string())?;
    if let Some(n) = hook::fragment_slide(&window) {
        // a link to a slide the deck lacks opens the first one
        let _ = session.navigate(|nav, deck| nav.goto_number(deck, n));
    }
    let canvas = window
        .document()
        .and_then(|d| d.get_element_by_id(CANVAS_ID))
        .and_then(|e| e.dyn_into::<web_sys::HtmlCanvasElement>().ok())
        .ok_or_else(|| format!("the page has no <canvas id=\"{CANVAS_ID}\">"))?;
    let mut app = LecternApp::new(session);
    app.set_player();
    let app = Rc::new(RefCell::new(app));
    let hook = hook::Hook::install(&window, app.clone())?;
    let mut options = eframe::WebOptions::default();
    // WebGL2 everywhere (the slides need nothing more, and headless browsers' WebGPU is not
    // dependable yet); the water scene, which would need more, does not run here anyway.
    if let egui_wgpu::WgpuSetup::CreateNew(setup) = &mut options.wgpu_options.wgpu_setup {
        setup.instance_descriptor.backends = wgpu::Backends::GL;
    }
    let runner = eframe::WebRunner::new();
    runner
        .start(
            canvas,
            options,
            Box::new(move |cc| {
                crate::math::never_wait(&cc.egui_ctx);
                hook.watch_fragment(&cc.egui_ctx);
                Ok(Box::new(hook::Player::new(app, hook)))
            }),
        )
        .await
        .map_err(|e| format!("the player could not start: {}", page::js_error_text(&e)))?;
    page::started();
    // the runner lives as long as the page
    std::mem::forget(runner);
    Ok(())
}

/// Makes the bundle the source of project files, formulas and fonts.
fn install(bundle: &WebBundle) -> Result<(), String> {
    let formulas = bundle
        .formulas
        .iter()
        .map(|f| {
            Ok(crate::math::pool::Prerendered {
                src: f.src.clone(),
                syntax: f.syntax(),
                style: f.style(),
                rgba: f.rgba,
                em_px: f.em_px,
                result: bundle.rendered(f)?,
            })
        })
        .collect::<Result<Vec<_>, String>>()?;
    crate::math::pool::install(formulas);
    // egui keeps font bytes for the life of the page; a face named twice is kept once
    let mut kept: Vec<(usize, &'static [u8])> = Vec::new();
    let mut fonts = Vec::new();
    for f in &bundle.fonts {
        let bytes = match kept.iter().find(|(blob, _)| *blob == f.blob) {
            Some((_, bytes)) => *bytes,
            None => {
                let bytes: &'static [u8] =
                    Box::leak(bundle.bytes_of(f)?.to_vec().into_boxed_slice());
                kept.push((f.blob, bytes));
                bytes
            }
        };
        fonts.push((f.path.clone(), bytes));
    }
    crate::math::set_bundled_fonts(fonts);
    crate::project_files::install(bundle.project_files()?).map_err(String::from)
}
