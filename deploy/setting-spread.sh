#!/bin/sh
# How many non-test source files name a setting (issue 11's figure: at most 3, its field, its
# use, and the station only if it needs a special editor). Prints the count, then the files.
#   deploy/setting-spread.sh dead_band_px
#   deploy/setting-spread.sh --all     every field with a (setting) option in proto/, one line
#                                      each: count, name, files
#   deploy/setting-spread.sh --check   --all, and fails when a setting is in more than 3 files
#                                      and is not one of the exceptions below (a ctest)
#
# A file names setting NAME where NAME is the setting, not merely the same word:
#   - a proto field declared NAME (`optional float NAME = 3`),
#   - a protobuf accessor or a member: `.NAME`, `->NAME`, `set_NAME(`, `has_NAME(`, `clear_NAME(`,
#     `mutable_NAME(` (a struct member named like the setting is a hand copy of it),
#   - the name quoted: "NAME" (VisitFields, JSON keys of the config file, schema look-ups),
#   - protoc's field-number constant (`kGainDbFieldNumber` for gain_db).
# Comment lines do not count. A bare word (a parameter, a local, a member used inside its own struct) is not counted: for
# names such as `fps`, `scale`, `p`, `mode` or `camera` it is almost always something else.
# What the patterns still cannot tell apart (another message's field or another struct's member
# of the same name) is listed in COLLISIONS, file by file, with what it is there; those files
# are shown but not counted.
set -eu
cd "$(dirname "$0")/.."

# name|file|what it is there. A file listed here for a name is not counted for that setting.
COLLISIONS='
patch_size_px|proto/kapfix/v1/slices.proto|SspReport.patch_size_px: the patch an SSP run used, a result
patch_size_px|agent/modes/report_messages.cpp|fills SspReport.patch_size_px (a result)
patch_size_px|agent/modes/report_messages.hpp|SspReport input struct (a result)
dc_hysteresis_px|proto/kapfix/v1/slices.proto|SspReport.dc_hysteresis_px: the hysteresis an SSP run used, a result
window_s|groundstation/status/lock_quality.cpp|LockQuality::window_s: the telemetry window the station averages over
window_s|groundstation/status/lock_quality.hpp|LockQuality::window_s: the telemetry window the station averages over
exposure_ms|proto/kapfix/v1/photo.proto|PhotoMeta.exposure_ms: the exposure a photo was taken with, a result
exposure_ms|agent/photos/photo_quality.cpp|fills PhotoMeta.exposure_ms from ShutterShot::exposure_ms: the exposure a photo was planned for, a result
deadline_frames|common/selection/slice_selection_options.hpp|SliceSelectionOptions::deadline_frames: the run limit common/ takes
deadline_frames|common/selection/slice_selection.cpp|SliceSelectionOptions::deadline_frames: the run limit common/ takes
deadline_frames|tools/analyze/ssp_command.cpp|kapfix-analyze ssp --deadline-frames (an offline run)
deadline_frames|groundstation/slices/ssp_panel.cpp|the station SSP panel sends SetMode with its deadline (the command, not a setting edit)
'

# Names the patterns cannot count at all (the word is a field of many messages and a member of
# many structs): shown, never checked. Counting them needs the compiler, not grep.
UNCOUNTABLE='name mode camera fps scale channel p i d axis strategy sampling subpixel shutter controller slice_count'

# Settings allowed in more than 3 files, each with why (or with what is left to do), one a line:
#   name|why
# None is, today: every setting goes through the schema (issue 11).
EXCEPTIONS='
gain_db|a camera control: each backend that has it is one of its uses (Aravis, V4L2, sim), through the seam FrameSource::Apply(CameraSettings)
exposure_us|a camera control: each backend that has it is one of its uses (Aravis, V4L2); the config merge also names it: a fixed exposure and automatic exposure exclude each other
auto_exposure|a camera control: each backend that has it is one of its uses (Aravis, V4L2, sim); the config merge also names it: a fixed exposure and automatic exposure exclude each other
'

