//! The page around the canvas: the bundle's bytes, and errors shown as text (a player that
//! cannot start must say why, never leave a blank canvas).

use wasm_bindgen::JsCast as _;

/// The element `index.html` keeps for a readable error.
const ERROR_ID: &str = "lectern-error";

/// The bundle's bytes, which `index.html` put in `window.LECTERN_BUNDLE` (a `Uint8Array`), opened
/// from `bundle.js`'s gzip as Z85 text.
pub fn bundle_bytes(window: &web_sys::Window) -> Result<Vec<u8>, String> {
    js_sys::Reflect::get(window, &"LECTERN_BUNDLE".into())
        .ok()
        .and_then(|v| v.dyn_into::<js_sys::Uint8Array>().ok())
        .map(|a| a.to_vec())
        .ok_or_else(|| {
            "the slides' bundle (bundle.js) is missing or damaged: export the page again \
             with `lectern export DECK --web DIR`"
                .to_owned()
        })
}

/// Shows `message` in the page's error box and hides the canvas.
pub fn show_error(message: &str) {
    let Some(doc) = web_sys::window().and_then(|w| w.document()) else {
        return;
    };
    if let Some(el) = doc.get_element_by_id(ERROR_ID) {
        el.set_text_content(Some(&format!(
            "lectern could not show the slides: {message}"
        )));
        let _ = el.set_attribute("style", "display: block");
    }
    if let Some(canvas) = doc
        .get_element_by_id(super::CANVAS_ID)
        .and_then(|e| e.dyn_into::<web_sys::HtmlElement>().ok())
    {
        let _ = canvas.style().set_property("display", "none");
    }
}

/// The "loading" line goes once the player runs.
pub fn started() {
    if let Some(el) = web_sys::window()
        .and_then(|w| w.document())
        .and_then(|d| d.get_element_by_id("lectern-loading"))
    {
        el.remove();
    }
}

/// A panic (a bug) shows on the page too, after eframe's own handler has logged it.
pub fn show_panics() {
    let before = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        show_error(&format!("the player stopped: {info}"));
        before(info);
    }));
}

/// A JavaScript error's text.
pub fn js_error_text(e: &wasm_bindgen::JsValue) -> String {
    e.as_string()
        .or_else(|| {
            e.dyn_ref::<js_sys::Error>()
                .map(|e| String::from(e.message()))
        })
        .unwrap_or_else(|| format!("{e:?}"))
}
