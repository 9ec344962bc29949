#!/usr/bin/env bash
# The profile store under kill -9 and under two processes at once (app/profile/ProfileStore.h):
#  (a) 20 rounds of a writer killed at a random moment; after each, the store is intact and holds every version the
#      writer had acknowledged, with its events (the next round reopens the store the kill left);
#  (b) four writers at once on one store, two of them on the same profile: all finish, nothing is lost or doubled.
# usage: profile_store_kill.sh PROFILE_STORE_STRESS
set -u
stress=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

db=$work/kill.sqlite
for round in $(seq 1 20); do
  "$stress" "$db" ann feeding 1000000 >"$work/acks" 2>"$work/err" &
  pid=$!
  sleep "0.$((RANDOM % 35 + 5))"
  kill -9 "$pid"
  wait "$pid" 2>/dev/null
  acked=$(grep -c '^acked' "$work/acks")
  last=$(tail -n 1 "$work/acks" | sed -n 's/^acked \([0-9]*\)$/\1/p')
  if ! summary=$("$stress" --check "$db" ann feeding); then
    fail "round $round: $summary"
    continue
  fi
  stored=$(awk '{print $2}' <<<"$summary")
  if [[ -n $last && $stored -lt $last ]]; then
    fail "round $round: the writer acknowledged version $last but the store holds $stored"
  else
    echo "ok: round $round: $acked writes acknowledged before the kill (last version ${last:-none}), $summary"
  fi
  [[ -s $work/err ]] && fail "round $round: the writer said: $(head -c 300 "$work/err")"
done

shared=$work/shared.sqlite
pids=()
for writer in "bea cooking" "cy cooking" "dee books" "dee books"; do
  # shellcheck disable=SC2086
  "$stress" "$shared" $writer 200 >/dev/null 2>"$work/err.${#pids[@]}" &
  pids+=($!)
done
for i in "${!pids[@]}"; do
  wait "${pids[$i]}" || fail "concurrent writer $i failed: $(head -c 300 "$work/err.$i")"
done
for expected in "bea cooking 200" "cy cooking 200" "dee books 400"; do
  read -r user domain count <<<"$expected"
  summary=$("$stress" --check "$shared" "$user" "$domain") || fail "$user/$domain: $summary"
  [[ $summary == "versions $count events $((2 * count))" ]] || fail "$user/$domain: $summary, wanted $count versions"
  echo "ok: concurrent $user/$domain: $summary"
done

echo "$failures failure(s)"
[[ $failures -eq 0 ]]
