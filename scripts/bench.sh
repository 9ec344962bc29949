#!/usr/bin/env bash
# bench.sh [BUILD_DIR] — build the Google Benchmark suites (Release, -DCBTL_BUILD_BENCH=ON) in BUILD_DIR
# (default build/) and run every benchmark executable (bin/*_bench), writing each one's results as JSON to
# BUILD_DIR/bench-results/<name>.json and a readable copy to BUILD_DIR/bench-results/<name>.txt.
#
# The configure step switches BUILD_DIR to CMAKE_BUILD_TYPE=Release (benchmarks of a debug build measure
# nothing useful); use a separate folder (scripts/bench.sh build-bench) to leave a development build as it is.
# Environment: BENCH_JOBS (ninja -j, default: number of cores), BENCH_FILTER (extended regex on the
# executable names, e.g. '^compiler_bench$'), BENCH_ARGS (extra arguments for every executable, e.g.
# --benchmark_repetitions=5).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-build}
case $build in /*) ;; *) build=$root/$build ;; esac
jobs=${BENCH_JOBS:-$(nproc 2>/dev/null || echo 2)}
filter=${BENCH_FILTER:-.}

cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCBTL_BUILD_BENCH=ON
# Only the benchmark executables (and what they need), not the whole tree.
targets=$(ninja -C "$build" -t targets all | sed -n 's/^\([A-Za-z0-9_]*_bench\): phony$/\1/p' | grep -v "^cmake_" | sort -u | grep -E "$filter" || true)
if [ -z "$targets" ]; then
  echo "bench.sh: no benchmark targets match '$filter'" >&2
  exit 1
fi
# shellcheck disable=SC2086
ninja -C "$build" -j "$jobs" $targets

out=$build/bench-results
mkdir -p "$out"
{
  echo "# $(date -u +%Y-%m-%dT%H:%M:%SZ) on $(uname -n): $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg)"
  echo "# $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ //')"
} > "$out/machine.txt"
status=0
for name in $targets; do
  exe=$build/bin/$name
  [ -x "$exe" ] || { echo "bench.sh: $exe was not built" >&2; status=1; continue; }
  echo "== $name"
  # shellcheck disable=SC2086
  "$exe" --benchmark_out="$out/$name.json" --benchmark_out_format=json ${BENCH_ARGS:-} | tee "$out/$name.txt" ||
    status=1
done
echo "bench.sh: results in $out"
exit $status
