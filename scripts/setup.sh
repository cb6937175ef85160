#!/usr/bin/env bash
# Installs what enhanced_orb needs on Debian 12 (apt packages by name, only those missing) and
# builds the package standalone: build files in build/, the catkin devel space in devel/ (so that
# rosrun finds the executables). Safe to run again.
#
#   bash scripts/setup.sh            install and build
#   source devel/setup.bash    afterwards, for rosrun / roslaunch / rostest
set -euo pipefail
# Debian's python3 must come first: catkin needs its catkin_pkg.
export PATH=/usr/bin:/bin:/usr/sbin:/sbin:$PATH
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)

PACKAGES=(
  # build
  build-essential cmake catkin libopencv-dev libgtest-dev libbenchmark-dev pybind11-dev python3-dev python3-setuptools
  libroscpp-dev libnodeletlib-dev libnodelet-dev libimage-transport-dev libcv-bridge-dev librosbag-dev libmessage-filters-dev
  libdynamic-reconfigure-config-init-mutex-dev python3-dynamic-reconfigure libdiagnostic-updater-dev
  ros-message-generation ros-message-runtime ros-std-msgs ros-sensor-msgs ros-diagnostic-msgs ros-cmake-modules
  # run and test
  rosbash rospack-tools python3-roslaunch python3-rosmaster python3-rostopic python3-rosnode
  python3-rosservice python3-rosparam python3-rosbag python3-rostest librostest-dev
  image-transport-tools libnodeletlib-tools python3-rospy python3-sensor-msgs python3-std-msgs
  python3-numpy python3-opencv python3-cv-bridge python3-matplotlib python3-diagnostic-msgs
  python3-tf2-msgs python3-geometry-msgs python3-pytest
  # demo data, viewer, checks
  visp-images-data rviz xvfb xauth clang-format catkin-lint
  # fuzzing and sanitizers
  clang libclang-rt-14-dev valgrind
)

bash "$ROOT/scripts/install_packages.sh" setup "${PACKAGES[@]}"

echo "setup: building in $ROOT/build"
cmake -S "$ROOT" -B "$ROOT/build" -DCATKIN_DEVEL_PREFIX="$ROOT/devel" -DCMAKE_BUILD_TYPE=Release \
  -DPYTHON_EXECUTABLE=/usr/bin/python3 >"$ROOT/build.log" 2>&1 \
  || { tail -n 40 "$ROOT/build.log"; exit 1; }
make -C "$ROOT/build" -j"$(nproc)" all tests >>"$ROOT/build.log" 2>&1 || { grep -E "error|Error" "$ROOT/build.log" | head -n 40; exit 1; }
# catkin caches the environment of run_tests (PYTHONPATH, LD_LIBRARY_PATH) at configure time, from
# the devel folders that exist then: configure once more now that the first build made them.
cmake "$ROOT/build" >>"$ROOT/build.log" 2>&1
echo "setup: built (log: build.log)"

# The embedded demo bag is built here, not committed.
if [ ! -f "$ROOT/bags/demo.bag" ]; then
  python3 "$ROOT/bags/make_demo_bag.py" "$ROOT/bags/demo.bag"
fi
