// What accuracy costs in time (issue 5): for each scene and each arithmetic,
// the time per solve (by the formulation numeric::solve() picks, solver
// reused; the reference is the dense exact solve) and, as counters, the normwise relative
// error of the velocities against the exact solution and whether the case
// is the exact one.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <type_traits>

#include "superball/cases/scene_file.hpp"
#include "superball/numeric/chain.hpp"
#include "superball/numeric/collision.hpp"

namespace {

using namespace superball;

/// The largest n of CollisionSolver's fixed-size path (numeric/src/collision/small_solver.hpp).
constexpr int kSmallMaxBodies = 8;

/// Which path of CollisionSolver a row times (double and long double).
enum class Path {
  Default,  ///< Settings::defaults(): the fixed-size path for n <= 8, else the general one
  General   ///< Settings::small_sizes = false: the runtime-sized path at every n
};

/// Time per solve of \p problem by a reused Solver; its last answer in \p out.
template <class Solver, class S>
void time_solves(benchmark::State& state, const numeric::Problem<S>& problem, int digits, numeric::Solution<S>& out,
                 Path path = Path::Default) {
  numeric::Settings<S> settings = numeric::Settings<S>::defaults(digits);
  if (path == Path::General) settings.small_sizes = false;
  Solver solver(settings);
  solver.compute(problem, out);
  for (auto _ : state) {
    solver.compute(problem, out);
    benchmark::DoNotOptimize(out.velocities_after.data());
  }
}

/// The formulation numeric::solve() picks, labelled "chain", "dense" (the
/// general path) or "dense, fixed-size" (double and long double, n <= 8:
/// the path of small_solver.cpp, bit for bit the general one); \p path
/// General times the general path where the fixed-size one would run.
template <class S>
void measure(benchmark::State& state, const numeric::ExactScene& scene, int digits, Path path = Path::Default) {
  const auto exact = numeric::CollisionSolver<cln::cl_RA>().compute(numeric::Problem<cln::cl_RA>::from(scene));
  const auto problem = numeric::Problem<S>::from(scene, digits);
  numeric::Solution<S> out;
  if (numeric::solves_as_chain(problem)) {
    time_solves<numeric::ChainSolver<S>>(state, problem, digits, out);
    state.SetLabel("chain");
  } else {
    time_solves<numeric::CollisionSolver<S>>(state, problem, digits, out, path);
    state.SetLabel(std::is_floating_point<S>::value && path == Path::Default && problem.n <= kSmallMaxBodies ? "dense, fixed-size" : "dense");
  }
  // max_i |U_i − exact U_i| / max_i |exact U_i|, measured in exact arithmetic.
  cln::cl_RA error = 0, scale = 0;
  for (std::size_t i = 0; i < exact.velocities_after.size(); ++i) {
    const cln::cl_RA e = exact.velocities_after[i];
    cln::cl_RA v;
    if constexpr (std::is_same_v<S, cln::cl_RA>) {
      v = out.velocities_after[i];
    } else if constexpr (std::is_same_v<S, numeric::MpFloat>) {
      v = numeric::rational(out.velocities_after[i]);
    } else {
      v = cln::rational(cln::cl_float(static_cast<double>(out.velocities_after[i])));
      if constexpr (std::is_same_v<S, long double>) {  // keep the bits a double cannot hold
        const long double rest = out.velocities_after[i] - static_cast<long double>(static_cast<double>(out.velocities_after[i]));
        v = v + cln::rational(cln::cl_float(static_cast<double>(rest)));
      }
    }
    error = std::max(error, cln::abs(v - e));
    scale = std::max(scale, cln::abs(e));
  }
  state.counters["rel_error"] = cln::double_approx(scale > 0 ? error / scale : error);
  state.counters["case_ok"] = out.closed == exact.closed ? 1 : 0;
  state.counters["status_ok"] = out.status == numeric::Status::Success ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  static const char* scenes[] = {"paper-4.4-alpha2", "hard-eps-1e-8", "hard-mass-ratio-1e12", "chain-32"};
  static std::vector<numeric::ExactScene> loaded;
  for (const char* s : scenes)
    loaded.push_back(numeric::ExactScene::from(load_scene(std::string(SUPERBALL_SCENES_DIR "/") + s + ".toml")));
  for (std::size_t k = 0; k < loaded.size(); ++k) {
    const auto& scene = loaded[k];
    const std::string name = std::string("accuracy/") + scenes[k] + "/";
    benchmark::RegisterBenchmark((name + "double").c_str(), [&scene](benchmark::State& s) { measure<double>(s, scene, 0); });
    benchmark::RegisterBenchmark((name + "long-double").c_str(), [&scene](benchmark::State& s) { measure<long double>(s, scene, 0); });
    if (scene.n <= kSmallMaxBodies) {  // the general path beside the fixed-size one: same answers, bit for bit
      benchmark::RegisterBenchmark((name + "double/general-path").c_str(),
                                   [&scene](benchmark::State& s) { measure<double>(s, scene, 0, Path::General); });
      benchmark::RegisterBenchmark((name + "long-double/general-path").c_str(),
                                   [&scene](benchmark::State& s) { measure<long double>(s, scene, 0, Path::General); });
    }
    for (int d : {20, 50, 100})
      benchmark::RegisterBenchmark((name + "digits:" + std::to_string(d)).c_str(),
                                   [&scene, d](benchmark::State& s) { measure<numeric::MpFloat>(s, scene, d); });
    benchmark::RegisterBenchmark((name + "exact").c_str(), [&scene](benchmark::State& s) { measure<cln::cl_RA>(s, scene, 0); });
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
}
