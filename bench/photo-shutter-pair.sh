#!/usr/bin/env bash
# Issue 13's photo benchmark: the same simulated kite flight (SPEC §3's swing with gusts,
# motion blur over the photo's exposure) flown with the interval and with the best-phase
# shutter, photos every 2 s for 60 s, on several seeds. Prints one row per flight and, per
# seed, best-phase's figures against interval's in the same world and seed.
# Usage: bench/photo-shutter-pair.sh [BUILD_DIR] [SEED ...]   (default build/default, 1…5)
#        PHOTO_EXPOSURE_MS=30 bench/photo-shutter-pair.sh …      (default 10 ms)
# Needs jq. About 20–40 s per flight.
set -euo pipefail

build_dir="${1:-build/default}"
shift || true
seeds=("$@")
exposure_ms="${PHOTO_EXPOSURE_MS:-10}"
if [ ${#seeds[@]} -eq 0 ]; then seeds=(1 2 3 4 5); fi
agent="$build_dir/agent/kapfix-agent"
[ -x "$agent" ] || { echo "photo-shutter-pair: no $agent (build kapfix-agent)" >&2; exit 2; }
command -v jq > /dev/null || { echo "photo-shutter-pair: needs jq" >&2; exit 2; }

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

fly() {  # seed shutter → summary.json path
  local seed="$1" shutter="$2" dir="$work/$1-$2"
  mkdir -p "$dir"
  nice -n 5 "$agent" --sim --max-speed --blur --seed "$seed" --photo-interval 2 \
    --photo-exposure "$exposure_ms" --shutter "$shutter" --duration 60 --report "$dir/report" --photos "$dir/photos" \
    --state-dir "$dir/state" --command-address "ipc://$dir/command" \
    --stream-address "ipc://$dir/stream" > /dev/null 2> "$dir.log" ||
    { echo "photo-shutter-pair: seed $seed $shutter failed, see:" >&2; tail -3 "$dir.log" >&2; exit 1; }
  echo "$dir/report/summary.json"
}

row='[.shutter, .photos, .photo_view_speed_px_mean, .photo_view_blur_px_mean,
      .photo_offset_px_mean, .photo_sharpness_mean, .photo_wait_s_mean, .rms_error_px]
     | map(if type == "number" then (. * 1000 | round / 1000) else . end) | @tsv'
printf 'seed\tshutter\tphotos\tspeed_px\tblur_px\toffset_px\tsharpness\twait_s\tloop_rms_px\n'
for seed in "${seeds[@]}"; do
  interval="$(fly "$seed" interval)"
  best="$(fly "$seed" best-phase)"
  printf '%s\t%s\n' "$seed" "$(jq -r "$row" "$interval")"
  printf '%s\t%s\n' "$seed" "$(jq -r "$row" "$best")"
  jq -rn --slurpfile i "$interval" --slurpfile b "$best" --arg seed "$seed" '
    ($i[0]) as $i | ($b[0]) as $b |
    "\($seed)\tratio\tspeed ÷\(($i.photo_view_speed_px_mean / $b.photo_view_speed_px_mean * 100
      | round) / 100)\tsharpness ×\(($b.photo_sharpness_mean / $i.photo_sharpness_mean * 100
      | round) / 100)\twait \($b.photo_wait_s_mean * 1000 | round / 1000) s"'
done
