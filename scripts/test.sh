#!/usr/bin/env bash
# Installs what is missing, builds, runs every test (gtests, rostests, a 60 s fuzzing run) and prints
# "N passed, N failed". Exits non-zero on any failure.
set -uo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bash "$ROOT/scripts/setup.sh" || exit 1
export PATH=/usr/bin:/bin:/usr/sbin:/sbin:$PATH

# rostest starts its own master; keep its logs and state out of the user's ~/.ros.
export ROS_HOME=$(mktemp -d /tmp/enhanced_orb_test.XXXXXX)
export ROS_LOG_DIR=$ROS_HOME/log
rm -rf "$ROOT/build/test_results"
make -C "$ROOT/build" run_tests -j1 >"$ROOT/build/run_tests.log" 2>&1
# A short fuzzing run of the core library counts as one more test.
bash "$ROOT/scripts/fuzz.sh" 60 --junit "$ROOT/build/test_results/enhanced_orb/fuzz-core.xml"
python3 "$ROOT/scripts/summarize_tests.py" "$ROOT/build/test_results"
