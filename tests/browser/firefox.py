#!/usr/bin/env python3
"""An optional check of the exported page in Debian's headless Firefox ESR (docs/web.md), not
run by CI. Debian has no geckodriver, so this speaks Firefox's own Marionette protocol (built
into Firefox: length-prefixed JSON over TCP) with nothing but the standard library.

Usage: firefox.py URL_OF_INDEX_HTML [--shot PNG] [--slide N]
Prints one JSON object of what it saw; exit status 0 when the page got ready.
"""
import argparse
import base64
import json
import os
import shutil
import socket
import subprocess
import sys
import tempfile
import time


class Marionette:
    def __init__(self, port):
        deadline = time.monotonic() + 60
        while True:
            try:
                self.sock = socket.create_connection(("127.0.0.1", port), timeout=120)
                break
            except OSError:
                if time.monotonic() > deadline:
                    raise
                time.sleep(0.2)
        self.id = 0
        self._read()  # the hello

    def _read(self):
        head = b""
        while not head.endswith(b":"):
            c = self.sock.recv(1)
            if not c:
                raise EOFError("Marionette closed the connection")
            head += c
        n = int(head[:-1])
        body = b""
        while len(body) < n:
            body += self.sock.recv(n - len(body))
        return json.loads(body)

    def call(self, name, params=None):
        self.id += 1
        msg = json.dumps([0, self.id, name, params or {}]).encode()
        self.sock.sendall(str(len(msg)).encode() + b":" + msg)
        while True:
            reply = self._read()
            if reply[0] == 1 and reply[1] == self.id:
                if reply[2]:
                    raise RuntimeError("%s: %r" % (name, reply[2]))
                return reply[3]

    def script(self, js, args=None):
        return self.call("WebDriver:ExecuteScript", {"script": js, "args": args or []}).get("value")


def wait_for(m, js, timeout_s):
    start = time.monotonic()
    while time.monotonic() - start < timeout_s:
        if m.script(js):
            return time.monotonic() - start
        time.sleep(0.05)
    return None


def main():
    p = argparse.ArgumentParser()
    p.add_argument("url")
    p.add_argument("--shot")
    p.add_argument("--slide", type=int, help="also open URL#/N and check it lands there")
    args = p.parse_args()
    port = 2828 + os.getpid() % 1000
    profile = tempfile.mkdtemp(prefix="lectern-firefox-")
    with open(os.path.join(profile, "user.js"), "w") as f:
        f.write('user_pref("marionette.port", %d);\n' % port)
        # no GPU: let WebGL run on Mesa's software rasteriser rather than refuse it
        f.write('user_pref("webgl.force-enabled", true);\n')
        f.write('user_pref("webgl.disabled", false);\n')
    # headless Firefox gets no WebGL without a GPU; under a display (xvfb-run) it uses Mesa's
    headless = [] if os.environ.get("DISPLAY") else ["--headless"]
    ff = subprocess.Popen(
        ["firefox-esr"] + headless + ["--marionette", "--no-remote", "--profile", profile,
         "--window-size=1280,720"],
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    seen = {}
    try:
        m = Marionette(port)
        m.call("WebDriver:NewSession", {"capabilities": {}})
        m.call("WebDriver:SetWindowRect", {"width": 1280, "height": 720})
        t0 = time.monotonic()
        m.call("WebDriver:Navigate", {"url": args.url})
        ready = wait_for(m, "return !!(window.lectern && window.lectern.ready)", 60)
        seen["ready_after_s"] = None if ready is None else round(time.monotonic() - t0, 2)
        seen["error_box"] = m.script(
            "var e = document.getElementById('lectern-error'); return e && e.textContent")
        seen["webgl2_renderer"] = m.script(
            "var g = document.createElement('canvas').getContext('webgl2');"
            " if (!g) return null; var i = g.getExtension('WEBGL_debug_renderer_info');"
            " return i ? g.getParameter(i.UNMASKED_RENDERER_WEBGL) : g.getParameter(g.RENDERER)")
        if ready is not None:
            seen["slides"] = m.script("return window.lectern.slides()")
            seen["in_page_load_to_first_slide_ms"] = m.script(
                "var f = window.lectern.frames; return f && f.length > 1 ? f[1].t : null")
            if args.shot:
                png = m.call("WebDriver:TakeScreenshot", {"full": False})["value"]
                with open(args.shot, "wb") as f:
                    f.write(base64.b64decode(png))
            if args.slide:
                # a fresh load of the link, as a student following it from a course page
                m.call("WebDriver:Navigate", {"url": "about:blank"})
                m.call("WebDriver:Navigate", {"url": args.url.split("#")[0] + "#/%d" % args.slide})
                wait_for(m, "return !!(window.lectern && window.lectern.ready)", 60)
                seen["linked_slide"] = m.script("return window.lectern.slide()")
                seen["linked_points_after_s"] = wait_for(
                    m, "var p = window.lectern && JSON.parse(window.lectern.plotData());"
                       " return !!p && p.rows.length > 0", 20)
                if args.shot:
                    png = m.call("WebDriver:TakeScreenshot", {"full": False})["value"]
                    with open(args.shot.replace(".png", "-linked.png"), "wb") as f:
                        f.write(base64.b64decode(png))
        m.call("WebDriver:DeleteSession")
    finally:
        ff.kill()
        ff.wait()
        shutil.rmtree(profile, ignore_errors=True)
    print(json.dumps(seen))
    sys.exit(0 if seen.get("ready_after_s") is not None else 1)


if __name__ == "__main__":
    main()
