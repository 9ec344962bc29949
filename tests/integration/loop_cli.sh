#!/usr/bin/env bash
# The REPL's loop from the command line, for scripts and other programs: `cbtl solve --observe FILE` (observations
# from a file, checked against their declarations), `--format json` (one cbtl-solution document), and the status
# marker every solve ends with (solved / unsatisfiable / error; exit 0 / 3 / 1).
# usage: loop_cli.sh CBTL DOMAINS_DIR
set -u
cbtl=$1
domains=$2
source "$(dirname "$0")/expect.sh"

# Cooking's program under a domain name no simulator serves: every observation must come from the file.
pantry=$work/pantry.cbtl
sed 's/^domain cooking;/domain pantry;/' "$cooking" >"$pantry"
stock() { printf '{"stock[salt]": %s, "stock[pepper]": %s, "stock[sugar]": 5, "stock[flour]": 5}\n' "$1" "$2"; }
stock 5 5 >"$work/plenty.json"
stock 0.1 5 >"$work/no-salt.json"   # the seasoning spec needs 0.9 .. 1.1 of salt
echo '{"stock[salt]": 5}' >"$work/partial.json"
echo '{"stock[salt]": "lots", "stock[pepper]": 5, "stock[sugar]": 5, "stock[flour]": 5}' >"$work/bad-type.json"
echo '{"stok": 1}' >"$work/bad-key.json"
echo '{"stock[salt]": 5,' >"$work/not-json.json"
echo '[1, 2]' >"$work/not-object.json"

expect 0 '^status: solved$' -- "$cbtl" solve "$pantry" --observe "$work/plenty.json"
expect 3 '^status: unsatisfiable$' -- "$cbtl" solve "$pantry" --observe "$work/no-salt.json" --max-iters 300
expect 3 'no --observe file; observations are zero' -- "$cbtl" solve "$pantry" --max-iters 300
expect 1 'partial.json: no value for stock\[flour\], stock\[pepper\], stock\[sugar\]' -- \
  "$cbtl" solve "$pantry" --observe "$work/partial.json"
expect 1 '^status: error$' -- "$cbtl" solve "$pantry" --observe "$work/partial.json"
expect 1 'bad-type.json: /stock\[salt\]: expected a real number' -- "$cbtl" solve "$pantry" --observe "$work/bad-type.json"
expect 1 "bad-key.json: /stok: the program has no observation 'stok' \(it has: stock\[flour\]" -- \
  "$cbtl" solve "$pantry" --observe "$work/bad-key.json"
expect 1 'not-json.json: not JSON' -- "$cbtl" solve "$pantry" --observe "$work/not-json.json"
expect 1 'not-object.json: expected an object' -- "$cbtl" solve "$pantry" --observe "$work/not-object.json"
expect 1 'missing.json: cannot read' -- "$cbtl" solve "$pantry" --observe "$work/missing.json"
expect 2 'format' -- "$cbtl" solve "$pantry" --format yaml
# With a simulator the file's values are written over the simulator's.
expect 0 '^status: solved$' -- "$cbtl" solve "$cooking" --observe "$work/partial.json"

# json: one document, the same bytes for the same seed, the file's observation in it, the status field set.
json() { python3 -c 'import json, sys; d = json.load(sys.stdin); print(eval(sys.argv[1]))' "$1"; }
out=$("$cbtl" solve "$pantry" --observe "$work/plenty.json" --format json --seed 4)
again=$("$cbtl" solve "$pantry" --observe "$work/plenty.json" --format json --seed 4)
[[ $out == "$again" ]] || fail "json solve: two runs with --seed 4 differ"
[[ $(json 'd["status"], d["format"], d["version"]' <<<"$out") == "('solved', 'cbtl-solution', 1)" ]] ||
  fail "json solve: header: $(head -c 200 <<<"$out")"
