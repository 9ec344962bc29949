#!/usr/bin/env bash
# fuzz.sh [SECONDS] [TARGET] — fuzz with libFuzzer for SECONDS (default 600). TARGET: cbtlc (default: the
# whole cbtlc pipeline, tests/fuzz/cbtlc_fuzz.cpp) or runtime (load, solve, re-check, unroll and learn from
# every program the compiler accepts, tests/fuzz/cbtl_runtime_fuzz.cpp).
#
# Configures build-fuzz/ with clang (ASan + UBSan + libFuzzer coverage), builds only the fuzz target, seeds
# a corpus from every .cbtl file of the tree (golden cases, domains, the standard library) and runs
# the target with the language's dictionary. Findings (crash-*, leak-*, timeout-*, oom-*) land in
# build-fuzz/fuzz[-runtime]/artifacts/, the grown corpus in build-fuzz/fuzz[-runtime]/corpus/ (kept between
# runs), and the full log in build-fuzz/fuzz[-runtime]/fuzz.log. Environment: FUZZ_JOBS (ninja -j, default 1), CLANGXX (default
# /usr/bin/clang++), FUZZ_BUILD (default build-fuzz).
set -euo pipefail
seconds=${1:-600}
target=${2:-cbtlc}
case "$target" in
  cbtlc) binary=cbtlc_fuzz; workdir=fuzz ;;
  runtime) binary=cbtl_runtime_fuzz; workdir=fuzz-runtime ;;
  *) echo "fuzz.sh: unknown target '$target' (cbtlc, runtime)" >&2; exit 2 ;;
esac
root=$(cd "$(dirname "$0")/.." && pwd)
build=${FUZZ_BUILD:-$root/build-fuzz}
clangxx=${CLANGXX:-/usr/bin/clang++}
jobs=${FUZZ_JOBS:-1}

if [ ! -f "$build/build.ninja" ]; then
  cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER="$clangxx" \
        -DCBTL_FUZZ=ON -DCBTL_SANITIZE=ON -DCBTL_BUILD_BENCH=OFF
fi
ninja -C "$build" -j "$jobs" "$binary"

work=$build/$workdir
mkdir -p "$work/corpus" "$work/seeds" "$work/artifacts" "$work/cwd"
# Seeds: every .cbtl input in the tree, copied flat under unique names (libFuzzer reads a directory).
find "$root/tests/golden" "$root/domains" "$root/stdlib/std" -name '*.cbtl' -print0 |
  while IFS= read -r -d '' f; do
    cp "$f" "$work/seeds/$(echo "${f#"$root"/}" | tr '/' '_')"
  done

# Relative imports resolve inside a directory that does not exist (see the target); the working directory
# is an empty scratch folder all the same, so no input can reach the tree by a relative path.
cd "$work/cwd"
set +e
"$build/bin/$binary" "$work/corpus" "$work/seeds" \
    -dict="$root/tests/fuzz/cbtl.dict" \
    -max_total_time="$seconds" -timeout=5 -rss_limit_mb=2048 -max_len=65536 \
    -artifact_prefix="$work/artifacts/" -print_final_stats=1 2>&1 | tee "$work/fuzz.log"
status=${PIPESTATUS[0]}
set -e
echo "fuzz.sh: libFuzzer exited $status; corpus $(find "$work/corpus" -type f | wc -l) files;" \
     "artifacts: $(find "$work/artifacts" -type f | wc -l) (in $work/artifacts)"
exit "$status"
