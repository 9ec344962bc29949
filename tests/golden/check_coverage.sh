#!/usr/bin/env bash
# check_coverage.sh CBTLC GOLDEN_DIR — fails if a diagnostic code of `cbtlc explain --list` appears in no
# .err golden under GOLDEN_DIR (as "error[CODE]" / "warning[CODE]" or a JSON "code":"CODE").
#
# The allow-list holds the codes that cannot be produced from a source file, each with the reason.
set -u
cbtlc=$1
dir=$2
declare -A allowed=(
  [E0901]="internal: the IR validator rejected the compiler's own output; no input can cause it"
)
codes=$("$cbtlc" explain --list | awk '{print $1}')
[ -n "$codes" ] || { echo "cbtlc explain --list printed no codes"; exit 1; }
missing=0
for code in $codes; do
  if [ -n "${allowed[$code]:-}" ]; then continue; fi
  if ! grep -rqE --include='*.err' "(error|warning)\[$code\]|\"code\":\"$code\"" "$dir"; then
    echo "no golden case produces $code ($("$cbtlc" explain --list | grep "^$code " | cut -c8-))"
    missing=$((missing + 1))
  fi
done
for code in "${!allowed[@]}"; do
  if ! grep -qx "$code" <<< "$codes"; then echo "allow-list names $code, which cbtlc no longer lists"; missing=$((missing + 1)); fi
done
if [ $missing -gt 0 ]; then
  echo "$missing diagnostic code(s) without a golden case; add tests/golden/<area>/<case>.cbtl"
  exit 1
fi
echo "every diagnostic code except ${!allowed[*]} has a golden case ($(wc -w <<< "$codes") codes)"
