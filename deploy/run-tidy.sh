#!/usr/bin/env bash
# clang-tidy over our own sources, with the compile commands of the CI build.
# Usage: deploy/run-tidy.sh [build-dir]   (default build/ci; configure it first)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build/ci}
[ -f "$build/compile_commands.json" ] || { echo "run-tidy: no $build/compile_commands.json (configure first)" >&2; exit 2; }
mapfile -t files < <(git ls-files 'common/*.cpp' 'tools/*.cpp' 'agent/*.cpp' 'proto/*.cpp' 'bench/*.cpp')
echo "run-tidy: ${#files[@]} files"
printf '%s\n' "${files[@]}" | xargs -P "$(nproc)" -n 4 clang-tidy -p "$build" --quiet 2>&1 \
  | grep -v -E '^[0-9]+ warnings? generated|^Suppressed|^Use -header-filter' | tee /tmp/kapfix-tidy.log
if grep -q -E 'warning:|error:' /tmp/kapfix-tidy.log; then
  echo "run-tidy: clang-tidy found problems" >&2
  exit 1
fi
echo "run-tidy: clean"
