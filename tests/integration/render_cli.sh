#!/usr/bin/env bash
# `cbtl render`: a picture of each scene; a bad scene or state is a clear error (exit 1), never a crash.
# Without a usable EGL/OpenGL the command exits 70 and this test is skipped (exit 77).
# usage: render_cli.sh CBTL DOMAINS_DIR
set -u
cbtl=$1
domains=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0

out=$("$cbtl" render "$domains/feeding/feeding.xml" --out "$work/feeding.png" --width 160 --height 120 2>&1)
rc=$?
if [[ $rc -eq 70 ]]; then
  echo "skipped: no offscreen rendering here: $out"
  exit 77
fi
check_png() {
  local f=$1
  if [[ ! -s $f ]] || [[ $(head -c 8 "$f" | od -An -tx1 | tr -d ' \n') != 89504e470d0a1a0a ]]; then
    echo "FAIL: $f is not a PNG"; failures=$((failures + 1))
  else
    echo "ok: $f ($(stat -c %s "$f") bytes)"
  fi
}
[[ $rc -eq 0 ]] || { echo "FAIL (exit $rc): render feeding: $out"; failures=$((failures + 1)); }
check_png "$work/feeding.png"
"$cbtl" render "$domains/home/home.xml" --out "$work/home.png" --width 160 --height 120 >/dev/null 2>&1 \
  || { echo "FAIL: render home"; failures=$((failures + 1)); }
check_png "$work/home.png"

printf '<mujoco><worldbody><body name="b"><geom type="sphere" size="oops"/></body></worldbody></mujoco>' >"$work/bad.xml"
out=$("$cbtl" render "$work/bad.xml" --out "$work/bad.png" 2>&1); rc=$?
[[ $rc -eq 1 ]] && grep -q "bad.xml" <<<"$out" && echo "ok: bad scene -> exit 1" \
  || { echo "FAIL (exit $rc): bad scene: $out"; failures=$((failures + 1)); }
out=$("$cbtl" render "$work/missing.xml" --out "$work/m.png" 2>&1); rc=$?
[[ $rc -eq 1 ]] && echo "ok: missing scene -> exit 1" || { echo "FAIL (exit $rc): missing scene: $out"; failures=$((failures + 1)); }
printf '{"arm": [0, 0' >"$work/state.json"
out=$("$cbtl" render "$domains/feeding/feeding.xml" --state "$work/state.json" --out "$work/s.png" 2>&1); rc=$?
[[ $rc -eq 1 ]] && echo "ok: corrupt state -> exit 1" || { echo "FAIL (exit $rc): corrupt state: $out"; failures=$((failures + 1)); }

echo "$failures failed"
[[ $failures -eq 0 ]]
