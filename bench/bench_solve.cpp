// Time per collision solve for the paper scene (§4.4, alpha_2 reading) in
// each arithmetic.  The solver is constructed once and reused, as in a sweep.
#include <benchmark/benchmark.h>

#include "superball/cases/scene_file.hpp"
#include "superball/numeric/certify.hpp"
#include "superball/numeric/chain.hpp"
#include "superball/numeric/collision.hpp"

namespace {

using namespace superball;

const numeric::ExactScene& paper_scene() {
  static const numeric::ExactScene s = numeric::ExactScene::from(load_scene(SUPERBALL_SCENES_DIR "/paper-4.4-alpha2.toml"));
  return s;
}

template <class S>
void BM_Solve(benchmark::State& state) {
  const int digits = static_cast<int>(state.range(0));
  const auto problem = numeric::Problem<S>::from(paper_scene(), digits);
  numeric::CollisionSolver<S> solver(numeric::Settings<S>::defaults(digits));
  numeric::Solution<S> out;
  solver.compute(problem, out);
  for (auto _ : state) {
    solver.compute(problem, out);
    benchmark::DoNotOptimize(out.velocities_after.data());
  }
  if (out.status != numeric::Status::Success) state.SkipWithError("the solve did not succeed");
}

BENCHMARK_TEMPLATE(BM_Solve, double)->Arg(0)->Name("solve/paper/double");
BENCHMARK_TEMPLATE(BM_Solve, long double)->Arg(0)->Name("solve/paper/long-double");
BENCHMARK_TEMPLATE(BM_Solve, cln::cl_R)->Arg(20)->Name("solve/paper/digits:20");
BENCHMARK_TEMPLATE(BM_Solve, cln::cl_R)->Arg(50)->Name("solve/paper/digits:50");
BENCHMARK_TEMPLATE(BM_Solve, cln::cl_R)->Arg(100)->Name("solve/paper/digits:100");
BENCHMARK_TEMPLATE(BM_Solve, cln::cl_RA)->Arg(0)->Name("solve/paper/exact");

/// The exact solve in CLN rationals throughout (Settings::integer_kernel =
/// false), the path before the integer kernel, side by side with it.
void BM_SolveRationals(benchmark::State& state) {
  const auto problem = numeric::Problem<cln::cl_RA>::from(paper_scene());
  auto settings = numeric::Settings<cln::cl_RA>::defaults();
  settings.integer_kernel = false;
  numeric::CollisionSolver<cln::cl_RA> solver(settings);
  numeric::Solution<cln::cl_RA> out;
  for (auto _ : state) {
    solver.compute(problem, out);
    benchmark::DoNotOptimize(out.velocities_after.data());
  }
  if (out.status != numeric::Status::Success) state.SkipWithError("the solve did not succeed");
}
BENCHMARK(BM_SolveRationals)->Name("solve/paper/exact-rationals");

/// cases/scenes/chain-32.toml by the banded ChainSolver (what numeric::solve
/// picks for it) in double, exact (integer kernel) and exact in rationals.
const numeric::ExactScene& chain_scene() {
  static const numeric::ExactScene s = numeric::ExactScene::from(load_scene(SUPERBALL_SCENES_DIR "/chain-32.toml"));
  return s;
}
template <class S>
void BM_SolveChain(benchmark::State& state) {
  const auto problem = numeric::Problem<S>::from(chain_scene());
  auto settings = numeric::Settings<S>::defaults();
  settings.integer_kernel = state.range(0) != 0;
  numeric::ChainSolver<S> solver(settings);
  numeric::Solution<S> out;
  for (auto _ : state) {
    solver.compute(problem, out);
    benchmark::DoNotOptimize(out.velocities_after.data());
  }
  if (out.status != numeric::Status::Success) state.SkipWithError("the solve did not succeed");
  state.counters["iterations"] = out.pivots;
}
BENCHMARK_TEMPLATE(BM_SolveChain, double)->Arg(1)->Name("solve/chain-32/double");
BENCHMARK_TEMPLATE(BM_SolveChain, cln::cl_RA)->Arg(1)->Name("solve/chain-32/exact");
BENCHMARK_TEMPLATE(BM_SolveChain, cln::cl_RA)->Arg(0)->Name("solve/chain-32/exact-rationals");

/// `--precision auto` on the paper scene: the double solve plus its
/// certificate, on a converted problem (compare with solve/paper/double).
void BM_SolveCertified(benchmark::State& state) {
  const auto problem = numeric::Problem<double>::from(paper_scene());
  numeric::CollisionSolver<double> solver;
  numeric::Solution<double> out;
  numeric::Certificate c;
  for (auto _ : state) {
    solver.compute(problem, out);
    c = numeric::certify(problem, out);
    benchmark::DoNotOptimize(c);
  }
  if (!c.case_certain) state.SkipWithError("not certified");
  state.counters["bound"] = c.relative_error;
}
BENCHMARK(BM_SolveCertified)->Name("solve/paper/double+certificate");

/// End to end from the exact scene: conversion, solve, certificate, and the
/// escalation when needed (choose_precision), against conversion + solve.
void BM_AutoEndToEnd(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(numeric::choose_precision(paper_scene(), numeric::default_rtol));
}
BENCHMARK(BM_AutoEndToEnd)->Name("end-to-end/paper/auto");
void BM_DoubleEndToEnd(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(numeric::solve(numeric::Problem<double>::from(paper_scene())));
}
BENCHMARK(BM_DoubleEndToEnd)->Name("end-to-end/paper/double");

}  // namespace

BENCHMARK_MAIN();
