#!/usr/bin/env bash
# sweep_cli.sh CBTL DOMAINS — `cbtl sweep` on one machine: a grid expanded into trials with their own folders and
# completion markers, --jobs 2 equal to a serial run byte for byte, a sweep killed mid-trial and run again equal to
# an uninterrupted one, --collect (tables, summary.csv, figures), --list, --index, --emit-slurm, and every bad
# config refused with the file and the JSON pointer of the mistake.
set -u
cbtl=$(realpath "$1")
domains=$(realpath "$2")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
cd "$work" || exit 1

cat >sweep.json <<JSON
{
  "name": "small",
  "defaults": {"steps": 300, "eval-every": 100, "eval-tasks": 2},
  "experiments": [
    {"name": "cooking", "program": "$domains/cooking/cooking.cbtl",
     "approaches": ["cbtl", "no-personalization"], "seeds": "0..1"},
    {"name": "shifts", "program": "$domains/cooking/cooking.cbtl", "approaches": ["cbtl"], "seeds": "0",
     "options": {"nonstationary": "no-adapt"}, "grid": {"shift-every": [100, 200]}}
  ],
  "plots": [
    {"out": "figures/cooking.png", "results": ["cooking"], "ymin": -1, "ymax": 1},
    {"out": "figures/shifts.svg", "layout": "together", "results": ["shifts/shift-every=100", "shifts/shift-every=200"]}
  ],
  "slurm": {"partition": "cpu", "cpus-per-task": 2, "mem": "3G", "time": "00:30:00", "array-limit": 3,
            "sbatch": ["--account=lab"]}
}
JSON

# Trials and their folders; nothing has run yet.
list=$("$cbtl" sweep sweep.json --out serial --list) || fail "--list exited $?"
[ "$(grep -c todo <<<"$list")" = 6 ] || fail "--list before running: $list"
grep -q "^    5  todo     shifts/shift-every=200 cbtl seed 0  $work/serial/shifts/shift-every=200/cbtl/seed0$" <<<"$list" ||
  fail "--list does not show the grid's last trial as expected: $list"
# --collect with nothing finished: names the unfinished experiments, exit 1, no summary.
err=$("$cbtl" sweep sweep.json --out serial --collect 2>&1 >/dev/null)
[ $? = 1 ] && grep -q "cooking: 4 of 4 trials not finished" <<<"$err" || fail "--collect of nothing: $err"

# Serial and parallel: the same files.
"$cbtl" sweep sweep.json --out serial --jobs 1 >serial.txt 2>serial.err || fail "the serial sweep exited $?: $(cat serial.err)"
"$cbtl" sweep sweep.json --out parallel --jobs 2 >/dev/null 2>parallel.err || fail "the parallel sweep exited $?"
grep -q "^\[6/6 trials\] .*ETA 0:00$" parallel.err || fail "no progress count and ETA: $(cat parallel.err)"
for f in $(cd serial && find . -type f \( -name '*.csv' -o -name '*.json' \) ! -name timing.json | sort); do
  cmp -s "serial/$f" "parallel/$f" || fail "--jobs 2 changed $f"
done
for f in cooking/summary.csv shifts/shift-every=100/summary.csv shifts/shift-every=200/summary.csv \
  cooking/cbtl/seed1/complete.json figures/cooking.png figures/shifts.svg; do
  [ -s "serial/$f" ] || fail "the sweep did not write $f"
done
grep -q "^== shifts/shift-every=200$" serial.txt || fail "no table for the grid's second experiment"
grep -q "^cbtl .*±" serial.txt || fail "no table rows: $(head -5 serial.txt)"
# Every trial done: --list says so, running again runs nothing and changes nothing.
[ "$("$cbtl" sweep sweep.json --out serial --list | grep -c ' done ')" = 6 ] || fail "--list after the sweep"
cp serial/cooking/summary.csv before.csv
"$cbtl" sweep sweep.json --out serial >/dev/null 2>again.err || fail "a finished sweep run again exited $?"
grep -q "6 of 6 trials already finished" again.err && ! grep -q "^\[" again.err ||
  fail "a finished sweep ran trials again: $(cat again.err)"
cmp -s before.csv serial/cooking/summary.csv || fail "running a finished sweep again changed its summary"

# Killed in the middle of a trial, then run again: the files of the uninterrupted sweep.
CBTL_TEST_KILL_AT=step:150 "$cbtl" sweep sweep.json --out killed --jobs 1 -q >/dev/null 2>&1
rc=$?
[ $rc = 137 ] || fail "CBTL_TEST_KILL_AT did not kill the sweep (exit $rc)"
[ -f killed/cooking/cbtl/seed0/checkpoint.json ] && [ ! -f killed/cooking/cbtl/seed0/complete.json ] ||
  fail "the kill did not leave an interrupted first trial"
"$cbtl" sweep sweep.json --out killed --list | grep -q "^    0  partial" || fail "--list does not show the partial trial"
"$cbtl" sweep sweep.json --out killed --jobs 2 >/dev/null 2>&1 || fail "the resumed sweep exited $?"
for f in $(cd serial && find . -type f \( -name '*.csv' -o -name 'profile.json' -o -name 'complete.json' \) | sort); do
  cmp -s "serial/$f" "killed/$f" || fail "the resumed sweep's $f differs from the uninterrupted one's"
