# expect.sh — what the CLI integration scripts share; sourced after they set `cbtl` and `domains`.
# Sets `cooking`, a scratch folder `work` (removed at exit) and the count `failures`, and defines
#   expect CODE PATTERN -- command...   run the command; fail unless it exits CODE and its output
#                                       (stdout and stderr) matches the extended regex PATTERN ('' = any)
#   fail MESSAGE                        count a failure
cooking=$domains/cooking/cooking.cbtl
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

expect() {
  local code=$1 pattern=$2
  shift 3
  local out rc
  out=$("$@" 2>&1)
  rc=$?
  if [[ $rc -ne $code ]]; then
    echo "FAIL (exit $rc, wanted $code): $*"; echo "$out" | head -20; failures=$((failures + 1)); return
  fi
  if [[ -n $pattern ]] && ! grep -qE -- "$pattern" <<<"$out"; then
    echo "FAIL (output lacks /$pattern/): $*"; echo "$out" | head -20; failures=$((failures + 1)); return
  fi
  echo "ok ($rc): $*"
}
