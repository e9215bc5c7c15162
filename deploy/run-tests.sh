#!/usr/bin/env bash
# Builds kapfix with warnings as errors and runs every test (CTest).
# Installs the Debian packages first when any is missing (deploy/setup-debian.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
bash deploy/setup-debian.sh
cmake --preset ci
cmake --build --preset ci -j "$(nproc)"
ctest --preset ci -j "$(nproc)"
