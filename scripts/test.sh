#!/usr/bin/env bash
# Installs what is missing, builds, runs every test (gtests, rostests, the Python module's pytest
# tests, a 60 s fuzzing run) and prints "N passed, N failed". Exits non-zero on any failure.
set -uo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bash "$ROOT/scripts/setup.sh" || exit 1
export PATH=/usr/bin:/bin:/usr/sbin:/sbin:$PATH

# rostest starts its own master; keep its logs and state out of the user's ~/.ros.
export ROS_HOME=$(mktemp -d /tmp/enhanced_orb_test.XXXXXX)
export ROS_LOG_DIR=$ROS_HOME/log
# Tests that read the shared data fail, rather than skip, when it is missing.
export ENHANCED_ORB_REQUIRE_DATA=1
rm -rf "$ROOT/build/test_results"
make -C "$ROOT/build" run_tests -j1 >"$ROOT/build/run_tests.log" 2>&1
# The Python module (test/python), from the devel space, against the C++ adapter; beside it the
# ORB-SLAM3 report's start table (test_orbslam3_report.py), the sequence tables' loss intervals
# (test_report_intervals.py) and README's pose summary (test_report_glance.py).
(set +u && source "$ROOT/devel/setup.bash" && cd "$ROOT" && python3 -m pytest -q -p no:cacheprovider test/python \
  --junitxml="$ROOT/build/test_results/enhanced_orb/pytest-python.xml") >"$ROOT/build/pytest.log" 2>&1 \
  || tail -n 30 "$ROOT/build/pytest.log"
[ -s "$ROOT/build/test_results/enhanced_orb/pytest-python.xml" ] \
  || printf '<testsuites><testsuite name="python" tests="1" failures="1"><testcase classname="python" name="pytest">
<failure message="pytest did not run: see build/pytest.log"/></testcase></testsuite></testsuites>\n' \
    >"$ROOT/build/test_results/enhanced_orb/pytest-python.xml"
# The identity tests once more on a build with only the portable kernels (-DENHANCED_ORB_PORTABLE=ON).
PORTABLE="$ROOT/build_portable"
PORTABLE_XML="$ROOT/build/test_results/enhanced_orb/gtest-test_identity_portable.xml"
mkdir -p "$(dirname "$PORTABLE_XML")"
portable_failed() {
  printf '<testsuites><testsuite name="portable" tests="1" failures="1"><testcase classname="portable" name="%s">
<failure message="see build_portable.log"/></testcase></testsuite></testsuites>\n' "$1" >"$PORTABLE_XML"
}
if cmake -S "$ROOT" -B "$PORTABLE" -DENHANCED_ORB_PORTABLE=ON -DCATKIN_DEVEL_PREFIX="$PORTABLE/devel" \
    -DCMAKE_BUILD_TYPE=Release -DPYTHON_EXECUTABLE=/usr/bin/python3 >"$PORTABLE.log" 2>&1 \
    && make -C "$PORTABLE" -j"$(nproc)" test_identity >>"$PORTABLE.log" 2>&1; then
  "$PORTABLE/devel/lib/enhanced_orb/test_identity" --gtest_output=xml:"$PORTABLE_XML" >>"$PORTABLE.log" 2>&1 \
    || [ -s "$PORTABLE_XML" ] || portable_failed "test_identity did not finish"
else
  portable_failed "build"
fi
# The installed package, used by programs written for cv::ORB and for ORB-SLAM3's ORBextractor.
bash "$ROOT/scripts/install_check.sh" "$ROOT/build/test_results/enhanced_orb"
# The ROS-free libraries and gtests once more, cross-built for aarch64 and run under qemu-user.
bash "$ROOT/scripts/aarch64.sh" "$ROOT/build/test_results/enhanced_orb"
# The kernels built for AVX2 must not define a function the linker could pick for the
# whole library (a weak symbol: an inline function or template instance), which a CPU without
# that instruction set would then run.
WEAK_XML="$ROOT/build/test_results/enhanced_orb/kernels-weak-symbols.xml"
weak=$(for o in "$ROOT"/build/CMakeFiles/enhanced_orb_core.dir/src/core/kernels/*avx*.o; do
  nm -C "$o" | grep -E " [WVu] " | sed "s|^|$(basename "$o"): |"; done)
if [ -n "$weak" ] || { [ "$(uname -m)" = x86_64 ] \
    && ! ls "$ROOT"/build/CMakeFiles/enhanced_orb_core.dir/src/core/kernels/*avx*.o >/dev/null 2>&1; }; then
  printf '<testsuites><testsuite name="kernels" tests="1" failures="1"><testcase classname="kernels" name="no_weak_symbols">
<failure message="weak symbols in the AVX kernels, or no AVX kernel objects"/></testcase></testsuite></testsuites>\n' >"$WEAK_XML"
  echo "$weak"
else
  printf '<testsuites><testsuite name="kernels" tests="1" failures="0"><testcase classname="kernels" name="no_weak_symbols"/></testsuite></testsuites>\n' >"$WEAK_XML"
fi
# A short fuzzing run of the core library counts as one more test.
bash "$ROOT/scripts/fuzz.sh" 60 --junit "$ROOT/build/test_results/enhanced_orb/fuzz-core.xml"
python3 "$ROOT/scripts/summarize_tests.py" "$ROOT/build/test_results"
