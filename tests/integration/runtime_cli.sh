#!/usr/bin/env bash
# End-to-end checks of `cbtl run` and `cbtl solve`: outputs, determinism, and exit codes for bad input.
# usage: runtime_cli.sh CBTL DOMAINS_DIR
set -u
cbtl=$1
domains=$2
source "$(dirname "$0")/expect.sh"

# A short Cooking trial writes every output; the same seed reproduces it byte for byte.
expect 0 "eval satisfaction" -- "$cbtl" run "$cooking" --steps 300 --eval-every 100 --eval-tasks 2 --seed 3 --out "$work/a"
for f in train.csv eval.csv config.json profile.json models/0.json models/300.json; do
  [[ -s $work/a/$f ]] || { echo "FAIL: missing $f"; failures=$((failures + 1)); }
done
expect 0 "" -- "$cbtl" run "$cooking" --steps 300 --eval-every 100 --eval-tasks 2 --seed 3 --out "$work/b" -q
cmp -s "$work/a/train.csv" "$work/b/train.csv" && cmp -s "$work/a/eval.csv" "$work/b/eval.csv" \
  || { echo "FAIL: the same seed gave different CSVs"; failures=$((failures + 1)); }
lines=$(wc -l <"$work/a/eval.csv")
[[ $lines -eq 5 ]] || { echo "FAIL: eval.csv has $lines lines, wanted 5 (header + steps 0,100,200,300)"; failures=$((failures + 1)); }

# Every approach runs, and can start from a saved profile.
for a in cbtl no-personalization free-explore exploit-only epsilon-greedy; do
  expect 0 "" -- "$cbtl" run "$cooking" --approach "$a" --steps 200 --eval-every 100 --eval-tasks 1 -q --profile "$work/a/profile.json"
done
expect 0 "" -- "$cbtl" run "$cooking" --steps 200 --eval-every 100 --eval-tasks 1 -q --nonstationary user-reset --shift-every 50
expect 0 "" -- "$cbtl" run "$cooking" --steps 200 --eval-every 100 --eval-tasks 1 -q --unsatisfiable-stock 0.5 --replan

# One CSP: its solution and plan, and with --explain the constraint statistics.
expect 0 "serve\\(seasoning\\)" -- "$cbtl" solve "$cooking" --seed 1
expect 0 "rejected +evaluated" -- "$cbtl" solve "$cooking" --seed 1 --explain --profile "$work/a/profile.json"
cat >"$work/infeasible.cbtl" <<'CBTL'
domain nothing;
var a : real in 0 .. 1;
require impossible: a > 2;
sample a ~ uniform;
CBTL
expect 3 "impossible +.*infeasible.cbtl:3:1" -- "$cbtl" solve "$work/infeasible.cbtl" --max-iters 200

# A clearance no plan can keep (the user of Books 1.5 m away from the robot: the handover base is closer) makes the
# request unsolvable, and the failure names the declaration with its place.
sed -e 's|world "../home/home.xml";|world "'"$domains"'/home/home.xml";|' \
    -e 's|clearance person: "user" >= 5 cm;|clearance person: "user" >= 150 cm;|' \
    "$domains/books/books.cbtl" >"$work/farbooks.cbtl"
expect 3 "every collision check keeps clearance person: 1500 mm from user \\(.*farbooks.cbtl:[0-9]+:1\\)" -- \
  "$cbtl" solve "$work/farbooks.cbtl" --max-iters 300

# Bad input: clear errors and exit codes, never a crash.
expect 2 "unknown approach 'ours'" -- "$cbtl" run "$cooking" --approach ours
expect 2 "" -- "$cbtl" run "$cooking" --steps notanumber
expect 2 "unknown --nonstationary" -- "$cbtl" run "$cooking" --nonstationary sometimes
expect 1 "^cbtl run: error: cannot read file .*missing.cbtl.$" -- "$cbtl" run "$work/missing.cbtl"
printf '{"format": "cbtl-profile", "version": 1, "domain": "cooking", "generators": {"userEnjoysMeal": 3}}' >"$work/corrupt.json"
expect 1 "corrupt.json: generators.userEnjoysMeal" -- "$cbtl" run "$cooking" --steps 10 --profile "$work/corrupt.json"
printf 'not json' >"$work/garbage.json"
expect 1 "garbage.json: not valid JSON" -- "$cbtl" solve "$cooking" --profile "$work/garbage.json"
printf 'domain broken;\nvar x : real in 0 .. 1\n' >"$work/broken.cbtl"
expect 1 "broken.cbtl:" -- "$cbtl" run "$work/broken.cbtl"
expect 1 "no simulator for domain 'nothing'" -- "$cbtl" run "$work/infeasible.cbtl" --steps 10
expect 1 "no task named 'cookDinner'" -- "$cbtl" solve "$cooking" --task cookDinner

# Feeding gives the drink where the caregiver put it, far end of the table included: the first dry-run tier has no
# planner, so the grasp's approach and the way back from the handle must be straight segments that keep the user's
# clearance (before they were, the solver moved this drink 45 cm first).
printf '{"drinkXY": [0.32, 0.67], "plateXY": [0.377, 0.474]}' >"$work/far-drink.json"
for seed in 0 1 2; do
  expect 0 '^  drinkPos = \(0\.32, 0\.67\)$' -- "$cbtl" solve "$domains/feeding/feeding.cbtl" --task giveDrink \
    --seed "$seed" --observe "$work/far-drink.json"
done

echo "$failures failed"
[[ $failures -eq 0 ]]
