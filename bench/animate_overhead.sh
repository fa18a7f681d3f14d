#!/usr/bin/env bash
# What `lightcone animate` costs against single renders (issue 54: at its defaults, at most 1.05
# times the summed single renders): animates N frames of a scene, renders the same N moments with
# one `render` call each, and prints the ratio of animate's whole process to the calls' whole
# processes summed (each starting, reading the scene, rendering and writing its file), and to
# the render time alone they report (--stats). Both run at the scene's own exposure: a scene
# that gives none has the automatic one, which animate meters and smooths over the frames.
#
#   bench/animate_overhead.sh [SCENE] [N] [TAU0] [FPS]   (after ./scripts/build.sh)
#
# SCENE is a scene file (default scenes/rocket.json) or bodies:COUNT, COUNT moving spheres of
# bench/targets.py's sphere_scene (the targets' animate row is `bodies:20000 24 0 24`); TAU0 is
# the scene's camera.proper_time (2 for rocket.json, 0 for bodies:COUNT); FPS defaults to 30.
# Images are 640x360 at 1 sample. REPEATS=R measures each R times, alternating, and prints the
# medians; LIGHTCONE=BINARY names the program (default build/lightcone), and OLD=BINARY also
# times another build's animate in the same run (for a before and after).
set -euo pipefail
cd "$(dirname "$0")/.."
scene=${1:-scenes/rocket.json}
frames=${2:-120}
tau0=${3:-2}
fps=${4:-30}
repeats=${REPEATS:-1}
new=${LIGHTCONE:-./build/lightcone}
options=(--width 640 --height 360 --samples 1 --quiet)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
if [[ $scene == bodies:* ]]; then
  python3 -c 'import sys; sys.path.insert(0, "bench"); import targets
targets.sphere_scene(sys.argv[1], int(sys.argv[2]), 640, 360)' "$out/bodies.json" "${scene#bodies:}"
  scene=$out/bodies.json
fi
now() { date +%s.%N; }
# Seconds of one run of animate by the program $1.
animate_seconds() {
  local start
  start=$(now)
  "$1" animate "$scene" --fps "$fps" --frames "0-$((frames - 1))" -o "$out/a-%04d.png" \
    "${options[@]}"
  awk -v s="$start" -v e="$(now)" 'BEGIN { printf "%.6f", e - s }'
}
# Seconds of the N render calls' whole processes, and of their renders (--stats), summed.
renders_seconds() {
  local whole=0 rendering=0 start stats
  for ((i = 0; i < frames; i++)); do
    tau=$(awk -v t="$tau0" -v i="$i" -v f="$fps" 'BEGIN { printf "%.17g", t + i / f }')
    start=$(now)
    stats=$("$new" render "$scene" -o "$out/r.png" --stats "${options[@]}" \
      --set "camera.proper_time=$tau" 2>&1)
    whole=$(awk -v a="$whole" -v s="$start" -v e="$(now)" 'BEGIN { printf "%.6f", a + e - s }')
    seconds=$(echo "$stats" | sed -n 's/.*"seconds":\([0-9.e-]*\).*/\1/p')
    rendering=$(awk -v a="$rendering" -v b="$seconds" 'BEGIN { printf "%.6f", a + b }')
  done
  echo "$whole $rendering"
}
median() { sort -g | awk '{ v[NR] = $1 } END { print (v[int((NR + 1) / 2)] + v[int(NR / 2) + 1]) / 2 }'; }
animate_new=() animate_old=() whole=() rendering=()
for ((r = 0; r < repeats; r++)); do
  # Alternating, so that the machine's load falls on each alike.
  for job in $(printf '%s\n' new old renders | shuf); do
    case $job in
      new) animate_new+=("$(animate_seconds "$new")") ;;
      old) if [ -n "${OLD:-}" ]; then animate_old+=("$(animate_seconds "$OLD")"); fi ;;
      renders)
        read -r w g < <(renders_seconds)
        whole+=("$w") rendering+=("$g")
        ;;
    esac
  done
done
w=$(printf '%s\n' "${whole[@]}" | median)
g=$(printf '%s\n' "${rendering[@]}" | median)
report() {
  local a
  a=$(printf '%s\n' "${@:2}" | median)
  awk -v who="$1" -v a="$a" -v n="$frames" -v w="$w" -v g="$g" 'BEGIN {
    printf "%s animate, %d frames: %.3f s; %d render calls: %.3f s in all (ratio %.3f), ",
           who, n, a, n, w, a / w
    printf "of which %.3f s rendering (ratio %.3f)\n", g, a / g }'
}
echo "medians of $repeats: $scene at $fps fps"
report "$new" "${animate_new[@]}"
if [ -n "${OLD:-}" ]; then report "$OLD" "${animate_old[@]}"; fi
