#!/usr/bin/env bash
# color_terminal.sh CBTLC — `cbtlc check` colours its diagnostics in a real terminal (tmux), and not when
# NO_COLOR is set or with --color never; piped output is never coloured (every golden case shows that).
set -u
cbtlc=$(realpath "$1")
command -v tmux >/dev/null || { echo "tmux is not installed (scripts/install-deps.sh installs it)"; exit 1; }
work=$(mktemp -d)
tmux_cmd=(tmux -L "cbtl-color-test-$$" -f /dev/null)
trap '"${tmux_cmd[@]}" kill-server 2>/dev/null; rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
printf 'var x : real in 0 .. 1;\nrequire x = 0.5;\n' >"$work/bad.cbtl"

# run NAME COMMAND: runs COMMAND in a fresh tmux window and prints the pane with its escape sequences.
run() {
  "${tmux_cmd[@]}" new-session -d -s "$1" -x 160 -y 30 "cd '$work' && $2; echo '[done]'; sleep 30"
  local i
  for ((i = 0; i < 100; i++)); do
    "${tmux_cmd[@]}" capture-pane -p -t "$1" 2>/dev/null | grep -q '^\[done\]' && break
    sleep 0.1
  done
  "${tmux_cmd[@]}" capture-pane -e -p -t "$1"
}
esc=$'\x1b\['
out=$(run plain "TERM=xterm '$cbtlc' check bad.cbtl")
grep -q "error\[E0101\]" <<<"$out" || fail "the terminal shows no diagnostic: $out"
grep -q "$esc" <<<"$out" || fail "no colour in a terminal"
out=$(run nocolor "TERM=xterm NO_COLOR=1 '$cbtlc' check bad.cbtl")
grep -q "error\[E0101\]" <<<"$out" || fail "NO_COLOR: no diagnostic: $out"
grep -q "$esc" <<<"$out" && fail "NO_COLOR=1 still coloured"
out=$(run never "TERM=xterm '$cbtlc' check bad.cbtl --color never")
grep -q "$esc" <<<"$out" && fail "--color never still coloured"
out=$("$cbtlc" check "$work/bad.cbtl" 2>&1)
grep -q "$esc" <<<"$out" && fail "piped output is coloured"
out=$("$cbtlc" check "$work/bad.cbtl" --color always 2>&1)
grep -q "$esc" <<<"$out" || fail "--color always is not coloured when piped"
if [[ $failures -gt 0 ]]; then echo "$failures failure(s)"; exit 1; fi
echo "colour: all checks passed"
