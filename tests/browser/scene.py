#!/usr/bin/env python3
"""The water scene in the exported page (issue #25), in Debian's headless Chromium (software
WebGL2 through SwiftShader), run by tests/web_player.rs beside player.py: on a slide with live
Scene widgets it saves the canvas (the Rust test crops the widget and compares it with
render-scene's frame), switches a toggle off and saves again, drags across the widget (orbit)
and saves again, presses Tab for scene mode,
measures its frame rate in the page, and checks the console. Prints one JSON object of
figures on the last line; exit status 0 when every check here passed.

Usage: scene.py --url URL --slide N --shots DIR [--size WxH] [--fps-seconds S]
       scene.py --no-webgl2 --url URL --shots DIR   (a browser without WebGL2: expect the note
                                                     and the exported still, no canvas)
"""
import argparse
import json
import sys

from selenium.webdriver.common.action_chains import ActionChains
from selenium.webdriver.common.by import By
from selenium.webdriver.common.keys import Keys

from player import browser, canvas_png, key, severe, wait_for

SCENE = "return JSON.parse(window.lectern.scene())"


def scene(d):
    return d.execute_script(SCENE)


def settle(d, frames=3):
    """Waits for `frames` animation frames, so what the page last drew is on the canvas."""
    d.execute_async_script(
        "var done = arguments[arguments.length - 1], n = %d;"
        "function f() { if (--n <= 0) done(true); else requestAnimationFrame(f); }"
        "requestAnimationFrame(f);" % frames)


def check(args, figures):
    size = tuple(int(v) for v in args.size.split("x"))
    d = browser(size)
    d.set_script_timeout(args.fps_seconds + 60)
    try:
        d.get(args.url + "#/%d" % args.slide)
        wait_for(d, "return window.lectern && window.lectern.ready === true")
        assert d.execute_script("return window.lectern.slide()") == args.slide, "not on the slide"
        wait_for(d, "var s = JSON.parse(window.lectern.scene()); return s.widget !== null", 60)
        s = scene(d)
        assert s["gpu"], "no scene device in the page: %r" % s
        assert not s["widget"]["problems"], "the Scene widget reports %r" % s["widget"]["problems"]
        figures["widget"] = s["widget"]
        settle(d)
        with open(args.shots + "/scene-widget.png", "wb") as f:
            f.write(canvas_png(d))
        # a toggle, as the controls' tick box sets it
        assert d.execute_script("return window.lectern.sceneToggle('shadows', false)") is True, \
            "no shadows toggle on the slide's Scene widget"
        settle(d, 6)
        with open(args.shots + "/scene-widget-no-shadows.png", "wb") as f:
            f.write(canvas_png(d))
        # a drag across the widget orbits its camera, as in scene mode
        w = figures["widget"]
        canvas = d.find_element(By.ID, "lectern-canvas")
        ActionChains(d).move_to_element_with_offset(
            canvas, w["x"] + w["w"] / 2 - size[0] / 2, w["y"] + w["h"] / 2 - size[1] / 2
        ).click_and_hold().move_by_offset(120, 0).move_by_offset(60, 0).release().perform()
        settle(d, 6)
        # (the widget takes the drag: it is no swipe to the next slide)
        assert d.execute_script("return window.lectern.slide()") == args.slide, \
            "the drag paged instead of orbiting"
        with open(args.shots + "/scene-widget-orbited.png", "wb") as f:
            f.write(canvas_png(d))
        # Tab: scene mode, its frame rate measured in the page over a few seconds
        key(d, Keys.TAB)
        wait_for(d, "var s = JSON.parse(window.lectern.scene()); return s.mode === 'scene'"
                    " && s.sceneMode !== null && (s.sceneMode.frames || 0) > 2", 120)
        s = scene(d)
        assert not s["sceneMode"]["errors"], "scene mode reports %r" % s["sceneMode"]["errors"]
        # let the quality ladder settle, then count frames
        d.execute_async_script(
            "var done = arguments[arguments.length - 1]; setTimeout(function () { done(0); }, %d);"
            % int(1000 * args.settle_seconds))
        rate = d.execute_async_script(
            "var done = arguments[arguments.length - 1], ms = %d;"
            "var f0 = JSON.parse(window.lectern.scene()).sceneMode.frames, t0 = performance.now();"
            "setTimeout(function () {"
            "  var s = JSON.parse(window.lectern.scene()).sceneMode;"
            "  done({frames: s.frames - f0, ms: performance.now() - t0, rung: s.rung,"
            "        renderSize: s.renderSize});"
            "}, ms);" % int(1000 * args.fps_seconds))
        figures["scene_mode_fps"] = round(1e3 * rate["frames"] / rate["ms"], 2)
        figures["scene_mode_rung"] = rate["rung"] + 1
        figures["scene_mode_render_size"] = rate["renderSize"]
        s = scene(d)
        figures["backend"] = s["sceneMode"]["backend"]
        figures["float_targets_in_webgl2"] = d.execute_script(
            "var gl = document.createElement('canvas').getContext('webgl2');"
            "return !!(gl && gl.getExtension('EXT_color_buffer_float'))")
        with open(args.shots + "/scene-mode.png", "wb") as f:
            f.write(canvas_png(d))
        key(d, Keys.TAB)
        wait_for(d, "return JSON.parse(window.lectern.scene()).mode === 'slides'", 30)
        errors = severe(d)
        assert not errors, "console errors: %r" % errors
    finally:
        d.quit()


