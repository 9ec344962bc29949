#!/usr/bin/env bash
# robot-trial-ab.sh BASE_REV [RUNS] — one robot trial per domain (CBTL, seed 0, 5,000 steps, evaluation every 500 on
# 10 tasks: the paper's protocol) with the working tree's cbtl and with BASE_REV's, in turn (A B A B ...), RUNS
# pairs (default 3), printing each run's CPU seconds (user + system, from /usr/bin/time) and per domain the median
# of both and their ratio. BASE_REV is checked out into a git worktree under build-ab/ and built there (cbtl only).
# Each binary runs its own revision's domain files (a program the newer language accepts may not parse in the older
# one). Alternating the two keeps a drifting machine speed out of the ratio. The working tree's build/ must be built.
# Domains: DOMAINS (default "cleaning books feeding").
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
base=${1:?usage: bench/robot-trial-ab.sh BASE_REV [RUNS]}
runs=${2:-3}
domains=${DOMAINS:-cleaning books feeding}
tree=$root/build-ab/tree
if [ ! -d "$tree" ]; then git -C "$root" worktree add --detach "$tree" "$base"; fi
git -C "$tree" checkout --quiet --detach "$base"
cmake -S "$tree" -B "$tree/build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCBTL_BUILD_BENCH=OFF >/dev/null
cmake --build "$tree/build" -j "$(nproc)" --target cbtl >/dev/null
new=$root/build/bin/cbtl
old=$tree/build/bin/cbtl

cpu() {  # prints the CPU seconds of one trial of the tree's own domain file; fails loudly if the run fails
  local bin=$1 tree=$2 domain=$3 t
  t=$(mktemp)
  if ! /usr/bin/time -f '%U %S' -o "$t" "$bin" run "$tree/domains/$domain/$domain.cbtl" --approach cbtl --seed 0 \
    --steps 5000 --eval-every 500 --eval-tasks 10 >/dev/null 2>&1; then
    echo "robot-trial-ab.sh: $bin failed on $tree/domains/$domain/$domain.cbtl" >&2
    exit 1
  fi
  awk '{ printf "%.2f\n", $1 + $2 }' "$t"
  rm -f "$t"
}
median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

for d in $domains; do
  a=() b=()
  for ((i = 1; i <= runs; ++i)); do
    a+=("$(cpu "$new" "$root" "$d")")
    b+=("$(cpu "$old" "$tree" "$d")")
    echo "$d run $i: working tree ${a[-1]} s, $base ${b[-1]} s"
  done
  ma=$(printf '%s\n' "${a[@]}" | median)
  mb=$(printf '%s\n' "${b[@]}" | median)
  echo "$d: median CPU working tree $ma s, $base $mb s, ratio $(awk -v x="$ma" -v y="$mb" 'BEGIN { printf "%.2f", x / y }')"
done
