#!/usr/bin/env python3
"""Drives the exported web page in Debian's headless Chromium (selenium + chromium-driver,
software WebGL2 through SwiftShader) and checks what tests/web_player.rs asks, printing one
JSON object of measurements on the last line. Exit status 0 when every check passed.

Usage: player.py --url URL [--url URL] --shots DIR --euler N --slope N --spiral N
                 --work-precision N --skipped N,N,... --expect CSV
       player.py --broken DIR   (a page whose bundle is damaged: expect the readable error)
"""
import argparse
import base64
import json
import math
import sys
import tempfile
import time

from selenium import webdriver
from selenium.webdriver.common.action_chains import ActionChains
from selenium.webdriver.common.by import By
from selenium.webdriver.common.keys import Keys

FLAGS = [
    "--headless=new", "--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
    "--disable-background-networking", "--disable-component-update", "--disable-sync",
    "--no-first-run", "--hide-scrollbars", "--force-device-scale-factor=1",
]


def browser(size):
    opts = webdriver.ChromeOptions()
    opts.binary_location = "/usr/bin/chromium"
    for f in FLAGS:
        opts.add_argument(f)
    opts.add_argument("--user-data-dir=" + tempfile.mkdtemp(prefix="lectern-chromium-"))
    opts.add_argument("--window-size=%d,%d" % size)
    opts.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    service = webdriver.ChromeService(executable_path="/usr/bin/chromedriver")
    d = webdriver.Chrome(options=opts, service=service)
    # the window's inner size is what the canvas gets: make it exactly `size`
    inner = d.execute_script("return [window.innerWidth, window.innerHeight]")
    outer = d.get_window_size()
    d.set_window_size(outer["width"] + size[0] - inner[0], outer["height"] + size[1] - inner[1])
    return d


def wait_for(d, script, timeout_s=60.0):
    start = time.monotonic()
    while time.monotonic() - start < timeout_s:
        v = d.execute_script(script)
        if v:
            return time.monotonic() - start
        time.sleep(0.02)
    raise AssertionError("timed out waiting for: " + script)


def canvas_png(d):
    """The canvas's pixels as the page shows them (PNG bytes, screenshot of the viewport)."""
    return base64.b64decode(d.get_screenshot_as_base64())


def severe(d):
    return [e for e in d.get_log("browser") if e.get("level") == "SEVERE"]


def plot(d):
    return json.loads(d.execute_script("return window.lectern.plotData()"))


def key(d, k):
    ActionChains(d).send_keys(k).perform()


# A key pressed inside the page, timed by the page's own clock (no WebDriver round trip): the
# hook's frame log (`window.lectern.frames`, src/web/hook.rs) says when the first frame that
# shows the change was painted. `want` is a slide number, or "plot": a frame whose plot hash
# differs from the last frame's (the test sets `trackPlot` first).
IN_PAGE_KEY = """
var key = arguments[0], want = arguments[1], done = arguments[arguments.length - 1];
var CODES = {"ArrowRight": "ArrowRight", "ArrowLeft": "ArrowLeft", "+": "Equal", "-": "Minus"};
var h = window.lectern, canvas = document.getElementById("lectern-canvas");
canvas.focus();
var frames = h.frames, last = frames[frames.length - 1], before = last ? last.plot : null;
var o = {key: key, code: CODES[key] || key, bubbles: true, cancelable: true};
var t0 = performance.now();
canvas.dispatchEvent(new KeyboardEvent("keydown", o));
canvas.dispatchEvent(new KeyboardEvent("keyup", o));
(function poll() {
  for (var i = frames.indexOf(last) + 1; i < frames.length; i++) {
    var e = frames[i];
    if (e.t === null) break;
    var shown = want === "plot" ? e.plot !== null && e.plot !== before : e.slide === want;
    if (shown) { done({ms: e.t - t0, ui_ms: e.ui - t0}); return; }
  }
  if (performance.now() - t0 > 10000) { done(null); return; }
  setTimeout(poll, 2);
})();
"""


