#!/usr/bin/env bash
# Takes the README's picture of kapfix-station after SSP, under Xvfb (no display needed).
#
#   deploy/station-screenshot.sh [--build DIR] [--out FILE] --agent HOST [--command-port N] [--stream-port N]
#       against a running agent (e.g. `kapfix-agent --sim`): connects, starts SSP, and saves
#       the window 3 s after the finished SSP report.
#   deploy/station-screenshot.sh [--build DIR] [--out FILE] --demo
#       no agent: replays a synthetic session (tests/groundstation/demo_session_writer.cpp).
#
# Defaults: --build build/h, --out docs/station_after_ssp.png. The station starts with fresh
# settings (a private XDG_CONFIG_HOME), so the layout is the default one.
set -euo pipefail
cd "$(dirname "$0")/.."
build=build/h
out=docs/station_after_ssp.png
station_args=()
demo=0
while [ $# -gt 0 ]; do
  case "$1" in
    --build) build=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --agent|--command-port|--stream-port) station_args+=("$1" "$2"); shift 2 ;;
    --demo) demo=1; shift ;;
    *) echo "station-screenshot: unknown argument $1" >&2; exit 2 ;;
  esac
done
[ -x "$build/groundstation/kapfix-station" ] || { echo "station-screenshot: build kapfix-station in $build first" >&2; exit 2; }
tmp=$(mktemp -d "${TMPDIR:-/tmp}/kapfix-screenshot.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
if [ "$demo" = 1 ]; then
  QT_QPA_PLATFORM=offscreen "$build/tests/groundstation/kapfix_station_demo_session" "$tmp/demo.kfxrec"
  station_args+=(--replay "$tmp/demo.kfxrec")
else
  [ ${#station_args[@]} -gt 0 ] || { echo "station-screenshot: give --agent HOST or --demo" >&2; exit 2; }
  station_args+=(--run-ssp)
fi
mkdir -p "$(dirname "$out")"
XDG_CONFIG_HOME="$tmp/config" HOME="$tmp" xvfb-run -a -s "-screen 0 1600x1000x24" \
  "$build/groundstation/kapfix-station" "${station_args[@]}" --screenshot "$out"
echo "station-screenshot: $out"
