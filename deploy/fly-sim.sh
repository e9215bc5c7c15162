#!/usr/bin/env bash
# The main job, on simulation: set up, build, then fly the virtual kite over an aerial photo.
#   1. SSP: a free swing, the displacement graph of every slice, the recommended slice;
#   2. fixation on a stored reference in that slice through the open-loop swing (SPEC §3),
#      scored against the simulation's truth.
# Usage: deploy/fly-sim.sh [scene.jpg] [strategy]      figures and plots land in out/flight/
# (The closed loop with simulated servos arrives with kapfix-agent --sim, issue 3.)
set -euo pipefail
cd "$(dirname "$0")/.."
bash deploy/setup-debian.sh
scene=${1:-/usr/share/doc/opencv-doc/examples/data/aero1.jpg}
strategy=${2:-pyr}
out=out/flight
echo "== building (preset default) =="
cmake --preset default > /dev/null
cmake --build --preset default -j "$(nproc)" --target kapfix-analyze
analyze=build/default/tools/analyze/kapfix-analyze
mkdir -p "$out"
echo "== slice selection on $scene (strategy $strategy) =="
"$analyze" ssp --image "$scene" --strategy "$strategy" --out "$out/ssp" | tee "$out/ssp.txt"
best=$(sed -n 's/^best_slice: //p' "$out/ssp.txt")
echo "== fixating slice $best through the swing =="
"$analyze" swing --image "$scene" --strategy "$strategy" --slice "$best" --gusts \
  --out "$out/swing" | tee "$out/swing.txt"
echo "== done: plots and CSV in $out/ =="
