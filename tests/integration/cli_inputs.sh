#!/usr/bin/env bash
# Every validated numeric option of every `cbtl` command: a bad value is a usage error (exit 2) whose message
# names the option, before any work starts; a good boundary value is accepted. Also the error format of bad
# input (exit 1, "cbtl <command>: error: ...").
# usage: cli_inputs.sh CBTL DOMAINS_DIR
set -u
cbtl=$1
domains=$2
source "$(dirname "$0")/expect.sh"

# bad OPTION VALUE...: each value is rejected with exit 2 and a message naming OPTION, for run and experiment.
bad_trial() {
  local option=$1
  shift
  for value in "$@"; do
    expect 2 "^cbtl [a-z ]+: error: $option: " -- "$cbtl" run "$cooking" "$option" "$value" -q
    expect 2 "^cbtl [a-z ]+: error: $option: " -- "$cbtl" experiment "$cooking" "$option" "$value" -q --seeds 0
  done
}

bad_trial --steps -1 x 1.5
bad_trial --eval-every 0 -3
bad_trial --eval-tasks 0 -1 99999999999
bad_trial --max-eval-steps 0 -1
bad_trial --epsilon -0.1 1.01 nan inf
bad_trial --shift-every 0 -10
bad_trial --periodic-reset-every 0 -1
bad_trial --unsatisfiable-stock -0.5 2 nan
bad_trial --max-iters 0 -1
bad_trial --num-improvements -1
bad_trial --max-improvement-attempts -1
bad_trial --memory-size 0 -1

# --seed is unsigned: "-1" used to wrap to 2^64 - 1.
for value in -1 -0 abc 1.5 18446744073709551616; do
  expect 2 "^cbtl [a-z ]+: error: --seed: " -- "$cbtl" run "$cooking" --seed "$value" -q
  expect 2 "^cbtl [a-z ]+: error: --seed: " -- "$cbtl" solve "$cooking" --seed "$value"
done
for option in --max-iters --memory-size; do
  expect 2 "^cbtl [a-z ]+: error: $option: " -- "$cbtl" solve "$cooking" "$option" 0
done
expect 2 "^cbtl [a-z ]+: error: --num-improvements: " -- "$cbtl" solve "$cooking" --num-improvements -2
expect 2 "^cbtl [a-z ]+: error: --max-improvement-attempts: " -- "$cbtl" solve "$cooking" --max-improvement-attempts -2

# experiment's own lists.
for value in -1..3 0..-2 x "" 5..2; do
  expect 2 "cbtl experiment: error: --seeds" -- "$cbtl" experiment "$cooking" --seeds "$value" -q
done
for value in x -100 10,y; do
  expect 2 "cbtl experiment: error: --columns" -- "$cbtl" experiment "$cooking" --columns "$value" -q --seeds 0 --steps 10
done

# render: camera angles and distance (checked before the scene is read).
scene=$domains/feeding/feeding.xml
expect 2 "^cbtl [a-z ]+: error: --elevation: " -- "$cbtl" render "$scene" --out "$work/x.png" --elevation 91
expect 2 "^cbtl [a-z ]+: error: --elevation: " -- "$cbtl" render "$scene" --out "$work/x.png" --elevation nan
expect 2 "^cbtl [a-z ]+: error: --azimuth: " -- "$cbtl" render "$scene" --out "$work/x.png" --azimuth 1e9
expect 2 "^cbtl [a-z ]+: error: --distance: " -- "$cbtl" render "$scene" --out "$work/x.png" --distance -1
expect 2 "^cbtl [a-z ]+: error: --width: " -- "$cbtl" render "$scene" --out "$work/x.png" --width 0
expect 2 "^cbtl [a-z ]+: error: --height: " -- "$cbtl" render "$scene" --out "$work/x.png" --height -5

# llm: timeouts, attempts and rounds (checked before any request).
expect 2 "^cbtl [a-z ]+: error: --timeout-ms: " -- "$cbtl" llm probe --base-url http://127.0.0.1:9/v1 --model m --timeout-ms 0
expect 2 "^cbtl [a-z ]+: error: --connect-timeout-ms: " -- "$cbtl" llm probe --base-url http://127.0.0.1:9/v1 --model m --connect-timeout-ms -1
expect 2 "^cbtl [a-z ]+: error: --attempts: " -- "$cbtl" llm probe --base-url http://127.0.0.1:9/v1 --model m --attempts 0
expect 2 "^cbtl [a-z ]+: error: --rounds: " -- "$cbtl" llm books --rounds 0
expect 2 "^cbtl [a-z ]+: error: --attempts: " -- "$cbtl" llm books --attempts 11

# Boundary values are accepted: a periodic reset every step, epsilon 0 and 1, zero training steps.
expect 0 "" -- "$cbtl" run "$cooking" --steps 4 --eval-every 2 --eval-tasks 1 --max-eval-steps 1 -q \
  --nonstationary periodic-reset --periodic-reset-every 1 --shift-every 1
expect 0 "" -- "$cbtl" run "$cooking" --steps 0 --eval-tasks 1 --max-eval-steps 1 -q --approach epsilon-greedy --epsilon 1
expect 0 "" -- "$cbtl" run "$cooking" --steps 2 --eval-every 1 --eval-tasks 1 --max-eval-steps 1 -q --epsilon 0 \
  --unsatisfiable-stock 1 --seed 18446744073709551615
