#!/usr/bin/env bash
# Builds the package with a sanitizer into build/<mode> and runs the test suite there.
#
#   bash scripts/sanitize.sh [address|thread]
#
# address: AddressSanitizer + UndefinedBehaviorSanitizer (leaks too) on every gtest, then every
#   rostest with the sanitizer runtime preloaded into the nodelet manager and the test nodes (rate
#   checks off, 2,000 frames of load instead of 10,000: the chain runs several times slower).
# thread: ThreadSanitizer on the gtests (the library, including its concurrency tests); the
#   nodelet manager and roscpp are not instrumented, so the nodelets are not run under it.
set -uo pipefail
MODE=${1:-address}
case "$MODE" in address|thread) ;; *) echo "sanitize: mode is address or thread" >&2; exit 2 ;; esac
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bash "$ROOT/scripts/setup.sh" || exit 1
export PATH=/usr/bin:/bin:/usr/sbin:/sbin:$PATH
B="$ROOT/build/$MODE"
echo "sanitize: building with $MODE in $B"
configure() {
  cmake -S "$ROOT" -B "$B" -DENHANCED_ORB_SANITIZER="$MODE" -DCATKIN_DEVEL_PREFIX="$B/devel" \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPYTHON_EXECUTABLE=/usr/bin/python3 >>"$B.log" 2>&1
}
mkdir -p "$B"
: >"$B.log"
configure && make -C "$B" -j"$(nproc)" all tests >>"$B.log" 2>&1 && configure \
  || { grep -E "error" "$B.log" | head -n 20; exit 1; }

export ROS_HOME=$(mktemp -d /tmp/enhanced_orb_sanitize.XXXXXX)
export ROS_LOG_DIR=$ROS_HOME/log
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
rm -rf "$B/test_results"
if [ "$MODE" = address ]; then
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 make -C "$B" run_tests_enhanced_orb_gtest -j1 >"$B/run_tests.log" 2>&1
  LD_PRELOAD="$(gcc -print-file-name=libasan.so):$(gcc -print-file-name=libubsan.so)" \
    ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 \
    make -C "$B" run_tests_enhanced_orb_rostest run_tests_enhanced_orb_roslaunch-check -j1 >>"$B/run_tests.log" 2>&1
else
  TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1:suppressions=$ROOT/scripts/tsan.supp" make -C "$B" run_tests_enhanced_orb_gtest -j1 \
    >"$B/run_tests.log" 2>&1
fi
grep -E "ERROR: (Address|Thread|Leak)Sanitizer|runtime error|WARNING: ThreadSanitizer" "$B/run_tests.log" | head -n 20
grep -rlE "ERROR: (Address|Leak)Sanitizer|runtime error|WARNING: ThreadSanitizer" "$ROS_LOG_DIR" 2>/dev/null | head -n 5
python3 "$ROOT/scripts/summarize_tests.py" "$B/test_results"
