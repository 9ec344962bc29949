#!/usr/bin/env bash
# The main job on embedded defaults (no network, no API key):
#  1. check every domain file and print its constraint-graph summary;
#  2. Feeding with the Kinova arm: the study's participant 0 answers meals 1-4, then the robot serves meal 5 twice
#     over, once having learned from those answers (CBTL) and once not (No Personalization): the complaints per
#     bite and drink, and pictures of the scene and of the user's view for every choice (cbtl study demo);
#  3. run the paper's Cooking experiment for CBTL and No Personalization over three seeds (10,000 steps,
#     evaluation every 100 steps on 10 held-out tasks) and print the summary table.
# usage: demo.sh BUILD_DIR      run it (cbtl and cbtlc built in BUILD_DIR/bin)
#        demo.sh --announce     only say what `make demo` does and how long it takes
set -euo pipefail
if [ "${1:-}" = "--announce" ]; then
  cat <<'TXT'
make demo: installs the Debian packages cbtlc and cbtl need (none of the test tools), builds only those two
programs (about 8 minutes the first time on 2 cores; seconds when built already), then runs the demo (about
10 seconds): the domains checked, Feeding's robot serving meal 5 with and without what it learned, and the
paper's Cooking experiment on three seeds.
TXT
  exit 0
fi
build=${1:-build}
status=0
for f in domains/cooking/cooking.cbtl domains/cleaning/cleaning.cbtl domains/books/books.cbtl domains/feeding/feeding.cbtl; do
  "$build/bin/cbtlc" check --summary "$f" || status=1
done
echo
echo "Feeding with the robot: meal 5 after the participant's answers to meals 1-4, learned (CBTL) or not"
echo "(cbtl study demo; pictures of every choice in $build/demo/feeding)"
"$build/bin/cbtl" study demo domains/feeding/feeding.cbtl --trials 2 --width 320 --height 240 \
  --out "$build/demo/feeding" --force || status=1
echo
echo "Cooking: CBTL vs No Personalization (cbtl experiment, seeds 0..2)"
"$build/bin/cbtl" experiment domains/cooking/cooking.cbtl --approaches cbtl,no-personalization --seeds 0..2 \
  --steps 10000 --eval-every 100 --eval-tasks 10 --out "$build/demo/cooking" --force || status=1
exit $status
