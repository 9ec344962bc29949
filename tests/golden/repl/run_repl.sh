#!/usr/bin/env bash
# run_repl.sh CBTL ROOT CASE.repl — a REPL transcript golden: pipes CASE.repl into `cbtl repl --echo` and compares
# what it prints (stdout, then stderr, then `[exit N]`) with CASE.out.
#
# The session runs in a fresh folder holding links to ROOT's domains/ and tests/, so paths in the case are the
# repository's (domains/cooking/cooking.cbtl) and files it writes (profile save p.json) land in the folder.
# The case's first line may give options: `# ARGS: --seed 3`.
# With CBTL_UPDATE_GOLDEN=1 the expected file is rewritten instead (review it with git diff).
set -u
cbtl=$1
root=$2
case_path=$(cd "$(dirname "$3")" && pwd)/$(basename "$3")
expected=${case_path%.repl}.out
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
ln -s "$root/domains" "$work/domains"
ln -s "$root/tests" "$work/tests"
args=$(head -n1 "$case_path" | sed -n 's|^# ARGS: *||p')
cd "$work" || exit 2
# shellcheck disable=SC2086
"$cbtl" repl --echo $args < "$case_path" > actual.out 2> actual.err
code=$?
cat actual.err >> actual.out
echo "[exit $code]" >> actual.out
if [ "${CBTL_UPDATE_GOLDEN:-0}" = "1" ]; then
  cp actual.out "$expected"
  exit 0
fi
if ! diff -u "$expected" actual.out; then exit 1; fi
if [ "$code" -ge 70 ]; then echo "cbtl repl exited with $code (internal error)"; exit 1; fi
exit 0
