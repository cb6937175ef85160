#!/usr/bin/env bash
# Builds the libFuzzer target over the core library (clang, with AddressSanitizer and
# UndefinedBehaviorSanitizer) and runs it.
#
#   bash scripts/fuzz.sh [SECONDS] [--junit FILE]     default 60 s; longer: bash scripts/fuzz.sh 3600
# The corpus grows in build_fuzz/corpus; a crash leaves build_fuzz/crash-* to reproduce with
#   build_fuzz/fuzz_extract build_fuzz/crash-...
set -uo pipefail
export PATH=/usr/bin:/bin:/usr/sbin:/sbin:$PATH
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
SECONDS_TO_RUN=60
JUNIT=""
while (($#)); do
  case "$1" in
    --junit) JUNIT=$2; shift ;;
    *) SECONDS_TO_RUN=$1 ;;
  esac
  shift
done
OUT="$ROOT/build_fuzz"
mkdir -p "$OUT/corpus"

# shellcheck disable=SC2046
# The portable kernels only (no ENHANCED_ORB_X86_KERNELS): the fuzzer also covers that build.
clang++ -std=c++17 -g -O1 -ffp-contract=off -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined \
  -I"$ROOT/include" -I"$ROOT/src/core" "$ROOT"/src/core/*.cpp "$ROOT"/src/core/kernels/*_scalar.cpp \
  "$ROOT"/src/core/kernels/*_vector128.cpp "$ROOT/fuzz/fuzz_extract.cpp" \
  $(pkg-config --cflags --libs opencv4) -o "$OUT/fuzz_extract" || exit 1

start=$(date +%s)
(cd "$OUT" && ./fuzz_extract -max_total_time="$SECONDS_TO_RUN" -max_len=2048 -timeout=20 -rss_limit_mb=4096 \
  -print_final_stats=1 corpus >"$OUT/fuzz.log" 2>&1)
status=$?
elapsed=$(( $(date +%s) - start ))
runs=$(grep -o "stat::number_of_executed_units: *[0-9]*" "$OUT/fuzz.log" | grep -o "[0-9]*$")
if [ $status -eq 0 ]; then
  echo "fuzz: ${runs:-?} inputs in ${elapsed} s, no finding"
else
  echo "fuzz: FINDING after ${elapsed} s (exit $status); see $OUT/fuzz.log:"
  grep -E "ERROR|SUMMARY|runtime error|deadly signal" "$OUT/fuzz.log" | head -n 10
fi
if [ -n "$JUNIT" ]; then
  mkdir -p "$(dirname "$JUNIT")"
  {
    echo '<?xml version="1.0" encoding="UTF-8"?>'
    echo "<testsuite name=\"fuzz\" tests=\"1\" failures=\"$((status != 0))\" errors=\"0\">"
    echo "  <testcase classname=\"fuzz\" name=\"fuzz_extract_${SECONDS_TO_RUN}s\" time=\"$elapsed\">"
    [ $status -eq 0 ] || echo "    <failure message=\"fuzzer finding, see build_fuzz/fuzz.log\"/>"
    echo "  </testcase>"
    echo "</testsuite>"
  } >"$JUNIT"
fi
exit $status
