#!/usr/bin/env bash
# `cbtl study serve` as a process: the first stdout line names the port it got (--port 0), a participant's answers
# survive kill -9 (the restarted server continues at the page after the last answer), a second server cannot take
# the port of one that listens, SIGTERM stops it with exit 0, a database that is not one is refused.
# usage: study_serve.sh CBTL DOMAINS_DIR
set -u
cbtl=$1
program=$2/feeding/feeding.cbtl
work=$(mktemp -d)
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill -9 "$p" 2>/dev/null; done
  rm -rf "$work"
}
trap cleanup EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# Starts a server on $1 (a port, 0 for any) over $work/study.sqlite; sets $pid and $port.
start() {
  "$cbtl" study serve "$program" --db "$work/study.sqlite" --port "$1" --no-pictures "${@:2}" >"$work/out" \
    2>"$work/err" &
  pid=$!
  pids+=("$pid")
  port=""
  for _ in $(seq 1 600); do
    port=$(sed -n 's|^listening on http://127.0.0.1:\([0-9]*\)/$|\1|p' "$work/out" | head -1)
    [[ -n $port ]] && return 0
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.1
  done
  fail "no 'listening on' line: $(cat "$work/out" "$work/err")"
  return 1
}

# HTTP through python3 (no curl on a fresh machine): METHOD PATH [BODY] -> "status body", with the participant's key
# $key when set.
key=""
http() {
  python3 - "$port" "$key" "$@" <<'PY'
import sys, urllib.request, urllib.error
port, key, method, path = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4]
body = sys.argv[5].encode() if len(sys.argv) > 5 else b""
headers = {"Content-Type": "application/json"}
if key:
    headers["Authorization"] = "Bearer " + key
req = urllib.request.Request(f"http://127.0.0.1:{port}{path}", data=body if method == "POST" else None, method=method,
                             headers=headers)
try:
    with urllib.request.urlopen(req, timeout=120) as r:
        print(r.status, r.read().decode())
except urllib.error.HTTPError as e:
    print(e.code, e.read().decode())
PY
}

record() {  # TRIAL KIND MEAL RESPONSE
  http POST /api/participants/p1/records \
    "{\"trial_index\": $1, \"kind\": \"$2\", \"meal\": $3, \"elapsed_ms\": $((1000 * $1)), \"rt_ms\": 500, \"response\": $4}"
}

start 0 || exit 1
begun=$(http POST /api/participants/p1 '{}')
[[ $begun == "200 "*'"page":"consent"'* ]] || fail "begin: $begun"
key=$(python3 -c 'import json, sys; print(json.loads(sys.argv[1].split(" ", 1)[1])["key"])' "$begun")
# Without the key nothing about the participant is answered, and a second begin hands out no key.
key_kept=$key
key=""
[[ $(http GET /api/participants/p1) == "403 "* ]] || fail "a state without the key"
[[ $(http GET /api/participants/nobody) == "$(http GET /api/participants/p1)" ]] ||
  fail "an unknown and a known participant are told apart without a key"
[[ $(http POST /api/participants/p1 '{}') == "403 "* ]] || fail "a second begin without the key"
key=$key_kept
record 0 consent 0 '{"agree": true}' | grep -q '^200 ' || fail "consent"
record 1 demographics 0 \
  '{"age": null, "gender": "prefer-not-to-say", "gender_other": "", "robot_experience": false, "fed_experience": false}' \
  | grep -q '^200 ' || fail "demographics"
record 2 rating 1 '{"likert": 4}' | grep -q '^200 ' || fail "rating"
answered=$(record 3 answers 1 '{"dip": "noDip", "signal": "button", "verbosity": "silent", "blocked": [false, true]}')
[[ $answered == "200 "* && $answered == *'"meal":2,'* && $answered == *'"page":"rating"'* ]] ||
  fail "answers of meal 1: $answered"
