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

/// A rewrite of the fixed-size path free of its one constraint, as evidence
/// for issue 16 point 2: the answer need not be the general path's bit for
/// bit.  The all-open case only (the paper scene's), n bodies known at
/// compile time, no obstacle: one pass over the entries forms DᵀMD densely
/// (K) with the sums of |v| per place (Ka) and M's groups; A = diag(m) + K
/// and b̃ = m u − K u; LDLᵀ with one reciprocal per pivot (no division in
/// the elimination or the solve); then the residual check on the same
/// quantities as the solver's (complete.cpp): the rows m(W − u) + K(W + u)
/// relative to m|W| + m|u| + Ka(|W| + |u|), the momentum of each group of M,
/// the gaps, energies, momenta and the dissipation ½(W + u)ᵀK(W + u) — as a
/// dense product formed beside the solve instead of the entry-by-entry
/// scatter.  With check = false only the solve and the answer are written.
template <int N, bool check>
bool unconstrained_rewrite(const numeric::Problem<double>& p, double feasibility, double residual, numeric::Solution<double>& out) {
  double m[N], u[N], K[N][N] = {}, Ka[N][N] = {};
  for (int i = 0; i < N; ++i) m[i] = p.mass[static_cast<std::size_t>(i)], u[i] = p.u[static_cast<std::size_t>(i)];
  int group[N];
  for (int i = 0; i < N; ++i) group[i] = i;
  const auto join = [&group](int a, int b) {  // relabel a's group with b's label
    const int from = group[a], to = group[b];
    for (int i = 0; i < N; ++i) group[i] = group[i] == from ? to : group[i];
  };
  for (const auto& e : p.entries) {
    const double v = e.value, a = std::abs(v);
    if (check && v != 0) {
      join(e.i, e.j);
      if (!e.diagonal()) join(e.k, e.l), join(e.i, e.k);
    }
    K[e.i][e.k] += v, K[e.i][e.l] -= v, K[e.j][e.k] -= v, K[e.j][e.l] += v;
    if (check) Ka[e.i][e.k] += a, Ka[e.i][e.l] += a, Ka[e.j][e.k] += a, Ka[e.j][e.l] += a;
    if (e.diagonal()) continue;
    K[e.k][e.i] += v, K[e.k][e.j] -= v, K[e.l][e.i] -= v, K[e.l][e.j] += v;
    if (check) Ka[e.k][e.i] += a, Ka[e.k][e.j] += a, Ka[e.l][e.i] += a, Ka[e.l][e.j] += a;
  }
  double A[N][N], W[N], inverse[N];
  for (int i = 0; i < N; ++i) {
    double b = m[i] * u[i];
    for (int j = 0; j < N; ++j) b -= K[i][j] * u[j], A[i][j] = K[i][j];
    A[i][i] += m[i];
    W[i] = b;
  }
  for (int j = 0; j < N; ++j) {
    if (!(A[j][j] > 0)) return false;
    inverse[j] = 1 / A[j][j];
    for (int r = j + 1; r < N; ++r) {
      const double l = A[r][j] * inverse[j];
      for (int i = r; i < N; ++i) A[i][r] -= A[i][j] * l;
      A[r][j] = l;
    }
  }
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < i; ++j) W[i] -= A[i][j] * W[j];
  for (int i = 0; i < N; ++i) W[i] *= inverse[i];
  for (int i = N - 1; i >= 0; --i)
    for (int j = i + 1; j < N; ++j) W[i] -= A[j][i] * W[j];
  double vscale = 0;
  for (int i = 0; i < N; ++i) vscale = std::max({vscale, std::abs(W[i]), std::abs(u[i])});
  for (int c = 0; c + 1 < N; ++c) {
    const double gap = W[c] - W[c + 1];
    if (gap < -feasibility * vscale) return false;  // a contact must close: not this kernel's case
    out.gaps[static_cast<std::size_t>(c)] = gap, out.reactions[static_cast<std::size_t>(c)] = 0;
  }
  for (int i = 0; i < N; ++i) out.velocities_after[static_cast<std::size_t>(i)] = W[i];
  out.pivots = 0;
  out.status = numeric::Status::Success;
  if (!check) return true;
  double motion = 0, dissipation = 0, ke_before = 0, ke_after = 0, p_before = 0, p_after = 0, sum[N] = {}, size_of[N] = {}, ratio[N];
  for (int i = 0; i < N; ++i) {
    double force = 0, size = std::abs(m[i] * W[i]) + std::abs(m[i] * u[i]);
    for (int j = 0; j < N; ++j) force += K[i][j] * (W[j] + u[j]), size += Ka[i][j] * (std::abs(W[j]) + std::abs(u[j]));
    const double r = std::abs(m[i] * (W[i] - u[i]) + force);
    ratio[i] = size > 0 ? r / size : 0;
    dissipation += (W[i] + u[i]) * force;
    ke_before += m[i] * u[i] * u[i] / 2, ke_after += m[i] * W[i] * W[i] / 2, p_before += m[i] * u[i], p_after += m[i] * W[i];
    sum[group[i]] += m[i] * (W[i] - u[i]), size_of[group[i]] += m[i] * (std::abs(W[i]) + std::abs(u[i]));
  }
  for (int r = 0; r < N; ++r) motion = std::max(motion, ratio[r]);
  for (int r = 0; r < N; ++r)
    if (group[r] == r && size_of[r] > 0) motion = std::max(motion, std::abs(sum[r]) / size_of[r]);
  double complementarity = 0;
  for (int c = 0; c + 1 < N; ++c)
    if (out.gaps[static_cast<std::size_t>(c)] < 0) complementarity = std::max(complementarity, -out.gaps[static_cast<std::size_t>(c)] / vscale);
  out.kinetic_energy_before = ke_before, out.kinetic_energy_after = ke_after, out.momentum_before = p_before, out.momentum_after = p_after;
  out.dissipation = dissipation / 2;
  out.residual_motion = motion, out.residual_complementarity = complementarity;
  if (!(motion <= residual && complementarity <= residual)) out.status = numeric::Status::NumericalIssue;
  return true;
}

