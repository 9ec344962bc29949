#!/usr/bin/env bash
# scripts/preference-curves.py on a small made-up experiment: means per checkpoint, the standard error over seeds,
# two folders pooled, a seed given twice refused.
# usage: preference_curves.sh SCRIPT
set -u
script=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# eval.csv of one seed: training_step, satisfaction, preferences met, dip met
seed() {
  mkdir -p "$1"
  {
    echo "training_step,eval_mean_user_satisfaction,eval_preferences_met_rate,eval_dip_met_rate"
    echo "0,$2,0.5,$4"
    echo "1000,$3,0.5,$5"
  } >"$1/eval.csv"
}
seed "$work/a/cbtl/seed0" -0.2 0.6 0.25 0.75
seed "$work/b/cbtl/seed1" 0.0 1.0 0.75 1.0
seed "$work/a/no-personalization/seed0" -0.2 -0.2 0.25 0.25

out=$(python3 "$script" "$work/a" "$work/b" 2>&1) || fail "exit $?: $out"
# cbtl: step 0 mean -0.10, step 1000 +0.80; per-seed means 0.2 and 0.5 -> 0.350 +- 0.150
grep -qF "| cbtl | -0.10 | +0.80 | +0.350 ± 0.150 |" <<<"$out" || fail "satisfaction row: $out"
grep -qF "| no-personalization | -0.20 | -0.20 | -0.200 ± 0.000 |" <<<"$out" || fail "one seed: $out"
grep -qF "| cbtl | 0.50 | 0.88 |" <<<"$out" || fail "dip row: $out"
grep -q "preferences: met" <<<"$out" && fail "the overall preferences column is not a preference: $out"
out=$(python3 "$script" "$work/a" "$work/a" 2>&1) && fail "a seed twice accepted: $out"
grep -q "more than one folder" <<<"$out" || fail "a seed twice: $out"
out=$(python3 "$script" "$work/none" 2>&1) && fail "a missing folder accepted: $out"
grep -q "is not a folder" <<<"$out" || fail "a missing folder: $out"
mkdir "$work/empty"
out=$(python3 "$script" "$work/empty" 2>&1) && fail "an empty folder accepted: $out"
grep -q "no <approach>/seed<N>/eval.csv" <<<"$out" || fail "an empty folder: $out"

[[ $failures -eq 0 ]] && echo "preference_curves: all checks passed"
exit $((failures > 0))
