// Solves per second in a sweep of the paper scene (§4.4, alpha_2 reading)
// along K34 from 0 to 20, on 1 and 2 threads, double and exact: what
// `superball sweep` does before printing.  Each point is a scene of its own
// (the value set, the exact entry checks, the conversion, the solve).
// items_per_second = solves per second, wall clock.
#include <benchmark/benchmark.h>

#include "superball/cases/scene_file.hpp"
#include "superball/numeric/collision.hpp"
#include "superball/numeric/parallel.hpp"
#include "superball/numeric/sweep.hpp"

namespace {

using namespace superball;

const Scene& paper_scene() {
  static const Scene s = load_scene(SUPERBALL_SCENES_DIR "/paper-4.4-alpha2.toml");
  return s;
}

/// The single solve a sweep point is measured against (issue 28), as
/// bench_solve's solve/paper/double/0: one CollisionSolver and one Solution,
/// the paper scene solved again and again.
void BM_SolveReused(benchmark::State& state) {
  const auto problem = numeric::Problem<double>::from(numeric::ExactScene::from(paper_scene()));
  numeric::CollisionSolver<double> solver(numeric::Settings<double>::defaults());
  numeric::Solution<double> out;
  for (auto _ : state) {
    solver.compute(problem, out);
    benchmark::DoNotOptimize(out.velocities_after.data());
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_SolveReused)->Name("solve/paper/double/0");

/// numeric::sweep over \p points values of K34 on state.range(0) threads.
void BM_Sweep(benchmark::State& state, const char* precision, int points) {
  const Parameter k34 = Parameter::parse("K.3-4", paper_scene());
  const auto values = numeric::linspace(0, 20, points);
  const auto p = numeric::Precision::parse(precision);
  const int threads = static_cast<int>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(numeric::sweep(paper_scene(), k34, values, p, threads));
  state.SetItemsProcessed(state.iterations() * points);
}
BENCHMARK_CAPTURE(BM_Sweep, double, "double", 10001)->Name("sweep/paper/double")->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Sweep, exact, "exact", 1001)->Name("sweep/paper/exact")->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);

/// --switch-points on K34 = 0:20:401: the exact case at every value, then 64
/// bisections per change (two changes), on state.range(0) threads.
void BM_SwitchPoints(benchmark::State& state) {
  const Parameter k34 = Parameter::parse("K.3-4", paper_scene());
  const auto points = numeric::sweep(paper_scene(), k34, numeric::linspace(0, 20, 401), numeric::Precision::parse("double"));
  const int threads = static_cast<int>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(numeric::switch_points(paper_scene(), k34, points, 64, threads));
  state.SetItemsProcessed(state.iterations() * (401 + 2 * 64));
}
BENCHMARK(BM_SwitchPoints)->Name("switch-points/paper")->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);

/// The control: tasks of pure arithmetic (no memory, no CLN) through the same
/// parallel_map, 10001 tasks of about 10 µs.  Its speed-up from 1 to 2
/// threads is what the machine gives two threads at the time of the run;
/// the sweeps above cannot do better.
void BM_Control(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  const std::size_t tasks = 10001;
  for (auto _ : state)
    benchmark::DoNotOptimize(numeric::parallel_map(tasks, threads, [] { return 0; }, [](int&, std::size_t i) {
      double x = static_cast<double>(i);
      for (int k = 0; k < 10000; ++k) x = x * 0.999999 + 1e-6;
      return x;
    }));
  state.SetItemsProcessed(state.iterations() * static_cast<benchmark::IterationCount>(tasks));
}
BENCHMARK(BM_Control)->Name("control/arithmetic")->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);

/// One point's scene without its solve: K34 set, the exact entry checks
/// (ExactScene::from: rationals, M positive semi-definite decided exactly)
/// and the conversion to double.  Compare with bench_solve's solve/paper/double.
void BM_PointScene(benchmark::State& state) {
  const Parameter k34 = Parameter::parse("K.3-4", paper_scene());
  const cln::cl_RA value = 10;
  for (auto _ : state)
    benchmark::DoNotOptimize(numeric::Problem<double>::from(numeric::ExactScene::from(numeric::with_value(paper_scene(), k34, value))));
}
BENCHMARK(BM_PointScene)->Name("sweep-point-scene/paper/double");

}  // namespace

BENCHMARK_MAIN();
