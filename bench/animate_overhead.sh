#!/usr/bin/env bash
# What `lightcone animate` costs against single renders (issue: 120 frames at most 1.05 times
# 120 single `lightcone render` calls): animates N frames of a scene, then renders the same N
# moments with one `render` call each, and prints the ratio of animate's time to the calls'
# whole time (each starting, reading the scene, rendering and writing its file) and to the
# render time alone they report (--stats). TAU0 is the scene's camera.proper_time (2 for
# rocket.json).
#   bench/animate_overhead.sh [SCENE] [N] [TAU0]   (after ./scripts/build.sh)
set -euo pipefail
cd "$(dirname "$0")/.."
scene=${1:-scenes/rocket.json}
frames=${2:-120}
tau0=${3:-2}
fps=30
options=(--width 640 --height 360 --samples 1 --quiet)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
start=$(date +%s.%N)
./build/lightcone animate "$scene" --fps $fps --frames "0-$((frames - 1))" -o "$out/a-%04d.png" \
  "${options[@]}"
end=$(date +%s.%N)
total=0
calls_start=$(date +%s.%N)
for ((i = 0; i < frames; i++)); do
  tau=$(awk -v t="$tau0" -v i="$i" -v f="$fps" 'BEGIN { printf "%.17g", t + i / f }')
  stats=$(./build/lightcone render "$scene" -o "$out/r.png" --stats "${options[@]}" \
    --set "camera.proper_time=$tau" 2>&1)
  seconds=$(echo "$stats" | sed -n 's/.*"seconds":\([0-9.e-]*\).*/\1/p')
  total=$(awk -v a="$total" -v b="$seconds" 'BEGIN { printf "%.9f", a + b }')
done
calls_end=$(date +%s.%N)
awk -v s="$start" -v e="$end" -v n="$frames" -v t="$total" -v cs="$calls_start" \
  -v ce="$calls_end" 'BEGIN {
  printf "animate, %d frames: %.3f s; %d render calls: %.3f s in all (ratio %.3f), of which ",
         n, e - s, n, ce - cs, (e - s) / (ce - cs)
  printf "%.3f s rendering (ratio %.3f)\n", t, (e - s) / t }'