before=$(http GET /api/participants/p1)
# One log line per participant event on stderr, with the time, the page and what became of it (never the answers).
grep -Eq '^[0-9]{4}-[0-9]{2}-[0-9]{2}T[0-9:]{8}Z participant "p1" begin: ' "$work/err" || fail "no begin line: $(cat "$work/err")"
grep -q 'participant "p1" trial 3 ("answers", meal 1): stored$' "$work/err" || fail "no answers line: $(cat "$work/err")"
record 3 answers 1 '{"dip": "dip", "signal": "button", "verbosity": "silent", "blocked": [false, true]}' >/dev/null
grep -q 'participant "p1" trial 3 ("answers", meal 1): refused 409 ' "$work/err" || fail "no refusal line: $(cat "$work/err")"
! grep -q 'noDip' "$work/err" || fail "the log holds an answer: $(cat "$work/err")"

# Hostile requests are answered, never abort the server: bytes that are not UTF-8 in the path (`GET /%ff` once
# killed it with exit 134: its error reply quoted the raw path), control bytes, methods it does not serve.
raw() {  # REQUEST-LINE -> the status line and body of the reply, sent as raw bytes (urllib would re-encode them)
  python3 - "$port" "$1" <<'PY'
import socket, sys
port, line = int(sys.argv[1]), sys.argv[2]
with socket.create_connection(("127.0.0.1", port), timeout=30) as c:
    c.sendall(line.encode("latin-1") + b"\r\nHost: x\r\nConnection: close\r\n\r\n")
    data = b""
    while chunk := c.recv(65536):
        data += chunk
head, _, body = data.partition(b"\r\n\r\n")
print(head.split(b"\r\n")[0].decode("latin-1"), body.decode("utf-8"))
PY
}
for line in 'GET /%ff HTTP/1.1' 'GET /%ff%fe/%c3%28 HTTP/1.1' 'GET /p/%ff HTTP/1.1' 'GET /api/participants/%ff HTTP/1.1' \
  'GET /api/participants/p1/views/1/%ff.png HTTP/1.1' 'DELETE /%01%02 HTTP/1.1' 'BREW /%ff HTTP/1.1'; do
  reply=$(raw "$line" 2>&1)
  [[ $reply == "HTTP/1.1 4"* ]] || fail "'$line' got: $reply"
  kill -0 "$pid" 2>/dev/null || { fail "'$line' stopped the server: $(cat "$work/err")"; break; }
done
[[ $(raw 'GET /%ff HTTP/1.1') == *'"error":"no such page: '* ]] || fail "GET /%ff: no JSON error: $(raw 'GET /%ff HTTP/1.1')"
# A chunked upload is refused before its body is read (the 64 KiB limit held only with a Content-Length: a 400 MB
# chunked body was read whole): one 64 KiB chunk sent, the 411 must come without the rest.
chunked=$(python3 - "$port" <<'PY'
import socket, sys
with socket.create_connection(("127.0.0.1", int(sys.argv[1])), timeout=10) as c:
    c.sendall(b"POST /api/participants/p1/records HTTP/1.1\r\nHost: x\r\nContent-Type: application/json\r\n"
              b"Transfer-Encoding: chunked\r\n\r\n" + b"10000\r\n" + b" " * 0x10000 + b"\r\n")
    try:
        print(c.recv(65536).split(b"\r\n")[0].decode())
    except socket.timeout:
        print("no reply: the server waits for the rest of the body")
PY
)
[[ $chunked == "HTTP/1.1 411"* ]] || fail "a chunked upload: $chunked"
[[ $(http GET /api/participants/p1) == "$before" ]] || fail "the server after hostile requests"

# A second server on the same port is refused, and the first keeps answering.
"$cbtl" study serve "$program" --db "$work/other.sqlite" --port "$port" --no-pictures >"$work/out2" 2>&1 &
second=$!
pids+=("$second")
for _ in $(seq 1 600); do kill -0 "$second" 2>/dev/null || break; sleep 0.1; done
if kill -0 "$second" 2>/dev/null; then
  fail "a second server took port $port: $(cat "$work/out2")"
