// The cost of a map point (issue 15), side by side with a solve and a sweep
// point: the paper scene (§4.4, alpha_2 reading) over K34 in [0, 20] and
// alpha_2 in [-100, 0] (M positive semi-definite throughout), double, one
// thread, the grid points only (no boundaries).  items_per_second = points
// (or solves) per second.  solve/paper/double/0 is bench_solve's single
// solve (issue 28 measures a grid point and a sweep value against it, in the
// same run); batch/paper/double/128x128 the grid's points through a
// numeric::Batch alone (batch.hpp), without the PSD filter and the MapPoint,
// one point at a time, and /lanes through Batch::solve_each() (several at once).
#include <benchmark/benchmark.h>

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "superball/cases/scene_file.hpp"
#include "superball/numeric/batch.hpp"
#include "superball/numeric/map.hpp"
#include "superball/numeric/problem.hpp"
#include "superball/numeric/sweep.hpp"

namespace {

using namespace superball;

const Scene& paper_scene() {
  static const Scene s = load_scene(SUPERBALL_SCENES_DIR "/paper-4.4-alpha2.toml");
  return s;
}

/// The solve alone: the paper scene's Problem<double>, made once.
void BM_Solve(benchmark::State& state) {
  const auto problem = numeric::Problem<double>::from(numeric::ExactScene::from(paper_scene()));
  for (auto _ : state) benchmark::DoNotOptimize(numeric::solve(problem));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_Solve)->Name("solve/paper/double");

/// The baseline of issue 28's goal, bench_solve's solve/paper/double/0 here
/// too (so that a ratio comes from one run): a CollisionSolver and its
/// Solution made once, the same problem solved again and again.
void BM_SolveReused(benchmark::State& state) {
  const auto problem = numeric::Problem<double>::from(numeric::ExactScene::from(paper_scene()));
  numeric::CollisionSolver<double> solver(numeric::Settings<double>::defaults());
  numeric::Solution<double> out;
  solver.compute(problem, out);
  for (auto _ : state) {
    solver.compute(problem, out);
    benchmark::DoNotOptimize(out.velocities_after.data());
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_SolveReused)->Name("solve/paper/double/0");

/// The paper scene's Batch (batch.hpp) over K34 and alpha_2, and the 128
/// values of each axis of BM_MapPoints' grid.
struct PaperGrid {
  numeric::ExactScene exact = numeric::ExactScene::from(paper_scene());
  numeric::Batch<double> batch{exact, {entry(2, 3, 2, 3), entry(0, 1, 0, 3)}};  // K34, alpha_2 (pairs 1-2 and 1-4)
  std::vector<double> xs = axis(0, 20), ys = axis(-100, 0);

  std::size_t entry(int i, int j, int k, int l) const {
    for (std::size_t e = 0; e < exact.entries.size(); ++e)
      if (exact.entries[e].i == i && exact.entries[e].j == j && exact.entries[e].k == k && exact.entries[e].l == l) return e;
    throw std::logic_error("no such entry");
  }
  static std::vector<double> axis(int from, int to) {
    std::vector<double> values;
    for (const auto& v : numeric::linspace(from, to, 128)) values.push_back(cln::double_approx(v));
    return values;
  }
};

/// Each item one point of the 128 × 128 grid of BM_MapPoints set and
/// solved by the Batch, without the map around it (no PSD check, no
/// MapPoint).
void BM_BatchPoints(benchmark::State& state) {
  PaperGrid g;
  std::size_t k = 0;
  for (auto _ : state) {
    const std::size_t i = k % 128, j = (k / 128) % 128;
    g.batch.set(0, g.xs[i], i == 0);
    g.batch.set(1, g.ys[j], j == 127);
    benchmark::DoNotOptimize(g.batch.solve().velocities_after.data());
    ++k;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_BatchPoints)->Name("batch/paper/double/128x128");

/// BM_BatchPoints through Batch::solve_each(): the grid's points 4 at a
/// time in SIMD lanes, pivots included (the map's and the sweep's way), a
/// lane that branches otherwise than the first one again alone.  Each item
/// one point.
void BM_BatchLanes(benchmark::State& state) {
  PaperGrid g;
  double sum = 0;
  for (auto _ : state) {
    g.batch.solve_each(
        128 * 128, [&](std::size_t k) { g.batch.set(0, g.xs[k % 128], k % 128 == 0), g.batch.set(1, g.ys[k / 128], k / 128 == 127); },
        [&](std::size_t, const numeric::Solution<double>& sol) { sum += sol.velocities_after[0]; });
  }
  benchmark::DoNotOptimize(sum);
  state.SetItemsProcessed(state.iterations() * 128 * 128);
}
BENCHMARK(BM_BatchLanes)->Name("batch/paper/double/128x128/lanes");

/// A sweep of state.range(0) values of K34 on one thread (`superball
/// sweep`'s points).  16384 values: the cost of a value, the sweep's fixed
/// cost (its checks of the scene at the ends, the batch's conversion) shared
/// by them; 2 values: that fixed cost alone, so that a value's own cost is
/// (t(16384) − t(2)) / 16382.
void BM_SweepPoints(benchmark::State& state) {
  const Parameter k34 = Parameter::parse("K.3-4", paper_scene());
  const int count = static_cast<int>(state.range(0));
  const auto values = numeric::linspace(0, 20, count);
  for (auto _ : state) benchmark::DoNotOptimize(numeric::sweep(paper_scene(), k34, values, numeric::Precision{}, 1));
  state.SetItemsProcessed(state.iterations() * count);
}
BENCHMARK(BM_SweepPoints)->Name("sweep/paper/double")->Arg(16384)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);

/// A steps × steps map of (K34, alpha_2) on one thread, grid points only.  128: the cost of a point with map()'s fixed cost (its
/// checks of the scene, the axes' values and texts) shared by 16384 points;
/// 2: that fixed cost with 4 points, so that a point's own cost is
/// (t(128) − t(2)) / 16380.
void map_points(benchmark::State& state, int steps) {
  const Scene& s = paper_scene();
  const numeric::Axis x{Parameter::parse("K.3-4", s), 0, 20, steps}, y{Parameter::parse("alpha.2", s), -100, 0, steps};
  numeric::MapSettings settings;
  settings.boundaries = false;
  for (auto _ : state) benchmark::DoNotOptimize(numeric::map(s, x, y, settings));
  state.SetItemsProcessed(state.iterations() * steps * steps);
}
void BM_MapPoints(benchmark::State& state) { map_points(state, 128); }
BENCHMARK(BM_MapPoints)->Name("map/paper/double/128x128")->UseRealTime()->Unit(benchmark::kMillisecond);
void BM_MapFixed(benchmark::State& state) { map_points(state, 2); }
BENCHMARK(BM_MapFixed)->Name("map/paper/double/2x2")->UseRealTime()->Unit(benchmark::kMillisecond);

/// The exact boundary points of a map: the bisections of label_changes()
/// on the K34 segments between neighbours of different region along the
/// line alpha_2 = -100 ... -60 (9 lines of 64 grid steps), by case and
/// superball verdict, to 2^-64 of the step, one thread; state.range(0) = 1
/// with the shortcut (the map's), 0 every label from an exact solve (the
/// same brackets, bit for bit).  items_per_second = boundary points per second.
void BM_Boundaries(benchmark::State& state) {
  const Scene& s = paper_scene();
  const Parameter k34 = Parameter::parse("K.3-4", s), alpha2 = Parameter::parse("alpha.2", s);
  const numeric::Label by_region = [](const numeric::ExactPoint& e) { return numeric::Region::of(e).label(); };
  const numeric::ProvenLabel proven = [](const numeric::ProvenPoint& p) -> std::optional<std::string> {
    if (!p.superball) return std::nullopt;
    return numeric::Region{p.closed, *p.superball}.label();
  };
  std::vector<Scene> lines;
  for (int j = 0; j <= 8; ++j) lines.push_back(numeric::with_value(s, alpha2, cln::cl_RA(-100 + 5 * j)));
  const auto values = numeric::linspace(0, 20, 64);
  std::size_t points = 0;
  for (auto _ : state) {
    for (const Scene& line : lines)
      points += numeric::label_changes(line, k34, values, by_region, 64, 1, state.range(0) ? proven : numeric::ProvenLabel{}).size();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(points));
}
BENCHMARK(BM_Boundaries)->Name("map/paper/boundaries/shortcut")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

/// The boundary stage of a map as map() runs it: a 64 × 64 map of (K34,
/// alpha_2) over [0, 20] × [-110, 0] (its four curves: two case boundaries,
/// the superball edge and the edge of M positive semi-definite) on one
/// thread, with its boundaries (state.range(0) = 1) or the grid alone (0).
/// The cost of a boundary point is the difference over the boundary points
/// (counter "boundaries"); items_per_second = maps per second.
void BM_MapBoundaries(benchmark::State& state) {
  const Scene& s = paper_scene();
  const numeric::Axis x{Parameter::parse("K.3-4", s), 0, 20, 64}, y{Parameter::parse("alpha.2", s), -110, 0, 64};
  numeric::MapSettings settings;
  settings.boundaries = state.range(0) != 0;
  std::size_t boundaries = 0;
  for (auto _ : state) boundaries = numeric::map(s, x, y, settings).boundaries.size();
  state.counters["boundaries"] = static_cast<double>(boundaries);
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_MapBoundaries)->Name("map/paper/64x64/boundaries")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