files_naming() {
  name=$1
  # protoc's field-number constant names the field too: gain_db -> kGainDbFieldNumber.
  camel=$(printf '%s' "$name" | sed -E 's/(^|_)([a-z0-9])/\U\2/g')
  pattern="\"$name\"|(\\.|->)$name\\b|\\b(set|has|clear|mutable)_$name\\(|\\bk${camel}FieldNumber\\b|^[[:space:]]*(optional[[:space:]]+|repeated[[:space:]]+)?[A-Za-z0-9_.]+[[:space:]]+$name[[:space:]]*="
  # A comment line (// or #) that mentions the setting is no use of it.
  git ls-files -- '*.cpp' '*.hpp' '*.proto' '*.h' '*.cc' '*.py' ':!tests/**' ':!build/**' |
    xargs grep -HE -- "$pattern" | grep -vE '^[^:]+:[[:space:]]*(//|#)' | cut -d: -f1 | sort -u ||
    true
}

collisions_of() {
  printf '%s\n' "$COLLISIONS" | awk -F'|' -v n="$1" '$1 == n { print $2 }'
}

counted_files() {
  all=$(files_naming "$1")
  skip=$(collisions_of "$1")
  for f in $all; do
    if ! printf '%s\n' "$skip" | grep -qxF "$f"; then echo "$f"; fi
  done
}

is_uncountable() {
  for word in $UNCOUNTABLE; do
    if [ "$word" = "$1" ]; then return 0; fi
  done
  return 1
}

exception_of() {
  printf '%s\n' "$EXCEPTIONS" | awk -F'|' -v n="$1" '$1 == n { print $2 }'
}

setting_names() {
  # A setting is a field declared with a `(setting)` option: "optional float p = 2 [(setting)".
  grep -h '\[(setting)' proto/kapfix/v1/*.proto |
    sed -E 's/^ *(optional +)?[A-Za-z0-9_.]+ +([a-z0-9_]+) *=.*/\2/' | sort -u
}

case "${1:-}" in
  --all | --check)
    failed=0
    report=$(for name in $(setting_names); do
      if is_uncountable "$name"; then
        printf '  - %-22s (a word of many messages and structs: not counted)\n' "$name"
        continue
      fi
      files=$(counted_files "$name")
      count=$(printf '%s\n' "$files" | grep -c . || true)
      printf '%3d %-22s %s\n' "$count" "$name" "$(printf '%s' "$files" | tr '\n' ' ')"
    done | sort -n)
    printf '%s\n' "$report"
    if [ "$1" = "--check" ]; then
      # A collision whose file no longer names the word is stale: the list must stay true.
      printf '%s\n' "$COLLISIONS" | grep . | while IFS='|' read -r name file what; do
        if ! files_naming "$name" | grep -qxF "$file"; then
          echo "FAIL: stale collision: $file no longer names $name ($what)"
          echo stale >"${TMPDIR:-/tmp}/setting-spread.$$"
        fi
      done
      if [ -e "${TMPDIR:-/tmp}/setting-spread.$$" ]; then
        rm -f "${TMPDIR:-/tmp}/setting-spread.$$"
        failed=1
      fi
      for name in $(setting_names); do
        is_uncountable "$name" && continue
        count=$(counted_files "$name" | grep -c . || true)
        why=$(exception_of "$name")
        if [ "$count" -le 3 ]; then
          if [ -n "$why" ]; then
            echo "FAIL: stale exception: $name is in $count files now; drop it from EXCEPTIONS"
            failed=1
          fi
          continue
        fi
        if [ -n "$why" ]; then
          echo "exception: $name in $count files: $why"
        else
          echo "FAIL: $name is named in $count non-test source files (at most 3)"
          failed=1
        fi
      done
    fi
    exit "$failed"
    ;;
esac

name=${1:?usage: setting-spread.sh SETTING_NAME | --all | --check}
files=$(counted_files "$name")
count=$(printf '%s\n' "$files" | grep -c . || true)
echo "$name: $count non-test source files"
printf '%s\n' "$files" | grep . | sed 's/^/  /' || true
skipped=$(collisions_of "$name")
if [ -n "$skipped" ]; then
  echo "not counted (the same word, another thing):"
  printf '%s\n' "$COLLISIONS" | awk -F'|' -v n="$name" '$1 == n { print "  " $2 ": " $3 }'
fi
