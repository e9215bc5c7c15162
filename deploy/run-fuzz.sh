#!/usr/bin/env bash
# Builds the link's libFuzzer targets (preset "fuzz": clang, ASan + UBSan, only the libraries
# they exercise) and runs each for a bounded number of executions over a copy of its kept
# corpus (tests/fuzz/corpus; the checkout stays clean). Fails on any crash, sanitizer finding,
# leak, time-out or broken invariant, leaving the input under build/fuzz/artifacts/.
# Usage: deploy/run-fuzz.sh [runs-per-fuzzer]   (default 60000: 120,000 executions in all)
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-60000}
[[ "$runs" =~ ^[1-9][0-9]*$ ]] || { echo "usage: deploy/run-fuzz.sh [runs-per-fuzzer]" >&2; exit 2; }

fuzzers=(stream_message_decoding_fuzzer command_handling_fuzzer multipart_request_fuzzer
         subscription_sequence_fuzzer)
# [bytes] Longest input tried. Commands: just past kMaxCommandBytes (64 KiB), so the size limit's
# edge is reachable. Stream messages: the decoder's work grows with length only, not in kind;
# the 4 MiB limit itself is covered by tests/proto.
declare -A max_len=([stream_message_decoding_fuzzer]=8192 [command_handling_fuzzer]=65552 [multipart_request_fuzzer]=65552
                 [subscription_sequence_fuzzer]=4096)

start=$(date +%s)
cmake --preset fuzz >/dev/null
cmake --build --preset fuzz -j "$(nproc)" -- --quiet
echo "run-fuzz: configure and build $(($(date +%s) - start)) s"

work=$(mktemp -d "${TMPDIR:-/tmp}/kapfix-fuzz.XXXXXX")
trap 'rm -rf "$work"' EXIT
artifacts=build/fuzz/artifacts
mkdir -p "$artifacts"
status=0
for fuzzer in "${fuzzers[@]}"; do
  cp -r "tests/fuzz/corpus/$fuzzer" "$work/$fuzzer"
  log="$work/$fuzzer.log"
  start=$(date +%s)
  # -timeout [s] per input: any input taking that long is a hang. -rss_limit_mb: ASan's
  # overhead included, far above what one request may cost.
  if "build/fuzz/tests/fuzz/$fuzzer" -runs="$runs" -max_len="${max_len[$fuzzer]}" -timeout=10 \
    -rss_limit_mb=2048 -artifact_prefix="$artifacts/$fuzzer-" "$work/$fuzzer" >"$log" 2>&1; then
    done_runs=$(sed -n 's/^Done \([0-9]*\) runs.*/\1/p' "$log")
    echo "$fuzzer: ${done_runs:-?} runs, no crash, $(($(date +%s) - start)) s"
  else
    tail -n 60 "$log" >&2
    echo "$fuzzer: FAILED after $(($(date +%s) - start)) s; the input is in $artifacts/ (run" \
      "build/fuzz/tests/fuzz/$fuzzer <file> to reproduce; once fixed, add it to" \
      "tests/fuzz/corpus/$fuzzer/)" >&2
    status=1
  fi
done
exit "$status"
