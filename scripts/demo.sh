#!/usr/bin/env bash
# The main job on embedded defaults (no network, no API key):
#  1. check every domain file and print its constraint-graph summary;
#  2. solve the Feeding request the simulated world asks for, against its MuJoCo scene, and print the plan;
#  3. run the paper's Cooking experiment for CBTL and No Personalization over three seeds (10,000 steps,
#     evaluation every 100 steps on 10 held-out tasks) and print the summary table.
set -euo pipefail
build=${1:-build}
status=0
for f in domains/cooking/cooking.cbtl domains/cleaning/cleaning.cbtl domains/books/books.cbtl domains/feeding/feeding.cbtl; do
  "$build/bin/cbtlc" check --summary "$f" || status=1
done
echo
echo "Feeding: the simulated world's first request, solved against the scene (cbtl solve)"
"$build/bin/cbtl" solve domains/feeding/feeding.cbtl --seed 1 || status=1
echo
echo "Cooking: CBTL vs No Personalization (cbtl experiment, seeds 0..2)"
"$build/bin/cbtl" experiment domains/cooking/cooking.cbtl --approaches cbtl,no-personalization --seeds 0..2 \
  --steps 10000 --eval-every 100 --eval-tasks 10 --out "$build/demo" --force || status=1
exit $status
