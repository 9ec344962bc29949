#!/usr/bin/env bash
# Results are never lost or mixed (`cbtl run/experiment --out`): a folder holding a run is refused; --force
# replaces only the run's files; kill -9 at chosen moments (CBTL_TEST_KILL_AT) and at an arbitrary one, then
# --resume, gives the bytes of an uninterrupted run; a second process is locked out; a failed write names its file.
# usage: results_cli.sh CBTL DOMAINS_DIR
set -u
cbtl=$1
domains=$2
source "$(dirname "$0")/expect.sh"

# Every file present parses: JSON files as JSON, CSV files as rows of the header's width.
parses() {  # parses DIR
  python3 - "$1" <<'PY' || return 1
import csv, json, os, sys
root = sys.argv[1]
for d, _, files in os.walk(root):
    for f in files:
        p = os.path.join(d, f)
        if f.endswith(".json"):
            json.load(open(p))
        elif f.endswith(".jsonl"):
            for line in open(p):
                json.loads(line)
        elif f.endswith(".csv"):
            rows = list(csv.reader(open(p)))
            assert rows, p + " is empty"
            assert all(len(r) == len(rows[0]) for r in rows), p + " has a row of another width"
PY
}

same_results() {  # same_results DIR_A DIR_B: train.csv, eval.csv, profile.json, models/*.json byte for byte
  local a=$1 b=$2 f
  for f in train.csv eval.csv profile.json $(cd "$a" && ls models/*.json); do
    cmp -s "$a/$f" "$b/$f" || { fail "$b/$f differs from the uninterrupted run's"; return; }
  done
  [[ $(cd "$a" && ls models) == $(cd "$b" && ls models) ]] || fail "$b/models holds other files than $a/models"
  [[ -f $b/complete.json ]] || fail "$b has no completion marker"
}

run=(run "$cooking" --steps 1000 --eval-every 100 --eval-tasks 2 --seed 5 -q)
"$cbtl" "${run[@]}" --out "$work/whole" || fail "the uninterrupted run failed"
[[ -f $work/whole/complete.json && ! -e $work/whole/checkpoint.json ]] || fail "a complete run lacks complete.json or kept checkpoint.json"

# A second run into the same folder is refused, naming the folder and both ways out.
expect 1 "'$work/whole' already holds a run .*--force.*--resume" -- "$cbtl" "${run[@]}" --out "$work/whole"
expect 2 "excludes" -- "$cbtl" "${run[@]}" --out "$work/whole" --force --resume
# --force replaces the run's files and leaves the user's.
cp -r "$work/whole" "$work/forced"
echo mine >"$work/forced/notes.txt"
echo stale >"$work/forced/models/5000.json"
expect 0 "" -- "$cbtl" "${run[@]}" --out "$work/forced" --force
[[ $(cat "$work/forced/notes.txt") == mine ]] || fail "--force touched notes.txt"
[[ ! -e $work/forced/models/5000.json ]] || fail "--force kept a stale model of the old run"
same_results "$work/whole" "$work/forced"
# --resume of a complete run changes nothing.
expect 0 "" -- "$cbtl" "${run[@]}" --out "$work/forced" --resume
same_results "$work/whole" "$work/forced"
# --resume with other options is refused, naming the keys.
expect 1 "cannot resume .*steps \(this command: 2000, the run: 1000\)" -- \
  "$cbtl" run "$cooking" --steps 2000 --eval-every 100 --eval-tasks 2 --seed 5 -q --out "$work/forced" --resume

# kill -9 at chosen moments of the loop, then --resume: every file present parses, and the result is the same.
for at in step:437 model:300 checkpoint:600 finish:1000 step:0; do
  dir=$work/killed-${at/:/-}
  CBTL_TEST_KILL_AT=$at "$cbtl" "${run[@]}" --out "$dir" 2>/dev/null
  rc=$?
  [[ $rc -eq 137 ]] || fail "CBTL_TEST_KILL_AT=$at: exit $rc, wanted 137 (killed)"
  [[ ! -e $dir/complete.json ]] || fail "a killed run ($at) has a completion marker"
  parses "$dir" || fail "a file of the run killed at $at does not parse"
  expect 0 "" -- "$cbtl" "${run[@]}" --out "$dir" --resume
  same_results "$work/whole" "$dir"
done

# kill -9 at an arbitrary moment (whenever it lands, even after the end, the same must hold).
long=(run "$cooking" --steps 4000 --eval-every 100 --eval-tasks 2 --seed 9 -q)
"$cbtl" "${long[@]}" --out "$work/long-whole" || fail "the long run failed"
for delay in 0.05 0.3; do
  dir=$work/long-$delay
  "$cbtl" "${long[@]}" --out "$dir" &
  pid=$!
  sleep "$delay"
  kill -9 "$pid" 2>/dev/null
  wait "$pid" 2>/dev/null
  parses "$dir" || fail "a file of the run killed after ${delay}s does not parse"
  expect 0 "" -- "$cbtl" "${long[@]}" --out "$dir" --resume
  same_results "$work/long-whole" "$dir"
done

# A second process on the same folder: flock(1) holds DIR/.lock, as a running cbtl would.
mkdir -p "$work/locked"
expect 1 "in use by another cbtl process" -- flock "$work/locked/.lock" "$cbtl" "${run[@]}" --out "$work/locked"
expect 1 "in use by another cbtl process" -- flock "$work/whole/.lock" "$cbtl" "${run[@]}" --out "$work/whole" --resume

# A full disk: the failed write names its file, and the run does not claim to be complete.
for f in train.csv checkpoint.json profile.json; do
  expect 1 "$f.*No space left on device" -- env CBTL_TEST_WRITE_FAILS=$f "$cbtl" "${run[@]}" --out "$work/full-$f"
  [[ ! -e $work/full-$f/complete.json ]] || fail "a run whose $f could not be written has a completion marker"
done

# cbtl experiment: refused, forced, killed and resumed (finished trials are read back, not rerun).
exp=(experiment "$cooking" --approaches cbtl,no-personalization --seeds 0..1 --steps 300 --eval-every 100 --eval-tasks 2 -q)
"$cbtl" "${exp[@]}" --out "$work/exp" >/dev/null || fail "the experiment failed"
expect 1 "'$work/exp' already holds a run \(summary.csv.*--force.*--resume" -- "$cbtl" "${exp[@]}" --out "$work/exp"
expect 0 "" -- "$cbtl" "${exp[@]}" --out "$work/exp" --force
# seed 0 finishes first (an earlier, shorter command); the kill then lands in cbtl seed 1. --jobs 1: with trials on
# several threads, whichever reaches step 150 first (often a no-personalization trial) takes the kill.
"$cbtl" experiment "$cooking" --approaches cbtl,no-personalization --seeds 0 --steps 300 --eval-every 100 --eval-tasks 2 -q \
  --out "$work/exp-killed" >/dev/null || fail "the one-seed experiment failed"
rm "$work/exp-killed/summary.csv"
CBTL_TEST_KILL_AT=step:150 "$cbtl" "${exp[@]}" --out "$work/exp-killed" --resume --jobs 1 >/dev/null 2>&1
[[ -f $work/exp-killed/cbtl/seed1/checkpoint.json ]] || fail "the kill did not land in cbtl seed 1"
[[ ! -e $work/exp-killed/summary.csv ]] || fail "a killed experiment wrote summary.csv"
expect 0 "" -- "$cbtl" "${exp[@]}" --out "$work/exp-killed" --resume
cmp -s "$work/exp/summary.csv" "$work/exp-killed/summary.csv" || fail "the resumed experiment's summary.csv differs"
same_results "$work/exp/cbtl/seed0" "$work/exp-killed/cbtl/seed0"
same_results "$work/exp/no-personalization/seed1" "$work/exp-killed/no-personalization/seed1"

# Trials on several threads give exactly a serial run's results (--jobs), in Cooking and in a robot domain whose
# trials share the scene's motion cache.
"$cbtl" "${exp[@]}" --out "$work/exp-serial" --jobs 1 >/dev/null || fail "the serial experiment failed"
"$cbtl" "${exp[@]}" --out "$work/exp-parallel" --jobs 3 >/dev/null || fail "the parallel experiment failed"
cmp -s "$work/exp-serial/summary.csv" "$work/exp-parallel/summary.csv" || fail "--jobs 3 changed summary.csv"
for t in cbtl/seed0 cbtl/seed1 no-personalization/seed0 no-personalization/seed1; do
  same_results "$work/exp-serial/$t" "$work/exp-parallel/$t"
done
cleaning=$domains/cleaning/cleaning.cbtl
robot=(experiment "$cleaning" --approaches cbtl,no-personalization --seeds 0..1 --steps 30 --eval-every 30 --eval-tasks 1 -q)
"$cbtl" "${robot[@]}" --out "$work/robot-serial" --jobs 1 >/dev/null || fail "the serial Cleaning experiment failed"
"$cbtl" "${robot[@]}" --out "$work/robot-parallel" --jobs 2 >/dev/null || fail "the parallel Cleaning experiment failed"
cmp -s "$work/robot-serial/summary.csv" "$work/robot-parallel/summary.csv" || fail "--jobs 2 changed Cleaning's summary.csv"
for t in cbtl/seed0 cbtl/seed1 no-personalization/seed0 no-personalization/seed1; do
  same_results "$work/robot-serial/$t" "$work/robot-parallel/$t"
done

if [[ $failures -ne 0 ]]; then
  echo "$failures failure(s)"
  exit 1
fi
echo "all results_cli checks passed"
