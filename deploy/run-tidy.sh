#!/usr/bin/env bash
# clang-tidy over our own sources, with the compile commands of the CI build.
# Usage: deploy/run-tidy.sh [build-dir]   (default build/ci; configure it first)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build/ci}
[ -f "$build/compile_commands.json" ] || { echo "run-tidy: no $build/compile_commands.json (configure first)" >&2; exit 2; }
# The folders whose files cost most (the most headers: Qt, then protobuf and OpenCV) first, so
# that the two clang-tidy processes end close together.
files=()
for dir in groundstation agent bench tools proto common link; do
  mapfile -t -O "${#files[@]}" files < <(git ls-files "$dir/*.cpp")
done
echo "run-tidy: ${#files[@]} files"
log=$(mktemp "${TMPDIR:-/tmp}/kapfix-tidy.XXXXXX")
db=$(mktemp -d "${TMPDIR:-/tmp}/kapfix-tidy-db.XXXXXX")
trap 'rm -rf "$log" "$db"' EXIT
# A file that two targets compile (its program and its test, two benchmarks) has a compile
# command for each, and clang-tidy checks it once per command: keep only the first (the program's).
if command -v jq >/dev/null; then
  jq 'reduce .[] as $c ({}; if has($c.file) then . else .[$c.file] = $c end) | [.[]]' \
    "$build/compile_commands.json" >"$db/compile_commands.json"
else
  cp "$build/compile_commands.json" "$db/"
fi
# The findings in the log decide, not clang-tidy's exit status (xargs reports 123 for any
# non-zero one); only "could not run clang-tidy at all" (124..127) fails here. grep -v exits 1
# when every line is filtered out (a clean run), so its status is ignored.
status=0
printf '%s\n' "${files[@]}" | xargs -P "$(nproc)" -n 1 clang-tidy -p "$db" --quiet >"$log" 2>&1 || status=$?
if [ "$status" -ge 124 ]; then
  cat "$log" >&2
  echo "run-tidy: could not run clang-tidy (xargs exit $status)" >&2
  exit 1
fi
{ grep -v -E '^[0-9]+ warnings? generated|^Suppressed|^Use -header-filter' "$log" || true; } >&2
if grep -q -E 'warning:|error:' "$log"; then
  echo "run-tidy: clang-tidy found problems" >&2
  exit 1
fi
echo "run-tidy: clean"
