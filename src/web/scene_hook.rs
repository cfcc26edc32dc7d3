//! The scene half of the test hook (`window.lectern`, [`super::hook`]): `scene()` is
//! [`LecternApp::scene_json`] (where the slide's first Scene widget is, scene mode's frame
//! count, rung, render size and backend line), and `sceneToggle(id, on)` sets a technique as
//! the controls' tick box does ([`LecternApp::set_scene_toggle`]) and wakes the page;
//! `sceneFish(n)` sets scene mode's school size as its panel's slider does.

use std::cell::RefCell;
use std::rc::Rc;

use wasm_bindgen::JsValue;
use wasm_bindgen::closure::Closure;

use crate::app::LecternApp;

/// Adds `scene` and `sceneToggle` to the hook's `object`; they read `app` between frames.
pub fn install(object: &js_sys::Object, app: Rc<RefCell<LecternApp>>, ctx: &egui::Context) {
    let (a, c) = (app.clone(), ctx.clone());
    let scene = Closure::<dyn Fn() -> JsValue>::new(move || match a.try_borrow_mut() {
        Ok(mut app) => JsValue::from(app.scene_json(&c)),
        Err(_) => JsValue::NULL,
    });
    let (a, c) = (app.clone(), ctx.clone());
    let fish = Closure::<dyn Fn(u32) -> JsValue>::new(move |n: u32| match a.try_borrow_mut() {
        Ok(mut app) => {
            c.request_repaint();
            JsValue::from(app.set_scene_fish(n as usize))
        }
        Err(_) => JsValue::NULL,
    });
    let _ = js_sys::Reflect::set(object, &"sceneFish".into(), fish.as_ref());
    fish.forget();
    let c = ctx.clone();
    let toggle = Closure::<dyn Fn(String, bool) -> JsValue>::new(move |id: String, on: bool| {
        match app.try_borrow_mut() {
            Ok(mut app) => {
                let done = app.set_scene_toggle(&c, &id, on);
                c.request_repaint();
                JsValue::from(done)
            }
            Err(_) => JsValue::NULL,
        }
    });
    let _ = js_sys::Reflect::set(object, &"scene".into(), scene.as_ref());
    let _ = js_sys::Reflect::set(object, &"sceneToggle".into(), toggle.as_ref());
    // the page keeps them as long as it lives
    scene.forget();
    toggle.forget();
}
