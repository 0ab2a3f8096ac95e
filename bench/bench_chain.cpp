// Long chains (issue 5): time per solve of a falling chain of n bodies on a
// fixed obstacle, M coupling nearest and next-nearest neighbour pairs, by
// the banded ChainSolver (O(n) per active-set iteration).  The counter
// `iterations` is the number of active-set iterations.
#include <benchmark/benchmark.h>

#include "superball/numeric/chain.hpp"

namespace {

using namespace superball::numeric;

/// A falling stack of light bodies: masses 0.001 … 0.007 repeating, K = 1
/// on (i, i+1), 1/2 on (i, i+2), a coupling 1/4 between (i, i+1) and
/// (i+1, i+2) (M diagonally dominant, so positive definite); the bodies fall
/// onto a fixed obstacle, the top fastest: speeds step down from 1.9 to 1.0
/// m/s in tenths (−1.9 + ⌊10 i/(n−1)⌋/10), so every contact closes, as the
/// collision law requires.  For n ≥ 2000 every contact stays closed and the
/// chain stops on the obstacle (the active set is found without an
/// iteration); for n = 32 24 of the 31 contacts stay closed.
Problem<double> chain(int n) {
  Problem<double> p;
  p.n = n;
  p.fixed_bottom = true;
  for (int i = 0; i < n; ++i) {
    p.mass.push_back(i + 1 == n ? 0.0 : 0.001 * (1 + i % 7));
    p.u.push_back(i + 1 == n ? 0.0 : -1.9 + (10 * i / (n - 1)) / 10.0);  // the top falls fastest
  }
  for (int i = 0; i + 1 < n; ++i) {
    p.entries.push_back({i, i + 1, i, i + 1, 1.0});
    if (i + 2 < n) {
      p.entries.push_back({i, i + 2, i, i + 2, 0.5});
      p.entries.push_back({i, i + 1, i + 1, i + 2, 0.25});
    }
  }
  return p;
}

/// Time per solve of the chain of state.range(0) bodies by \p Solver.
template <class Solver>
void BM_Solve(benchmark::State& state) {
  const Problem<double> p = chain(static_cast<int>(state.range(0)));
  Solver solver;
  Solution<double> out;
  solver.compute(p, out);
  for (auto _ : state) {
    solver.compute(p, out);
    benchmark::DoNotOptimize(out.velocities_after.data());
  }
  if (out.status != Status::Success) state.SkipWithError("the solve did not succeed");
  state.counters["iterations"] = out.pivots;
  state.counters["bodies"] = static_cast<double>(p.n);
  state.SetComplexityN(state.range(0));
}
BENCHMARK_TEMPLATE(BM_Solve, ChainSolver<double>)
    ->Name("chain/double")
    ->RangeMultiplier(10)
    ->Range(10, 1000000)
    ->Unit(benchmark::kMillisecond)
    ->Complexity();
// The dense formulation on the same chains, for comparison (O(n³)).
BENCHMARK_TEMPLATE(BM_Solve, CollisionSolver<double>)
    ->Name("chain-dense/double")
    ->RangeMultiplier(10)
    ->Range(10, 1000)
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
