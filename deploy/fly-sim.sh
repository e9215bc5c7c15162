#!/usr/bin/env bash
# The main job, on simulation: set up, build, then fly the virtual kite over an aerial photo
# with the real agent and the headless station, as an operator would:
#   1. kapfix-agent --sim starts idle, its link on loopback;
#   2. kapfix-ctl runs SSP over a free swing and confirms the recommended slice;
#   3. the agent fixates that slice in closed loop (simulated servos, gusts) for DURATION s;
#   4. a stabilised photo is taken and received; the flight report is written.
# Usage: deploy/fly-sim.sh [scene.jpg] [duration_s]        results land in out/flight/
set -euo pipefail
cd "$(dirname "$0")/.."
bash deploy/setup-debian.sh
scene=${1:-/usr/share/doc/opencv-doc/examples/data/aero1.jpg}
duration=${2:-20}
out=out/flight
echo "== building (preset default) =="
cmake --preset default > /dev/null
cmake --build --preset default -j "$(nproc)" --target kapfix-agent kapfix-ctl
agent=build/default/agent/kapfix-agent
ctl=build/default/tools/ctl/kapfix-ctl
rm -rf "$out"
mkdir -p "$out/station"
"$agent" --sim --scene "$scene" --mode idle --photos "$out/photos" --report "$out/report" \
  > "$out/summary.json" 2> "$out/agent.log" &
agent_pid=$!
trap 'kill "$agent_pid" 2>/dev/null || true' EXIT
echo "== agent $agent_pid flying in simulation over $scene (log: $out/agent.log) =="
echo "== slice selection over a free swing =="
"$ctl" --timeout 10000 ssp --wait --frames 150 | tee "$out/ssp.txt"
best=$(sed -n 's/^recommended_slice: //p' "$out/ssp.txt")
echo "== confirming slice $best and fixating for $duration s =="
"$ctl" slice "$best"   # confirms the slice: the agent fixates on it
"$ctl" watch --count 5
sleep "$duration"
echo "== stabilised photo =="
"$ctl" photo --note "fly-sim" --save "$out/station"
"$ctl" status
kill -INT "$agent_pid"
wait "$agent_pid"
trap - EXIT
echo "== flight report ($out/report/) =="
cat "$out/summary.json"
echo "== done: report, telemetry CSV, displacement plot, photos in $out/ =="
