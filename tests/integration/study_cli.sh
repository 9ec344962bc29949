#!/usr/bin/env bash
# `cbtl study simulate` and `cbtl study demo` end to end: simulated participants through the study server's HTTP API
# with the analysis of its database (and the same results whatever --jobs), the in-process simulation's tables and
# CSVs, the demonstration's complaints and its pictures (when offscreen rendering works), a used output folder
# refused, a program of another domain refused.
# usage: study_cli.sh CBTL DOMAINS_DIR
set -u
cbtl=$1
domains=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

out=$("$cbtl" study simulate "$domains/feeding/feeding.cbtl" --participants 3 --out "$work/h" 2>&1); rc=$?
[[ $rc -eq 0 ]] || fail "simulate over HTTP exit $rc: $out"
grep -q "3 simulated participants" <<<"$out" || fail "simulate over HTTP header: $out"
[[ $(wc -l <"$work/h/records.jsonl") -eq 39 ]] || fail "records.jsonl: $(wc -l <"$work/h/records.jsonl") records, not 3 x 13"
[[ $(wc -l <"$work/h/ratings.csv") -eq 6 ]] || fail "ratings.csv rows: $(cat "$work/h/ratings.csv")"
jobs_out=$("$cbtl" study simulate "$domains/feeding/feeding.cbtl" --participants 3 --jobs 3 --out "$work/j" 2>&1)
for f in ratings.csv accuracy.csv paths.csv flows.csv; do
  cmp -s "$work/h/$f" "$work/j/$f" || fail "--jobs 3 changed $f: $jobs_out"
done
analyzed=$("$cbtl" study analyze "$work/h/study.sqlite" 2>&1); rc=$?
[[ $rc -eq 0 ]] || fail "analyze exit $rc: $analyzed"
# Three participants: the tests are shown, with the warning that so few cannot support a finding.
grep -q "^warning: meals 1, 2, 3, 4, 5 have fewer than 20 non-neutral ratings .*read these p-values as a pilot's" \
  <<<"$analyzed" || fail "analyze of 3 participants without the warning: $analyzed"
out=$("$cbtl" study simulate "$domains/feeding/feeding.cbtl" --participants 3 --out "$work/h" 2>&1); rc=$?
[[ $rc -eq 1 ]] && grep -q "already exists" <<<"$out" || fail "used study database (exit $rc): $out"

out=$("$cbtl" study simulate "$domains/feeding/feeding.cbtl" --in-process --participants 2 --out "$work/s" 2>&1); rc=$?
[[ $rc -eq 0 ]] || fail "simulate exit $rc: $out"
grep -q "CBTL better / tied / worse" <<<"$out" && grep -q "0 refused" <<<"$out" || fail "simulate table: $out"
# header + 2 participants x 5 meals x 2 approaches
[[ $(wc -l <"$work/s/study.csv") -eq 21 ]] || fail "study.csv rows: $(wc -l <"$work/s/study.csv")"
[[ $(wc -l <"$work/s/meals.csv") -eq 11 ]] || fail "meals.csv rows: $(wc -l <"$work/s/meals.csv")"
out=$("$cbtl" study simulate "$domains/feeding/feeding.cbtl" --in-process --participants 2 --out "$work/s" 2>&1); rc=$?
[[ $rc -eq 1 ]] && grep -q "already holds study.csv" <<<"$out" || fail "used folder (exit $rc): $out"
out=$("$cbtl" study simulate "$domains/cooking/cooking.cbtl" --participants 1 2>&1); rc=$?
[[ $rc -eq 1 ]] && grep -q "Feeding domain" <<<"$out" || fail "another domain (exit $rc): $out"
out=$("$cbtl" study simulate "$domains/feeding/feeding.cbtl" --participants 0 2>&1); rc=$?
[[ $rc -eq 2 ]] || fail "--participants 0 (exit $rc): $out"

out=$("$cbtl" study demo "$domains/feeding/feeding.cbtl" --trials 1 --width 64 --height 48 --out "$work/d" 2>&1); rc=$?
[[ $rc -eq 0 ]] || fail "demo exit $rc: $out"
grep -Eq "^  cbtl +\([0-9], [0-9], [0-9]\)$" <<<"$out" || fail "demo complaints line: $out"
grep -q "drink 1" <<<"$out" || fail "demo table: $out"
if grep -q "no pictures" <<<"$out"; then
  echo "pictures skipped: no offscreen rendering here"
else
  for f in cbtl-bite-1-scene cbtl-bite-1-view no-personalization-drink-1-view; do
    [[ $(head -c 8 "$work/d/$f.png" 2>/dev/null | od -An -tx1 | tr -d ' \n') == 89504e470d0a1a0a ]] || fail "$f.png"
  done
fi
[[ $failures -eq 0 ]] && echo "study_cli: all ok"
exit $((failures > 0))