# Before any of the page's scripts: a browser without WebGL2, as the page sees one.
NO_WEBGL2 = """
delete window.WebGL2RenderingContext;
var getContext = HTMLCanvasElement.prototype.getContext;
HTMLCanvasElement.prototype.getContext = function (kind) {
  return kind === "webgl2" ? null : getContext.apply(this, arguments);
};
"""


def check_no_webgl2(args, figures):
    """The note says why, the still is shown (its rect and size in the figures, a screenshot in
    no-webgl2.png for the Rust test to compare with the JPEG), and the canvas is hidden."""
    size = tuple(int(v) for v in args.size.split("x"))
    d = browser(size)
    try:
        d.execute_cdp_cmd("Page.addScriptToEvaluateOnNewDocument", {"source": NO_WEBGL2})
        d.get(args.url)
        wait_for(d, "var e = document.getElementById('lectern-error');"
                    " return e && e.offsetParent !== null && e.textContent.length > 0", 30)
        text = d.find_element(By.ID, "lectern-error").text
        assert "WebGL2" in text, "the note does not say why: %r" % text
        figures["no_webgl2_text"] = text
        wait_for(d, "var i = document.getElementById('lectern-still');"
                    " return i && i.complete && i.naturalWidth > 0", 30)
        figures["still"] = d.execute_script(
            "var i = document.getElementById('lectern-still'), r = i.getBoundingClientRect();"
            "return {x: r.left, y: r.top, w: r.width, h: r.height,"
            "        naturalWidth: i.naturalWidth, naturalHeight: i.naturalHeight};")
        assert d.execute_script(
            "return document.getElementById('lectern-canvas').offsetParent === null"), \
            "the canvas is still shown"
        assert d.execute_script("return !window.lectern || !window.lectern.ready"), \
            "the player started without WebGL2"
        with open(args.shots + "/no-webgl2.png", "wb") as f:
            f.write(canvas_png(d))
        errors = severe(d)
        assert not errors, "console errors: %r" % errors
    finally:
        d.quit()


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--url", required=True)
    p.add_argument("--slide", type=int)
    p.add_argument("--shots", required=True)
    p.add_argument("--size", default="1280x720")
    p.add_argument("--settle-seconds", type=float, default=6.0)
    p.add_argument("--fps-seconds", type=float, default=5.0)
    p.add_argument("--no-webgl2", action="store_true")
    args = p.parse_args()
    figures = {}
    ok = True
    try:
        (check_no_webgl2 if args.no_webgl2 else check)(args, figures)
    except AssertionError as e:
        print("FAILED " + str(e), file=sys.stderr)
        ok = False
    print(json.dumps(figures))
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
