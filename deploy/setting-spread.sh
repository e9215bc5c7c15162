#!/bin/sh
# How many non-test source files name a setting (issue 11's figure: at most 3, its field, its
# use, and the station only if it needs a special editor). Prints the count, then the files.
#   deploy/setting-spread.sh dead_band_px
set -eu
name=${1:?usage: setting-spread.sh SETTING_NAME}
cd "$(dirname "$0")/.."
files=$(git ls-files -- '*.cpp' '*.hpp' '*.proto' '*.h' '*.cc' '*.py' \
          ':!tests/**' ':!build/**' | xargs grep -lw -- "$name" || true)
count=$(printf '%s\n' "$files" | grep -c . || true)
echo "$name: $count non-test source files"
printf '%s\n' "$files" | grep . | sed 's/^/  /' || true
