//! The player's app around [`LecternApp`]: the `#/N` URL fragment (1-based) opens slide N and
//! follows paging, so a course page can link to a slide; and `window.lectern`, the hook the
//! browser tests read: `ready` (true once the first slide is drawn), `slide()` (1-based),
//! `slides()` (the count) and `plotData()` (the current slide's first plot widget's points as
//! JSON, the numbers `export --data` writes: [`crate::app::plot_data`]), and `editorField`
//! (where to click to type an equation, once `N` shows the editor) and `editing` (a field has
//! the keyboard). For timing inside the page (no WebDriver round trips), `frames` logs the last
//! painted frames, each `{start, ui, t, slide, plot}`: `performance.now()` when the frame's `ui`
//! began (`start`: an input dispatched before it is in this frame), once it returned (`ui`) and
//! once the frame was painted (`t`, a microtask after eframe's paint), the 1-based slide, and
//! — while a test sets `trackPlot` — a hash of `plotData()`'s text, so a test sees which frame
//! first showed new points.

use std::cell::RefCell;
use std::rc::Rc;

use wasm_bindgen::JsCast as _;
use wasm_bindgen::JsValue;
use wasm_bindgen::closure::Closure;

use crate::app::LecternApp;

/// `#/13` → 13.
pub fn fragment_slide(window: &web_sys::Window) -> Option<usize> {
    parse_fragment(&window.location().hash().ok()?)
}

fn parse_fragment(hash: &str) -> Option<usize> {
    hash.strip_prefix("#/")?
        .trim()
        .parse()
        .ok()
        .filter(|&n| n > 0)
}

pub struct Hook {
    window: web_sys::Window,
    object: js_sys::Object,
    /// `(hook)`: notes when the frame's `ui` began.
    begin_frame: js_sys::Function,
    /// `(hook, slide, plot)`: appends to `hook.frames` (see the module's doc).
    log_frame: js_sys::Function,
}

/// The frames `frames` keeps.
const FRAMES_KEPT: usize = 600;

impl Hook {
    /// Puts `window.lectern` on the page; its functions read `app` between frames.
    pub fn install(window: &web_sys::Window, app: Rc<RefCell<LecternApp>>) -> Result<Self, String> {
        let object = js_sys::Object::new();
        let set = |name: &str, value: &JsValue| {
            js_sys::Reflect::set(&object, &name.into(), value)
                .map(|_| ())
                .map_err(|e| super::page::js_error_text(&e))
        };
        set("ready", &JsValue::FALSE)?;
        set("frames", &js_sys::Array::new())?;
        set("trackPlot", &JsValue::FALSE)?;
        // the painted time: a microtask runs once eframe's frame callback (ui, then paint) returns
        let begin_frame =
            js_sys::Function::new_with_args("hook", "hook.frameStart = performance.now();");
        let log_frame = js_sys::Function::new_with_args(
            "hook, slide, plot",
            &format!(
                "var e = {{ start: hook.frameStart, ui: performance.now(), t: null, slide: slide, plot: plot }};\n\
                 hook.frames.push(e);\n\
                 if (hook.frames.length > {FRAMES_KEPT}) hook.frames.shift();\n\
                 queueMicrotask(function () {{ e.t = performance.now(); }});"
            ),
        );
        let a = app.clone();
        let slide = Closure::<dyn Fn() -> JsValue>::new(move || match a.try_borrow() {
            Ok(app) => JsValue::from(app.nav().index() as u32 + 1),
            Err(_) => JsValue::NULL,
        });
        let a = app.clone();
        let slides = Closure::<dyn Fn() -> JsValue>::new(move || match a.try_borrow() {
            Ok(app) => JsValue::from(app.session().deck().slides.len() as u32),
            Err(_) => JsValue::NULL,
        });
        let a = app;
        let plot = Closure::<dyn Fn() -> JsValue>::new(move || match a.try_borrow_mut() {
            Ok(mut app) => JsValue::from(app.first_plot_json()),
            Err(_) => JsValue::NULL,
        });
        set("slide", slide.as_ref())?;
        set("slides", slides.as_ref())?;
        set("plotData", plot.as_ref())?;
        // the page keeps them as long as it lives
        slide.forget();
        slides.forget();
        plot.forget();
        js_sys::Reflect::set(window, &"lectern".into(), &object)
            .map_err(|e| super::page::js_error_text(&e))?;
        Ok(Self {
            window: window.clone(),
            object,
            begin_frame,
            log_frame,
        })
    }

    /// A fragment typed into the address bar (or a link followed) wakes the player.
    pub fn watch_fragment(&self, ctx: &egui::Context) {
        let ctx = ctx.clone();
        let wake = Closure::<dyn Fn()>::new(move || ctx.request_repaint());
        let _ = self
            .window
            .add_event_listener_with_callback("hashchange", wake.as_ref().unchecked_ref());
        wake.forget();
    }