template <bool check>
void BM_UnconstrainedRewrite(benchmark::State& state) {
  const auto problem = numeric::Problem<double>::from(paper_scene());
  const auto settings = numeric::Settings<double>::defaults();
  const numeric::Solution<double> reference = numeric::solve(problem);
  numeric::Solution<double> out = reference;
  bool ok = !problem.fixed_bottom && problem.n == 4;
  for (auto _ : state) {
    problem.check("unconstrained_rewrite()");  // the argument checks the solver makes
    ok = unconstrained_rewrite<4, check>(problem, settings.feasibility, settings.residual, out) && ok;
    benchmark::DoNotOptimize(out.velocities_after.data());
  }
  // The same answer to rounding; with the check, the same verdict and
  // derived values.
  const double scale = std::abs(reference.velocities_after[0]);
  for (int i = 0; i < 4; ++i)
    ok = ok && std::abs(out.velocities_after[static_cast<std::size_t>(i)] - reference.velocities_after[static_cast<std::size_t>(i)]) <= 1e-13 * scale;
  if (check)
    ok = ok && out.status == reference.status && std::abs(out.dissipation - reference.dissipation) <= 1e-12 * reference.kinetic_energy_before &&
         std::abs(out.kinetic_energy_after - reference.kinetic_energy_after) <= 1e-12 * reference.kinetic_energy_before;
  if (!ok) state.SkipWithError("the rewrite's answer differs from the solver's");
}
BENCHMARK_TEMPLATE(BM_UnconstrainedRewrite, true)->Name("solve/paper/double/unconstrained-rewrite");
BENCHMARK_TEMPLATE(BM_UnconstrainedRewrite, false)->Name("solve/paper/double/unconstrained-rewrite-no-check");
BENCHMARK_TEMPLATE(BM_Solve, numeric::MpFloat)->Arg(20)->Name("solve/paper/digits:20");
BENCHMARK_TEMPLATE(BM_Solve, numeric::MpFloat)->Arg(50)->Name("solve/paper/digits:50");
BENCHMARK_TEMPLATE(BM_Solve, numeric::MpFloat)->Arg(100)->Name("solve/paper/digits:100");
/// The same precisions in CLN floats (digits_format()), digits:N's arithmetic
/// before MPFR, side by side with it.
BENCHMARK_TEMPLATE(BM_Solve, cln::cl_R)->Arg(20)->Name("solve/paper/digits:20/cln");
BENCHMARK_TEMPLATE(BM_Solve, cln::cl_R)->Arg(50)->Name("solve/paper/digits:50/cln");
BENCHMARK_TEMPLATE(BM_Solve, cln::cl_R)->Arg(100)->Name("solve/paper/digits:100/cln");
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
