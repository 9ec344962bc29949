#!/usr/bin/env bash
# repl_terminal.sh CBTL DOMAINS — `cbtl repl` in a real terminal (tmux): tab completion of commands and names,
# history kept in $XDG_STATE_HOME and read back by the next session, Ctrl-C abandoning a line and stopping a solve
# without ending the session, Ctrl-D ending it. Polls the pane (no fixed sleeps decide a result).
set -u
cbtl=$1
domains=$2
source "$(dirname "$0")/expect.sh"
command -v tmux >/dev/null || { echo "tmux is not installed (scripts/install-deps.sh installs it)"; exit 1; }

tmux_cmd=(tmux -L "cbtl-repl-test-$$" -f /dev/null)
trap '"${tmux_cmd[@]}" kill-server 2>/dev/null; rm -rf "$work"' EXIT
state=$work/state

# wait_for REGEX: until the pane shows it (10 s at most).
wait_for() {
  local i
  for ((i = 0; i < 100; i++)); do
    if "${tmux_cmd[@]}" capture-pane -p -t repl 2>/dev/null | grep -qE -- "$1"; then return 0; fi
    sleep 0.1
  done
  fail "the terminal never showed /$1/; it shows:"
  "${tmux_cmd[@]}" capture-pane -p -t repl 2>/dev/null | grep -v '^$' | tail -15
  return 1
}
last_line() { "${tmux_cmd[@]}" capture-pane -p -t repl | grep -v '^$' | tail -1; }
start() {
  "${tmux_cmd[@]}" new-session -d -s repl -x 200 -y 50 \
    "env XDG_STATE_HOME='$state' TERM=xterm '$cbtl' repl '$cooking' --max-iters 1000000000; echo \"[exit \$?]\"; sleep 60"
  wait_for '^cbtl> ?$'
}
keys() { "${tmux_cmd[@]}" send-keys -t repl "$@"; }

start
# Completion: a command, then one of its words, then a name from the program.
keys "li" Tab
wait_for '^cbtl> list ?$'
keys "ta" Tab
wait_for '^cbtl> list tasks ?$'
keys Enter
wait_for 'cookMeal +22 variables'
keys "observe st" Tab
wait_for '^cbtl> observe stock\[$'
keys "sa" Tab
wait_for '^cbtl> observe stock\[salt\] ?$'
keys "= 0" Enter
wait_for '^stock\[salt\] = 0$'
# An event completes to its name and "(", with no space after it: the arguments follow directly.
keys "feedback mealC" Tab
wait_for '^cbtl> feedback mealCritique\( ?$'
keys "s"  # typed right after the completion: no space in between (tmux drops a trailing one from the screen)
wait_for '^cbtl> feedback mealCritique\(s$'
keys C-c
wait_for '^cbtl> ?$'
# Ctrl-C abandons a half-typed line and the session goes on.
keys "help und"
wait_for '^cbtl> help und$'
keys C-c
wait_for '^cbtl> ?$'
keys "help undo" Enter
wait_for 'undo the last learn'
# Ctrl-C stops a solve that would run for minutes (no stock: unsatisfiable, a billion-iteration budget).
for ing in pepper sugar flour; do keys "observe stock[$ing] = 0" Enter; done
wait_for '^stock\[flour\] = 0$'
keys "solve" Enter
wait_for '^cbtl> solve$'
# A Ctrl-C that lands before the solve starts is cleared with the prompt's line; so press it until one stops it.
interrupted=0
for ((i = 0; i < 40 && !interrupted; i++)); do
  sleep 0.25
  keys C-c
  "${tmux_cmd[@]}" capture-pane -p -t repl | grep -q '^status: interrupted$' && interrupted=1
done
wait_for '^status: interrupted$'
keys "list tasks" Enter
wait_for '^cbtl> list tasks$'
# Ctrl-D ends the session with exit 0; the history file holds what was typed, not the abandoned line.
keys C-d
wait_for '^\[exit 0\]$'
history=$state/cbtl/repl_history
[[ -f $history ]] || fail "no history file at $history"
grep -q 'help\\040undo' "$history" || fail "the history lacks 'help undo'"
grep -q 'help\\040und$' "$history" && fail "the abandoned line is in the history"
"${tmux_cmd[@]}" kill-session -t repl

# A new session reads the history back: Up recalls the last command.
start
keys Up
wait_for '^cbtl> list tasks$'
keys Enter
wait_for 'cookMeal +22 variables'
keys "quit" Enter
wait_for '^\[exit 0\]$'

if [[ $failures -ne 0 ]]; then
  echo "$failures failure(s)"
  exit 1
fi
echo "all repl_terminal checks passed"
