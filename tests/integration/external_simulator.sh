#!/usr/bin/env bash
# External simulators (docs/simulator-protocol.md) end to end:
#  - the coffee domain (a .cbtl file and a Python simulator, no C++) fits its program, runs, learns the hidden
#    drinker's tastes, and gives the same results for the same seed, serially and on two jobs;
#  - Cooking served over the protocol by `cbtl simulator serve` gives byte-identical results to Cooking in process;
#  - a simulator that goes wrong (crashes, prints noise, hangs, sends an undeclared event, an ill-typed value, a
#    manifest that does not fit, a newer protocol) is a clear error (exit 1) naming the request and the line, and
#    never hangs the run.
# usage: external_simulator.sh CBTL DOMAINS_DIR
set -u
cbtl=$(realpath "$1")
domains=$(realpath "$2")
source "$(dirname "$0")/expect.sh"
coffee=$domains/coffee/coffee.cbtl
faulty="python3 $(cd "$(dirname "$0")" && pwd)/simulators/faulty_sim.py $domains/coffee"
# Every run below is bounded: a hang would fail the test instead of stalling it.
limit="timeout 120"

# --- the coffee domain ------------------------------------------------------------------------------------
expect 0 "simulator 'coffee_sim.py' fits .*: protocol 1; 2 observations, 1 action, 1 feedback event, 1 task" -- \
  $limit "$cbtl" simulator check "$coffee"
expect 0 '"waterLeft"' -- $limit "$cbtl" simulator check "$coffee" --seed 4

# From another folder: the `simulator` line runs in the program's folder.
(cd "$work" && expect 0 "fits" -- $limit "$cbtl" simulator check "$coffee")

expect 0 "eval satisfaction" -- $limit "$cbtl" run "$coffee" --steps 150 --eval-every 50 --eval-tasks 20 --seed 0 \
  --out "$work/coffee0"
# CBTL learns the hidden tastes: the last checkpoint's cups are liked.
last=$(tail -n 1 "$work/coffee0/eval.csv")
python3 - "$work/coffee0/eval.csv" <<'PY' || fail "coffee: CBTL did not learn the drinker's tastes"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
first, last = float(rows[0]["eval_mean_user_satisfaction"]), float(rows[-1]["eval_mean_user_satisfaction"])
met = {k: float(rows[-1]["eval_%s_met_rate" % k]) for k in ("temperature", "strength")}
print("coffee: eval satisfaction %+.2f at step 0, %+.2f at step %s; met at the end: %s"
      % (first, last, rows[-1]["training_step"], met))
sys.exit(0 if last >= 0.8 and last > first and min(met.values()) >= 0.9 else 1)
PY
# Same seed, same results.
expect 0 "" -- $limit "$cbtl" run "$coffee" --steps 150 --eval-every 50 --eval-tasks 20 --seed 0 \
  --out "$work/coffee0b" -q
cmp -s "$work/coffee0/eval.csv" "$work/coffee0b/eval.csv" || fail "coffee: the same seed gave another eval.csv"
cmp -s "$work/coffee0/train.csv" "$work/coffee0b/train.csv" || fail "coffee: the same seed gave another train.csv"
# A run killed (-9) mid-way and resumed gives the bytes of the uninterrupted one: the resumed run replays the
# training world's requests to a new simulator process, which must answer as the first did.
CBTL_TEST_KILL_AT=step:70 $limit "$cbtl" run "$coffee" --steps 150 --eval-every 50 --eval-tasks 20 --seed 0 \
  --out "$work/killed" -q >/dev/null 2>&1
rc=$?
[[ $rc -eq 137 ]] || fail "coffee: CBTL_TEST_KILL_AT=step:70 exited $rc, wanted 137 (killed)"
expect 0 "" -- $limit "$cbtl" run "$coffee" --steps 150 --eval-every 50 --eval-tasks 20 --seed 0 \
  --out "$work/killed" --resume -q
for f in train.csv eval.csv profile.json; do
  cmp -s "$work/coffee0/$f" "$work/killed/$f" || fail "coffee: the resumed run's $f differs from the uninterrupted one's"
done
# Serial and parallel experiments agree (each trial has its own simulator process).
expect 0 "" -- $limit "$cbtl" experiment "$coffee" --approaches cbtl,no-personalization --seeds 0..1 --steps 60 \
  --eval-every 30 --eval-tasks 5 --jobs 1 --out "$work/serial" -q
expect 0 "" -- $limit "$cbtl" experiment "$coffee" --approaches cbtl,no-personalization --seeds 0..1 --steps 60 \
  --eval-every 30 --eval-tasks 5 --jobs 2 --out "$work/parallel" -q
