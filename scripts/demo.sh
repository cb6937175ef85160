#!/usr/bin/env bash
# The demo: installs what is missing, builds, makes the demo bag if absent, and plays it through
# the nodelet pipeline (default mode) with the paper preset and the original ORB beside it, all at
# the same budget. Prints progress and a summary table (matches to the previous frame that survive
# RANSAC, keypoints, ms); writes it and annotated frames (default | paper | original) to output/.
#
#   bash scripts/demo.sh [--rviz] [--bag FILE.bag] [--frames N] [--rate R] [--output DIR]
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BAG="$ROOT/bags/demo.bag"
FRAMES=""
RATE=0.5  # three chains (default, paper, baseline) and the monitor share the machine
OUTPUT="$ROOT/output"
RVIZ=false
while (($#)); do
  case "$1" in
    --rviz) RVIZ=true ;;
    --bag) BAG=$(realpath "$2"); shift ;;
    --frames) FRAMES=$2; shift ;;
    --rate) RATE=$2; shift ;;
    --output) OUTPUT=$(realpath -m "$2"); shift ;;
    -h|--help) sed -n '2,7p' "$0"; exit 0 ;;
    *) echo "demo: unknown argument $1 (see --help)" >&2; exit 2 ;;
  esac
  shift
done

bash "$ROOT/scripts/setup.sh"
export PATH=/usr/bin:/bin:/usr/sbin:/sbin:$PATH
set +u
# shellcheck disable=SC1091
source "$ROOT/devel/setup.bash"
set -u

if [ ! -f "$BAG" ]; then  # setup.sh makes the demo bag; another bag must exist
  echo "demo: no bag at $BAG" >&2
  exit 1
fi
if [ -z "$FRAMES" ]; then
  FRAMES=$(python3 -c "import rosbag,sys; print(rosbag.Bag(sys.argv[1]).get_message_count('/cam0/image_raw'))" "$BAG")
fi
if [ "$RVIZ" = true ] && [ -z "${DISPLAY:-}" ]; then
  echo "demo: no display (DISPLAY is unset): rviz not opened"
  RVIZ=false
fi

mkdir -p "$OUTPUT"
echo "demo: playing $BAG ($FRAMES frames) at rate $RATE; ROS log in $OUTPUT/roslaunch.log"
roslaunch enhanced_orb euroc.launch bag:="$BAG" rate:="$RATE" delay:=3 compare:=true rviz:="$RVIZ" \
  >"$OUTPUT/roslaunch.log" 2>&1 &
LAUNCH=$!
trap 'kill -INT $LAUNCH 2>/dev/null || true; wait $LAUNCH 2>/dev/null || true' EXIT
for _ in $(seq 100); do  # the master roslaunch starts
  rosnode list >/dev/null 2>&1 && break
  sleep 0.3
done
status=0
python3 "$ROOT/scripts/demo_monitor.py" --output "$OUTPUT" --frames "$FRAMES" --bag "$BAG" || status=$?
exit $status