    /// Called when the frame's `ui` begins (its time goes into the frame's log entry).
    fn begin_frame(&self) {
        let _ = self.begin_frame.call1(&JsValue::NULL, &self.object);
    }

    /// Appends this frame to `frames` (called once the app's `ui` returned, before the paint).
    fn log_frame(&self, slide: usize, plot: Option<&str>) {
        let plot = match plot {
            Some(text) => {
                use std::hash::{Hash as _, Hasher as _};
                let mut h = std::collections::hash_map::DefaultHasher::new();
                text.hash(&mut h);
                // 32 bits: exact as a JavaScript number
                JsValue::from(h.finish() as u32)
            }
            None => JsValue::NULL,
        };
        let _ = self.log_frame.call3(
            &JsValue::NULL,
            &self.object,
            &JsValue::from(slide as u32),
            &plot,
        );
    }

    /// A test asked for each frame's plot hash.
    fn tracking_plot(&self) -> bool {
        js_sys::Reflect::get(&self.object, &"trackPlot".into()).is_ok_and(|v| v.is_truthy())
    }

    /// `window.lectern` itself (the scene's half adds its functions: [`super::scene_hook`]).
    pub fn object(&self) -> &js_sys::Object {
        &self.object
    }

    fn set_ready(&self) {
        let _ = js_sys::Reflect::set(&self.object, &"ready".into(), &JsValue::TRUE);
    }

    /// `editing`: a text field has the keyboard (keys are text, not paging or `+`).
    fn set_editing(&self, editing: bool) {
        let _ = js_sys::Reflect::set(&self.object, &"editing".into(), &JsValue::from(editing));
    }

    /// `editorField`: the centre of the first equation field on screen, in CSS pixels from
    /// the canvas's corner (`N` shows the editor), or `null`.
    fn set_editor_field(&self, rect: Option<egui::Rect>) {
        let value = match rect {
            Some(r) => {
                let o = js_sys::Object::new();
                let _ = js_sys::Reflect::set(&o, &"x".into(), &r.center().x.into());
                let _ = js_sys::Reflect::set(&o, &"y".into(), &r.center().y.into());
                o.into()
            }
            None => JsValue::NULL,
        };
        let _ = js_sys::Reflect::set(&self.object, &"editorField".into(), &value);
    }
}

pub struct Player {
    app: Rc<RefCell<LecternApp>>,
    hook: Hook,
    /// The fragment as last read or written.
    fragment: String,
    /// The slide the fragment names (0-based).
    shown: Option<usize>,
    frames: u64,
}

impl Player {
    pub fn new(app: Rc<RefCell<LecternApp>>, hook: Hook) -> Self {
        Self {
            app,
            hook,
            fragment: String::new(),
            shown: None,
            frames: 0,
        }
    }

    /// The fragment changed (a link, the address bar, Back): go where it says.
    fn follow_fragment(&mut self, app: &mut LecternApp) {
        let hash = self.hook.window.location().hash().unwrap_or_default();
        if hash == self.fragment {
            return;
        }
        if let Some(n) = parse_fragment(&hash) {
            let _ = app
                .session_mut()
                .navigate(|nav, deck| nav.goto_number(deck, n));
        }
        self.fragment = hash;
    }

    /// Paging moved: the fragment follows (a history entry per slide, so Back goes back).
    fn write_fragment(&mut self, index: usize) {
        if self.shown == Some(index) {
            return;
        }
        self.shown = Some(index);
        let hash = format!("#/{}", index + 1);
        if hash != self.fragment {
            let _ = self.hook.window.location().set_hash(&hash);
            self.fragment = hash;
        }
    }
}

impl eframe::App for Player {
    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        let app = self.app.clone();
        let Ok(mut app) = app.try_borrow_mut() else {
            return;
        };
        self.hook.begin_frame();
        self.follow_fragment(&mut app);
        app.ui(ui, frame);
        let index = app.nav().index();
        let plot = self.hook.tracking_plot().then(|| app.first_plot_json());
        self.hook.log_frame(index + 1, plot.as_deref());
        self.write_fragment(index);
        self.hook
            .set_editor_field(crate::app::first_field_rect(ui.ctx()));
        self.hook.set_editing(ui.ctx().text_edit_focused());
        // "ready" once a whole frame has reached the screen (the first one also installs the
        // fonts, which lays the slide out again in the next)
        self.frames += 1;
        if self.frames == 2 {
            self.hook.set_ready();
        } else if self.frames < 2 {
            ui.ctx().request_repaint();
        }
    }

    fn clear_color(&self, visuals: &egui::Visuals) -> [f32; 4] {
        match self.app.try_borrow() {
            Ok(app) => eframe::App::clear_color(&*app, visuals),
            Err(_) => [0.0, 0.0, 0.0, 1.0],
        }
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn fragments() {
        assert_eq!(super::parse_fragment("#/13"), Some(13));
        assert_eq!(super::parse_fragment("#/0"), None);
        assert_eq!(super::parse_fragment("#13"), None);
        assert_eq!(super::parse_fragment(""), None);
    }
}
