#!/usr/bin/env bash
# Reproduces every table and figure in docs/results.md: the paper's Cooking experiments (Figure 3, Table 1,
# Figure 5), Figure 3 for Cleaning and Books, Books' first 1,000 steps, Feeding's preferences, the Feeding study
# with 60 simulated participants and the demonstration; then the figures, copied to docs/images/results/.
#
# Usage: [JOBS=N] [QUICK=1] scripts/results.sh [BUILD_DIR] [OUT_DIR]
#   JOBS   trials in parallel (default: the machine's cores); results are the same for any JOBS
#   QUICK  1: Cooking only (about 3 minutes on 2 cores) instead of everything (docs/results.md says how long)
# The experiments are two sweeps (bench/sweeps/paper-cooking.json, paper-robots.json): run again on the same OUT_DIR,
# the script keeps every finished trial and continues the others, so an interrupted run loses nothing; a new
# OUT_DIR starts from scratch. Tables go to stdout, CSVs and figures under OUT_DIR.
set -euo pipefail
build=${1:-build}
out=${2:-results}
jobs=${JOBS:-$(nproc)}
cbtl="$build/bin/cbtl"
images=docs/images/results
mkdir -p "$out/figures" "$images"
start=$(date +%s)

echo "== Cooking: Figure 3, Table 1, Figure 5 (bench/sweeps/paper-cooking.json)"
"$cbtl" sweep bench/sweeps/paper-cooking.json --out "$out/cooking" --jobs "$jobs" -q

if [[ ${QUICK:-0} != 1 ]]; then
  echo "== Cleaning and Books: Figure 3; Books' first 1,000 steps; Feeding's preferences (bench/sweeps/paper-robots.json)"
  "$cbtl" sweep bench/sweeps/paper-robots.json --out "$out/robots" --jobs "$jobs" -q
  for domain in cleaning books; do
    echo "-- $domain: what was learned, against the hidden user"
    python3 scripts/learned-vs-hidden.py "$domain" "$out/robots/figure3-$domain"
  done
  echo "-- feeding: each preference's learning curve; what was learned of the occlusion sensitivity"
  python3 scripts/preference-curves.py "$out/robots/feeding-preferences"
  python3 scripts/learned-vs-hidden.py feeding "$out/robots/feeding-preferences"
  echo "== Feeding: the five meals with 60 simulated participants, judged by the simulator (in one process)"
  "$cbtl" study simulate domains/feeding/feeding.cbtl --in-process --participants 60 --out "$out/study" --force
  echo "== Feeding: the web study's server with 60 simulated participants through its HTTP API, analysed"
  "$cbtl" study simulate domains/feeding/feeding.cbtl --participants 60 --out "$out/study-web" --force
  echo "== Feeding: the demonstration"
  "$cbtl" study demo domains/feeding/feeding.cbtl --out "$out/demo" --force
  echo "== Figure 3, the three environments side by side"
  "$cbtl" plot "$out/cooking/figure3-cooking" "$out/robots/figure3-cleaning" "$out/robots/figure3-books" \
    --panel-title Cooking --panel-title Cleaning --panel-title Books --ymin -1 --ymax 1 --out "$out/figures/figure3.png"
fi

cp "$out"/cooking/figures/*.png "$out"/figures/ 2>/dev/null || true
[[ -d $out/robots/figures ]] && cp "$out"/robots/figures/*.png "$out"/figures/
cp "$out"/figures/*.png "$images"/
echo "figures: $out/figures (copied to $images); $(($(date +%s) - start)) s in all"
