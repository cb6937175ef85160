#!/usr/bin/env bash
# Downloads an official EuRoC MAV rosbag (resumable, size-checked) into bags/.
#
#   bash bags/download_euroc.sh [SEQUENCE]     default MH_01_easy
#
# SEQUENCE: MH_01_easy ... MH_05_difficult, V1_01_easy ... V1_03_difficult, V2_01_easy ... V2_03_difficult.
# EUROC_BASE_URL overrides where the dataset is served from (it has moved before).
set -euo pipefail
SEQUENCE=${1:-MH_01_easy}
BASE=${EUROC_BASE_URL:-http://robotics.ethz.ch/~asl-datasets/ijrr_euroc_mav_dataset}
case "$SEQUENCE" in
  MH_0[1-5]_*) FOLDER=machine_hall ;;
  V1_0[1-3]_*) FOLDER=vicon_room1 ;;
  V2_0[1-3]_*) FOLDER=vicon_room2 ;;
  *) echo "download_euroc: unknown sequence '$SEQUENCE' (e.g. MH_01_easy, V1_02_medium)" >&2; exit 2 ;;
esac
URL="$BASE/$FOLDER/$SEQUENCE/$SEQUENCE.bag"
OUT="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/$SEQUENCE.bag"

# The size the server announces (last Content-Length after redirects).
expected=$(curl -sIL "$URL" | tr -d '\r' | awk 'tolower($1) == "content-length:" {n = $2} END {print n}')
[ -n "$expected" ] || { echo "download_euroc: no answer from $URL" >&2; exit 1; }

if [ -f "$OUT" ] && [ "$(stat -c %s "$OUT")" = "$expected" ]; then
  echo "download_euroc: $OUT is complete"
  exit 0
fi
echo "download_euroc: $URL ($((expected / 1048576)) MiB) -> $OUT"
curl -L --fail --continue-at - --output "$OUT.part" "$URL"   # resumes a partial download
actual=$(stat -c %s "$OUT.part")
if [ "$actual" != "$expected" ]; then
  echo "download_euroc: size $actual differs from the announced $expected; run again to resume" >&2
  exit 1
fi
mv "$OUT.part" "$OUT"
echo "download_euroc: done. roslaunch enhanced_orb euroc.launch bag:=$OUT"