[[ $(json 'd["observation"]["stock[salt]"]' <<<"$out") == 5* ]] || fail "json solve: observation not from the file"
[[ $(json 'd["recheck"]["holds"]' <<<"$out") == True ]] || fail "json solve: re-check does not hold"
[[ $(json 'd["plan"][-1]["action"]' <<<"$out") == serve ]] || fail "json solve: plan does not end with serve"
[[ $(json 'd["assignment"]["used[salt]"]' <<<"$out") == True ]] || fail "json solve: salt not used"
# Quantities respect the stock given in the file.
[[ $(json 'all(d["assignment"][f"quantity[{i}]"] <= 5 for i in ("salt", "pepper"))' <<<"$out") == True ]] ||
  fail "json solve: a quantity exceeds the file's stock"
out=$("$cbtl" solve "$pantry" --observe "$work/no-salt.json" --format json --max-iters 300)
[[ $? -eq 3 ]] || fail "json unsatisfiable solve: exit code"
[[ $(json 'd["status"], "assignment" in d, len(d["constraints"]) > 0' <<<"$out") == "('unsatisfiable', False, True)" ]] ||
  fail "json unsatisfiable solve: $(head -c 200 <<<"$out")"
out=$("$cbtl" solve "$pantry" --observe "$work/bad-key.json" --format json 2>/dev/null)
[[ $(json 'd["status"]' <<<"$out") == error ]] || fail "json error: $out"

# feedback: typed events learned into a profile; a bad event anywhere changes nothing.
critique='mealCritique(seasoning, salt, 3, 31, 0.9, wantHotter, wantMore)'
profile=$work/alice.json
expect 0 'learned 2 labels from 1 event; the new profile .*alice.json holds 2 labels \(was 0\)' -- \
  "$cbtl" feedback "$cooking" --profile "$profile" --event "$critique"
cp "$profile" "$work/before.json"
expect 1 "argument 6 \(heat\): 'tooHot' is not a TempCritique" -- \
  "$cbtl" feedback "$cooking" --profile "$profile" --event "$critique" --event "${critique/wantHotter/tooHot}"
expect 1 "expected ',' or '\)'" -- "$cbtl" feedback "$cooking" --profile "$profile" --event 'mealCritique(seasoning salt)'
expect 1 "no feedback event named 'praise'" -- "$cbtl" feedback "$cooking" --profile "$profile" --event 'praise()'
expect 1 'mealCritique takes 7 arguments, not 2' -- \
  "$cbtl" feedback "$cooking" --profile "$profile" --event 'mealCritique(seasoning, salt)'
cmp -s "$profile" "$work/before.json" || fail "feedback: a rejected event changed the profile"
expect 2 'event' -- "$cbtl" feedback "$cooking" --profile "$profile"
# About a solution: solve, then give feedback on what it chose; the profile grows and the next solve reads it.
"$cbtl" solve "$cooking" --profile "$profile" --format json >"$work/sol.json"
expect 0 'holds 4 labels \(was 2\)' -- \
  "$cbtl" feedback "$cooking" --profile "$profile" --solution "$work/sol.json" --event "${critique/salt/pepper}"
expect 1 'sol-unsat.json: /status: the solve it records found no solution' -- \
  bash -c "'$cbtl' solve '$pantry' --observe '$work/no-salt.json' --format json --max-iters 50 >'$work/sol-unsat.json'; \
           '$cbtl' feedback '$cooking' --profile '$profile' --solution '$work/sol-unsat.json' --event '$critique'"
expect 1 'plenty.json: not a cbtl-solution' -- \
  "$cbtl" feedback "$cooking" --profile "$profile" --solution "$work/plenty.json" --event "$critique"
expect 0 '^status: solved$' -- "$cbtl" solve "$cooking" --profile "$profile"

