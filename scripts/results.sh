#!/usr/bin/env bash
# Regenerates docs/RESULTS.md, its CSV files and plots (docs/results/) and README's pose summary
# from the shared data: the equal-budget comparison (lighting pairs and EuRoC), real camera motion
# (the EuRoC moving sequence and the KITTI driving excerpts), the paper's evaluation (Tables 2-4,
# Figures 6-7), the benchmarks, the nodelet chain's figures and the aarch64 test run.
#
#   bash scripts/results.sh [EUROC_ASL_DIR [LIGHTING_DIR [MOVING_SEQUENCE_DIR]]]
#   defaults ../shared/data/euroc/V1_01_easy_micro, ../shared/data/lighting and
#   ../shared/data/euroc/MH_01_easy_moving (a EuRoC ASL or KITTI odometry folder with ground truth)
# With COMPARE_DIR set, the comparison's CSV files are kept there (scripts/report.py compare
# COMPARE_DIR docs/RESULTS.md then rewrites its section without running it again).
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
EUROC=$(realpath "${1:-$ROOT/../shared/data/euroc/V1_01_easy_micro}")
LIGHTING=$(realpath "${2:-$ROOT/../shared/data/lighting}")
MOVING=$(realpath "${3:-$ROOT/../shared/data/euroc/MH_01_easy_moving}")
OUT="$ROOT/docs/results"
bash "$ROOT/scripts/setup.sh"
export PATH=/usr/bin:/bin:/usr/sbin:/sbin:$PATH
set +u
# shellcheck disable=SC1091
source "$ROOT/devel/setup.bash"
set -u
mkdir -p "$OUT"
start=$(date +%s)

echo "results: equal budgets on $LIGHTING and $EUROC"
if [ -n "${COMPARE_DIR:-}" ]; then
  mkdir -p "$COMPARE_DIR"
  COMPARE=$(realpath "$COMPARE_DIR")
  KEEP_COMPARE=true
else
  COMPARE=$(mktemp -d)
  KEEP_COMPARE=false
fi
"$ROOT/devel/lib/enhanced_orb/enhanced_orb_compare" --lighting "$LIGHTING" --euroc "$EUROC" --output "$COMPARE"

echo "results: real camera motion on $MOVING (relative pose from every third frame at 1000 features, every"
echo "         sixth at 500 and 2000; stereo tracking at every frame; about 70 minutes)"
SEQUENCES=()
for run in "1000 3" "500 6" "2000 6"; do
  read -r budget every <<<"$run"
  "$ROOT/devel/lib/enhanced_orb/enhanced_orb_compare" --sequence "$MOVING" --budgets "$budget" --sequence-every "$every" \
    --output "$COMPARE/sequence_$budget"
  SEQUENCES+=("$COMPARE/sequence_$budget")
done

# Driving: the KITTI odometry excerpts beside the moving sequence (monocular, every frame, every
# budget; about 10 minutes each per budget here).
DRIVING=()
for excerpt in "$ROOT"/../shared/data/kitti/*/; do
  [ -f "$excerpt/poses.txt" ] || continue
  name=$(basename "$excerpt")
  echo "results: driving on $name"
  "$ROOT/devel/lib/enhanced_orb/enhanced_orb_compare" --sequence "$excerpt" --budgets 500,1000,2000 \
    --output "$COMPARE/driving_$name"
  DRIVING+=("$name")
done

echo "results: evaluation on $EUROC"
"$ROOT/devel/lib/enhanced_orb/enhanced_orb_compare" --paper --euroc "$EUROC" --output "$OUT" --every 19

echo "results: benchmarks"
"$ROOT/devel/lib/enhanced_orb/benchmark_extraction" --frames "$EUROC/mav0/cam0/data" --benchmark_min_time=0.2 \
  --benchmark_repetitions=7 --benchmark_enable_random_interleaving=true \
  --benchmark_out="$OUT/benchmark.json" --benchmark_out_format=json >/dev/null

echo "results: callgrind profile of the enhanced ORB at 1000 features (5 frames)"
PROFILE=$(mktemp -d)
mapfile -t SOME < <(ls "$EUROC"/mav0/cam0/data/*.png | head -n 5)
# Collected inside the stream's call only (judgment, enhancement, extraction): the calls it makes are
# not named here, since each entry of a named function toggles the collection.
valgrind --tool=callgrind --toggle-collect='enhanced_orb::OrbExtractor::extract(cv::Mat const&, enhanced_orb::CameraMotion&*' \
  --callgrind-out-file="$PROFILE/callgrind.out" "$ROOT/devel/lib/enhanced_orb/enhanced_orb_extract" \
  --max-features 1000 "${SOME[@]}" --output "$PROFILE" >/dev/null 2>&1
# Inclusive instruction counts of the stages: what each costs with everything it calls.
callgrind_annotate --inclusive=yes "$PROFILE/callgrind.out" 2>/dev/null \
  | grep -E "PROGRAM TOTALS|enhanced_orb::([A-Z][a-zA-Z]+::)?[a-zA-Z]+\(|cv::Feature2D::compute|cv::FAST\(|cv::resize|cv::threshold\(" \
  | sed -E 's/\?\?\?://; s/^([^)]*\)  [^(]*)\(.*$/\1/' | awk '!seen[$NF]++' >"$OUT/callgrind.txt"
rm -rf "$PROFILE"

echo "results: the ROS-free gtests cross-built for aarch64, under qemu (about 10 minutes)"
bash "$ROOT/scripts/aarch64.sh" "$ROOT/build_aarch64/test_results" || echo "results: some aarch64 tests failed"

echo "results: the nodelet chain"
BAG=$(mktemp -d)/euroc.bag
"$ROOT/devel/lib/enhanced_orb/euroc_to_bag" "$EUROC" "$BAG" >/dev/null
export ROS_HOME=$(mktemp -d)
roslaunch enhanced_orb pipeline.launch >"$ROS_HOME/pipeline.log" 2>&1 &
LAUNCH=$!
# The second camera's chain in the same manager, as a stereo rig runs it.
sleep 5
roslaunch enhanced_orb pipeline.launch camera:=cam1 manager:=/cam0/enhanced_orb_manager >"$ROS_HOME/pipeline1.log" 2>&1 &
LAUNCH1=$!
trap 'kill -INT $LAUNCH $LAUNCH1 2>/dev/null || true; wait $LAUNCH $LAUNCH1 2>/dev/null || true; rm -rf "$(dirname "$BAG")"; [ "$KEEP_COMPARE" = true ] || rm -rf "$COMPARE"' EXIT
python3 "$ROOT/bench/pipeline_benchmark.py" --bag "$BAG" --output "$OUT/pipeline.csv" \
  --stereo-topic /cam1/image_raw --stereo-camera cam1

python3 "$ROOT/scripts/report.py" paper "$OUT"
python3 "$ROOT/scripts/report.py" compare "$COMPARE" "$ROOT/docs/RESULTS.md"
python3 "$ROOT/scripts/report.py" sequence "${SEQUENCES[@]}" "$ROOT/docs/RESULTS.md"
for name in "${DRIVING[@]}"; do
  python3 "$ROOT/scripts/report.py" sequence "$COMPARE/driving_$name" --section "driving_$name" "$ROOT/docs/RESULTS.md"
done
python3 "$ROOT/scripts/report.py" glance "$ROOT/docs/RESULTS.md" "$ROOT/README.md"
python3 "$ROOT/scripts/report.py" aarch64 "$ROOT/build_aarch64/test_results" "$ROOT/docs/RESULTS.md"
echo "results: done in $(( $(date +%s) - start )) s"
