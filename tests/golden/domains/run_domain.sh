#!/usr/bin/env bash
# run_domain.sh CBTLC DOMAIN.cbtl EXPECTED — the domain file must check cleanly (no diagnostics at all)
# and its emitted graph must equal EXPECTED.out. CBTL_UPDATE_GOLDEN=1 rewrites EXPECTED.out.
set -u
cbtlc=$1; file=$2; expected=$3
cd "$(dirname "$file")" || exit 2
base=$(basename "$file")
"$cbtlc" emit --format text "$base" > "$expected.actual" 2> "$expected.stderr"
code=$?
if [ $code -ne 0 ] || [ -s "$expected.stderr" ]; then
  cat "$expected.stderr"; rm -f "$expected.actual" "$expected.stderr"; echo "cbtlc exited $code"; exit 1
fi
rm -f "$expected.stderr"
if [ "${CBTL_UPDATE_GOLDEN:-0}" = "1" ]; then mv "$expected.actual" "$expected.out"; exit 0; fi
diff -u "$expected.out" "$expected.actual"; status=$?
rm -f "$expected.actual"
exit $status