# Feeding: the dip the user names for the food on the plate is the one the next solve offers.
feeding=$domains/feeding/feeding.cbtl
"$cbtl" solve "$feeding" --format json --seed 2 >"$work/bite.json"
food=$(json 'd["observation"]["foodOnPlate"]' <"$work/bite.json")
offered=$(json 'd["assignment"]["acquireBite.dip"]' <"$work/bite.json")
ideal=$(json '[x for x in d["observation"]["dipChoices"] if x != d["assignment"]["acquireBite.dip"]][0]' <"$work/bite.json")
expect 0 'learned [0-9]+ labels? from 1 event' -- "$cbtl" feedback "$feeding" --profile "$work/bob.json" \
  --solution "$work/bite.json" --event "dipAnswer($food, $offered, $ideal)"
chosen=$("$cbtl" solve "$feeding" --format json --seed 2 --profile "$work/bob.json" | json 'd["assignment"]["acquireBite.dip"]')
[[ $chosen == "$ideal" ]] || fail "feeding: after 'dipAnswer($food, $offered, $ideal)' the solve offers $chosen"

# The profile store: feedback and run write versions with their events; profile lists, shows, exports, imports and
# rolls back; nothing is ever deleted.
db=$work/profiles.sqlite
expect 0 "version 1 in .*profiles.sqlite\) holds 2 labels" -- \
  "$cbtl" feedback "$cooking" --profile-db "$db" --user ann --event "$critique"
expect 0 "version 2 in .*profiles.sqlite\) holds 4 labels \(was 2\)" -- \
  "$cbtl" feedback "$cooking" --profile-db "$db" --user ann --solution "$work/sol.json" --event "${critique/salt/pepper}"
expect 0 'stored the learned model as version 3 of ann.s cooking profile .*\(([1-9][0-9]*) feedback events\)' -- \
  "$cbtl" run "$cooking" --profile-db "$db" --user ann --steps 150 --eval-every 150 --eval-tasks 1
expect 0 '^ann +cooking +version 3 +\(3 versions, [1-9][0-9]* events\)' -- "$cbtl" profile list --db "$db"
expect 0 'event 2  command  mealCritique\(seasoning, pepper, .*\(with its solution\)' -- \
  "$cbtl" profile history --db "$db" ann cooking
expect 0 'version 3 .*run: cbtl, seed 0, 150 steps' -- "$cbtl" profile history --db "$db" ann cooking
expect 0 'event [0-9]+  simulator  mealCritique' -- "$cbtl" profile history --db "$db" ann cooking
expect 0 "version 4 of ann's cooking profile holds version 1's model" -- "$cbtl" profile rollback --db "$db" ann cooking 1
expect 0 "version 4 of 4 \(rollback to 1, .*\): 2 labels" -- "$cbtl" profile show --db "$db" ann cooking
"$cbtl" profile export --db "$db" ann cooking --version 2 --out "$work/v2.json" 2>/dev/null
cmp -s <(python3 -m json.tool --sort-keys "$work/v2.json") <(python3 -m json.tool --sort-keys "$profile") ||
  fail "profile export: version 2 is not the model the JSON profile has after the same two events"
expect 0 '"n"|"generators"' -- "$cbtl" profile export --db "$db" ann cooking
expect 0 "imported .*v2.json as version 1 of bo's cooking profile" -- "$cbtl" profile import --db "$db" bo "$work/v2.json"
expect 0 '^status: solved$' -- "$cbtl" solve "$cooking" --profile "$work/v2.json"
expect 1 "'ann' has no version 9 of a cooking profile" -- "$cbtl" profile rollback --db "$db" ann cooking 9
expect 1 "'cy' has no cooking profile" -- "$cbtl" profile show --db "$db" cy cooking
expect 1 'no such profile store' -- "$cbtl" profile list --db "$work/none.sqlite"
expect 1 'not a SQLite database' -- "$cbtl" profile list --db "$work/plenty.json"
expect 1 'not a cbtl-profile' -- "$cbtl" profile import --db "$db" ann "$work/plenty.json"
expect 1 'not a SQLite database' -- "$cbtl" feedback "$cooking" --profile-db "$work/plenty.json" --user ann --event "$critique"
expect 2 'user' -- "$cbtl" feedback "$cooking" --profile-db "$db" --event "$critique"
expect 2 'profile' -- "$cbtl" run "$cooking" --profile "$profile" --profile-db "$db" --user ann
expect 2 '' -- "$cbtl" profile
[[ $(sqlite3 "$db" 'PRAGMA integrity_check') == ok ]] || fail "profile store: integrity check"
[[ $(sqlite3 "$db" 'PRAGMA journal_mode') == wal ]] || fail "profile store: not in WAL mode"

