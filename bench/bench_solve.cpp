// Time per collision solve for the paper scene (§4.4, alpha_2 reading) in
// each arithmetic.  The solver is constructed once and reused, as in a sweep.
#include <benchmark/benchmark.h>

#include <Eigen/Dense>
#include <cln/float.h>
#include <cmath>
#include <limits>
#include <vector>

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

/// The same solves on the general path (Settings::small_sizes = false): the
/// runtime-sized solver that every n > 8 takes, side by side with the
/// fixed-size path of the rows above (same results bit for bit).
template <class S>
void BM_SolveGeneral(benchmark::State& state) {
  const auto problem = numeric::Problem<S>::from(paper_scene());
  numeric::Settings<S> settings = numeric::Settings<S>::defaults();
  settings.small_sizes = false;
  numeric::CollisionSolver<S> solver(settings);
  numeric::Solution<S> out;
  solver.compute(problem, out);
  for (auto _ : state) {
    solver.compute(problem, out);
    benchmark::DoNotOptimize(out.velocities_after.data());
  }
  if (out.status != numeric::Status::Success) state.SkipWithError("the solve did not succeed");
}
BENCHMARK_TEMPLATE(BM_SolveGeneral, double)->Name("solve/paper/double/general-path");
BENCHMARK_TEMPLATE(BM_SolveGeneral, long double)->Name("solve/paper/long-double/general-path");

/// The naive prototype of issue 16, as a baseline: fixed-size Eigen
/// matrices, A = diag(m) + DᵀMD and b̃ from the entries, the full inverse
/// A⁻¹, G = A⁻¹Cᵀ, N = CG and q = CA⁻¹b̃, then the 2^(n−1) cases in the order
/// of their bit masks, each by the fixed-size inverse of N on the closed
/// contacts (the open rows and columns replaced by the identity), until one
/// is complementary; U⁺ = A⁻¹b̃ + Gλ.  It stops at the first complementary
/// case (on the paper scene the first, every contact open) and makes no
/// residual check: a lower bound on what the prototype costs.  NF free
/// bodies, NC = n − 1 contacts; a fixed bottom body when NF < NC + 1.
template <int NF, int NC>
struct NaivePrototype {
  using Square = Eigen::Matrix<double, NF, NF>;
  using Contacts = Eigen::Matrix<double, NC, NC>;
  Eigen::Matrix<double, NF, 1> velocities;

  bool solve(const numeric::Problem<double>& p) {
    constexpr int n = NC + 1;
    Eigen::Matrix<double, n, n> K = Eigen::Matrix<double, n, n>::Zero();  // DᵀMD over every body
    for (const auto& e : p.entries) {
      Eigen::Matrix<double, n, 1> a = Eigen::Matrix<double, n, 1>::Zero(), b = a;
      a(e.i) = 1, a(e.j) = -1, b(e.k) = 1, b(e.l) = -1;
      K += e.value * (e.diagonal() ? Eigen::Matrix<double, n, n>(a * a.transpose()) : Eigen::Matrix<double, n, n>(a * b.transpose() + b * a.transpose()));
    }
    Eigen::Matrix<double, n, 1> u;
    for (int i = 0; i < n; ++i) u(i) = p.u[static_cast<std::size_t>(i)];
    Square A = K.template topLeftCorner<NF, NF>();
    Eigen::Matrix<double, NF, 1> b = -(K * u).template head<NF>();
    for (int i = 0; i < NF; ++i) A(i, i) += p.mass[static_cast<std::size_t>(i)], b(i) += p.mass[static_cast<std::size_t>(i)] * u(i);
    Eigen::Matrix<double, NC, NF> C = Eigen::Matrix<double, NC, NF>::Zero();
    for (int c = 0; c < NC; ++c) {
      C(c, c) = 1;
      if (c + 1 < NF) C(c, c + 1) = -1;
    }
    const Square Ainv = A.inverse();
    const Eigen::Matrix<double, NF, NC> G = Ainv * C.transpose();
    const Contacts N = C * G;
    const Eigen::Matrix<double, NF, 1> W0 = Ainv * b;
    Eigen::Matrix<double, NC, 1> q = C * W0;
    if (NF == NC) q(NC - 1) -= u(n - 1);  // the fixed body's velocity
    const double tol = 64 * std::numeric_limits<double>::epsilon() * q.cwiseAbs().maxCoeff();
    for (int mask = 0; mask < (1 << NC); ++mask) {
      Contacts Ns = Contacts::Identity();
      Eigen::Matrix<double, NC, 1> r = Eigen::Matrix<double, NC, 1>::Zero();
      for (int i = 0; i < NC; ++i) {
        if (!(mask >> i & 1)) continue;
        r(i) = -q(i);
        for (int j = 0; j < NC; ++j)
          if (mask >> j & 1) Ns(i, j) = N(i, j);
      }
      const Eigen::Matrix<double, NC, 1> lambda = Ns.inverse() * r;
      const Eigen::Matrix<double, NC, 1> w = q + N * lambda;
      bool ok = true;
      for (int i = 0; i < NC; ++i) ok = ok && ((mask >> i & 1) ? lambda(i) >= -tol : w(i) >= -tol);
      if (!ok) continue;
      velocities = W0 + G * lambda;
      return true;
    }
    return false;
  }
};

