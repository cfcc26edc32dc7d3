#!/usr/bin/env python3
"""Measures the live app as a lecturer feels it, on a running X display (Xvfb is fine):

- key press -> the new slide on screen: a Right key through XTest, then the screen polled
  (XGetImage of the window's area, hashed) until it changes ("first") and until it stops
  changing for SETTLE seconds ("settled");
- CPU per slide change (the app's utime+stime from /proc over the same span) and, with
  --frame-stats, the frames drawn for it;
- a saved deck -> on screen: the current slide's title edited in the deck file (written
  beside it and renamed over, as editors do), then the same polling;
- idle CPU: the app's CPU over IDLE seconds with nothing happening.

No dependencies beyond libX11/libXtst (ctypes). Usage (the app already running):
  scripts/slide-latency.py --pid PID --deck slides/lecture.ron [--frame-stats FILE]
"""

import argparse
import ctypes
import ctypes.util
import hashlib
import os
import re
import statistics
import sys
import time

X11 = ctypes.CDLL(ctypes.util.find_library("X11") or "libX11.so.6")
XTST = ctypes.CDLL(ctypes.util.find_library("Xtst") or "libXtst.so.6")


class XImage(ctypes.Structure):
    _fields_ = [
        ("width", ctypes.c_int),
        ("height", ctypes.c_int),
        ("xoffset", ctypes.c_int),
        ("format", ctypes.c_int),
        ("data", ctypes.c_void_p),
        ("byte_order", ctypes.c_int),
        ("bitmap_unit", ctypes.c_int),
        ("bitmap_bit_order", ctypes.c_int),
        ("bitmap_pad", ctypes.c_int),
        ("depth", ctypes.c_int),
        ("bytes_per_line", ctypes.c_int),
        ("bits_per_pixel", ctypes.c_int),
        ("red_mask", ctypes.c_ulong),
        ("green_mask", ctypes.c_ulong),
        ("blue_mask", ctypes.c_ulong),
        ("obdata", ctypes.c_void_p),
        ("create_image", ctypes.c_void_p),
        ("destroy_image", ctypes.c_void_p),
        ("get_pixel", ctypes.c_void_p),
        ("put_pixel", ctypes.c_void_p),
        ("sub_image", ctypes.c_void_p),
        ("add_pixel", ctypes.c_void_p),
    ]


X11.XOpenDisplay.restype = ctypes.c_void_p
X11.XOpenDisplay.argtypes = [ctypes.c_char_p]
X11.XDefaultRootWindow.restype = ctypes.c_ulong
X11.XDefaultRootWindow.argtypes = [ctypes.c_void_p]
X11.XGetImage.restype = ctypes.POINTER(XImage)
X11.XGetImage.argtypes = [
    ctypes.c_void_p,
    ctypes.c_ulong,
    ctypes.c_int,
    ctypes.c_int,
    ctypes.c_uint,
    ctypes.c_uint,
    ctypes.c_ulong,
    ctypes.c_int,
]
X11.XKeysymToKeycode.restype = ctypes.c_ubyte
X11.XKeysymToKeycode.argtypes = [ctypes.c_void_p, ctypes.c_ulong]
X11.XFlush.argtypes = [ctypes.c_void_p]
X11.XSync.argtypes = [ctypes.c_void_p, ctypes.c_int]
XTST.XTestFakeKeyEvent.argtypes = [ctypes.c_void_p, ctypes.c_uint, ctypes.c_int, ctypes.c_ulong]
DESTROY = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.POINTER(XImage))

XK_RIGHT = 0xFF53
XK_HOME = 0xFF50
ZPIXMAP = 2
SETTLE = 0.4


class Screen:
    def __init__(self, width, height):
        self.dpy = X11.XOpenDisplay(None)
        if not self.dpy:
            sys.exit("cannot open the X display (DISPLAY?)")
        self.root = X11.XDefaultRootWindow(self.dpy)
        self.size = (width, height)

    def hash(self):
        img = X11.XGetImage(self.dpy, self.root, 0, 0, *self.size, 0xFFFFFFFF, ZPIXMAP)
        if not img:
            sys.exit("XGetImage failed")
        n = img.contents.bytes_per_line * img.contents.height
        digest = hashlib.blake2b(ctypes.string_at(img.contents.data, n), digest_size=16).digest()
        DESTROY(img.contents.destroy_image)(img)
        return digest

    def key(self, keysym):
        code = X11.XKeysymToKeycode(self.dpy, keysym)
        XTST.XTestFakeKeyEvent(self.dpy, code, 1, 0)
        XTST.XTestFakeKeyEvent(self.dpy, code, 0, 0)
        X11.XFlush(self.dpy)

    def wait_change(self, before, t0, timeout=5.0):
        """Seconds from t0 to the first change, and to the last change before SETTLE quiet."""
        first = last = None
        current = before
        while True:
            now = time.monotonic()
            h = self.hash()
            if h != current:
                current = h
                last = now - t0
                if first is None:
                    first = last
            elif first is not None and now - t0 - last > SETTLE:
                return first, last
            if now - t0 > timeout:
                return first, last
            time.sleep(0.002)


