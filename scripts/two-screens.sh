#!/bin/sh
# Two virtual monitors on one X server, for trying the presenter view without hardware:
# a 1280x800 "laptop" (primary, left) and a 1920x1080 "projector" to its right.
# Xvfb cannot do this (winit lists RandR CRTCs; Xvfb has one, and its +xinerama mode crashes
# winit), so this uses Xorg's dummy driver. Debian 12, as root:
#   apt-get install -y --no-install-recommends xserver-xorg-core xserver-xorg-video-dummy x11-xserver-utils
# Usage: scripts/two-screens.sh [DISPLAY_NUMBER]   then   DISPLAY=:6 lectern
set -eu
n="${1:-6}"
here="$(cd "$(dirname "$0")" && pwd)"
Xorg ":$n" -config "$here/two-screens.xorg.conf" -noreset -nolisten tcp \
    -logfile "/tmp/lectern-xorg-$n.log" >/dev/null 2>&1 &
echo "Xorg :$n is pid $!"
sleep 2
DISPLAY=":$n" xrandr --addmode DUMMY1 1920x1080
DISPLAY=":$n" xrandr --output DUMMY1 --mode 1920x1080 --right-of DUMMY0
DISPLAY=":$n" xrandr --listmonitors
