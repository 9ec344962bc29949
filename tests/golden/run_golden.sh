#!/usr/bin/env bash
# run_golden.sh CBTLC CASE.cbtl — runs the compiler on one golden case and compares with CASE.out/.err.
#
# The case's first line may say which arguments to pass: `// ARGS: emit --format json` (default `check`).
# The file name is appended as given, relative to the case's folder, so output is machine independent.
# CASE.err holds stderr followed by a line `[exit N]`. Missing .out means stdout must be empty.
# With CBTL_UPDATE_GOLDEN=1 the expected files are rewritten instead (review them with git diff).
set -u
cbtlc=$1
case_path=$2
dir=$(dirname "$case_path")
name=$(basename "$case_path" .cbtl)
cd "$dir" || exit 2
args=$(head -n1 "$name.cbtl" | sed -n 's|^// ARGS: *||p')
[ -n "$args" ] || args=check
# shellcheck disable=SC2086
"$cbtlc" $args "$name.cbtl" > "$name.out.actual" 2> "$name.err.actual"
code=$?
echo "[exit $code]" >> "$name.err.actual"
if [ "${CBTL_UPDATE_GOLDEN:-0}" = "1" ]; then
  if [ -s "$name.out.actual" ]; then mv "$name.out.actual" "$name.out"; else rm -f "$name.out.actual" "$name.out"; fi
  mv "$name.err.actual" "$name.err"
  exit 0
fi
status=0
[ -f "$name.out" ] || : > "$name.out.expected.empty"
if ! diff -u "${name}.out$([ -f "$name.out" ] || echo .expected.empty)" "$name.out.actual"; then status=1; fi
if ! diff -u "$name.err" "$name.err.actual"; then status=1; fi
rm -f "$name.out.actual" "$name.err.actual" "$name.out.expected.empty"
if [ "$code" -ge 70 ]; then echo "compiler exited with $code (internal error)"; status=1; fi
exit $status
