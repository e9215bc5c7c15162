#!/bin/sh
# How many non-test source files name a setting (issue 11's figure: at most 3, its field, its
# use, and the station only if it needs a special editor). Prints the count, then the files.
#   deploy/setting-spread.sh dead_band_px
#   deploy/setting-spread.sh --all     every field with a (setting) option in proto/, one line
#                                      each: count, name, files
set -eu
cd "$(dirname "$0")/.."

files_naming() {
  git ls-files -- '*.cpp' '*.hpp' '*.proto' '*.h' '*.cc' '*.py' ':!tests/**' ':!build/**' |
    xargs grep -lw -- "$1" || true
}

if [ "${1:-}" = "--all" ]; then
  # A setting is a field declared with a `(setting)` option: "optional float p = 2 [(setting)".
  names=$(grep -h '\[(setting)' proto/kapfix/v1/*.proto |
            sed -E 's/^ *(optional +)?[A-Za-z0-9_.]+ +([a-z0-9_]+) *=.*/\2/' | sort -u)
  for name in $names; do
    files=$(files_naming "$name")
    count=$(printf '%s\n' "$files" | grep -c . || true)
    printf '%3d %-22s %s\n' "$count" "$name" "$(printf '%s' "$files" | tr '\n' ' ')"
  done | sort -n
  exit 0
fi

name=${1:?usage: setting-spread.sh SETTING_NAME | --all}
files=$(files_naming "$name")
count=$(printf '%s\n' "$files" | grep -c . || true)
echo "$name: $count non-test source files"
printf '%s\n' "$files" | grep . | sed 's/^/  /' || true
