#!/usr/bin/env bash
# Downloads an official EuRoC MAV rosbag (resumable, size-checked) into bags/.
#
#   bash bags/download_euroc.sh [SEQUENCE]     default MH_01_easy
#
# SEQUENCE: MH_01_easy ... MH_05_difficult, V1_01_easy ... V1_03_difficult, V2_01_easy ... V2_03_difficult.
# The dataset is now published in ETH's research collection (RESEARCH_COLLECTION below), whose file
# links are not derived from the sequence name: there, download SEQUENCE.bag by hand. The script
# fetches from a tree laid out as BASE/<folder>/SEQUENCE/SEQUENCE.bag: EUROC_BASE_URL (a mirror),
# else the dataset's former server, and says where to look when neither answers.
set -euo pipefail
SEQUENCE=${1:-MH_01_easy}
RESEARCH_COLLECTION=https://www.research-collection.ethz.ch/entities/researchdata/bcaf173e-5dac-484b-bc37-faf97a594f1f
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
expected=$({ curl -sIL --max-time 30 "$URL" || true; } | tr -d '\r' | awk 'tolower($1) == "content-length:" {n = $2} END {print n}')
if [ -z "$expected" ]; then
  echo "download_euroc: no answer from $URL" >&2
  echo "  EuRoC is published at $RESEARCH_COLLECTION" >&2
  echo "  download $SEQUENCE.bag there, then: roslaunch enhanced_orb euroc.launch bag:=/path/to/$SEQUENCE.bag" >&2
  echo "  or set EUROC_BASE_URL to a mirror laid out as BASE/$FOLDER/$SEQUENCE/$SEQUENCE.bag" >&2
  exit 1
fi

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
