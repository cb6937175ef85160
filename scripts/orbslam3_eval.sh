#!/usr/bin/env bash
# enhanced_orb inside ORB-SLAM3 v1.0: builds a stock and an adapted copy of a user's ORB-SLAM3 source
# tree (the adapted one with enhanced_orb::OrbSlamExtractor in place of its ORBextractor, as
# docs/ORB_SLAM3.md describes), runs both, stereo and monocular, on a EuRoC folder under every light
# condition of the sequence evaluation (enhanced_orb_compare --write-sequence), and prints a table
# (scripts/report.py orbslam3):
# frames tracked, "Fail to track local map" events, map resets, maps, ATE RMSE after alignment.
#
#   bash scripts/orbslam3_eval.sh SRC VOCABULARY DATA [WORK]
#
#   SRC         an ORB-SLAM3 v1.0 source tree (git clone of UZ-SLAMLab/ORB_SLAM3, tag v1.0); it is
#               copied, never changed
#   VOCABULARY  ORBvoc.txt (the official one, unpacked from Vocabulary/ORBvoc.txt.tar.gz); the same
#               file for both builds. scripts/orbslam3/train_vocabulary.sh trains a replacement.
#   DATA        a EuRoC ASL folder with cam0, cam1 and state_groundtruth_estimate0 (e.g.
#               ../shared/data/euroc/MH_01_easy_moving)
#   WORK        scratch folder for the builds, frames and runs (default /tmp/enhanced_orb_orbslam3);
#               builds are kept, so a second run only runs
#
# Environment: REPEATS (default 3: stereo runs per cell; ORB-SLAM3 is multi-threaded and not
# deterministic), MONO_REPEATS (default twice REPEATS: monocular runs per cell, each a draw of the
# start, below; three draws were seen to rank two starts either way),
# CONDITIONS (default: every condition of the sequence evaluation), SENSORS (default "stereo mono"),
# PRESETS (default "default motion": the adapted build runs once per preset, through
# ENHANCED_ORB_CONFIG=config/<preset>.yaml, docs/ORB_SLAM3.md), PANGOLIN_SRC (a Pangolin v0.6
# source tree to build into WORK when Pangolin is not installed; the viewer stays off),
# START_EVERY and START_FRAMES (default 10 and 10: with "mono" in SENSORS, each build also starts
# from every START_EVERY-th frame of each condition for START_FRAMES frames, to show how soon its
# monocular map starts; START_EVERY=0 skips this), START_SEEDS (default "1": the seeds of the
# two-view RANSAC each start is run with, below).
#
# A monocular map starts from the first pair of frames whose two-view reconstruction passes
# ORB-SLAM3's checks, and that reconstruction is a RANSAC whose seed ORB-SLAM3 fixes at 0: one run's
# start is one draw, the same in every repeat. Both copies read that seed from ORBSLAM3_EVAL_SEED
# instead (0 when unset, as shipped; nothing else changes), and repeat r of a run draws seed r, so
# that the repeats of a monocular run are draws of its start, for both builds alike. glibc's
# srand() takes 0 as 1: seed 1 is the start as shipped, and seeds 0 and 1 are one draw.
#
# ORB-SLAM3 is GPL-3: it is built and run here for evaluation only, in WORK; nothing of it enters
# this repository. Time here (2 cores): about 70 minutes to build both copies, about 15 s per run
# (216 runs with the default repeats and two presets), about 1.5 s per monocular start (720).
set -euo pipefail
export PATH=/usr/bin:/bin:/usr/sbin:/sbin:$PATH
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
if (($# < 3)); then
  sed -n '2,/^set -euo/p' "$0" | sed '$d' | sed 's/^# \{0,1\}//'
  exit 2
fi
SRC=$(realpath "$1")
VOCABULARY=$(realpath "$2")
DATA=$(realpath "$3")
WORK=$(realpath -m "${4:-/tmp/enhanced_orb_orbslam3}")
REPEATS=${REPEATS:-3}
MONO_REPEATS=${MONO_REPEATS:-$((2 * REPEATS))}
SENSORS=${SENSORS:-stereo mono}
PRESETS=${PRESETS:-default motion}
for p in $PRESETS; do
  [ -f "$ROOT/config/$p.yaml" ] || { echo "orbslam3_eval: no preset file config/$p.yaml" >&2; exit 2; }
done
JOBS=$(nproc)
for f in "$SRC/CMakeLists.txt" "$SRC/src/ORBextractor.cc" "$SRC/include/ORBextractor.h" \
  "$SRC/Examples/Stereo/stereo_euroc.cc" "$SRC/Examples/Monocular/mono_euroc.cc"; do
  [ -f "$f" ] || { echo "orbslam3_eval: $f is missing: SRC must be an ORB-SLAM3 v1.0 source tree" >&2; exit 2; }
done
[ -f "$VOCABULARY" ] || { echo "orbslam3_eval: no vocabulary file $VOCABULARY" >&2; exit 2; }
[ -f "$DATA/mav0/cam0/data.csv" ] || [ -f "$DATA/cam0/data.csv" ] \
  || { echo "orbslam3_eval: $DATA is not a EuRoC ASL folder (no mav0/cam0/data.csv)" >&2; exit 2; }
mkdir -p "$WORK"
log() { echo "orbslam3_eval: $*"; }

# --- what it needs ---------------------------------------------------------------------------------
PACKAGES=(build-essential cmake libopencv-dev libeigen3-dev libboost-serialization-dev libssl-dev
  python3-numpy libglew-dev libepoxy-dev libgl1-mesa-dev libwayland-dev libxkbcommon-dev wayland-protocols)
bash "$ROOT/scripts/install_packages.sh" orbslam3_eval "${PACKAGES[@]}"
[ -f "$ROOT/devel/lib/libenhanced_orb_core.so" ] && [ -x "$ROOT/devel/lib/enhanced_orb/enhanced_orb_compare" ] \
  || bash "$ROOT/scripts/setup.sh"

# --- Pangolin (ORB-SLAM3 links it even with the viewer off) ----------------------------------------
PANGOLIN_ARGS=()
if [ -n "${PANGOLIN_SRC:-}" ]; then
  if [ ! -f "$WORK/pangolin/install/.done" ]; then
    log "building Pangolin from $PANGOLIN_SRC (log: $WORK/pangolin/build.log)"
    rm -rf "$WORK/pangolin" && mkdir -p "$WORK/pangolin"
    cp -r "$PANGOLIN_SRC" "$WORK/pangolin/src"
    # gcc 12 no longer includes <limits> through <cmath>
    grep -q "#include <limits>" "$WORK/pangolin/src/include/pangolin/gl/colour.h" \
      || sed -i 's|#include <stdexcept>|#include <stdexcept>\n#include <limits>|' \
        "$WORK/pangolin/src/include/pangolin/gl/colour.h"
    cmake -S "$WORK/pangolin/src" -B "$WORK/pangolin/build" -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_INSTALL_PREFIX="$WORK/pangolin/install" -DBUILD_EXAMPLES=OFF -DBUILD_TOOLS=OFF \
      -DBUILD_PANGOLIN_PYTHON=OFF -DBUILD_PANGOLIN_VIDEO=OFF -DBUILD_TESTS=OFF \
      >"$WORK/pangolin/build.log" 2>&1
    make -C "$WORK/pangolin/build" -j"$JOBS" install >>"$WORK/pangolin/build.log" 2>&1 \
      || { tail -n 30 "$WORK/pangolin/build.log"; exit 1; }
    touch "$WORK/pangolin/install/.done"
  fi
  PANGOLIN_ARGS=(-DCMAKE_PREFIX_PATH="$WORK/pangolin/install")
  export LD_LIBRARY_PATH="$WORK/pangolin/install/lib:${LD_LIBRARY_PATH:-}"
fi

# The two-view RANSAC's seed read from ORBSLAM3_EVAL_SEED (0 when unset) in the copy in DIR; returns
# 1 when the copy reads it already.
seed_from_environment() {  # DIR
  local file=$1/src/TwoViewReconstruction.cc
  grep -q ORBSLAM3_EVAL_SEED "$file" && return 1
  grep -q 'DUtils::Random::SeedRandOnce(0);' "$file" \
    || { echo "orbslam3_eval: $file does not seed its RANSAC with 0: not ORB-SLAM3 v1.0" >&2; exit 2; }
  sed -i -e '1i #include <cstdlib>' -e 's/DUtils::Random::SeedRandOnce(0);/DUtils::Random::SeedRandOnce(std::getenv("ORBSLAM3_EVAL_SEED") ? std::atoi(std::getenv("ORBSLAM3_EVAL_SEED")) : 0);/' "$file"
}

# --- the two copies ---------------------------------------------------------------------------------
# Both: C++14 (gcc 12 defaults to C++17, where Eigen's aligned allocation differs from the C++14
# library's), only the two EuRoC examples, the viewer off. The adapted copy also: ORBextractor.h
# replaced by a class deriving from enhanced_orb::OrbSlamExtractor, ORBextractor.cc left out,
# enhanced_orb_core linked. Thirdparty (DBoW2, g2o) is built once and shared.
prepare_copy() {  # NAME
  local dst=$WORK/$1
  rm -rf "$dst" && mkdir -p "$dst/Examples/Stereo" "$dst/Examples/Monocular"
  cp -r "$SRC/include" "$SRC/src" "$dst/"
  [ -d "$SRC/cmake_modules" ] && cp -r "$SRC/cmake_modules" "$dst/"
  cp "$SRC"/Examples/Stereo/{stereo_euroc.cc,EuRoC.yaml} "$dst/Examples/Stereo/"
  cp "$SRC"/Examples/Monocular/{mono_euroc.cc,EuRoC.yaml} "$dst/Examples/Monocular/"
  if [ "$1" = stock ]; then
    cp -r "$SRC/Thirdparty" "$dst/"
  else
    ln -s ../stock/Thirdparty "$dst/Thirdparty"
  fi
  sed -i 's/ORB_SLAM3::System::STEREO, *true)/ORB_SLAM3::System::STEREO, false)/' "$dst/Examples/Stereo/stereo_euroc.cc"
  sed -i 's/ORB_SLAM3::System::MONOCULAR, *true)/ORB_SLAM3::System::MONOCULAR, false)/' \
    "$dst/Examples/Monocular/mono_euroc.cc"
  # The library part of CMakeLists.txt (everything before "# Build examples"), then two examples.
  sed -n '/^# Build examples/q;p' "$SRC/CMakeLists.txt" \
    | sed -e 's/-std=c++11/-std=c++14/' -e '/^add_subdirectory(Thirdparty\/g2o)/d' >"$dst/CMakeLists.txt"
  if [ "$1" != stock ]; then
    sed -i '/src\/ORBextractor.cc/d' "$dst/CMakeLists.txt"
    cat >>"$dst/CMakeLists.txt" <<EOF
# enhanced_orb in place of ORBextractor
target_include_directories(\${PROJECT_NAME} PUBLIC $ROOT/include)
target_link_libraries(\${PROJECT_NAME} $ROOT/devel/lib/libenhanced_orb_core.so)
EOF
    cat >"$dst/include/ORBextractor.h" <<'EOF'
// ORBextractor: enhanced_orb's OrbSlamExtractor under the name ORB-SLAM3 uses.
#ifndef ORBEXTRACTOR_H
#define ORBEXTRACTOR_H

#include <enhanced_orb/orb_slam_extractor.h>

namespace ORB_SLAM3 {
class ORBextractor : public enhanced_orb::OrbSlamExtractor {
public:
  using enhanced_orb::OrbSlamExtractor::OrbSlamExtractor;
};
}  // namespace ORB_SLAM3

#endif
EOF
  fi
  cat >>"$dst/CMakeLists.txt" <<'EOF'
set(CMAKE_RUNTIME_OUTPUT_DIRECTORY ${PROJECT_SOURCE_DIR}/Examples/Stereo)
add_executable(stereo_euroc Examples/Stereo/stereo_euroc.cc)
target_link_libraries(stereo_euroc ${PROJECT_NAME})
set(CMAKE_RUNTIME_OUTPUT_DIRECTORY ${PROJECT_SOURCE_DIR}/Examples/Monocular)
add_executable(mono_euroc Examples/Monocular/mono_euroc.cc)
target_link_libraries(mono_euroc ${PROJECT_NAME})
EOF
}

build_thirdparty() {
  local tp=$WORK/stock/Thirdparty
  for lib in DBoW2 g2o; do
    if [ ! -f "$tp/$lib/lib/lib$lib.so" ]; then
      log "building $lib"
      cmake -S "$tp/$lib" -B "$tp/$lib/build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS=-std=c++14 \
        >"$tp/$lib/build.log" 2>&1
      make -C "$tp/$lib/build" -j"$JOBS" >>"$tp/$lib/build.log" 2>&1 || { tail -n 30 "$tp/$lib/build.log"; exit 1; }
    fi
  done
}

build_copy() {  # NAME
  local dst=$WORK/$1
  if [ ! -x "$dst/Examples/Stereo/stereo_euroc" ] || [ ! -x "$dst/Examples/Monocular/mono_euroc" ]; then
    log "building ORB-SLAM3 ($1; log: $dst/build.log)"
    cmake -S "$dst" -B "$dst/build" -DCMAKE_BUILD_TYPE=Release "${PANGOLIN_ARGS[@]}" >"$dst/build.log" 2>&1 \
      || { tail -n 30 "$dst/build.log"; exit 1; }
    make -C "$dst/build" -j"$JOBS" stereo_euroc mono_euroc >>"$dst/build.log" 2>&1 \
      || { grep -E "error" "$dst/build.log" | head -n 30; exit 1; }
  fi
}

for b in stock enhanced_orb; do
  [ -f "$WORK/$b/CMakeLists.txt" ] || prepare_copy "$b"
  # a new copy, or one prepared before the seed was read: read it, and build again (make rebuilds
  # one file)
  if seed_from_environment "$WORK/$b"; then
    rm -f "$WORK/$b/Examples/Stereo/stereo_euroc" "$WORK/$b/Examples/Monocular/mono_euroc"
  fi
  [ "$b" = stock ] && build_thirdparty
  build_copy "$b"
done

# --- the light conditions: one EuRoC folder each, every frame degraded once -------------------------
if [ ! -f "$WORK/frames/.done" ]; then
  log "writing the frames of every light condition to $WORK/frames"
  rm -rf "$WORK/frames"
  "$ROOT/devel/lib/enhanced_orb/enhanced_orb_compare" --sequence "$DATA" --write-sequence "$WORK/frames" \
    ${CONDITIONS:+--conditions "${CONDITIONS// /,}"}
  touch "$WORK/frames/.done"
fi
CONDITIONS=${CONDITIONS:-$(cd "$WORK/frames" && ls -d */ | tr -d / | tr '\n' ' ')}

# --- the runs -------------------------------------------------------------------------------------
# One run of ORB-SLAM3's EuRoC example in DIR, unless done there: the condition's frames, or COUNT of
# them from FIRST. ORB-SLAM3's examples crash when saving the trajectory of a map that never started:
# no trajectory file, the exit status in the log, the shell's report of the crash not printed.
run_in() {  # DIR RUN SENSOR CONDITION SEED [FIRST COUNT]; RUN is "stock" or "enhanced_orb-<preset>"
  local dir=$1 build=${2%%-*} times=$WORK/frames/$4/times.txt sensor=Monocular exe=mono_euroc config=
  # done before, with this seed (a run from before the seed was recorded runs again)
  [ -f "$dir/done" ] && [ "$(cat "$dir/seed" 2>/dev/null)" = "$5" ] && return 0
  rm -rf "$dir" && mkdir -p "$dir"
  if (($# > 5)); then
    sed -n "$(($6 + 1)),$(($6 + $7))p" "$times" >"$dir/times.txt"
    times=$dir/times.txt
  fi
  if [ "$3" = stereo ]; then
    sensor=Stereo exe=stereo_euroc
  fi
  [ "$build" = stock ] || config=$ROOT/config/${2#*-}.yaml
  echo "$5" >"$dir/seed"
  (cd "$dir" && { ORBSLAM3_EVAL_SEED=$5 ENHANCED_ORB_CONFIG=$config timeout 900 "$WORK/$build/Examples/$sensor/$exe" "$VOCABULARY" \
    "$WORK/$build/Examples/$sensor/EuRoC.yaml" "$WORK/frames/$4" "$times" run >log.txt 2>&1 \
    || echo "exit $?" >>log.txt; }) 2>/dev/null
  touch "$dir/done"
}
run_one() { run_in "$WORK/runs/$1/$2/$3/$4" "$1" "$2" "$3" "$4"; }  # RUN SENSOR CONDITION REPEAT
RUNS="stock"
for p in $PRESETS; do RUNS="$RUNS enhanced_orb-$p"; done
repeats_of() { if [ "$1" = mono ]; then echo "$MONO_REPEATS"; else echo "$REPEATS"; fi; }  # SENSOR
total=0
for s in $SENSORS; do total=$((total + $(repeats_of "$s") * $(wc -w <<<"$CONDITIONS") * $(wc -w <<<"$RUNS"))); done
n=0
for r in $(seq 1 $((MONO_REPEATS > REPEATS ? MONO_REPEATS : REPEATS))); do for c in $CONDITIONS; do for s in $SENSORS; do
  ((r <= $(repeats_of "$s"))) || continue
  for b in $RUNS; do
    n=$((n + 1))
    log "run $n/$total: $b $s $c #$r"
    run_one "$b" "$s" "$c" "$r"
  done
done; done; done

# --- the monocular start ---------------------------------------------------------------------------
# A monocular map starts from the first pair of frames whose two-view reconstruction ORB-SLAM3
# trusts (enough matches of level-0 keypoints, one clear solution, enough parallax); on a single
# run that is one draw. Here each build also starts from every START_EVERY-th frame of each
# condition and is given START_FRAMES frames from there: the frames in its trajectory (from the
# pair that started the map on) show how soon the map starts, over many starts. One run per start
# and seed of START_SEEDS: the start is decided by the tracking thread alone, the same way on the
# same frames with the same seed. The runs of seed 1 (the start as shipped) are in
# starts/RUN/CONDITION/FIRST, of seed s in FIRST.s.
START_EVERY=${START_EVERY:-10}
START_FRAMES=${START_FRAMES:-10}
START_SEEDS=${START_SEEDS:-1}
if [[ " $SENSORS " == *" mono "* ]] && ((START_EVERY > 0)); then
  n_frames=$(wc -l <"$WORK/frames/$(set -- $CONDITIONS; echo "$1")/times.txt")
  starts=$(seq 0 "$START_EVERY" $((n_frames - START_FRAMES)))
  log "monocular start: $(echo $starts | wc -w) starts of $START_FRAMES frames per build, condition and seed ($START_SEEDS)"
  for b in $RUNS; do for c in $CONDITIONS; do for f in $starts; do for seed in $START_SEEDS; do
    name=$f
    [ "$seed" = 1 ] || name=$f.$seed
    run_in "$WORK/starts/$b/$c/$name" "$b" mono "$c" "$seed" "$f" "$START_FRAMES"
  done; done; done; done
fi

python3 "$ROOT/scripts/report.py" orbslam3 "$WORK/runs" "$DATA" | tee "$WORK/results.md"
log "table in $WORK/results.md"
