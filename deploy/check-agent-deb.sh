#!/usr/bin/env bash
# Installs the kapfix-agent .deb into a clean Debian root and checks what a user with a fresh
# board would meet (issue 10): the package's dependencies (runtime libraries only, no Qt, no
# compiler), the keys postinst made (owned by kapfix, mode 0600, the names the shipped config
# uses), `systemd-analyze verify` on the unit, and `kapfix-agent --preflight --sim`.
# Needs root (debootstrap, chroot) and the network (Debian's mirror). Prints the time taken.
# Usage: sudo deploy/check-agent-deb.sh [--base DIR] [BUILD_DIR] [SUITE]
#        BUILD_DIR with kapfix-agent and kapfix-keygen built (default build/default),
#        SUITE the Debian release the build host runs (default: this machine's codename),
#        --package-only: build the .debs and check the agent's dependencies, nothing else
#        (CI: no root or network needed).
#        --base DIR a clean root made earlier by `debootstrap --variant=minbase SUITE DIR`,
#        copied instead of bootstrapping a new one (CI can cache it).
set -euo pipefail
base=""
package_only=0
if [ "${1:-}" = "--package-only" ]; then package_only=1; shift; fi
if [ "${1:-}" = "--base" ]; then base=$2; shift 2; fi
build=${1:-build/default}
suite=${2:-$(. /etc/os-release && echo "$VERSION_CODENAME")}
start=$(date +%s)
fail() { echo "check-agent-deb: FAIL: $*" >&2; exit 1; }
pass() { echo "check-agent-deb: PASS: $*"; }

# 1. The package, built by CPack (agent component only).
out=$(mktemp -d /tmp/kapfix-deb.XXXXXX)
# --package-only (CI, everything built): every package; else the agent's alone.
if [ "$package_only" = 1 ]; then
  (cd "$build" && cpack -G DEB -B "$out" >/dev/null)
else
  (cd "$build" && cpack -G DEB -D CPACK_COMPONENTS_ALL=agent -B "$out" >/dev/null)
fi
deb=$(ls "$out"/kapfix-agent_*.deb)
depends=$(dpkg-deb -f "$deb" Depends)
echo "check-agent-deb: $(basename "$deb"): Depends: $depends"
# Each package name (versions and alternatives stripped) against GUI and toolchain packages.
bad=$(tr ',|' '\n\n' <<<"$depends" | sed -E 's/\(.*//; s/^ *//; s/ *$//' |
      grep -Ei '^(libqt|qt[0-9]|libgl1|libgl-|libx11|g\+\+|gcc(-[0-9]+)?$|cpp|clang|cmake)|-dev$' || true)
if [ -n "$bad" ]; then
  fail "the agent package depends on GUI or build packages: $(echo $bad)"
fi
pass "runtime dependencies only (no Qt, no compiler)"
if [ "$package_only" = 1 ]; then
  ls "$out"/*.deb
  rm -rf "$out"
  exit 0
fi

# 2. A clean root of the same release, with the package installed as apt would.
root=$(mktemp -d /tmp/kapfix-root.XXXXXX)
trap 'umount -l "$root/proc" 2>/dev/null || true; rm -rf "$root" "$out"' EXIT
if [ -n "$base" ]; then
  cp -a "$base/." "$root/"
else
  debootstrap --variant=minbase "$suite" "$root" >/dev/null
fi
echo "check-agent-deb: clean root ready after $(( $(date +%s) - start )) s"
mount -t proc proc "$root/proc"
cp /etc/resolv.conf "$root/etc/resolv.conf"
cp "$deb" "$root/tmp/"
# A board runs systemd (minbase has none): it is there before the package, as on a board.
chroot "$root" apt-get install -y -q systemd >/dev/null
chroot "$root" apt-get install -y -q "/tmp/$(basename "$deb")" >/dev/null
pass "installed into a clean $suite root"

# 3. Keys and configuration.
# Owner by name inside the root (its own /etc/passwd), not the host's.
key_owner=$(chroot "$root" stat -c '%U %a' /etc/kapfix/agent.key)
[ "$key_owner" = "kapfix 600" ] || fail "agent.key is $key_owner, want kapfix 600"
[ -f "$root/etc/kapfix/agent.pub" ] || fail "no agent.pub"
[ -f "$root/etc/kapfix/authorized_keys" ] || fail "no authorized_keys"
grep -q '"/etc/kapfix/agent.key"' "$root/etc/kapfix/agent.json" ||
  fail "agent.json does not name /etc/kapfix/agent.key"
pass "postinst made agent.key (kapfix, 0600), agent.pub and an empty authorized_keys"

# 4. The unit, as systemd reads it.
chroot "$root" systemd-analyze verify /lib/systemd/system/kapfix-agent.service ||
  fail "systemd-analyze verify rejected the unit"
pass "systemd-analyze verify accepts kapfix-agent.service"

# 5. The agent itself, as the service's user.
chroot "$root" setpriv --reuid=kapfix --regid=kapfix --init-groups \
  kapfix-agent --config /etc/kapfix/agent.json --sim --preflight ||
  fail "kapfix-agent --preflight --sim failed"
pass "kapfix-agent --preflight --sim as user kapfix"
echo "check-agent-deb: all checks passed in $(( $(date +%s) - start )) s"