else
  wait "$second"
  rc=$?
  [[ $rc -eq 1 ]] && grep -q "cannot listen" "$work/out2" || fail "second server (exit $rc): $(cat "$work/out2")"
fi
[[ $(http GET /api/participants/p1) == "$before" ]] || fail "the first server after the second's attempt"
# A second server on the same database is refused (two once gave two participants one seed).
out=$(timeout 120 "$cbtl" study serve "$program" --db "$work/study.sqlite" --port 0 --no-pictures 2>&1)
rc=$?
[[ $rc -eq 1 ]] && grep -q "another study server is using this database" <<<"$out" ||
  fail "a second server on the same database (exit $rc): $out"

# Slow clients (one byte every 2 s, each holding a connection open) do not keep others out: 24 of them, three
# times what once took every request thread, while a participant's page is asked for.
slow=$(python3 - "$port" <<'PY'
import socket, sys, threading, time, urllib.request
port = int(sys.argv[1])
stop = time.time() + 9
def trickle():
    try:
        with socket.create_connection(("127.0.0.1", port), timeout=20) as c:
            for b in b"GET /p/slow HTTP/1.1\r\nHost: x\r\n":
                if time.time() > stop:
                    break
                c.sendall(bytes([b]))
                time.sleep(2)
    except OSError:
        pass
threads = [threading.Thread(target=trickle) for _ in range(24)]
for t in threads:
    t.start()
time.sleep(3)
start = time.time()
try:
    with urllib.request.urlopen(f"http://127.0.0.1:{port}/static/study.css", timeout=5) as r:
        print(r.status, round(time.time() - start, 2))
except Exception as e:
    print("no answer:", e)
for t in threads:
    t.join()
PY
)
[[ $slow == "200 "* ]] || fail "a request among slow clients: $slow"

kill -9 "$pid"
wait "$pid" 2>/dev/null
start 0 || exit 1
after=$(http GET /api/participants/p1)
[[ $after == "$before" ]] || fail "after kill -9 and a restart the state differs:
before: $before
after:  $after"

kill -TERM "$pid"
wait "$pid"
rc=$?
[[ $rc -eq 0 ]] && grep -q "^stopped$" "$work/out" || fail "SIGTERM: exit $rc, $(cat "$work/out" "$work/err")"

# The study's own title, people and consent text (--study-info) reach every participant's state.
cat >"$work/info.json" <<'JSON'
{"title": "Feeding study", "researcher": "Dr. A. Researcher", "contact": "study@example.org",
 "ethics_approval": "IRB-7", "consent": ["One paragraph.", "Another."]}
JSON
start 0 --study-info "$work/info.json" || exit 1
begun=$(http POST /api/participants/p2 '{}')
[[ $begun == "200 "*'"ethics_approval":"IRB-7"'* && $begun == *'"consent":["One paragraph.","Another."]'* ]] ||
  fail "the study info is not in the state: $begun"
kill -TERM "$pid"
wait "$pid"
echo '{"ethics": "IRB-7"}' >"$work/typo.json"
out=$("$cbtl" study serve "$program" --db "$work/study.sqlite" --port 0 --study-info "$work/typo.json" 2>&1)
rc=$?
[[ $rc -eq 1 ]] && grep -q 'typo.json: unknown field "ethics"' <<<"$out" || fail "a mistyped study info (exit $rc): $out"

echo "not a database" >"$work/bad.sqlite"
out=$("$cbtl" study serve "$program" --db "$work/bad.sqlite" --port 0 2>&1)
rc=$?
[[ $rc -eq 1 ]] && grep -q "bad.sqlite: not a SQLite database" <<<"$out" || fail "bad database (exit $rc): $out"

[[ $failures -eq 0 ]] && echo "study_serve: all ok"
exit $((failures > 0))
