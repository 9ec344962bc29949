#!/usr/bin/env bash
# `cbtl run` against a language-model server that answers every request with HTTP 500 (fake_llm_server.py): the
# circuit breaker opens after its threshold and the run finishes with a bounded number of requests; a person at a
# terminal (script(1) gives the command a pseudo-terminal) sees the faults as they happen, while piped output only
# gets the breaker's one-line notice; llm.json records the breaker and the retries spent.
# usage: llm_faults_cli.sh CBTL DOMAINS_DIR
set -u
cbtl=$(realpath "$1")
domains=$(realpath "$2")
here=$(realpath "$(dirname "$0")")
source "$here/expect.sh"
cd "$work" || exit 2
command -v python3 >/dev/null || { echo "python3 not found: skipped"; exit 77; }

python3 "$here/fake_llm_server.py" --status 500 --port-file port --count-file count &
server=$!
trap 'kill $server 2>/dev/null; rm -rf "$work"' EXIT
for _ in $(seq 1 100); do [[ -s port ]] && break; sleep 0.1; done
[[ -s port ]] || { echo "the fake server did not start"; exit 1; }
url="http://127.0.0.1:$(cat port)/v1"
run=(run "$domains/feeding/feeding.cbtl" --steps 4 --eval-every 2 --eval-tasks 1 --max-eval-steps 3 --max-iters 50
  --text-backend openai --llm-model test-model --llm-base-url "$url" --llm-attempts 3 --llm-breaker 2)

# Piped: the breaker's notice once, no live lines; 2 requests x 3 attempts reach the server.
"$cbtl" "${run[@]}" --out piped >piped.txt 2>&1 || fail "the piped run failed: $(cat piped.txt)"
[[ $(grep -c "warning: language model: circuit breaker open after 2 consecutive server failures" piped.txt) -eq 1 ]] ||
  fail "no single breaker notice: $(cat piped.txt)"
! grep -q "retrying in" piped.txt || fail "a live fault line when piped: $(cat piped.txt)"
[[ $(cat count) -eq 6 ]] || fail "the server saw $(cat count) requests, not 2 x 3"
python3 - piped/llm.json <<'PY' || fail "llm.json: $(cat piped/llm.json)"
import json, sys
f = json.load(open(sys.argv[1]))["faults"]
assert f["breaker"]["open"] is True and f["retries"]["used"] == 4 and f["retries"]["spent"] is False, f
PY

# A terminal: the first failed attempt is reported at once.
script -qec "$cbtl ${run[*]} --out tty" /dev/null >tty.txt 2>&1 || fail "the run on a terminal failed: $(cat tty.txt)"
grep -q "cbtl run: language model: 127.0.0.1:[0-9]* answered HTTP 500; retrying in [0-9.]* s (1 failed attempt so far" \
  tty.txt || fail "no live fault line on a terminal: $(cat tty.txt)"
grep -q "circuit breaker open" tty.txt || fail "no breaker notice on a terminal: $(cat tty.txt)"

# A spent retry budget is said on a terminal, and recorded.
script -qec "$cbtl ${run[*]} --llm-retry-budget 1 --out budget" /dev/null >budget.txt 2>&1 ||
  fail "the run with a retry budget of 1 failed: $(cat budget.txt)"
grep -q "language model: retry budget spent (1 of 1 retries" budget.txt || fail "no word of the budget: $(cat budget.txt)"
grep -q '"spent": true' budget/llm.json || fail "llm.json: $(cat budget/llm.json)"

if [[ $failures -gt 0 ]]; then echo "$failures failure(s)"; exit 1; fi
echo "llm_faults_cli: all checks passed"
