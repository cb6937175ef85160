#!/usr/bin/env bash
# Installs the built package to a scratch folder and builds, against that install only, two programs
# as their users wrote them (test/install: one for cv::ORB, one for ORB-SLAM3's ORBextractor, C++11),
# with only the type changed, then runs both on a EuRoC frame, and a Python program written for cv2
# against the installed Python module. One JUnit report per program.
#
#   bash scripts/install_check.sh RESULTS_DIR      (after scripts/setup.sh; scripts/test.sh calls it)
set -uo pipefail
export PATH=/usr/bin:/bin:/usr/sbin:/sbin:$PATH
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
RESULTS=${1:?RESULTS_DIR}
LOG=$ROOT/build/install_check.log
mkdir -p "$RESULTS"
: >"$LOG"
# The install lives outside the package folder: roslaunch looks for launch files anywhere below it,
# and a second pipeline.launch there makes `roslaunch enhanced_orb pipeline.launch` ambiguous.
WORK=$(mktemp -d "${TMPDIR:-/tmp}/enhanced_orb_install_check.XXXXXX")
trap 'rm -rf "$WORK"' EXIT
report() {  # PROGRAM PASSED(0/1)
  if [ "$2" = 0 ]; then
    printf '<testsuites><testsuite name="installed" tests="1" failures="0"><testcase classname="installed" name="%s"/></testsuite></testsuites>\n' \
      "$1" >"$RESULTS/installed-$1.xml"
  else
    printf '<testsuites><testsuite name="installed" tests="1" failures="1"><testcase classname="installed" name="%s"><failure message="see build/install_check.log"/></testcase></testsuite></testsuites>\n' \
      "$1" >"$RESULTS/installed-$1.xml"
    echo "install_check: $1 failed (log: build/install_check.log)"
  fi
}
PROGRAMS=(written_for_cv_orb written_for_orb_slam written_for_cv2)
# Through DESTDIR: catkin's Python install takes the configured prefix, and DESTDIR before it.
PREFIX_IN_BUILD=$(sed -n 's/^CMAKE_INSTALL_PREFIX:PATH=//p' "$ROOT/build/CMakeCache.txt")
PREFIX=$WORK/root$PREFIX_IN_BUILD
FRAME=$(ls "$ROOT"/../shared/data/euroc/V1_01_easy_micro/mav0/cam0/data/*.png 2>/dev/null | head -n 1)
if ! DESTDIR=$WORK/root cmake --install "$ROOT/build" >>"$LOG" 2>&1 \
    || ! cmake -S "$ROOT/test/install" -B "$WORK/build" -DENHANCED_ORB_PREFIX="$PREFIX" >>"$LOG" 2>&1 \
    || ! make -C "$WORK/build" >>"$LOG" 2>&1 || [ -z "$FRAME" ]; then
  [ -n "$FRAME" ] || echo "install_check: no EuRoC frame under ../shared" >>"$LOG"
  for p in "${PROGRAMS[@]}"; do report "$p" 1; done
  exit 1
fi
status=0
for p in "${PROGRAMS[@]}"; do
  if [ "$p" = written_for_cv2 ]; then
    # The install alone: no devel space on the paths.
    (cd "$WORK" && env -u ROS_PACKAGE_PATH PYTHONPATH="$PREFIX/lib/python3/dist-packages" \
      LD_LIBRARY_PATH="$PREFIX/lib" /usr/bin/python3 "$ROOT/test/install/$p.py" "$FRAME" "$PREFIX") >>"$LOG" 2>&1
  else
    "$WORK/build/$p" "$FRAME" >>"$LOG" 2>&1
  fi
  rc=$?
  report "$p" "$rc"
  ((rc == 0)) || status=1
done
exit $status
