#!/usr/bin/env bash
# ctest's entry to the browser test: checks its prerequisites (naming what is missing and how to get it: a test
# that silently skipped would hide a broken CI install), then runs study_browser.mjs with fresh artifacts.
# usage: run.sh CBTL PROGRAM ARTIFACTS_DIR
set -u
here=$(cd "$(dirname "$0")" && pwd)
missing=()
command -v node >/dev/null 2>&1 || missing+=("node (apt-get install nodejs)")
[[ -x /usr/bin/chromium ]] || missing+=("/usr/bin/chromium (apt-get install chromium)")
[[ -f "$here/node_modules/playwright-core/package.json" ]] || missing+=("playwright-core (npm ci --prefix $here)")
if [[ ${#missing[@]} -gt 0 ]]; then
  echo "study_browser: missing: ${missing[*]}; scripts/install-deps.sh installs them all" >&2
  exit 1
fi
rm -rf "$3"
mkdir -p "$3"
exec node "$here/study_browser.mjs" --cbtl "$1" --program "$2" --artifacts "$3"