for f in summary.csv cbtl/seed0/eval.csv cbtl/seed1/train.csv no-personalization/seed1/eval.csv; do
  if [[ ! -f "$work/serial/$f" ]]; then fail "experiment wrote no $f"; continue; fi
  cmp -s "$work/serial/$f" "$work/parallel/$f" || fail "coffee: --jobs 2 differs from --jobs 1 in $f"
done
# Nonstationary options reach the simulator: the drinker's tastes shift, and User Reset hears of it.
expect 0 "eval satisfaction" -- $limit "$cbtl" run "$coffee" --steps 60 --eval-every 30 --eval-tasks 5 \
  --nonstationary user-reset --shift-every 20 --out "$work/shift"
# The REPL and solve use the external simulator too.
expect 0 "status: solved" -- $limit "$cbtl" solve "$coffee" --seed 2
printf 'solve\nact\nquit\n' >"$work/session.repl"
expect 0 "tasteCritique" -- $limit "$cbtl" repl "$coffee" --echo <"$work/session.repl"

# --- the protocol reproduces an in-process domain exactly ------------------------------------------------
serve="$cbtl simulator serve $cooking"
expect 0 "" -- $limit "$cbtl" run "$cooking" --steps 200 --eval-every 100 --eval-tasks 3 --seed 1 --out "$work/inproc" -q
expect 0 "" -- $limit "$cbtl" run "$cooking" --steps 200 --eval-every 100 --eval-tasks 3 --seed 1 --out "$work/proto" -q \
  --simulator "$serve"
for f in train.csv eval.csv profile.json; do
  cmp -s "$work/inproc/$f" "$work/proto/$f" || fail "cooking over the protocol: $f differs from in process"
done

# The reference server answers bad requests with "ok": false and carries on.
served=$(printf '%s\n' 'not json' '{"id":1,"op":"reset","world":0,"seed":1}' \
  '{"id":2,"op":"hello","protocol":1,"domain":"cooking","options":{}}' \
  '{"id":3,"op":"act","world":0,"action":"serve","args":{"mealName":"soup"}}' \
  '{"id":4,"op":"act","world":0,"action":"fly","args":{}}' '{"id":5,"op":"observe","world":7}' \
  '{"id":6,"op":"teleport"}' '{"id":7,"op":"bye"}' | $limit "$cbtl" simulator serve "$cooking" 2>&1)
rc=$?
[[ $rc -eq 0 ]] || fail "simulator serve exited $rc on bad requests"
# answer ID OK [PATTERN]: the answer with that id says "ok": OK (and matches PATTERN).
answer() {
  local line
  line=$(grep -E "\"id\":$1[,}]" <<<"$served")
  grep -q "\"ok\":$2" <<<"$line" || fail "simulator serve: request $1 should be ok:$2: ${line:-no answer}"
  [[ -z ${3:-} ]] || grep -qE -- "$3" <<<"$line" || fail "simulator serve: request $1's answer lacks /$3/: $line"
}
grep -q '^{"error":"[^"]*","ok":false}$' <<<"$served" || fail "simulator serve: no answer to the line that is not JSON"
answer 1 false "say hello first"
answer 2 true '"protocol":1'
answer 3 true '"step":'
answer 4 false "the program calls no action 'fly'"
answer 5 false "there is no world 7"
answer 6 false "no request .{1,2}teleport"
answer 7 true

# `simulator check` exercises what a run does, so a simulator that fits but breaks on acting, idling or twinning is
# caught by it, with the request that broke the protocol.
expect 0 "act brew\(.*\): applied, step" -- $limit "$cbtl" simulator check "$coffee"
expect 0 "answered every request: reset, observe, act, idle, twin" -- $limit "$cbtl" simulator check "$coffee"
check_with() { $limit "$cbtl" simulator check "$coffee" --simulator "$@"; }
expect 1 "broke the protocol at act brew\(.*\) \(world\): .*not JSON: 'brewing a .* cup'" -- check_with "$faulty noise"
expect 1 "broke the protocol at act brew\(.*\): .*exited with status 3" -- check_with "$faulty crash"
expect 1 "broke the protocol at act brew\(.*\): .*the grinder jammed" -- check_with "$faulty refuse"
expect 1 "broke the protocol at twin: .*exited with status 1" -- check_with "$faulty twin-keyerror"
expect 1 "KeyError: 'twin'" -- check_with "$faulty twin-keyerror"
expect 1 "broke the protocol at idle.*: .*not JSON: 'waiting...'" -- check_with "$faulty idle-noise"

# A run whose training world gets stuck (the tank runs dry, so no cup can be brewed) is not an ordinary result: a
# warning with the cause, and exit 3 unless the user accepts it.
expect 3 "warning: [0-9]+ of [0-9]+ training requests failed \(.*above --max-failure-rate 10 %\): [0-9]+ not solved" -- \
  $limit "$cbtl" run "$coffee" --steps 40 --eval-every 20 --eval-tasks 3 -q --simulator "$faulty dry"