# A stored model damaged by hand is bad input with a way out (exit 1), not "a bug" (exit 70).
cp "$db" "$work/damaged.sqlite"
sqlite3 "$work/damaged.sqlite" "UPDATE versions SET model = '{not json' WHERE version = 1"
expect 1 "version 1 of the cooking profile of 'ann' is damaged.*rollback" -- \
  "$cbtl" profile show --db "$work/damaged.sqlite" ann cooking --version 1
expect 1 "version 1 of the cooking profile of 'ann' is damaged" -- \
  "$cbtl" profile export --db "$work/damaged.sqlite" ann cooking --version 1
expect 0 "version 4 of 4" -- "$cbtl" profile show --db "$work/damaged.sqlite" ann cooking
# A store that fails SQLite's integrity check (one byte of a user-name index changed) is never written to.
cp "$db" "$work/corrupt.sqlite"
sqlite3 "$work/corrupt.sqlite" 'PRAGMA wal_checkpoint(TRUNCATE)' >/dev/null
python3 - "$work/corrupt.sqlite" <<'PY'
import sqlite3, sys
path = sys.argv[1]
with sqlite3.connect(path) as c:
    root = c.execute("SELECT rootpage FROM sqlite_master WHERE name = 'sqlite_autoindex_users_1'").fetchone()[0]
    size = c.execute("PRAGMA page_size").fetchone()[0]
data = bytearray(open(path, "rb").read())
at = data.find(b"ann", (root - 1) * size, root * size)
data[at + 2] = ord("X")
open(path, "wb").write(data)
PY
[[ $(sqlite3 "$work/corrupt.sqlite" 'PRAGMA integrity_check') != ok ]] || fail "the corrupted copy passes the check"
expect 1 "fails SQLite's integrity check.*nothing was written" -- \
  "$cbtl" profile import --db "$work/corrupt.sqlite" ann "$work/v2.json"
# A store emptied to 0 bytes (a truncating copy, a full disk) is refused, not silently a new empty store.
: >"$work/emptied.sqlite"
expect 1 'emptied.sqlite: an empty file \(0 bytes\), not a profile store.*delete the file' -- \
  "$cbtl" feedback "$cooking" --profile-db "$work/emptied.sqlite" --user ann --event "$critique"
expect 1 'an empty file \(0 bytes\)' -- "$cbtl" profile list --db "$work/emptied.sqlite"
[[ ! -s $work/emptied.sqlite ]] || fail "the emptied store was written to"
expect 1 'not a regular file' -- "$cbtl" profile list --db "$work"

# Two `cbtl feedback` processes learning into one profile at once lose nothing: each learns from the version the
# other stored (read, learn and store are one write transaction), so the model holds every label.
learn_many() { for _ in $(seq 25); do "$cbtl" feedback "$cooking" --profile-db "$work/duo.sqlite" --user duo \
  --event "$critique" >/dev/null || echo "a feedback failed"; done; }
learn_many >"$work/duo-a.log" 2>&1 &
learn_many >"$work/duo-b.log" 2>&1
wait
[[ ! -s $work/duo-a.log && ! -s $work/duo-b.log ]] || fail "concurrent feedback: $(cat "$work"/duo-*.log)"
expect 0 'version 50 of 50 .*: 100 labels' -- "$cbtl" profile show --db "$work/duo.sqlite" duo cooking

echo "$failures failure(s)"
[[ $failures -eq 0 ]]
