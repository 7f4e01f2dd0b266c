#!/usr/bin/env bash
# Installs a Linework package on a fresh Debian 12 the way a user does, and runs it there: a
# minimal bookworm (debootstrap --variant=minbase) in a temporary folder, `apt-get install
# ./linework_*.deb` inside it (the dependencies come from the Debian mirror), then `linework-cli
# info` on the installed demo study, `linework --version` and `linework --help` in German.
# Needs root, debootstrap and the network, and takes minutes, so it is not a CTest test
# (tests/installer/package_test.sh is); docs/packaging.md records its last result.
#
# Usage: scripts/check_fresh_install.sh PATH/linework_VERSION_ARCH.deb [MIRROR]
set -euo pipefail

if [ $# -lt 1 ] || [ ! -f "$1" ]; then
  echo "usage: scripts/check_fresh_install.sh PATH/linework_VERSION_ARCH.deb [MIRROR]" >&2
  exit 2
fi
deb=$(realpath "$1")
mirror=${2:-http://deb.debian.org/debian}
[ "$(id -u)" -eq 0 ] || { echo "check_fresh_install: debootstrap and chroot need root" >&2; exit 2; }
command -v debootstrap >/dev/null || { echo "check_fresh_install: apt-get install debootstrap" >&2; exit 2; }

system=$(mktemp -d "${TMPDIR:-/tmp}/linework-fresh-debian.XXXXXX")
log=$system.log
cleanup() {
  # Never delete through a mounted /proc.
  umount "$system/proc" 2>/dev/null || true
  if mountpoint -q "$system/proc"; then
    echo "check_fresh_install: $system/proc is still mounted; $system left in place" >&2
  else
    rm -rf "$system"
  fi
}
trap cleanup EXIT

echo "check_fresh_install: a minimal Debian 12 in $system (log: $log)"
debootstrap --variant=minbase bookworm "$system" "$mirror" >"$log" 2>&1 ||
  { tail -n 20 "$log"; echo "check_fresh_install: debootstrap failed" >&2; exit 1; }
# What a Debian 12 installation's sources are: the release, its updates and security.
cat >"$system/etc/apt/sources.list" <<EOF
deb $mirror bookworm main
deb $mirror bookworm-updates main
deb http://deb.debian.org/debian-security bookworm-security main
EOF
mount -t proc proc "$system/proc"
cp "$deb" "$system/tmp/"
in_system() { chroot "$system" env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin HOME=/root "$@"; }

echo "check_fresh_install: apt-get install ./tmp/$(basename "$deb")"
in_system apt-get update -qq >>"$log" 2>&1
in_system sh -c "cd / && DEBIAN_FRONTEND=noninteractive apt-get install -y ./tmp/$(basename "$deb")" \
  >>"$log" 2>&1 || { tail -n 30 "$log"; echo "check_fresh_install: apt-get install failed" >&2; exit 1; }
echo "check_fresh_install: installed; apt: $(grep -E 'newly installed' "$log" | tail -n 1)"

echo "\$ linework-cli info /usr/share/linework/demo/ct_head_ge_tilt"
in_system linework-cli info /usr/share/linework/demo/ct_head_ge_tilt
echo "\$ linework --version"
in_system linework --version
echo "\$ LC_ALL=de_DE.UTF-8 linework --help | head -n 2"
in_system env LC_ALL=de_DE.UTF-8 linework --help 2>/dev/null | head -n 2
echo "check_fresh_install: PASS"
