#!/usr/bin/env bash
# Static checks CI makes besides the tests: catkin_lint errors, and C++ files that clang-format
# (with the repository's .clang-format) would change. Exits non-zero on any finding.
set -uo pipefail
export PATH=/usr/bin:/bin:/usr/sbin:/sbin:$PATH
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$ROOT" || exit 1
status=0

echo "lint: catkin_lint --strict"
# On a copy of the project's own files (not build/ or devel/). Debian has no rosdep database:
# unknown dependencies are ignored, the rest is checked.
copy=$(mktemp -d)/enhanced_orb
mkdir -p "$copy"
git ls-files -co --exclude-standard -z | xargs -0 cp --parents -t "$copy"
catkin_lint --strict -W1 --quiet "$copy" 2> >(grep -v "rosdep\|unknown dependencies" >&2) || status=1
rm -rf "$(dirname "$copy")"

echo "lint: clang-format"
mapfile -t sources < <(git ls-files '*.cpp' '*.h' 2>/dev/null || find src include test -name '*.cpp' -o -name '*.h')
unformatted=()
for f in "${sources[@]}"; do
  clang-format --dry-run -Werror "$f" >/dev/null 2>&1 || unformatted+=("$f")
done
if ((${#unformatted[@]})); then
  echo "lint: clang-format would change: ${unformatted[*]} (run: clang-format -i FILE)"
  status=1
fi
[ $status -eq 0 ] && echo "lint: clean"
exit $status
