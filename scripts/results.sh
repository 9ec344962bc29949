#!/usr/bin/env bash
# Reproduces every figure in docs/results.md (Cooking; Cleaning and Books with ROBOT=1, about 30 minutes more on 2 cores).
# Usage: [ROBOT=1] scripts/results.sh [BUILD_DIR] [OUT_DIR]
# Each block is one `cbtl experiment` command; its table is printed and its CSVs land in OUT_DIR.
set -euo pipefail
build=${1:-build}
out=${2:-results}
cooking=domains/cooking/cooking.cbtl
cbtl="$build/bin/cbtl"

echo "== Figure 3: Cooking, 10 seeds, 10,000 steps, eval every 100 on 10 tasks"
"$cbtl" experiment "$cooking" --approaches cbtl,no-personalization,free-explore,exploit-only,epsilon-greedy \
  --seeds 0..9 --steps 10000 --eval-every 100 --eval-tasks 10 --columns 0,200,500,1000,2000,5000,10000 \
  --out "$out/figure3" --force -q

echo "== Table 1: unsatisfiable preferences (50% of restocks), 10 seeds x 10 eval tasks after 2,500 steps"
"$cbtl" experiment "$cooking" --approaches cbtl --replan --unsatisfiable-stock 0.5 \
  --seeds 0..9 --steps 2500 --eval-every 2500 --eval-tasks 10 --out "$out/table1-replan" --force -q
"$cbtl" experiment "$cooking" --approaches cbtl,no-personalization --unsatisfiable-stock 0.5 \
  --seeds 0..9 --steps 2500 --eval-every 2500 --eval-tasks 10 --out "$out/table1-noreplan" --force -q

echo "== Figure 5: nonstationary preferences (each range rescaled by U[0.9, 1.1] every 3,000 steps)"
for mode in no-adapt user-reset periodic-reset; do
  echo "-- cbtl, $mode"
  "$cbtl" experiment "$cooking" --approaches cbtl --nonstationary "$mode" --shift-every 3000 \
    --seeds 0..9 --steps 10000 --eval-every 100 --eval-tasks 10 --columns 0,2900,3100,3500,4000,5900,6500,8900,10000 \
    --out "$out/figure5-$mode" --force -q
done
echo "-- free-explore, no-adapt"
"$cbtl" experiment "$cooking" --approaches free-explore --nonstationary no-adapt --shift-every 3000 \
  --seeds 0..9 --steps 10000 --eval-every 100 --eval-tasks 10 --columns 0,2900,3100,3500,4000,5900,6500,8900,10000 \
  --out "$out/figure5-free-explore" --force -q

if [[ ${ROBOT:-0} == 1 ]]; then
  # Cleaning: surfacePreferred vs the hidden user; Books: the range of motion vs the hidden [0.1, 0.3] m and the
  # enjoyed book handed over first.
  for domain in cleaning books; do
    echo "== Figure 3: $domain, 10 seeds, 5,000 steps, eval every 500 on 10 tasks (the paper's protocol)"
    "$cbtl" experiment "domains/$domain/$domain.cbtl" \
      --approaches cbtl,no-personalization,free-explore,exploit-only,epsilon-greedy \
      --seeds 0..9 --steps 5000 --eval-every 500 --eval-tasks 10 --columns 0,500,1000,2000,3000,5000 \
      --out "$out/figure3-$domain" --force -q
    echo "-- $domain: what was learned, against the hidden user"
    python3 scripts/learned-vs-hidden.py "$domain" "$out/figure3-$domain"
  done
fi