expect 0 "" -- "$cbtl" experiment "$cooking" --steps 2 --eval-every 1 --eval-tasks 1 --max-eval-steps 1 -q --seeds 0 \
  --columns 0,2

# Bad input: exit 1 with "cbtl <command>: error:".
expect 1 "^cbtl run: error: .*missing.json" -- "$cbtl" run "$cooking" --steps 1 --profile "$work/missing.json"
expect 1 "^cbtl solve: error: .*missing.json" -- "$cbtl" solve "$cooking" --profile "$work/missing.json"
: >"$work/plainfile"
expect 1 "^cbtl experiment: error: .*plainfile" -- "$cbtl" experiment "$cooking" --seeds 0 --steps 1 --eval-tasks 1 -q \
  --out "$work/plainfile/sub"

# Commands: an unknown one is named with the nearest; `--seeds 0-9` is not seed 0 alone.
expect 2 "^cbtl: error: 'repll' is not a cbtl command; did you mean 'repl'\?" -- "$cbtl" repll
expect 2 "^cbtl: error: 'frobnicate' is not a cbtl command$" -- "$cbtl" frobnicate
expect 2 "--seeds wants 'LO..HI' or a comma-separated list, not '0-9'" -- "$cbtl" experiment "$cooking" --seeds 0-9
# Options: a mistyped one is named with the nearest option of its command (not CLI11's list of extra words).
expect 2 "^cbtl run: error: unknown option '--step'; did you mean '--steps'\?" -- "$cbtl" run "$cooking" --step 10
expect 2 "^cbtl experiment: error: unknown option '--seed'; did you mean '--seeds'\?" -- \
  "$cbtl" experiment "$cooking" --seed 3
expect 2 "^cbtl simulator check: error: unknown option '--sed'; did you mean '--seed'\?" -- \
  "$cbtl" simulator check "$cooking" --sed=2
expect 2 "^cbtl run: error: unknown option '--frobnicate'$" -- "$cbtl" run "$cooking" --frobnicate
expect 2 "^cbtl run: error: --max-failure-rate: " -- "$cbtl" run "$cooking" --max-failure-rate 1.5
# Help: options grouped by topic, examples at the end, for every command that runs a program.
for command in run experiment solve repl feedback "simulator check"; do
  # shellcheck disable=SC2086
  out=$("$cbtl" $command --help 2>&1)
  for part in "Examples:" "World and simulator:"; do
    grep -q "$part" <<<"$out" || fail "cbtl $command --help has no '$part'"
  done
done
for command in run experiment solve repl; do
  out=$("$cbtl" $command --help 2>&1)
  grep -q "^Solver:" <<<"$out" || fail "cbtl $command --help groups no Solver options"
done

# File inputs: what is not a regular file (a pipe that would block for ever, /dev/zero that never ends, a folder)
# and what is over its size limit is refused with exit 1 naming the file, in bounded time and memory (the limits
# below guard this script against a binary that reads without end).
# (AddressSanitizer reserves terabytes of address space for its shadow: under it, only the timeout applies.)
if grep -qa __asan_init "$cbtl"; then bounded() { timeout 20 "$@"; }; else bounded() { (ulimit -v 4000000; timeout 20 "$@"); }; fi
mkfifo "$work/pipe"
head -c $((5 * 1024 * 1024)) /dev/zero | tr '\0' ' ' >"$work/huge.cbtl"
truncate -s 300M "$work/huge.json"
feedback_event='mealCritique(seasoning, salt, 3, 31, 0.9, wantHotter, wantMore)'
expect 1 "cannot read file '.*pipe': not a regular file \(a pipe\)" -- bounded "$cbtl" solve "$work/pipe"
expect 1 "cannot read file '/dev/zero': not a regular file \(a device\)" -- bounded "$cbtl" solve /dev/zero
expect 1 "huge.cbtl': the program is larger than 4 MiB" -- bounded "$cbtl" solve "$work/huge.cbtl"
expect 1 "/dev/zero: not a regular file \(a device\), so not read as the profile" -- \
  bounded "$cbtl" solve "$cooking" --profile /dev/zero
expect 1 "pipe: not a regular file \(a pipe\), so not read as the observation file" -- \
  bounded "$cbtl" solve "$cooking" --observe "$work/pipe"
expect 1 "huge.json: the observation file is larger than 256 MiB" -- \
  bounded "$cbtl" solve "$cooking" --observe "$work/huge.json"
expect 1 "not a regular file \(a directory\), so not read as the observation file" -- \
  bounded "$cbtl" solve "$cooking" --observe "$work"
expect 1 "pipe: not a regular file \(a pipe\), so not read as the solution" -- \
  bounded "$cbtl" feedback "$cooking" --profile "$work/p.json" --solution "$work/pipe" --event "$feedback_event"
expect 1 "/dev/zero: not a regular file \(a device\), so not read as the profile" -- \
  bounded "$cbtl" profile import --db "$work/store.sqlite" ann /dev/zero
expect 1 "huge.json: the profile is larger than 256 MiB" -- \
  bounded "$cbtl" profile import --db "$work/store.sqlite" ann "$work/huge.json"

echo "$failures failed"
[[ $failures -eq 0 ]]
