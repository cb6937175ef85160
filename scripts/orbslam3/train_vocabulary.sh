#!/usr/bin/env bash
# Trains a replacement ORB vocabulary with the DBoW2 that an ORB-SLAM3 source tree ships, for
# scripts/orbslam3_eval.sh where the official Vocabulary/ORBvoc.txt is not at hand (users use the
# official one). The images must not be those of the sequence the vocabulary is then tested on.
#
#   bash scripts/orbslam3/train_vocabulary.sh SRC OUT.txt DIR [DIR ...]   (about 2 minutes here)
set -euo pipefail
export PATH=/usr/bin:/bin:/usr/sbin:/sbin:$PATH
HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
if (($# < 3)); then
  sed -n '2,6p' "$0" | sed 's/^# \{0,1\}//'
  exit 2
fi
SRC=$(realpath "$1")
OUT=$(realpath -m "$2")
shift 2
DBOW2=$SRC/Thirdparty/DBoW2
[ -f "$DBOW2/DBoW2/TemplatedVocabulary.h" ] || { echo "train_vocabulary: no DBoW2 under $SRC/Thirdparty" >&2; exit 2; }
bash "$HERE/../install_packages.sh" train_vocabulary build-essential libopencv-dev pkg-config
BIN=$(mktemp -d /tmp/train_vocabulary.XXXXXX)
trap 'rm -rf "$BIN"' EXIT
g++ -O2 -std=c++17 -w -I"$DBOW2" "$HERE/train_vocabulary.cpp" "$DBOW2"/DBoW2/*.cpp "$DBOW2"/DUtils/*.cpp \
  $(pkg-config --cflags --libs opencv4) -o "$BIN/train_vocabulary"
"$BIN/train_vocabulary" "$OUT" "$@"
