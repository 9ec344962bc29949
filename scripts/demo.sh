#!/usr/bin/env bash
# The main job on embedded defaults: check every domain file and print its constraint-graph summary.
set -euo pipefail
build=${1:-build}
status=0
for f in domains/cooking/cooking.cbtl domains/cleaning/cleaning.cbtl domains/books/books.cbtl domains/feeding/feeding.cbtl; do
  "$build/bin/cbtlc" check --summary "$f" || status=1
done
exit $status
