#!/usr/bin/env bash
# Renders every picture in README.md and docs/ with the commands the docs show, into
# docs/images/. Run after ./scripts/build.sh (and ./setup.sh --web, for the web page); it takes
# a few minutes on 2 cores.
set -euo pipefail
cd "$(dirname "$0")/.."
lc=./build/lightcone
out=docs/images
render() {  # render NAME SCENE [options...]
  local name=$1 scene=$2
  shift 2
  echo "lightcone render scenes/$scene -o $name.png $*" >&2
  "$lc" render "scenes/$scene" -o "$out/$name.png" --quiet "$@"
}
render terrell terrell.json
render terrell-classical terrell.json --set render.relativity=false
render terrell-simultaneous terrell.json --set render.light_delay=false
render cubes cubes.json
render cubes-classical cubes.json --set render.relativity=false
render street street.json
render street-classical street.json --set render.relativity=false
render sky sky.json
render sky-classical sky.json --set render.relativity=false
render sun-flyby-doppler sun-flyby.json --set render.searchlight=off
render sun-flyby-searchlight sun-flyby.json
render street-searchlight-physical street-searchlight.json
render street-searchlight-chang1996 street-searchlight.json --set render.searchlight=chang1996
render rainbow rainbow.json
render interceptor-surface interceptor.json
render interceptor-camera interceptor.json --set render.light_source_delay=camera
render street-lit street-lit.json
render street-lit-classical street-lit.json --set render.relativity=false
render headlight headlight.json
render headlight-rest headlight.json --set 'camera.velocity=[0,0,0]' --set 'lights[0].velocity=[0,0,0]'
render street-spectral street.json --set render.searchlight=off
render street-rgb3 street.json --set render.searchlight=off --set render.doppler=rgb3
render street-hue street.json --set render.searchlight=off --set render.doppler=hue
render doppler-swatches doppler-swatches.json
render terrell-doppler terrell.json --map doppler
render street-raster street.json --renderer raster
for tau in 0 1.5 3; do
  render "rocket-$tau" rocket.json --set camera.proper_time=$tau --width 480 --height 270
done
render wheel wheel.json
render wheel-later wheel.json --set camera.time=2.5
for tau in 1 3 5 7; do
  render "twin-$tau" twin-paradox.json --set camera.proper_time=$tau \
    --set render.doppler=off --set render.searchlight=off --width 360 --height 202
done
render terrell-blur terrell.json --set camera.shutter=2 --samples 64
render black-hole black-hole.json
render stars stars.json
# The strip of the guide: flying toward Orion at 0, 0.5, 0.9 and 0.99c.
render stars-0 stars.json --width 480 --height 270
render stars-0.5 stars.json --width 480 --height 270 --set camera.velocity=0,0,-0.5
render stars-0.9 stars.json --width 480 --height 270 --set camera.velocity=0,0,-0.9
render stars-0.99 stars.json --width 480 --height 270 --set camera.velocity=0,0,-0.99
render black-hole-order black-hole.json --map image_order
render lensed-clock lensed-clock.json
render infall infall.json
render orbit orbit.json
render plunge plunge.json
render texture-mapping texture-mapping.json
echo "lightcone animate scenes/rocket.json --fps 10 --frames 0-40 --video rocket.gif ..." >&2
"$lc" animate scenes/rocket.json --fps 10 --frames 0-40 --set camera.proper_time=0 \
  --width 256 --height 144 --samples 2 --video "$out/rocket.gif" --quiet
for t in 3.0 3.1 3.2; do
  render "slow-light-$t" slow-light.json --set camera.time=$t --width 480 --height 270
done
# The viewer's pictures, as F12 saves them (under a virtual X server when there is no display):
#   view_png NAME SCENE "VIEW OPTIONS" "X,Y X,Y ...": clicks at those points of the window, then F12.
view_png() {
  local name=$1 scene=$2 options=$3 clicks=$4
  local dir
  dir=$(mktemp -d)
  local display=${DISPLAY:-}
  local xvfb=""
  if [ -z "$display" ]; then
    display=:93
    Xvfb "$display" -screen 0 1280x800x24 -nolisten tcp >/dev/null 2>&1 &
    xvfb=$!
    for _ in $(seq 50); do [ -e "/tmp/.X11-unix/X${display#:}" ] && break; sleep 0.1; done
  fi
  echo "lightcone view scenes/$scene $options${clicks:+ (clicks at $clicks)} (F12)" >&2
  # shellcheck disable=SC2086
  (cd "$dir" && DISPLAY=$display "$OLDPWD/$lc" view "$OLDPWD/scenes/$scene" $options \
    >/dev/null 2>&1) &
  local viewer=$!
  local window
  window=$(DISPLAY=$display timeout 30 xdotool search --sync --name 'lightcone view' | head -1)
  sleep 2
  for click in $clicks; do
    DISPLAY=$display xdotool mousemove --window "$window" "${click%,*}" "${click#*,}" click 1
    sleep 2
  done
  DISPLAY=$display xdotool key --window "$window" F12
  sleep 2
  DISPLAY=$display xdotool key --window "$window" Escape
  wait "$viewer" || true
  if [ -n "$xvfb" ]; then
    kill "$xvfb"
    wait "$xvfb" || true  # (its display is free for the next picture's server)
  fi
  mv "$dir/lightcone-view-0001.png" "$out/$name.png"
  rm -rf "$dir"
}
view_png view-split street.json "--split --time-scale 0 --width 960 --height 540" ""
# The guide's "Measuring a picture": two probes and their ruler on the Terrell scene.
view_png view-probes terrell.json "--time-scale 0" "699,256 433,270"

# The web page (docs/web.md): built and served as the docs show, opened on a link.
web_screenshot() {
  echo "./scripts/build-web.sh && ./scripts/serve-web.sh; open #scene=street&beta=0.9" >&2
  ./scripts/build-web.sh >/dev/null
  PORT=8765 ./scripts/serve-web.sh >/dev/null 2>&1 &
  local server=$!
  sleep 1
  node web/test/screenshot_page.mjs "http://127.0.0.1:8765/#scene=street&beta=0.9" \
    "$out/web-page.png"
  # The guide's "Measuring a picture": a link with two probes.
  echo "open #scene=terrell&paused=on&probe=466.5,171.5;289.5,180.5" >&2
  node web/test/screenshot_page.mjs \
    "http://127.0.0.1:8765/#scene=terrell&paused=on&probe=466.5,171.5;289.5,180.5" \
    "$out/web-probes.png"
  kill "$server"
}
web_screenshot

# The Python tour (docs/python.md), as the page shows it.
echo "PYTHONPATH=build/python python3 examples/python/tour.py docs/images" >&2
PYTHONPATH=build/python python3 examples/python/tour.py "$out" >/dev/null