expect 3 "world 0 is reset once" -- $limit "$cbtl" run "$coffee" --steps 40 --eval-every 20 --eval-tasks 3 -q \
  --simulator "$faulty dry"
expect 0 "" -- $limit "$cbtl" run "$coffee" --steps 40 --eval-every 20 --eval-tasks 3 -q --simulator "$faulty dry" \
  --max-failure-rate 1
expect 3 "cbtl experiment: warning: [0-9]+ of [0-9]+ cbtl training requests failed" -- \
  $limit "$cbtl" experiment "$coffee" --approaches cbtl --seeds 0..1 --steps 40 --eval-every 20 --eval-tasks 3 -q \
  --simulator "$faulty dry"

# --- what goes wrong on the other side --------------------------------------------------------------------
run_with() { $limit "$cbtl" run "$coffee" --steps 40 --eval-every 20 --eval-tasks 3 -q --simulator "$@"; }
expect 1 "exited with status 3 before answering request [0-9]+ \(act brew\)" -- run_with "$faulty crash"
expect 1 "the boiler burst at request" -- run_with "$faulty crash"
expect 1 "its output line [0-9]+ is not JSON: 'brewing a .* cup' \(stdout carries the protocol only" -- \
  run_with "$faulty noise"
expect 1 "did not answer request [0-9]+ \(act brew\) within 3000 ms; it was stopped" -- \
  run_with "$faulty hang" --simulator-timeout-ms 3000
expect 1 "output line [0-9]+: feedback event 'spilled' is not declared by the program" -- \
  run_with "$faulty undeclared-event"
expect 1 "tasteCritique argument 'heat': 'lukewarm' is not a Heat \(expected heatGood, tooCold, or tooHot\)" -- \
  run_with "$faulty wrong-type"
expect 1 "a step result has no field \"satisfation\"" -- run_with "$faulty unknown-field"
expect 1 "'waterLeft': expected a finite number \(real\), got \"plenty\"" -- run_with "$faulty bad-observation"
expect 1 "it refused request [0-9]+ \(act brew\) \(its output line [0-9]+\): the grinder jammed" -- \
  run_with "$faulty refuse"
expect 1 "speaks protocol 2, cbtl speaks protocol 1" -- run_with "$faulty protocol2"
# Every mismatch of a manifest at once.
out=$(run_with "$faulty manifest" 2>&1)
for pattern in "does not fit the program \(5 problems\)" \
  "the program observes 'beansLeft' \(.*coffee.cbtl:[0-9]+:[0-9]+\); the simulator does not provide it" \
  "provides the observation 'outsideTemperature', which the program does not declare" \
  "the program calls the action 'brew' \(.*coffee.cbtl:[0-9]+:[0-9]+\); the simulator does not perform it" \
  "sends the feedback event 'spilled', which the program does not declare" \
  "may ask for the task 'makeTea', which the program does not define"; do
  grep -qE -- "$pattern" <<<"$out" || { fail "manifest check lacks /$pattern/"; echo "$out"; }
done
expect 1 "exited with status 127 before answering request 1 \(hello\)" -- run_with "no-such-simulator-program"
expect 1 "no-such-simulator-program: not found" -- run_with "no-such-simulator-program"
expect 1 "exited with status 0 before answering request 1 \(hello\)" -- run_with "true"
expect 2 "--simulator-timeout-ms" -- "$cbtl" run "$coffee" --simulator-timeout-ms 0
# A robot domain's scene state is what its plans are checked against, and it does not cross the protocol: refused.
expect 1 "has a robot scene \(world \"feeding.xml\"\).*runs with its built-in simulator" -- \
  "$cbtl" run "$domains/feeding/feeding.cbtl" --steps 1 -q --simulator "python3 $domains/coffee/coffee_sim.py"
# A domain with neither a built-in simulator nor a simulator line says how to give one.
sed '/^simulator /d' "$coffee" >"$work/nosim.cbtl"
expect 1 "no simulator for domain 'coffee' .*--simulator CMD" -- "$cbtl" run "$work/nosim.cbtl" --steps 1 -q
expect 1 "has no .simulator" -- "$cbtl" simulator check "$work/nosim.cbtl"
# ... and runs when given one on the command line, from the folder it names.
expect 0 "eval satisfaction" -- $limit "$cbtl" run "$work/nosim.cbtl" --steps 10 --eval-every 10 --eval-tasks 2 \
  --simulator "python3 $domains/coffee/coffee_sim.py"

if [[ $failures -gt 0 ]]; then echo "$failures failure(s)"; exit 1; fi
echo "external simulator: all checks passed"
