#!/usr/bin/env bash
# `cbtl experiment` as a person at a terminal sees it: a progress line with the count and an ETA after each trial
# (only on a terminal: none when piped), Ctrl-C saying what was kept with the exact command that continues, that
# command finishing the experiment, and the trials finished before it keeping their recorded times.
# usage: interrupt_cli.sh CBTL DOMAINS_DIR
set -u
cbtl=$(realpath "$1")
domains=$(realpath "$2")
source "$(dirname "$0")/expect.sh"
cd "$work" || exit 2
common=(experiment "$cooking" --approaches cbtl --seeds 0..3 --eval-every 100 --eval-tasks 5 --jobs 1)
quick=("${common[@]}" --steps 200)
args=("${common[@]}" --steps 3000)

# A terminal (script(1) gives the command a pseudo-terminal): the count and the ETA after every trial.
script -qec "$cbtl ${quick[*]}" /dev/null >tty.txt 2>&1 || fail "the experiment on a terminal failed: $(cat tty.txt)"
grep -q "^4 trials (1 approach x 4 seeds) on 1 job" tty.txt || fail "no trial count on a terminal: $(cat tty.txt)"
grep -q "^\[2/4 trials\] cbtl seed 1 (.* s); elapsed [0-9]*:[0-9][0-9], ETA [0-9]*:[0-9][0-9]" tty.txt ||
  fail "no progress line on a terminal: $(cat tty.txt)"
# Piped: the per-trial lines only.
"$cbtl" "${quick[@]}" >piped.txt 2>&1 || fail "the piped experiment failed"
! grep -q "trials\]" piped.txt || fail "a progress line when piped: $(cat piped.txt)"

# Ctrl-C after the first trial finished: what was kept, and the command that continues.
"$cbtl" "${args[@]}" --out "out dir" >run.out 2>run.err &
pid=$!
for _ in $(seq 1 600); do [[ -f "out dir/cbtl/seed0/complete.json" && -f "out dir/cbtl/seed1/checkpoint.json" ]] && break; sleep 0.1; done
kill -INT "$pid"
wait "$pid"
rc=$?
[[ $rc -eq 130 ]] || fail "Ctrl-C exit $rc"
grep -q "^cbtl experiment: interrupted; every finished trial, and each unfinished one up to its last checkpoint, stays in out dir; continue with:" run.err ||
  fail "no word of what was kept: $(cat run.err)"
resume=$(grep -A1 "continue with:" run.err | tail -1 | sed 's/^ *//')
[[ $resume == *"--out 'out dir'"*"--resume" ]] || fail "the resume command: $resume"
eval "$resume" >resumed.out 2>resumed.err || fail "the printed command failed: $(cat resumed.err)"
grep -q "cbtl seed 0: .*(finished earlier, [0-9.]* s)" resumed.err || fail "seed 0 not read back: $(cat resumed.err)"
[[ -f "out dir/summary.csv" ]] || fail "the resumed experiment wrote no summary"
# The table's s/trial is a time, not 0.00 for the trials finished earlier.
grep -Eq "^cbtl +.* [0-9]+\.[0-9]{2}$" resumed.out && ! grep -Eq "^cbtl +.* 0\.00$" resumed.out ||
  fail "s/trial after --resume: $(cat resumed.out)"

if [[ $failures -gt 0 ]]; then echo "$failures failure(s)"; exit 1; fi
echo "interrupt_cli: all checks passed"
