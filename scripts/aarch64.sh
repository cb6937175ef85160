#!/usr/bin/env bash
# Cross-builds the ROS-free libraries and every ROS-free gtest for aarch64 (arm64) and runs them
# under qemu-user, on an x86-64 Debian 12 machine. Installs g++-aarch64-linux-gnu and qemu-user;
# OpenCV and GoogleTest for arm64 come from Debian's archive into a sysroot of their own
# (scripts/aarch64_sysroot.sh), so the host's packages are never touched.
#
#   bash scripts/aarch64.sh [RESULTS_DIR]   gtest XML reports in RESULTS_DIR (default build_aarch64/test_results)
#
# Under emulation the identity test on every EuRoC frame takes about 25 minutes: here it runs on
# every ENHANCED_ORB_IDENTITY_STRIDE-th frame (default 5 here, 1 on native builds); every kernel
# and instruction-set test runs in full.
set -uo pipefail
export PATH=/usr/bin:/bin:/usr/sbin:/sbin:$PATH
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BUILD=$ROOT/build_aarch64
RESULTS=${1:-$BUILD/test_results}
mkdir -p "$BUILD" "$RESULTS"
LOG=$BUILD/aarch64.log
: >"$LOG"

report_failure() {  # one failed test case standing for a step or test that did not finish
  printf '<testsuites><testsuite name="aarch64" tests="1" failures="1"><testcase classname="aarch64" name="%s">
<failure message="see build_aarch64/aarch64.log"/></testcase></testsuite></testsuites>\n' "$1" >"$RESULTS/aarch64-$1.xml"
  echo "aarch64: $1 failed (log: build_aarch64/aarch64.log)"
}
failed_report() {  # a step the others need did not finish
  report_failure "$1"
  tail -n 30 "$LOG"
  exit 1
}

bash "$ROOT/scripts/install_packages.sh" aarch64 g++-aarch64-linux-gnu qemu-user cmake >>"$LOG" 2>&1 \
  || failed_report install
bash "$ROOT/scripts/aarch64_sysroot.sh" "$BUILD/arm64" >>"$LOG" 2>&1 || failed_report sysroot
SYSROOT=$BUILD/arm64/sysroot

echo "aarch64: cross-building the core library and its gtests"
cmake -S "$ROOT/cmake/ros_free" -B "$BUILD/build" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_TOOLCHAIN_FILE="$ROOT/cmake/aarch64-linux-gnu.cmake" -DENHANCED_ORB_SYSROOT="$SYSROOT" \
  -DENHANCED_ORB_TEST_RESULTS="$RESULTS" >>"$LOG" 2>&1 || failed_report configure
make -C "$BUILD/build" -j"$(nproc)" >>"$LOG" 2>&1 || failed_report build
if grep -q "warning:" "$LOG"; then
  grep "warning:" "$LOG" | head -n 20
fi

echo "aarch64: running the gtests under qemu-aarch64"
export ENHANCED_ORB_IDENTITY_STRIDE=${ENHANCED_ORB_IDENTITY_STRIDE:-5}
export ENHANCED_ORB_REQUIRE_DATA=1  # tests that read ../shared fail, rather than skip, without it
rm -f "$RESULTS"/test_*.xml "$RESULTS"/aarch64-*.xml
(cd "$BUILD/build" && ctest -j"$(nproc)" --output-on-failure --timeout 1500) >>"$LOG" 2>&1
status=$?
# Reports named for the architecture, beside the native ones when RESULTS_DIR is shared; a test
# that crashed under the emulator leaves none and counts as failed.
for t in $(cd "$BUILD/build" && ctest -N | sed -n 's/^ *Test *#[0-9]*: //p'); do
  if [ -s "$RESULTS/$t.xml" ]; then
    mv "$RESULTS/$t.xml" "$RESULTS/aarch64-$t.xml"
  else
    report_failure "$t"
  fi
done
grep -E "tests passed|tests failed|Total Test time" "$LOG" | tail -n 2
exit $status