void BM_NaivePrototype(benchmark::State& state) {
  const auto problem = numeric::Problem<double>::from(paper_scene());
  NaivePrototype<4, 3> prototype;  // the paper scene: 4 free bodies (the obstacle's mass is 5e6 kg)
  bool ok = !problem.fixed_bottom && problem.n == 4;
  for (auto _ : state) {
    ok = prototype.solve(problem) && ok;
    benchmark::DoNotOptimize(prototype.velocities.data());
  }
  // The prototype's answer against the solver's, to rounding.
  const auto reference = numeric::solve(problem);
  for (int i = 0; i < 4; ++i)
    ok = ok && std::abs(prototype.velocities(i) - reference.velocities_after[static_cast<std::size_t>(i)]) <=
                   1e-12 * std::abs(reference.velocities_after[0]);
  if (!ok) state.SkipWithError("the prototype's answer differs from the solver's");
}
BENCHMARK(BM_NaivePrototype)->Name("solve/paper/double/naive-prototype");
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

/// A candidate for digits:N, measured beside it (not what digits:N does):
/// the exact solve of the exact scene, then each of the answer's 15 values
/// (velocities, reactions, gaps, energies, momenta, dissipation) rounded
/// once to a CLN float of N digits, the correctly rounded answer.
void BM_ExactRounded(benchmark::State& state) {
  const auto format = cln::float_format(static_cast<int>(state.range(0)));
  const auto problem = numeric::Problem<cln::cl_RA>::from(paper_scene());
  numeric::CollisionSolver<cln::cl_RA> solver(numeric::Settings<cln::cl_RA>::defaults());
  numeric::Solution<cln::cl_RA> out;
  std::vector<cln::cl_F> rounded;
  auto round_all = [&] {
    rounded.clear();
    for (const auto* v : {&out.velocities_after, &out.reactions, &out.gaps})
      for (const auto& x : *v) rounded.push_back(cln::cl_float(x, format));
    for (const auto* x : {&out.kinetic_energy_before, &out.kinetic_energy_after, &out.momentum_before, &out.momentum_after, &out.dissipation})
      rounded.push_back(cln::cl_float(*x, format));
  };
  for (auto _ : state) {
    solver.compute(problem, out);
    round_all();
    benchmark::DoNotOptimize(rounded.data());
  }
  if (out.status != numeric::Status::Success || rounded.size() != 15) state.SkipWithError("the solve did not succeed");
}
BENCHMARK(BM_ExactRounded)->Arg(20)->Name("solve/paper/exact-rounded-to-digits:20");
BENCHMARK(BM_ExactRounded)->Arg(50)->Name("solve/paper/exact-rounded-to-digits:50");
BENCHMARK(BM_ExactRounded)->Arg(100)->Name("solve/paper/exact-rounded-to-digits:100");

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
