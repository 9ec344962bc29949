#!/usr/bin/env bash
# `cbtl` runs a graph that `cbtlc emit --format json` wrote exactly as it runs the .cbtl file: for each domain,
# `cbtl run` (same seed, small budgets) and `cbtl solve` give byte-identical outputs from both; the run
# folders differ only in config.json's "file". Also: the scene lookup of an emitted robot-domain graph
# (app/ScenePath.h), `cbtl experiment` on a graph, and a broken graph's error with its JSON Pointer.
# usage: emitted_graph_cli.sh CBTL CBTLC DOMAINS_DIR
set -u
cbtl=$1
cbtlc=$2
domains=$3
source "$(dirname "$0")/expect.sh"

# The run's stdout without what legitimately differs (wall clock, the output folder's name).
stable_stdout() { grep -v -e ' s wall clock;' -e '^wrote ' "$1"; }

run_trial() {  # run_trial FILE OUT ARGS... : one cbtl run, its stdout in OUT.stdout
  local file=$1 out=$2
  shift 2
  "$cbtl" run "$file" "$@" --out "$out" >"$out.stdout" 2>"$out.stderr" \
    || { fail "cbtl run $file exited $?"; cat "$out.stderr"; }
}

run_both() {  # run_both DOMAIN ARGS... : run from the .cbtl and from its graph, compare everything
  local d=$1
  shift
  local cbtl_file=$domains/$d/$d.cbtl graph=$work/graphs/$d.json
  run_trial "$cbtl_file" "$work/$d.src" "$@"
  run_trial "$graph" "$work/$d.json" "$@"
  grep -q "eval satisfaction" "$work/$d.json.stdout" || fail "$d: no summary from the emitted graph's run"
  diff <(stable_stdout "$work/$d.src.stdout") <(stable_stdout "$work/$d.json.stdout") \
    || fail "$d: cbtl run printed something else for the emitted graph"
  diff -r -x config.json -x timing.json "$work/$d.src" "$work/$d.json" || fail "$d: the run folders differ"
  diff <(grep -v '"file":' "$work/$d.src/config.json") <(grep -v '"file":' "$work/$d.json/config.json") \
    || fail "$d: config.json differs beyond its \"file\""
  grep -q "\"file\": \"$graph\"" "$work/$d.json/config.json" || fail "$d: config.json does not name the graph"
  "$cbtl" solve "$cbtl_file" --seed 2 --max-iters 300 >"$work/$d.solve.src" 2>&1
  "$cbtl" solve "$graph" --seed 2 --max-iters 300 >"$work/$d.solve.json" 2>&1
  cmp -s "$work/$d.solve.src" "$work/$d.solve.json" || fail "$d: cbtl solve differs for the emitted graph"
  grep -q ": Solved" "$work/$d.solve.json" || fail "$d: cbtl solve did not solve the emitted graph"
  echo "ok: $d runs and solves the same from its emitted graph"
}

# Emitted with the domain file's absolute path, into another folder: spans name the source folder, so the
# robot domains find their scenes from anywhere.
mkdir -p "$work/graphs"
for d in cooking cleaning books feeding; do
  expect 0 "" -- "$cbtlc" emit --format json "$domains/$d/$d.cbtl"
  "$cbtlc" emit --format json "$domains/$d/$d.cbtl" >"$work/graphs/$d.json"
done
run_both cooking --steps 60 --eval-every 30 --eval-tasks 2 --seed 4
# Robot domains: very few steps, short evaluation episodes (a Books episode's later steps plan motions and take
# tens of seconds on a loaded machine).
run_both feeding --steps 4 --eval-every 2 --eval-tasks 1 --max-iters 200 --seed 4
run_both cleaning --steps 4 --eval-every 2 --eval-tasks 1 --max-eval-steps 2 --max-iters 200 --seed 4
run_both books --steps 1 --eval-every 1 --eval-tasks 1 --max-eval-steps 1 --max-iters 200 --seed 4

# Emitted from the domain's folder (spans say "feeding.cbtl"), the graph alone in another folder: run where
# cbtlc ran, the span's folder has the scene; from a third folder there is none, and the message says where
# cbtl looked; with the scene copied beside the graph, the graph runs from anywhere.
mkdir -p "$work/ship/alone" "$work/elsewhere"
(cd "$domains/feeding" && "$cbtlc" emit --format json feeding.cbtl) >"$work/ship/alone/feeding.json"
pushd "$domains/feeding" >/dev/null
expect 0 ": Solved" -- "$cbtl" solve "$work/ship/alone/feeding.json" --max-iters 300
cd "$work/elsewhere"
expect 1 "world scene 'feeding.xml' not found \(looked for .*alone/feeding.xml, feeding.xml\)" \
  -- "$cbtl" solve "$work/ship/alone/feeding.json"
cp "$domains/feeding/feeding.xml" "$work/ship/alone/"
cp -r "$domains/assets" "$work/ship/"  # the scene includes ../assets/gen3.xml
expect 0 ": Solved" -- "$cbtl" solve "$work/ship/alone/feeding.json" --max-iters 300
popd >/dev/null

# cbtl experiment takes a graph as well.
expect 0 "" -- "$cbtl" experiment "$work/graphs/cooking.json" --approaches cbtl --seeds 0..1 --steps 20 \
  --eval-every 10 --eval-tasks 1 -q --out "$work/experiment"
[[ -s $work/experiment/summary.csv ]] || fail "cbtl experiment on a graph wrote no summary.csv"

# A broken graph: the reader's message names the field; not valid JSON, a wrong version.
sed 's/"op": "and"/"op": "nand"/' "$work/graphs/cooking.json" >"$work/broken.json"
expect 1 "broken.json: (/[a-z_]+/[0-9]+)+(/[a-z_]+)*/op: unknown operation 'nand'" \
  -- "$cbtl" run "$work/broken.json" --steps 10
sed 's/"version": [0-9]*/"version": 1/' "$work/graphs/cooking.json" >"$work/old.json"
expect 1 "old.json: /version: version 1 is not supported" -- "$cbtl" solve "$work/old.json"
printf '{ "format": "cbtl-constraint-graph", ' >"$work/cut.json"
expect 1 "cut.json: not valid JSON" -- "$cbtl" solve "$work/cut.json"

echo "$failures failed"
[[ $failures -eq 0 ]]
