// What accuracy costs in time (issue 5): for each scene and each arithmetic,
// the time per solve (by the formulation numeric::solve() picks, solver
// reused; the reference is the dense exact solve) and, as counters, the normwise relative
// error of the velocities against the exact solution and whether the case
// is the exact one.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "superball/cases/scene_file.hpp"
#include "superball/numeric/chain.hpp"
#include "superball/numeric/collision.hpp"

namespace {

using namespace superball;

/// Time per solve of \p problem by a reused Solver; its last answer in \p out.
template <class Solver, class S>
void time_solves(benchmark::State& state, const numeric::Problem<S>& problem, int digits, numeric::Solution<S>& out) {
  Solver solver(numeric::Settings<S>::defaults(digits));
  solver.compute(problem, out);
  for (auto _ : state) {
    solver.compute(problem, out);
    benchmark::DoNotOptimize(out.velocities_after.data());
  }
}

/// The formulation numeric::solve() picks (labelled "dense" or "chain").
template <class S>
void measure(benchmark::State& state, const numeric::ExactScene& scene, int digits) {
  const auto exact = numeric::CollisionSolver<cln::cl_RA>().compute(numeric::Problem<cln::cl_RA>::from(scene));
  const auto problem = numeric::Problem<S>::from(scene, digits);
  numeric::Solution<S> out;
  if (numeric::solves_as_chain(problem)) {
    time_solves<numeric::ChainSolver<S>>(state, problem, digits, out);
    state.SetLabel("chain");
  } else {
    time_solves<numeric::CollisionSolver<S>>(state, problem, digits, out);
    state.SetLabel("dense");
  }
  // max_i |U_i − exact U_i| / max_i |exact U_i|, measured in exact arithmetic.
  cln::cl_RA error = 0, scale = 0;
  for (std::size_t i = 0; i < exact.velocities_after.size(); ++i) {
    const cln::cl_RA e = exact.velocities_after[i];
    cln::cl_RA v;
    if constexpr (std::is_same_v<S, cln::cl_RA>) {
      v = out.velocities_after[i];
    } else if constexpr (std::is_same_v<S, cln::cl_R>) {
      v = cln::rational(out.velocities_after[i]);
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
    for (int d : {20, 50, 100})
      benchmark::RegisterBenchmark((name + "digits:" + std::to_string(d)).c_str(),
                                   [&scene, d](benchmark::State& s) { measure<cln::cl_R>(s, scene, d); });
    benchmark::RegisterBenchmark((name + "exact").c_str(), [&scene](benchmark::State& s) { measure<cln::cl_RA>(s, scene, 0); });
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
}
