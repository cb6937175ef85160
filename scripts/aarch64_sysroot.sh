#!/usr/bin/env bash
# Makes an arm64 (aarch64) sysroot of Debian 12's OpenCV and GoogleTest for the cross-build that
# scripts/aarch64.sh runs, without touching the host's dpkg: apt resolves the arm64 packages against
# an empty package database of its own, downloads them, and dpkg -x unpacks each into the sysroot.
# (Installing libopencv-*-dev:arm64 beside the amd64 packages is not possible on Debian 12: apt would
# remove OpenCV, cv_bridge and others.) Safe to run again; reuses what it downloaded.
#
#   bash scripts/aarch64_sysroot.sh DIR     the sysroot in DIR/sysroot, apt's state in DIR/apt
set -euo pipefail
DIR=$(mkdir -p "$1" && cd "$1" && pwd)
SYSROOT=$DIR/sysroot
APT=$DIR/apt
PACKAGES=(libopencv-core-dev libopencv-imgproc-dev libopencv-features2d-dev libopencv-imgcodecs-dev
  libopencv-calib3d-dev libgtest-dev libstdc++6 libc6)

if [ -f "$SYSROOT/.complete" ]; then
  echo "aarch64: sysroot ready in $SYSROOT"
  exit 0
fi
mkdir -p "$APT/lists/partial" "$APT/archives/partial" "$APT/etc/sources.list.d" "$APT/etc/preferences.d"
: >"$APT/status"
# The host's Debian sources, for arm64 only (third-party sources are left out).
for f in /etc/apt/sources.list /etc/apt/sources.list.d/*.sources /etc/apt/sources.list.d/*.list; do
  [ -f "$f" ] || continue
  grep -q "deb.debian.org\|debian.org/debian\|/debian-security\|/debian " "$f" 2>/dev/null || continue
  cp "$f" "$APT/etc/sources.list.d/"
done
[ -f /etc/apt/sources.list ] && grep -q "debian" /etc/apt/sources.list && cp /etc/apt/sources.list "$APT/etc/sources.list"
touch "$APT/etc/sources.list"
OPTS=(-o "APT::Architecture=arm64" -o "APT::Architectures::=arm64" -o "Dir::State=$APT" -o "Dir::State::lists=$APT/lists"
  -o "Dir::State::status=$APT/status" -o "Dir::Cache=$APT" -o "Dir::Cache::archives=$APT/archives"
  -o "Dir::Etc::sourcelist=$APT/etc/sources.list" -o "Dir::Etc::sourceparts=$APT/etc/sources.list.d"
  -o "Dir::Etc::preferencesparts=$APT/etc/preferences.d" -o "Debug::NoLocking=1" -o "APT::Install-Recommends=false")
echo "aarch64: resolving and downloading arm64 packages (about 170 MB the first time)"
apt-get "${OPTS[@]}" -qq update
apt-get "${OPTS[@]}" -qq -y --download-only install "${PACKAGES[@]}" >/dev/null
rm -rf "$SYSROOT"
mkdir -p "$SYSROOT"
for deb in "$APT"/archives/*.deb; do
  dpkg -x "$deb" "$SYSROOT"
done
# Absolute symbolic links inside the sysroot point into it, not at the host's files.
find "$SYSROOT" -type l -lname '/*' | while read -r link; do
  ln -sfn "$SYSROOT$(readlink "$link")" "$link"
done
# dpkg's alternatives are not run by dpkg -x: the reference BLAS and LAPACK take their usual names.
LIB=$SYSROOT/usr/lib/aarch64-linux-gnu
for lib in blas lapack; do
  [ -e "$LIB/lib$lib.so.3" ] || ln -s "$lib/lib$lib.so.3" "$LIB/lib$lib.so.3"
done
touch "$SYSROOT/.complete"
echo "aarch64: sysroot ready in $SYSROOT ($(du -sh "$SYSROOT" | cut -f1))"