# A drag inside the page, timed the same way: `phase` "down" presses the mouse at (x, y) (CSS
# pixels) and waits for the next painted frame, "move" moves it there with the button held and
# waits for a frame whose plot hash differs from the last frame's (the test sets `trackPlot`
# first), "up" lets go.
IN_PAGE_DRAG = """
var x = arguments[0], y = arguments[1], phase = arguments[2], done = arguments[arguments.length - 1];
var h = window.lectern, canvas = document.getElementById("lectern-canvas");
var frames = h.frames, last = frames[frames.length - 1], before = last ? last.plot : null;
var o = {clientX: x, clientY: y, screenX: x, screenY: y, button: 0, buttons: 1, pointerId: 1,
         pointerType: "mouse", isPrimary: true, bubbles: true, cancelable: true};
var t0 = performance.now();
if (phase === "up") {
  o.buttons = 0;
  canvas.dispatchEvent(new PointerEvent("pointerup", o));
  done(null);
  return;
}
// (eframe takes presses as pointer events and moves as mouse events)
canvas.dispatchEvent(phase === "down" ? new PointerEvent("pointerdown", o) : new MouseEvent("mousemove", o));
(function poll() {
  for (var i = frames.indexOf(last) + 1; i < frames.length; i++) {
    var e = frames[i];
    if (e.t === null) break;
    var shown = phase === "down" ? true : e.plot !== null && e.plot !== before;
    if (shown) { done({ms: e.t - t0, ui_ms: e.ui - t0}); return; }
  }
  if (performance.now() - t0 > 10000) { done(null); return; }
  setTimeout(poll, 2);
})();
"""


def key_in_page(d, k, want):
    r = d.execute_async_script(IN_PAGE_KEY, k, want)
    assert r is not None, "key %r: no frame showed %r within 10 s" % (k, want)
    return r