done

# SLURM: array task I runs its trials only; the script asks for the config's resources.
"$cbtl" sweep sweep.json --out tasks --index 4 -q || fail "--index 4 exited $?"
[ "$(find tasks -name complete.json | wc -l)" = 1 ] && [ -f tasks/shifts/shift-every=100/cbtl/seed0/complete.json ] ||
  fail "--index 4 ran: $(find tasks -name complete.json)"
err=$("$cbtl" sweep sweep.json --out tasks --index 6 2>&1)
[ $? = 2 ] && grep -q "the sweep has 6 array tasks (0..5)" <<<"$err" || fail "--index past the end: $err"
"$cbtl" sweep sweep.json --out slurm --emit-slurm >emit.txt || fail "--emit-slurm exited $?"
script=slurm/small.sbatch
for line in "#SBATCH --array=0-5%3" "#SBATCH --cpus-per-task=2" "#SBATCH --mem=3G" "#SBATCH --time=00:30:00" \
  "#SBATCH --partition=cpu" "#SBATCH --account=lab" "#SBATCH --output=$work/slurm/slurm/%A_%a.log" \
  "exec '$cbtl' sweep '$work/sweep.json' --out '$work/slurm' --index \"\$SLURM_ARRAY_TASK_ID\" --jobs 2 --quiet"; do
  grep -qxF -- "$line" "$script" || fail "the sbatch script lacks: $line"
done
[ -d slurm/slurm ] || fail "--emit-slurm did not make the log folder"
bash -n "$script" || fail "the sbatch script is not valid bash"
# The cluster's array limit: 6 trials and max-array-size 4 -> 2 trials per task, 3 tasks.
sed 's/"array-limit": 3,/"array-limit": 3, "max-array-size": 4,/' sweep.json >capped.json
"$cbtl" sweep capped.json --out capped --emit-slurm >/dev/null || fail "--emit-slurm (capped) exited $?"
grep -qxF "#SBATCH --array=0-2%3" capped/small.sbatch || fail "max-array-size not respected: $(grep array capped/small.sbatch)"

# Bad configs: the file, the JSON pointer, what is wrong; nothing runs.
bad() {  # bad NAME 'SED EXPRESSION' 'EXPECTED MESSAGE'
  sed "$2" sweep.json >"$1.json"
  local err
  err=$("$cbtl" sweep "$1.json" --out "bad-$1" 2>&1 >/dev/null)
  local rc=$?
  [ $rc = 1 ] && grep -qF -- "$3" <<<"$err" || fail "$1: exit $rc: $err"
  [ ! -e "bad-$1/cooking" ] || fail "$1: trials ran"
}
bad typo 's/"seeds": "0..1"/"sedes": "0..1"/' "/experiments/0/sedes: unknown key"
bad seeds 's/"seeds": "0..1"/"seeds": "0-9"/' "/experiments/0/seeds: '0-9': use \"LO..HI\""
bad approach 's/"no-personalization"\]/"no-personalisation"]/' "unknown approach 'no-personalisation'"
bad reserved 's/"eval-tasks": 2}/"eval-tasks": 2, "seed": 3}/' "/defaults/seed: the sweep sets this option itself"
bad range 's/"steps": 300/"steps": -5/' "/experiments/0 (cooking): options: --steps"
bad program '0,/cooking\/cooking.cbtl/s//cooking\/nope.cbtl/' "/experiments/0/program: no such file"
bad plot 's/"results": \["cooking"\]/"results": ["cookin"]/' "/plots/0/results/0: no experiment 'cookin' in this sweep"
echo '{"experiments": [' >broken.json
err=$("$cbtl" sweep broken.json 2>&1)
[ $? = 1 ] && grep -q "broken.json: not JSON" <<<"$err" || fail "broken JSON: $err"

# An experiment whose training requests mostly fail (a simulator whose training world runs dry) ends the sweep with
# exit 3 and the cause, unless its options accept it.
faulty="python3 $(cd "$(dirname "$0")" && pwd)/simulators/faulty_sim.py $domains/coffee dry"
cat >failing.json <<JSON
{"name": "failing", "defaults": {"steps": 40, "eval-every": 20, "eval-tasks": 2},
 "experiments": [{"name": "dry", "program": "$domains/coffee/coffee.cbtl", "approaches": ["cbtl"], "seeds": "0",
                  "options": {"simulator": "$faulty"}}]}
JSON
err=$("$cbtl" sweep failing.json --out failing --jobs 1 2>&1 >/dev/null)
[ $? = 3 ] && grep -q "cbtl sweep: dry: warning: .* cbtl training requests failed" <<<"$err" ||
  fail "a failing experiment in a sweep: $err"
sed 's|"simulator": "[^"]*"}|&|; s|dry"}}|dry", "max-failure-rate": 1}}|' failing.json >accepted.json
grep -q '"max-failure-rate": 1' accepted.json || fail "the test's accepted.json: $(cat accepted.json)"
"$cbtl" sweep accepted.json --out accepted --jobs 1 >/dev/null 2>&1 || fail "max-failure-rate 1 in a sweep: exit $?"

[ "$failures" = 0 ] && echo "sweep_cli: all checks passed"
exit $((failures > 0))
