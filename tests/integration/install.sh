#!/usr/bin/env bash
# `cmake --install` into a temporary prefix, then every domain runs from there with the installed cbtl, from a
# folder outside the source tree: the programs, the standard library, the domains (scenes, external simulators)
# and the docs are all installed, and nothing reaches back into the source or build tree.
# usage: install.sh BUILD_DIR
set -u
build=$(realpath "$1")
prefix=$(mktemp -d)
elsewhere=$(mktemp -d)
trap 'rm -rf "$prefix" "$elsewhere"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

cmake --install "$build" --prefix "$prefix" >"$elsewhere/install.log" 2>&1 || { cat "$elsewhere/install.log"; exit 1; }
for f in bin/cbtl bin/cbtlc share/cbtl/stdlib/std/prelude.cbtl share/cbtl/domains/feeding/feeding.xml \
  share/cbtl/domains/assets/gen3.xml share/cbtl/domains/coffee/coffee_sim.py share/doc/cbtl/tutorial.md \
  share/doc/cbtl/simulator-protocol.md share/doc/cbtl/README.md; do
  [[ -e $prefix/$f ]] || fail "not installed: $f"
done
[[ -x $prefix/share/cbtl/domains/coffee/coffee_sim.py ]] || fail "coffee_sim.py is not executable"
if find "$prefix" -name '*.cpp' -o -name '*.h' -o -name CMakeLists.txt | grep -q .; then
  fail "sources were installed: $(find "$prefix" -name '*.cpp' -o -name '*.h' | head -3)"
fi

cd "$elsewhere" || exit 1
domains=$prefix/share/cbtl/domains
for d in cooking coffee books cleaning feeding; do
  out=$("$prefix/bin/cbtlc" check "$domains/$d/$d.cbtl" --stdlib "$prefix/share/cbtl/stdlib" 2>&1) ||
    fail "cbtlc check $d: $out"
  out=$("$prefix/bin/cbtl" run "$domains/$d/$d.cbtl" --steps 2 --eval-every 2 --eval-tasks 1 --max-eval-steps 40 \
    --out "run-$d" 2>&1) || fail "cbtl run $d from the install prefix: $out"
  [[ -s run-$d/eval.csv ]] || fail "cbtl run $d wrote no eval.csv"
  echo "ok: $d runs from $prefix"
done
# Nothing installed names the build or source tree.
if grep -rlI -- "$build" "$prefix/share" >/dev/null; then fail "an installed file names the build tree"; fi
if [[ $failures -gt 0 ]]; then echo "$failures failure(s)"; exit 1; fi
echo "install: all checks passed"
