#!/usr/bin/env bash
# Peers (issue 5): this project's collision solve against Siconos' LCP
# solvers, on the same instances, in one run.
#
#   bench/peers/run.sh [extra Google Benchmark flags]
#
# 1. installs Debian's libsiconos-numerics-dev with apt-get (root, or sudo),
# 2. configures and builds bench_peers (Release, -DSUPERBALL_BUILD_BENCH=ON)
#    in its own build folder, BUILD_DIR (default: build-peers at the top of
#    the checkout), with JOBS parallel jobs (default 2),
# 3. runs it with 10 repetitions, aggregates only, single-threaded BLAS (our
#    solve is single-threaded; threaded OpenBLAS makes Siconos' small LAPACK
#    calls far slower), writes the JSON to BUILD_DIR/bench_peers.json and
#    prints the medians with their ratios and the accuracy counters.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"
build="${BUILD_DIR:-$root/build-peers}"
jobs="${JOBS:-2}"

sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
if ! $sudo apt-get install -y libsiconos-numerics-dev; then
  $sudo apt-get update
  $sudo apt-get install -y libsiconos-numerics-dev
fi

cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DSUPERBALL_BUILD_BENCH=ON -DSUPERBALL_BUILD_TESTS=OFF
cmake --build "$build" -j "$jobs" --target bench_peers

export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1
"$build/bench/peers/bench_peers" \
  --benchmark_repetitions=10 --benchmark_report_aggregates_only=true \
  --benchmark_out="$build/bench_peers.json" --benchmark_out_format=json "$@"
