#!/usr/bin/env bash
# Installs every Debian package that kapfix's build, tests, benchmarks and demo need.
# Idempotent: packages already present are skipped by apt; safe to run again.
# Usage: sudo deploy/setup-debian.sh             (or as root): the development machine
#        sudo deploy/setup-debian.sh --runtime   the board: only what kapfix-agent needs to run
#                                                (no compiler, no Qt, no Xvfb; normally the
#                                                agent .deb pulls these in itself)
set -euo pipefail

runtime_packages=(
  # libraries kapfix-agent links (Debian 12 names), and what its package scripts use
  libopencv-core406 libopencv-imgproc406 libopencv-imgcodecs406 libopencv-video406
  libopencv-videoio406
  libzmq5 libprotobuf32 libsodium23 libspdlog1.10 libfmt9
  libaravis-0.8-0 libusb-1.0-0 libsystemd0
  # a USB still camera for photos (issue 13)
  libgphoto2-6
  adduser udev kmod
  # opencv-doc: the scene photos that `kapfix-agent --sim` flies over
  opencv-doc
)

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
  # agent camera backends (SPEC §8: aravis needs libusb's -dev package beside it), systemd
  # notification; aravis-tools: the fake GigE Vision camera of the integration test
  libaravis-dev libusb-1.0-0-dev libsystemd-dev aravis-tools
  # a USB still camera for photos (issue 13): libgphoto2
  libgphoto2-dev
  # packaging and its install test (deploy/check-agent-deb.sh)
  debootstrap systemd
  # libraries used instead of home-grown code: CLI parsing, logging, JSON
  libcli11-dev libspdlog-dev nlohmann-json3-dev
  # tests and benchmarks
  libgtest-dev libgmock-dev googletest libbenchmark-dev
  # bench/photo-shutter-pair.sh reads the flights' summary.json
  jq
  # a peer from the .proto files alone: tools/python_client and tools/session in Python
  python3-zmq python3-protobuf
)

if [ "${1:-}" = "--runtime" ]; then packages=("${runtime_packages[@]}"); fi

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