def cpu_secs(pid):
    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def lines(path):
    if not path:
        return 0
    with open(path) as f:
        return sum(1 for _ in f)


def pct(values, p):
    s = sorted(values)
    return s[min(len(s) - 1, int(round(p / 100 * (len(s) - 1))))]


def summary(name, values, unit="ms", scale=1e3):
    if not values:
        print(f"{name}: no data")
        return
    v = [x * scale for x in values]
    print(
        f"{name}: median {statistics.median(v):.0f} {unit}, p95 {pct(v, 95):.0f}, "
        f"min {min(v):.0f}, max {max(v):.0f} (n = {len(v)})"
    )


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--pid", type=int, required=True)
    ap.add_argument("--deck", required=True, help="the deck the app presents (edited for saves)")
    ap.add_argument("--frame-stats", help="the app's --frame-stats file, to count frames")
    ap.add_argument("--presses", type=int, default=16)
    ap.add_argument("--passes", type=int, default=2)
    ap.add_argument("--saves", type=int, default=16)
    ap.add_argument("--idle", type=float, default=10.0)
    ap.add_argument("--size", default="1280x720")
    a = ap.parse_args()
    w, h = (int(v) for v in a.size.split("x"))
    screen = Screen(w, h)

    # Pass 1 visits each slide for the first time (formulas typeset, widgets built); pass 2
    # comes back to slides already made, as paging back and forth in a talk does.
    for p in range(1, a.passes + 1):
        screen.key(XK_HOME)
        screen.wait_change(screen.hash(), time.monotonic(), timeout=3.0)
        time.sleep(1.0)
        firsts, settled, cpus, frames = [], [], [], []
        for _ in range(a.presses):
            before = screen.hash()
            c0, f0 = cpu_secs(a.pid), lines(a.frame_stats)
            t0 = time.monotonic()
            screen.key(XK_RIGHT)
            first, last = screen.wait_change(before, t0)
            if first is None:
                print("a key press changed nothing (last slide?)")
                break
            time.sleep(0.3)
            firsts.append(first)
            settled.append(last)
            cpus.append(cpu_secs(a.pid) - c0)
            frames.append(lines(a.frame_stats) - f0)
        print(f"pass {p}:")
        summary("  key -> new slide on screen (first change)", firsts)
        summary("  key -> screen settled", settled)
        summary("  CPU per slide change", cpus)
        if a.frame_stats:
            print(f"  frames drawn per key press: {frames}")

    # Saves: the title of the slide on screen gets a counter, written as an editor does.
    with open(a.deck) as f:
        original = f.read()
    saves = []
    try:
        for i in range(a.saves):
            text, n = re.subn(r'title: "([^"]*?)( \(\d+\))?"', rf'title: "\1 ({i})"', original, 1)
            if n == 0:
                sys.exit("no title in the deck to edit")
            before = screen.hash()
            tmp = a.deck + ".bench-tmp"
            with open(tmp, "w") as f:
                f.write(text)
            t0 = time.monotonic()
            os.rename(tmp, a.deck)
            first, _ = screen.wait_change(before, t0)
            if first is not None:
                saves.append(first)
            time.sleep(0.5)
    finally:
        with open(a.deck + ".bench-tmp", "w") as f:
            f.write(original)
        os.rename(a.deck + ".bench-tmp", a.deck)
    summary("save -> on screen", saves)

    time.sleep(1.0)
    c0, f0 = cpu_secs(a.pid), lines(a.frame_stats)
    time.sleep(a.idle)
    idle = cpu_secs(a.pid) - c0
    print(
        f"idle: {100 * idle / a.idle:.1f} % CPU over {a.idle:.0f} s, "
        f"{lines(a.frame_stats) - f0 if a.frame_stats else '?'} frames drawn"
    )


if __name__ == "__main__":
    main()
