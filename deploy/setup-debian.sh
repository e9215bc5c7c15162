#!/usr/bin/env bash
# Installs every Debian package that kapfix's build, tests, benchmarks and demo need.
# Idempotent: packages already present are skipped by apt; safe to run again.
# Usage: sudo deploy/setup-debian.sh   (or as root)
set -euo pipefail

packages=(
  # toolchain
  build-essential cmake ninja-build pkg-config git
  clang clang-tidy clang-format libclang-rt-14-dev
  # vision core
  libopencv-dev libeigen3-dev opencv-doc libboost-math-dev
  # link
  libzmq3-dev cppzmq-dev libprotobuf-dev protobuf-compiler libsodium-dev
  # station
  qt6-base-dev libqcustomplot-dev libgl-dev xvfb xauth
  # agent camera backends (SPEC §8: aravis needs libusb's -dev package beside it)
  libaravis-dev libusb-1.0-0-dev
  # libraries used instead of home-grown code: CLI parsing, logging, JSON
  libcli11-dev libspdlog-dev nlohmann-json3-dev
  # tests and benchmarks
  libgtest-dev libgmock-dev googletest libbenchmark-dev
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup-debian: all ${#packages[@]} packages already installed"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "setup-debian: installing ${#missing[@]} packages: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
echo "setup-debian: done"
