#!/usr/bin/env bash
# Checks (default) or applies (--fix) .clang-format on every C++ file of the repository. Used by `make format`
# and by the ctest case format.clang_format, so `make test` fails on code that does not follow the layout.
set -euo pipefail
cd "$(dirname "$0")/.."
mode="${1:-}"
if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  mapfile -t files < <(git ls-files --cached --others --exclude-standard -- '*.h' '*.cpp' | grep -v '^tests/golden/')
else
  mapfile -t files < <(find . -path ./build\* -prune -o \( -name '*.h' -o -name '*.cpp' \) -print | grep -v '^./tests/golden/')
fi
existing=()
for f in "${files[@]}"; do [ -f "$f" ] && existing+=("$f"); done
if [ "$mode" = "--fix" ]; then
  clang-format -i "${existing[@]}"
  exit 0
fi
if ! clang-format --dry-run --Werror "${existing[@]}" 2>/tmp/cbtl-format.$$; then
  grep -o '^[^:]*:[0-9]*:[0-9]*: error' /tmp/cbtl-format.$$ | cut -d: -f1 | sort -u | sed 's/^/not formatted: /' >&2
  echo "check-format: run 'make format' (clang-format -i) and commit the result" >&2
  rm -f /tmp/cbtl-format.$$
  exit 1
fi
rm -f /tmp/cbtl-format.$$
echo "check-format: ${#existing[@]} files follow .clang-format"
