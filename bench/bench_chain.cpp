// Long chains (issue 5): time per solve of a falling chain of n bodies on a
// fixed obstacle, M coupling nearest and next-nearest neighbour pairs, by
// the banded ChainSolver (O(n) per active-set iteration).  The counter
// `iterations` is the number of active-set iterations.
#include <benchmark/benchmark.h>

#include "superball/numeric/chain.hpp"
#include "support/falling_chain.hpp"

namespace {

using namespace superball::numeric;

/// Time per solve of the chain of state.range(0) bodies by \p Solver.
template <class Solver>
void BM_Solve(benchmark::State& state) {
  const Problem<double> p = superball::test::falling_chain(static_cast<int>(state.range(0)));
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
