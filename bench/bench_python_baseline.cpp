// The C++ side of bench/python_side_by_side.py: the calls the Python module
// makes, made directly through the libraries, so that the script can put
// the Python figures beside them in one run (docs/PERFORMANCE.md, "The
// Python module").
//  - sweep/1e5: numeric::sweep of the paper scene (§4.4, alpha_2 reading)
//    over 10^5 exact values of K34 from 0 to 20, double, on 1 and 2 threads
//    (what superball.sweep(scene, "K.3-4", superball.linspace(0, 20, 100000))
//    does before its NumPy arrays);
//  - solve/double, solve/exact: present::solve_scene of the paper scene, the
//    call behind superball.solve(scene, "double" | "exact").
#include <benchmark/benchmark.h>

#include "superball/cases/scene_file.hpp"
#include "superball/numeric/sweep.hpp"
#include "superball/present/solution.hpp"

namespace {

using namespace superball;

const Scene& paper_scene() {
  static const Scene s = load_scene(SUPERBALL_SCENES_DIR "/paper-4.4-alpha2.toml");
  return s;
}

/// The Python sweep's length.
constexpr int kSweepValues = 100000;

void BM_Sweep(benchmark::State& state) {
  const Parameter k34 = Parameter::parse("K.3-4", paper_scene());
  const auto values = numeric::linspace(0, 20, kSweepValues);
  const auto p = numeric::Precision::parse("double");
  const int threads = static_cast<int>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(numeric::sweep(paper_scene(), k34, values, p, threads));
  state.SetItemsProcessed(state.iterations() * kSweepValues);
}
BENCHMARK(BM_Sweep)->Name("sweep/1e5")->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);

void BM_Solve(benchmark::State& state, const char* precision) {
  const auto p = numeric::Precision::parse(precision);
  for (auto _ : state) benchmark::DoNotOptimize(present::solve_scene(paper_scene(), p));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK_CAPTURE(BM_Solve, double, "double")->Name("solve/double")->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Solve, exact, "exact")->Name("solve/exact")->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