def median(xs):
    xs = sorted(xs)
    n = len(xs)
    return xs[n // 2] if n % 2 else 0.5 * (xs[n // 2 - 1] + xs[n // 2])


def time_keys(d, args, figures, tag, repeats=12):
    """Medians of key -> next slide and key -> new plot frame, measured in the page."""
    d.set_script_timeout(30)
    d.execute_script("location.hash = '#/1'")
    wait_for(d, "return window.lectern.slide() === 1", 10)
    paging = []
    for i in range(repeats):
        # right to slide 2, left back to 1
        k, want = ("ArrowRight", 2) if i % 2 == 0 else ("ArrowLeft", 1)
        paging.append(key_in_page(d, k, want))
    d.execute_script("location.hash = '#/%d'" % args.euler)
    wait_for(d, "return window.lectern.slide() === %d" % args.euler, 10)
    d.execute_script("window.lectern.trackPlot = true")
    # one frame with a plot hash to compare against
    key_in_page(d, "+", "plot")
    plotting = []
    for i in range(repeats):
        plotting.append(key_in_page(d, "-" if i % 2 == 0 else "+", "plot"))
    d.execute_script("window.lectern.trackPlot = false")
    for name, runs in [("key_to_next_slide_ms", paging), ("h_key_to_new_plot_frame_ms", plotting)]:
        figures[tag + "_" + name] = latency_figures(runs)


def latency_figures(runs):
    painted = [r["ms"] for r in runs]
    return {"median": round(median(painted), 1), "min": round(min(painted), 1),
            "max": round(max(painted), 1), "n": len(painted),
            # the same frames when the app's ui returned, before eframe's paint
            "ui_median": round(median([r["ui_ms"] for r in runs]), 1)}


def time_drag(d, args, figures, tag, repeats=12):
    """A drag across the slope field moves its start point: each move must bring a frame with
    new points; the median from the move to that frame painted, measured in the page. (Run on
    a freshly loaded page: the notes panel, open after the typing check, would cover the plot.)"""
    d.execute_script("location.hash = '#/%d'" % args.slope)
    wait_for(d, "return window.lectern.slide() === %d" % args.slope, 10)
    d.execute_script("window.lectern.trackPlot = true")
    w, h = (int(v) for v in args.size.split("x"))
    x, y = 0.5 * w, 0.6 * h  # inside the slope field's plot
    assert d.execute_async_script(IN_PAGE_DRAG, x, y, "down") is not None, "no frame after a press"
    runs = [d.execute_async_script(IN_PAGE_DRAG, x + (12 if i % 2 == 0 else 0), y, "move")
            for i in range(repeats)]
    d.execute_async_script(IN_PAGE_DRAG, x, y, "up")
    d.execute_script("window.lectern.trackPlot = false")
    # (the first move may only start the drag: egui decides a press is one once it has moved)
    dragging = [r for r in runs if r is not None]
    assert len(dragging) >= repeats - 2, \
        "a drag across the slope field changed plotData() on %d of %d moves" % (len(dragging), repeats)
    figures[tag + "_drag_to_new_plot_frame_ms"] = latency_figures(dragging)


# A continuous drag, as a mouse sends it: `n` moves `every` ms apart (each a new position, so
# each frame that takes one solves from a new start point), the button held. For each move, the
# first frame whose `ui` began after it (so its input had the move) and painted a plot unlike
# the frames before the move: the move's latency is that frame's painted time minus the move's.
IN_PAGE_CONTINUOUS_DRAG = """
var x = arguments[0], y = arguments[1], n = arguments[2], every = arguments[3];
var done = arguments[arguments.length - 1];
var h = window.lectern, canvas = document.getElementById("lectern-canvas");
var frames = h.frames, first = frames.length, moves = [];
function o(px) {
  return {clientX: px, clientY: y, screenX: px, screenY: y, button: 0, buttons: 1, pointerId: 1,
          pointerType: "mouse", isPrimary: true, bubbles: true, cancelable: true};
}
function move(i) {
  moves.push(performance.now());
  canvas.dispatchEvent(new MouseEvent("mousemove", o(x + 2 * (i + 1))));
  if (i + 1 < n) { setTimeout(function () { move(i + 1); }, every); return; }
  waitForLast();
}
// until a frame that began after the last move has been painted (or 10 s)
function waitForLast() {
  var last = moves[moves.length - 1], painted = frames.slice(first).some(function (e) {
    return e.start > last && e.t !== null;
  });
  if (painted || performance.now() - last > 10000) { finish(); return; }
  setTimeout(waitForLast, 5);
}
function finish() {
  var log = frames.slice(first), out = [];
  moves.forEach(function (t) {
    var before = null, shown = null;
    for (var k = 0; k < log.length; k++) {
      var e = log[k];
      if (e.start === undefined || e.t === null) continue;
      if (e.start <= t) { before = e.plot; continue; }
      if (e.plot !== null && e.plot !== before) { shown = e.t - t; break; }
    }
    if (shown !== null) out.push(shown);
  });
  done({latencies: out, moves: moves.length, frames: log.length,
        seconds: (moves[moves.length - 1] - moves[0]) / 1000});
}
move(0);
"""


def time_continuous_drag(d, args, figures, tag, moves=40, every_ms=16):
    """A drag across the slope field at a mouse's pace: the median latency of its moves (see
    IN_PAGE_CONTINUOUS_DRAG); every move must reach a frame with new points."""
    d.execute_script("location.hash = '#/%d'" % args.slope)
    wait_for(d, "return window.lectern.slide() === %d" % args.slope, 10)
    d.execute_script("window.lectern.trackPlot = true")
    w, h = (int(v) for v in args.size.split("x"))
    x, y = 0.5 * w, 0.6 * h
    assert d.execute_async_script(IN_PAGE_DRAG, x, y, "down") is not None, "no frame after a press"
    # egui starts a drag once the pointer has moved: the first move only does that
    d.execute_async_script(IN_PAGE_DRAG, x + 1, y, "move")
    r = d.execute_async_script(IN_PAGE_CONTINUOUS_DRAG, x + 1, y, moves, every_ms)
    d.execute_async_script(IN_PAGE_DRAG, x, y, "up")
    d.execute_script("window.lectern.trackPlot = false")
    lat = r["latencies"]
    assert len(lat) == moves, "%d of %d moves reached a frame with new points" % (len(lat), moves)
    figures[tag + "_continuous_drag_to_new_plot_frame_ms"] = {
        "median": round(median(lat), 1), "min": round(min(lat), 1), "max": round(max(lat), 1),
        "n": len(lat), "frames": r["frames"], "moves_per_s": round(moves / max(r["seconds"], 1e-3), 1)}


def walk_all_slides(d, args, figures, tag):
    """The "Done when" walk: every slide paging skips by the keyboard, the skipped ones (the
    optional project slides) by their `#/N` link; each painted, no console errors."""
    d.execute_script("location.hash = '#/1'")
    wait_for(d, "return window.lectern.slide() === 1", 10)
    n = d.execute_script("return window.lectern.slides()")
    skipped = [int(k) for k in args.skipped.split(",") if k] if args.skipped else []
    paged = [k for k in range(1, n + 1) if k not in skipped]
    slowest = (0.0, 1)
    for k in paged[1:]:
        ms = key_in_page(d, "ArrowRight", k)["ms"]
        slowest = max(slowest, (ms, k))
        errors = severe(d)
        assert not errors, "console errors on slide %d: %r" % (k, errors)
        assert d.execute_script("return location.hash") == "#/%d" % k, "fragment off at %d" % k
    for k in skipped:
        d.execute_script("location.hash = '#/%d'" % k)
        wait_for(d, "var f = window.lectern.frames, e = f[f.length - 1];"
                    " return e.slide === %d && e.t !== null" % k, 10)
        errors = severe(d)
        assert not errors, "console errors on slide %d: %r" % (k, errors)
    figures[tag + "_walk"] = {"paged": len(paged), "linked": len(skipped),
                              "slowest_key_ms": round(slowest[0], 1), "slowest_slide": slowest[1]}


def max_abs_point(p):
    """The largest |x| or |y| of Euler's path (`series,t,x,y` rows)."""
    assert p["columns"][:2] == ["series", "t"], "not paths in t: %r" % p["columns"]
    best = 0.0
    for r in p["rows"]:
        if str(r[0]).lower() != "euler":
            continue
        for c in r[2:]:
            if isinstance(c, (int, float)) and math.isfinite(c):
                best = max(best, abs(c))
    return best


def spiral_off(d, args, figures, tag):
    """On the spiral slide, h up (the slider's + key) until Euler's path leaves by orders of
    magnitude: the largest |x| the plot holds grows 100-fold."""
    d.execute_script("location.hash = '#/%d'" % args.spiral)
    wait_for(d, "return window.lectern.slide() === %d" % args.spiral, 10)
    start = max_abs_point(plot(d))
    assert 0.5 < start < 10, "the spiral slide starts at max |x| %r" % start
    # the key dispatched in the page (every press arrives), each waited for until a frame
    # shows new points; at the top of h's range a press changes nothing
    d.execute_script("window.lectern.trackPlot = true")
    key_in_page(d, "-", "plot")
    presses, now = 0, start
    while now < 100 * start and presses < 60:
        presses += 1
        if d.execute_async_script(IN_PAGE_KEY, "+", "plot") is None:
            break
        now = max_abs_point(plot(d))
    d.execute_script("window.lectern.trackPlot = false")
    assert now >= 100 * start, "after %d presses of + max |x| is %r (from %r)" % (presses, now, start)
    figures[tag + "_spiral"] = {"presses": presses, "max_abs_from": start, "max_abs_to": now}


def work_precision_link(d, args, figures, tag, url):
    """`index.html#/N` lands on the work-precision slide and its sweep brings points."""
    # a fresh load, as from a course page's link (not a fragment change in the open page)
    d.get("about:blank")
    d.get(url.split("#")[0] + "#/%d" % args.work_precision)
    wait_for(d, "return window.lectern && window.lectern.ready === true")
    assert d.execute_script("return window.lectern.slide()") == args.work_precision, "link missed"
    s = wait_for(d, "var p = JSON.parse(window.lectern.plotData());"
                    " return p !== null && p.rows.length > 0", 20)
    errors = severe(d)
    assert not errors, "console errors on the linked slide: %r" % errors
    figures[tag + "_work_precision_first_points_s"] = round(s, 2)


def rows_of_csv(path):
    with open(path) as f:
        lines = [l for l in f.read().splitlines() if l]
    out = []
    for l in lines[1:]:
        cells = []
        for c in l.split(","):
            try:
                v = float(c)
                cells.append(v if math.isfinite(v) else c)
            except ValueError:
                cells.append(c)
        out.append(cells)
    return lines[0].split(","), out


def series_counts(rows):
    out = {}
    for r in rows:
        out[r[0]] = out.get(r[0], 0) + 1
    return out


def same_rows(got, want, tol=1e-12):
    if len(got) != len(want):
        return "%d rows in the page %r, %d in export --data %r" % (
            len(got), series_counts(got), len(want), series_counts(want))
    for i, (g, w) in enumerate(zip(got, want)):
        if len(g) != len(w):
            return "row %d: %r vs %r" % (i, g, w)
        for a, b in zip(g, w):
            if isinstance(b, float):
                if not isinstance(a, (int, float)) or abs(a - b) > tol * max(1.0, abs(b)):
                    return "row %d: %r vs %r" % (i, g, w)
            elif a != b:
                return "row %d: %r vs %r" % (i, g, w)
    return None


def check_page(args, url, size, figures, tag):
    d = browser(size)
    try:
        t0 = time.monotonic()
        d.get(url)
        load_s = wait_for(d, "return window.lectern && window.lectern.ready === true")
        figures[tag + "_load_to_first_slide_s"] = round(time.monotonic() - t0, 3)
        # the page's own clock: navigation start to the painted frame that made `ready` true
        wait_for(d, "var f = window.lectern.frames; return f.length > 1 && f[1].t !== null", 10)
        figures[tag + "_load_to_first_slide_in_page_ms"] = round(
            d.execute_script("return window.lectern.frames[1].t"), 1)
        assert d.execute_script("return window.lectern.slide()") == 1, "not on slide 1"
        n = d.execute_script("return window.lectern.slides()")
        assert n >= 13, "only %d slides" % n
        if args.shots:
            # compared with export's PNG by the Rust test (tests/web_player.rs)
            with open("%s/slide1-%s.png" % (args.shots, tag), "wb") as f:
                f.write(canvas_png(d))
        canvas = d.find_element(By.ID, "lectern-canvas")
        key(d, Keys.ARROW_RIGHT)
        wait_for(d, "return window.lectern.slide() === 2", 10)
        assert d.execute_script("return location.hash") == "#/2", "the fragment did not follow"
        # the fragment opens a slide (a link from a course page)
        d.execute_script("location.hash = '#/13'")
        wait_for(d, "return window.lectern.slide() === 13", 10)
        # typing an equation: N shows the editor under the slide
        d.execute_script("location.hash = '#/%d'" % args.slope)
        wait_for(d, "return window.lectern.slide() === %d" % args.slope, 10)
        key(d, "n")
        wait_for(d, "return window.lectern.editorField !== null && window.lectern.editorField !== undefined", 10)
        field = d.execute_script("return window.lectern.editorField")
        ActionChains(d).move_to_element_with_offset(canvas, 0, 0).perform()
        ActionChains(d).move_by_offset(field["x"] - size[0] / 2, field["y"] - size[1] / 2).click().perform()
        # typed before the field has the keyboard, "+" and "-" would change h instead
        wait_for(d, "return window.lectern.editing === true", 10)
        # clear the field (End, then Backspace over the file's equation), type, Enter
        key(d, Keys.END)
        key(d, Keys.BACKSPACE * 60)
        key(d, args.equation)
        key(d, Keys.ENTER)
        header, want = rows_of_csv(args.expect)
        deadline = time.monotonic() + 15
        problem = "no plot data"
        while time.monotonic() < deadline:
            got = plot(d)
            if got is not None and got["columns"] == header:
                problem = same_rows(got["rows"], want)
                if problem is None:
                    break
            time.sleep(0.1)
        assert problem is None, "after typing %r: %s" % (args.equation, problem)
        # + on the Euler slide changes the computed points
        d.execute_script("location.hash = '#/%d'" % args.euler)
        wait_for(d, "return window.lectern.slide() === %d" % args.euler, 10)
        before = plot(d)
        assert before is not None, "no plot data on the Euler slide"
        key(d, "+")
        wait_for(d, "return window.lectern.plotData() !== %s" % json.dumps(json.dumps(before)), 10)
        if tag == "file":
            walk_all_slides(d, args, figures, tag)
            spiral_off(d, args, figures, tag)
            # reloads the page: the timings below start with the notes closed, as a student
            # pages through the deck (the typing check above left them open)
            work_precision_link(d, args, figures, tag, url)
            time_keys(d, args, figures, tag)
            time_drag(d, args, figures, tag)
            time_continuous_drag(d, args, figures, tag)
            # and with the self-study notes open under the slide (`N`): a heavier frame
            key(d, "n")
            time_keys(d, args, figures, tag + "_notes_open")
        errors = severe(d)
        assert not errors, "console errors: %r" % errors
    finally:
        d.quit()


def check_broken(args, figures):
    d = browser((800, 600))
    try:
        d.get("file://" + args.broken + "/index.html")
        wait_for(d, "var e = document.getElementById('lectern-error');"
                    " return e && e.offsetParent !== null && e.textContent.length > 0", 30)
        text = d.find_element(By.ID, "lectern-error").text
        assert "bundle" in text and "export" in text, "unclear error: %r" % text
        figures["broken_error_text"] = text
    finally:
        d.quit()


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--url", action="append", default=[])
    p.add_argument("--shots")
    p.add_argument("--size", default="1280x720")
    p.add_argument("--euler", type=int)
    p.add_argument("--slope", type=int)
    p.add_argument("--spiral", type=int)
    p.add_argument("--work-precision", type=int)
    p.add_argument("--skipped", default="", help="the slides paging skips, as 21,22,...")
    p.add_argument("--equation", default="-2*x + cos(3*t)")
    p.add_argument("--expect")
    p.add_argument("--broken")
    args = p.parse_args()
    size = tuple(int(v) for v in args.size.split("x"))
    figures = {}
    failed = []
    if args.broken:
        check_broken(args, figures)
    for i, url in enumerate(args.url):
        tag = "file" if url.startswith("file:") else "http"
        try:
            check_page(args, url, size, figures, tag)
        except AssertionError as e:
            failed.append("%s: %s" % (url, e))
    for f in failed:
        print("FAILED " + f, file=sys.stderr)
    print(json.dumps(figures))
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
