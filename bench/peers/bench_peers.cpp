// Peers, in the same run (issue 5): this project's collision solve against
// Siconos' LCP solvers (Debian's libsiconos-numerics-dev, C API) on the same
// instances.
//
// What is timed (median of the repetitions, per solve):
//  - ours/double-dense: CollisionSolver<double>::compute on the Problem: the
//    FULL solve (assembly of A = diag(m) + DᵀMD and b̃, the case with every
//    contact open and q; when a pivot is needed the LDLᵀ of A, N and Murty
//    pivoting; the velocities by clusters of the case and the independent
//    residual check).
//  - ours/double-chain: ChainSolver<double>::compute, the banded formulation
//    (clusters of a guessed case, block principal pivoting; no N).
//  - ours/exact: in CLN exact rationals, by the formulation numeric::solve()
//    picks (solves_as_chain()).
//  The row numeric::solve() picks in double is marked "(solve)"; it is what
//  the tool runs, and the ratios and the verdict are against it.
//  - siconos/...:  one call of the Siconos solver on (N, q) ONLY.  N and q are
//    built once, outside the timed loop, in double by our solver itself
//    (CollisionSolver::lcp, the operations compute() uses); leaving that
//    build out favours Siconos.  z is reset to 0 before each call (a cold start, as for
//    a new instance); the solver options are created once, outside the loop.
//    These are the "LCP only" rows.
//  - siconos-end-to-end/...: what a Siconos user must do to get U⁺ from the
//    scene (issue 16): the cheapest build of (N, q) we know
//    (CollisionSolver::lcp), N and q handed to Siconos, its solve from z = 0,
//    and W = W0 + Gλ, all inside the timed loop.  An instance whose A is not
//    positive definite once rounded to double (eps-1e-8) has no LCP in
//    double: its Siconos rows are not run, and ours declines too.
//
// Accuracy (benchmark counters, so they are in the same run's output):
//  - rel_err: ‖W − W*‖∞ / ‖W*‖∞ for the velocities after the collision W,
//    W* the exact solution (in the scene's velocity unit), evaluated exactly.
//    For Siconos, W = A⁻¹(b + Cᵀλ) = W0 + Gλ from its λ = z, in double, by the
//    same operations our solver uses for its own λ.
//  - case_ok: 1 when the computed case equals the exact one, {c : λ*_c > 0}.
//    A computed contact c counts as closed when N_cc λ_c > w_c, w_c = W_c −
//    W_{c+1} (whichever side of the complementarity pair is larger, in
//    velocity units); on an exact, strictly complementary solution that is
//    λ_c > 0.
//  - converged: 1 when the solver reported success (our Status::Success,
//    Siconos info == 0); iters: our pivots, Siconos' iterations.
//
// At the end a summary of the CPU medians, ratios and counters is printed,
// then the verdicts, LCP only and end to end: the speed-up of ours over the
// fastest Siconos solver that is right (success, case right, velocities
// within 1e-6), and whether ours is at least as accurate.
#include <benchmark/benchmark.h>
#include <cln/dfloat.h>
#include <cln/rational.h>
#include <cln/rational_io.h>
#include <cln/real.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <map>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "superball/cases/parameter.hpp"
#include "superball/cases/scene_file.hpp"
#include "superball/numeric/chain.hpp"
#include "superball/numeric/collision.hpp"

// Siconos numerics, C API.
#include "LCP_Solvers.h"
#include "LinearComplementarityProblem.h"
#include "NumericsMatrix.h"
#include "NumericsVerbose.h"
#include "SolverOptions.h"
#include "lcp_cst.h"

namespace {

using namespace superball;
using cln::cl_RA;

std::string text(const cl_RA& x) {
  std::ostringstream os;
  cln::fprint(os, x);
  return os.str();
}

// ---------------------------------------------------------------- instances

/// §4.1's epsilon family (case 1, alpha_2 = -1, m4 = infinity) at \p eps, set
/// on cases/scenes/paper-4.1-family.toml as `superball reproduce` does.
Scene epsilon_scene(const cl_RA& eps) {
  Scene scene = load_scene(SUPERBALL_SCENES_DIR "/paper-4.1-family.toml");
  const cl_RA alpha2 = -1;
  auto set = [&](const std::string& key, const cl_RA& x) { Parameter::parse(key, scene).set(scene, Number::parse(text(x))); };
  set("K.1-2", -alpha2 * (1 - eps + eps * eps));
  set("K.1-3", -alpha2 * eps * eps);
  set("K.1-4", -alpha2 * (1 + eps));
  set("mass.1", -alpha2 * eps * eps * eps);
  set("alpha.2", alpha2);
  scene.origin = "paper-4.1-family.toml, eps = " + text(eps);
  return scene;
}

/// A seeded random chain of \p n free bodies colliding.  M
/// lives on the nearest and next-nearest neighbour pairs (i, i+1), (i, i+2)
/// and couples only pairs that share a body or are next to each other,
/// ((i,i+1),(i,i+2)), ((i,i+2),(i+1,i+2)), ((i,i+2),(i+1,i+3)), so that
/// K = DᵀMD is banded.  Couplings are ±0.1 … ±5 (both signs), every diagonal
/// entry exceeds the sum of its row's |couplings| by 0.1 … 10, so M is
/// positive definite (checked exactly by ExactScene::from).  Masses are
/// log-uniform in 1e-2 … 1e3, velocities before in -2 … 2, non-decreasing
/// downwards (every contact closes or is at rest, as ExactScene::from requires).  All values are short decimals, exact as written.
Scene chain_scene(int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);  // the engine's output is fixed by the standard
  auto pick = [&](int lo, int hi) { return lo + static_cast<int>(rng() % static_cast<std::uint64_t>(hi - lo + 1)); };
  Scene s;
  s.title = "random chain, n = " + std::to_string(n);
  s.origin = "chain-" + std::to_string(n) + " (seed " + std::to_string(seed) + ")";
  std::vector<int> speeds;  // hundredths of m/s, sorted so that every contact closes
  for (int i = 0; i < n; ++i) {
    Body b;
    b.mass = Number::parse(std::to_string(pick(100, 999)) + "e" + std::to_string(pick(-4, 0)));
    speeds.push_back(pick(-200, 200));
    s.bodies.push_back(b);
  }
  std::sort(speeds.begin(), speeds.end());
  for (int i = 0; i < n; ++i)
    s.bodies[static_cast<std::size_t>(i)].velocity = Number::parse(std::to_string(speeds[static_cast<std::size_t>(i)]) + "/100");
  // Couplings, in tenths, and the row sums of their magnitudes.
  std::map<std::pair<int, int>, long long> row_sum;  // (i, j) 1-based pair -> Σ|coupling| in tenths
  auto key = [](const Pair& p) { return std::make_pair(p.i, p.j); };
  auto couple = [&](Pair a, Pair b) {
    if (a.j > n || b.j > n) return;
    const int v = (pick(0, 1) ? 1 : -1) * pick(1, 50);
    s.entries.push_back({a, b, Number::parse(std::to_string(v) + "/10")});
    row_sum[key(a)] += std::abs(v);
    row_sum[key(b)] += std::abs(v);
  };
  for (int i = 1; i < n; ++i) {
    couple({i, i + 1}, {i, i + 2});
    couple({i, i + 2}, {i + 1, i + 2});
    couple({i, i + 2}, {i + 1, i + 3});
  }
  for (int i = 1; i < n; ++i)
    for (int d = 1; d <= 2 && i + d <= n; ++d) {
      const Pair p{i, i + d};
      s.entries.push_back({p, p, Number::parse(std::to_string(row_sum[key(p)] + pick(1, 100)) + "/10")});
    }
  return s;
}

// ------------------------------------------------- the LCP (N, q) in double

/// The LCP our solver builds, w = q + Nλ, in double: CollisionSolver's own
/// lcp() (the same operations compute() uses), N in Siconos' column-major
/// dense storage, and the map back from λ to the velocities, W = W0 + Gλ.
struct Lcp {
  int n = 0, nf = 0, nc = 0;
  bool fixed_bottom = false;
  double u_fixed = 0;
  Eigen::MatrixXd G;
  Eigen::VectorXd W0;
  std::vector<double> N;  ///< nc × nc, column-major (Siconos' dense storage)
  std::vector<double> q;
  /// Why there is no LCP in double ("" when there is one): A rounded to
  /// double is not positive definite (eps-1e-8: κ(A)·u ≳ 1), so lcp() has no
  /// A⁻¹ to form N with, and our double solve declines too.
  std::string missing;

  static Lcp from(const numeric::Problem<double>& p) {
    Lcp l;
    l.n = p.n;
    l.fixed_bottom = p.fixed_bottom;
    l.nf = p.fixed_bottom ? p.n - 1 : p.n;
    l.nc = p.n - 1;
    l.u_fixed = p.u[static_cast<std::size_t>(p.n - 1)];
    numeric::CollisionSolver<double> solver(numeric::Settings<double>::defaults());
    numeric::CollisionSolver<double>::Lcp lcp;
    try {
      lcp = solver.lcp(p);
    } catch (const std::domain_error& e) {
      l.missing = e.what();
      return l;
    }
    l.G = lcp.G;
    l.W0 = lcp.W0;
    l.N.assign(lcp.N.data(), lcp.N.data() + lcp.N.size());  // Eigen's default storage is column-major too
    l.q.assign(lcp.q.data(), lcp.q.data() + lcp.q.size());
    return l;
  }

  double N_at(int i, int j) const { return N[static_cast<std::size_t>(j * nc + i)]; }

  /// W = W0 + Gλ (the fixed body keeps its velocity), summed as our solver does.
  std::vector<double> velocities(const std::vector<double>& lambda) const {
    std::vector<double> W(static_cast<std::size_t>(n));
    for (int i = 0; i < nf; ++i) {
      double w = W0(i);
      for (int c = 0; c < nc; ++c)
        if (lambda[static_cast<std::size_t>(c)] != 0) w += G(i, c) * lambda[static_cast<std::size_t>(c)];
      W[static_cast<std::size_t>(i)] = w;
    }
    if (fixed_bottom) W[static_cast<std::size_t>(n - 1)] = u_fixed;
    return W;
  }
};

// ------------------------------------------------------ reference, accuracy

struct Instance {
  std::string name;
  numeric::ExactScene scene;
  numeric::Problem<double> pd;
  numeric::Problem<cl_RA> pe;
  Lcp lcp;
  std::vector<cl_RA> W_exact;  ///< velocities after, exact (velocity unit)
  cl_RA W_norm;                ///< ‖W*‖∞
  std::vector<bool> closed;    ///< the exact case, λ*_c > 0
  int degenerate = 0;          ///< contacts with λ* = 0 and w* = 0
  int exact_pivots = 0;
};

/// ‖W − W*‖∞ / ‖W*‖∞, evaluated exactly (the doubles are exact rationals).
double relative_error(const Instance& in, const std::vector<double>& W) {
  cl_RA worst = 0;
  for (std::size_t i = 0; i < W.size(); ++i) {
    if (!std::isfinite(W[i])) return INFINITY;
    const cl_RA d = cln::abs(cln::rational(cln::cl_DF(W[i])) - in.W_exact[i]);
    if (d > worst) worst = d;
  }
  return cln::double_approx(worst / in.W_norm);
}

/// 1 when the case of (λ, W) is the exact case, else 0 (see the file comment).
/// Without an LCP in double (Lcp::missing) a contact counts as closed when λ_c > w_c.
double case_ok(const Instance& in, const std::vector<double>& lambda, const std::vector<double>& W) {
  for (int c = 0; c < in.lcp.nc; ++c) {
    const double w = W[static_cast<std::size_t>(c)] - W[static_cast<std::size_t>(c + 1)];
    const double scale = in.lcp.missing.empty() ? in.lcp.N_at(c, c) : 1.0;
    const bool closed = scale * lambda[static_cast<std::size_t>(c)] > w;
    if (closed != in.closed[static_cast<std::size_t>(c)]) return 0;
  }
  return 1;
}

/// Largest instance whose exact reference is the dense exact solve.
constexpr int kMaxDenseExactBodies = 64;

Instance make_instance(const std::string& name, const Scene& scene) {
  Instance in;
  in.name = name;
  in.scene = numeric::ExactScene::from(scene);
  in.pd = numeric::Problem<double>::from(in.scene);
  in.pe = numeric::Problem<cl_RA>::from(in.scene);
  in.lcp = Lcp::from(in.pd);
  // The reference is the dense exact solve up to kMaxDenseExactBodies (and
  // there the banded exact solve must give the same fractions), the banded
  // exact solve beyond (the dense one would take minutes).
  const auto exact = in.pe.n <= kMaxDenseExactBodies ? numeric::CollisionSolver<cl_RA>().compute(in.pe)
                                                      : numeric::ChainSolver<cl_RA>().compute(in.pe);
  if (exact.status != numeric::Status::Success) throw std::runtime_error(name + ": the exact solve did not succeed");
  if (in.pe.n <= kMaxDenseExactBodies && numeric::solves_as_chain(in.pe) &&
      numeric::ChainSolver<cl_RA>().compute(in.pe).velocities_after != exact.velocities_after)
    throw std::runtime_error(name + ": the banded and the dense exact solves differ");
  in.W_exact = exact.velocities_after;
  in.W_norm = 0;
  for (const auto& w : in.W_exact) in.W_norm = std::max(in.W_norm, cl_RA(cln::abs(w)));
  if (cln::zerop(in.W_norm)) throw std::runtime_error(name + ": every velocity after is 0, no relative error");
  for (int c = 0; c + 1 < in.pe.n; ++c) {
    const cl_RA lambda = -exact.reactions[static_cast<std::size_t>(c)];
    in.closed.push_back(lambda > 0);
    in.degenerate += cln::zerop(lambda) && cln::zerop(exact.gaps[static_cast<std::size_t>(c)]);
  }
  in.exact_pivots = exact.pivots;
  return in;
}

std::vector<Instance>& instances() {
  static std::vector<Instance> all;
  return all;
}

void set_accuracy(benchmark::State& state, double rel_err, double ok, bool converged, int iters) {
  state.counters["rel_err"] = rel_err;
  state.counters["case_ok"] = ok;
  state.counters["converged"] = converged ? 1 : 0;
  state.counters["iters"] = iters;
}

// ---------------------------------------------------------------- our solve

/// One of our solvers, reused across iterations as a sweep would: Solver is
/// CollisionSolver<S> (dense) or ChainSolver<S> (banded, chain.hpp).
template <class Solver, class S>
void bm_ours(benchmark::State& state, const Instance* in) {
  const numeric::Problem<S>& p = [&]() -> const numeric::Problem<S>& {
    if constexpr (std::is_same_v<S, double>)
      return in->pd;
    else
      return in->pe;
  }();
  Solver solver(numeric::Settings<S>::defaults());
  numeric::Solution<S> out;
  solver.compute(p, out);
  for (auto _ : state) {
    solver.compute(p, out);
    benchmark::DoNotOptimize(out.velocities_after.data());
    benchmark::ClobberMemory();
  }
  std::vector<double> W, lambda;
  for (const auto& w : out.velocities_after) W.push_back(numeric::ScalarTraits<S>::to_double(w));
  for (const auto& r : out.reactions) lambda.push_back(-numeric::ScalarTraits<S>::to_double(r));
  double err = 0;
  if constexpr (std::is_same_v<S, double>) {
    err = relative_error(*in, W);
  } else {  // exact: compare exactly
    cl_RA worst = 0;
    for (std::size_t i = 0; i < out.velocities_after.size(); ++i)
      worst = std::max(worst, cl_RA(cln::abs(out.velocities_after[i] - in->W_exact[i])));
    err = cln::double_approx(worst / in->W_norm);
  }
  set_accuracy(state, err, case_ok(*in, lambda, W), out.status == numeric::Status::Success, out.pivots);
}

/// Our double solve with every contact imposed open (compute_case): the
/// assembly, the velocities of that case (whose gaps are q) and the residual
/// check: the part of our dense solve that is no LCP at all, paid on any
/// instance.  N is not formed.
void bm_ours_no_pivots(benchmark::State& state, const Instance* in) {
  numeric::CollisionSolver<double> solver(numeric::Settings<double>::defaults());
  numeric::Solution<double> out;
  const ContactSet open(in->pd.n);
  solver.compute_case(in->pd, open, out);
  for (auto _ : state) {
    solver.compute_case(in->pd, open, out);
    benchmark::DoNotOptimize(out.velocities_after.data());
    benchmark::ClobberMemory();
  }
}

/// Skip a row that needs the LCP of an instance that has no LCP in double; true when skipped.
bool skipped_without_lcp(benchmark::State& state, const Instance* in) {
  if (in->lcp.missing.empty()) return false;
  state.SkipWithError(("not run: no LCP in double (" + in->lcp.missing + ")").c_str());
  for (auto _ : state) {
  }
  return true;
}

/// Building the LCP our solver solves, what Siconos gets for free: the
/// assembly, q, the LDLᵀ of A, G = A⁻¹C_Fᵀ and N (CollisionSolver::lcp,
/// including the copies of N, q, G and W0 it returns).
void bm_ours_lcp_build(benchmark::State& state, const Instance* in) {
  if (skipped_without_lcp(state, in)) return;
  numeric::CollisionSolver<double> solver(numeric::Settings<double>::defaults());
  for (auto _ : state) {
    auto lcp = solver.lcp(in->pd);
    benchmark::DoNotOptimize(lcp.N.data());
    benchmark::ClobberMemory();
  }
}

// -------------------------------------------------------------- Siconos

using LcpSolverFn = void (*)(LinearComplementarityProblem*, double*, double*, int*, SolverOptions*);

struct SiconosSolver {
  std::string name;  ///< in the benchmark name
  int id;            ///< SICONOS_LCP_*
  LcpSolverFn fn;
  double tol = -1;   ///< < 0: Siconos' default
  int itermax = -1;  ///< < 0: Siconos' default
};

/// lcp_enum tries the complementary bases in binary order (bit c set: w_c
/// basic, contact c open), solving one nc × nc system per basis.  Beyond this
/// many bases before the exact one a solve takes too long to be benchmarked.
constexpr double kMaxEnumBases = double(1 << 20);

double enum_bases_before_solution(const Instance& in) {
  double index = 0;
  for (int c = 0; c < in.lcp.nc; ++c)
    if (!in.closed[static_cast<std::size_t>(c)]) index += std::ldexp(1.0, c);
  return index + 1;
}

/// One Siconos solver on an instance.  LCP only (\p end_to_end false): N and
/// q built once, outside the timed loop, only the solve from z = 0 timed.
/// End to end: what a Siconos user must do to get U⁺ from a scene (issue
/// 16): build (N, q) the cheapest way we know (CollisionSolver::lcp: the
/// assembly, the LDLᵀ of A, G = A⁻¹C_Fᵀ, N = CG, q), hand them to the solver
/// (N copied into its dense matrix, q), solve from z = 0 and map λ back to
/// the velocities W = W0 + Gλ, all of it inside the timed loop.
void bm_siconos(benchmark::State& state, const Instance* in, SiconosSolver s, bool end_to_end) {
  if (skipped_without_lcp(state, in)) return;
  const int nc = in->lcp.nc;
  if (s.id == SICONOS_LCP_ENUM && enum_bases_before_solution(*in) > kMaxEnumBases) {
    std::ostringstream msg;
    msg << "not run: lcp_enum would solve " << enum_bases_before_solution(*in) << " linear systems of size " << nc
        << " (of 2^" << nc << " bases) before reaching the exact case";
    state.SkipWithError(msg.str().c_str());
    for (auto _ : state) {
    }
    return;
  }
  NumericsMatrix* M = NM_create(NM_DENSE, nc, nc);
  std::copy(in->lcp.N.begin(), in->lcp.N.end(), M->matrix0);
  std::vector<double> q = in->lcp.q;
  LinearComplementarityProblem problem{};
  problem.size = nc;
  problem.M = M;
  problem.q = q.data();
  SolverOptions* options = solver_options_create(s.id);
  if (s.tol >= 0) options->dparam[SICONOS_DPARAM_TOL] = s.tol;
  if (s.itermax >= 0) options->iparam[SICONOS_IPARAM_MAX_ITER] = s.itermax;
  if (s.id == SICONOS_LCP_ENUM) lcp_enum_init(&problem, options, 1);
  std::vector<double> z(static_cast<std::size_t>(nc), 0.0), w(static_cast<std::size_t>(nc), 0.0);
  int info = 0;
  numeric::CollisionSolver<double> ours(numeric::Settings<double>::defaults());
  Eigen::VectorXd W;
  if (!end_to_end) s.fn(&problem, z.data(), w.data(), &info, options);
  for (auto _ : state) {
    if (end_to_end) {
      const auto lcp = ours.lcp(in->pd);
      std::copy(lcp.N.data(), lcp.N.data() + lcp.N.size(), M->matrix0);  // column-major, as NM_DENSE
      std::copy(lcp.q.data(), lcp.q.data() + lcp.q.size(), q.begin());
      std::fill(z.begin(), z.end(), 0.0);
      s.fn(&problem, z.data(), w.data(), &info, options);
      W = lcp.W0 + lcp.G * Eigen::Map<const Eigen::VectorXd>(z.data(), nc);
      benchmark::DoNotOptimize(W.data());
    } else {
      std::fill(z.begin(), z.end(), 0.0);
      s.fn(&problem, z.data(), w.data(), &info, options);
      benchmark::DoNotOptimize(z.data());
    }
    benchmark::ClobberMemory();
  }
  const std::vector<double> velocities = in->lcp.velocities(z);
  // lcp_enum reports no iteration count: report the bases it tried.
  const int iters = s.id == SICONOS_LCP_ENUM ? options->iparam[SICONOS_LCP_IPARAM_ENUM_CURRENT_ENUM] + 1
                                             : options->iparam[SICONOS_IPARAM_ITER_DONE];
  set_accuracy(state, relative_error(*in, velocities), case_ok(*in, z, velocities), info == 0, iters);
  if (s.id == SICONOS_LCP_ENUM) lcp_enum_reset(&problem, options, 1);
  solver_options_delete(options);
  NM_free(M);
}

// ------------------------------------------------------------ the summary

/// The console output, then a summary of the CPU medians with the ratios to
/// the formulation numeric::solve() picks and the accuracy counters, per
/// instance; last, the speed-up of ours over Siconos against n.
class SummaryReporter : public benchmark::ConsoleReporter {
 public:
  /// \p picked: instance name -> the method numeric::solve() runs on it
  /// ("ours/double-dense" or "ours/double-chain"); \p bodies: its n.
  SummaryReporter(std::map<std::string, std::string> picked, std::map<std::string, int> bodies)
      : picked_(std::move(picked)), bodies_(std::move(bodies)) {}

  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& r : runs) {
      const bool median = r.run_type == Run::RT_Aggregate && r.aggregate_name == "median";
      const bool single = r.run_type == Run::RT_Iteration && r.repetitions <= 1;
      if (r.error_occurred) {
        rows_[r.run_name.str()] = Row{r.run_name.str(), 0, {}, r.error_message};
        order(r.run_name.str());
      } else if (median || single) {
        const double ns = r.GetAdjustedCPUTime() * 1e9 / benchmark::GetTimeUnitMultiplier(r.time_unit);
        std::map<std::string, double> counters;
        for (const auto& [k, v] : r.counters) counters[k] = v.value;
        rows_[r.run_name.str()] = Row{r.run_name.str(), ns, counters, ""};
        order(r.run_name.str());
      }
    }
  }

  void Finalize() override {
    ConsoleReporter::Finalize();
    std::ostream& os = GetOutputStream();
    os << "\nSummary: CPU medians per solve; ratio = time / the formulation numeric::solve() picks (marked *, full solve);\n"
          "siconos/ rows time the LCP (N, q) only (N, q built outside the loop); siconos-end-to-end/ rows time the\n"
          "cheapest build of (N, q), the LCP solve and the velocities W = W0 + G lambda, from the scene's problem.\n";
    std::string current;
    const Row* ours = nullptr;
    std::vector<const Row*> group;
    auto flush = [&] {
      if (group.empty()) return;
      verdict(os, ours, group);
      group.clear();
      ours = nullptr;
    };
    for (const std::string& name : names_) {
      const Row& r = rows_[name];
      const std::string inst = instance_of(name);
      if (inst != current) {
        flush();
        current = inst;
        os << "\n" << inst << "\n";
        char head[160];
        std::snprintf(head, sizeof head, "  %-40s %14s %10s %10s %8s %9s %7s\n", "solver", "median", "ratio", "rel_err", "case_ok",
                      "converged", "iters");
        os << head;
      }
      if (method_of(name) == picked_[inst]) ours = &r;
      group.push_back(&r);
    }
    flush();
    char line[240];
    for (const bool end_to_end : {false, true}) {
    os << "\nSpeed-up of ours (numeric::solve()'s formulation, double; \"declined\" when its status is not success) over the\n"
          "fastest Siconos solver that is right (converged, case right, rel_err <= "
       << kRightRelErr << "), "
       << (end_to_end ? "END TO END (Siconos: build of (N, q) + LCP + velocities)" : "LCP ONLY (Siconos given N and q)")
       << "; goal (end to end) >= 10x from 16 bodies, >= 100x from 128, no slower on 4 and 8:\n";
    std::snprintf(line, sizeof line, "  %-18s %5s %-6s %10s %9s  %-22s %10s %9s %9s %s\n", "instance", "n", "ours", "median", "rel_err",
                  "fastest right Siconos", "median", "rel_err", "speed-up", "ours as accurate");
    os << line;
    for (const Verdict& lcp_only : verdicts_) {
      Verdict v = lcp_only;
      if (end_to_end) v.right = v.e2e_right, v.right_ns = v.e2e_ns, v.right_err = v.e2e_err;
      const bool declined = std::isnan(v.ours_err), have = v.right_ns > 0;
      char err[32];
      std::snprintf(err, sizeof err, "%.1e", v.ours_err);
      std::snprintf(line, sizeof line, "  %-18s %5d %-6s %10s %9s  %-22s %10s %9.1e %8.2fx %s\n", v.instance.c_str(), v.n,
                    v.ours.c_str(), time_text(v.ours_ns).c_str(), declined ? "declined" : err, have ? v.right.c_str() : "none",
                    have ? time_text(v.right_ns).c_str() : "-", have ? v.right_err : NAN, have ? v.right_ns / v.ours_ns : NAN,
                    !have ? "-" : declined ? "no" : v.ours_err <= v.right_err ? "yes" : "no");
      os << line;
    }
    }
  }

 private:
  struct Row {
    std::string name;
    double ns = 0;
    std::map<std::string, double> counters;
    std::string error;
  };

  static std::string instance_of(const std::string& name) {
    const auto a = name.find('/'), b = name.find('/', a + 1);
    return name.substr(a + 1, b - a - 1);
  }
  static std::string method_of(const std::string& name) {
    const auto a = name.find('/'), b = name.find('/', a + 1);
    return name.substr(b + 1);
  }
  static std::string time_text(double ns) {
    char buf[64];
    if (ns < 1e4)
      std::snprintf(buf, sizeof buf, "%.0f ns", ns);
    else if (ns < 1e7)
      std::snprintf(buf, sizeof buf, "%.1f us", ns / 1e3);
    else
      std::snprintf(buf, sizeof buf, "%.1f ms", ns / 1e6);
    return buf;
  }
  double counter(const Row& r, const std::string& k) const {
    const auto it = r.counters.find(k);
    return it == r.counters.end() ? NAN : it->second;
  }

  /// A Siconos answer counts as right when the solver reported success, the
  /// case is the exact one and the velocities are within this relative error
  /// (the default tolerance of Siconos' iterative solvers): on eps-1e-8
  /// Newton-min and enum return the right case with velocities off by 2e8.
  static constexpr double kRightRelErr = 1e-6;

  bool right(const Row& r) const {
    return counter(r, "converged") == 1 && counter(r, "case_ok") == 1 && counter(r, "rel_err") <= kRightRelErr;
  }

  void verdict(std::ostream& os, const Row* ours, const std::vector<const Row*>& group) {
    const double base = ours ? ours->ns : NAN;
    const Row* fastest = nullptr;
    const Row* fastest_right = nullptr;
    const Row* exact = nullptr;
    const Row* e2e_right = nullptr;  // the fastest right end-to-end Siconos row
    for (const Row* r : group) {
      char line[200];
      if (!r->error.empty()) {
        std::snprintf(line, sizeof line, "  %-40s %s\n", method_of(r->name).c_str(), r->error.c_str());
        os << line;
        continue;
      }
      const std::string method = method_of(r->name) + (r == ours ? " *" : "");
      if (r->counters.empty())
        std::snprintf(line, sizeof line, "  %-40s %14s %9.2fx\n", method.c_str(), time_text(r->ns).c_str(), r->ns / base);
      else
        std::snprintf(line, sizeof line, "  %-40s %14s %9.2fx %10.2e %8.0f %9.0f %7.0f\n", method.c_str(),
                      time_text(r->ns).c_str(), r->ns / base, counter(*r, "rel_err"), counter(*r, "case_ok"),
                      counter(*r, "converged"), counter(*r, "iters"));
      os << line;
      if (method_of(r->name) == "ours/exact") exact = r;
      if (method_of(r->name).rfind("siconos-end-to-end/", 0) == 0 && right(*r) && (!e2e_right || r->ns < e2e_right->ns)) e2e_right = r;
      if (method_of(r->name).rfind("siconos/", 0) != 0) continue;
      if (!fastest || r->ns < fastest->ns) fastest = r;
      if (right(*r) && (!fastest_right || r->ns < fastest_right->ns)) fastest_right = r;
    }
    if (!ours) return;
    char line[300];
    if (fastest) {
      std::snprintf(line, sizeof line, "  fastest Siconos: %s, %s: speed-up of ours over it %.2fx\n",
                    method_of(fastest->name).c_str(), time_text(fastest->ns).c_str(), fastest->ns / base);
      os << line;
    }
    Verdict v;
    v.instance = instance_of(ours->name);
    v.n = bodies_.count(v.instance) ? bodies_.at(v.instance) : 0;
    v.ours = method_of(ours->name) == "ours/double-chain" ? "chain" : "dense";
    v.ours_ns = base;
    v.ours_err = counter(*ours, "converged") == 1 ? counter(*ours, "rel_err") : NAN;
    if (fastest_right) {
      v.right = method_of(fastest_right->name).substr(8);
      v.right_ns = fastest_right->ns;
      v.right_err = counter(*fastest_right, "rel_err");
      std::snprintf(line, sizeof line,
                    "  fastest Siconos that is right (converged, case right, rel_err <= %.0e): %s, %s: speed-up of ours over "
                    "it %.2fx\n",
                    kRightRelErr, v.right.c_str(), time_text(v.right_ns).c_str(), v.right_ns / base);
    } else {
      std::snprintf(line, sizeof line, "  no Siconos solver is right (converged, case right, rel_err <= %.0e)\n", kRightRelErr);
    }
    os << line;
    if (e2e_right) {
      v.e2e_right = method_of(e2e_right->name).substr(19);
      v.e2e_ns = e2e_right->ns;
      v.e2e_err = counter(*e2e_right, "rel_err");
      std::snprintf(line, sizeof line, "  end to end, the fastest right: %s, %s: speed-up of ours over it %.2fx\n", v.e2e_right.c_str(),
                    time_text(v.e2e_ns).c_str(), v.e2e_ns / base);
      os << line;
    }
    verdicts_.push_back(v);
    if (exact && fastest) {
      std::snprintf(line, sizeof line, "  ours/exact (rel_err 0) takes %.1fx the time of the fastest Siconos solver\n",
                    exact->ns / fastest->ns);
      os << line;
    }
  }

  void order(const std::string& name) {
    if (std::find(names_.begin(), names_.end(), name) == names_.end()) names_.push_back(name);
  }

  struct Verdict {
    std::string instance;
    int n = 0;
    std::string ours;  ///< "dense" or "chain"
    double ours_ns = 0;
    double ours_err = NAN;  ///< NaN when ours declined (status not success)
    std::string right;      ///< the fastest right Siconos solver ("" if none)
    double right_ns = 0, right_err = NAN;
    std::string e2e_right;  ///< the same, end to end (build of (N, q) + LCP + velocities)
    double e2e_ns = 0, e2e_err = NAN;
  };

  std::map<std::string, std::string> picked_;
  std::map<std::string, int> bodies_;
  std::vector<Verdict> verdicts_;
  std::map<std::string, Row> rows_;
  std::vector<std::string> names_;
};

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  numerics_set_verbose(0);
  if (!std::getenv("OPENBLAS_NUM_THREADS"))
    std::cerr << "note: OPENBLAS_NUM_THREADS is not set; Siconos' LAPACK calls may use threads (run.sh sets it to 1)\n";

  auto& all = instances();
  all.push_back(make_instance("paper-4.4-alpha2", load_scene(SUPERBALL_SCENES_DIR "/paper-4.4-alpha2.toml")));
  all.push_back(make_instance("eps-1e-8", epsilon_scene(cl_RA(1) / cl_RA(100000000))));
  for (int n : {8, 16, 32, 64, 128, 256}) all.push_back(make_instance("chain-" + std::to_string(n), chain_scene(n, static_cast<std::uint64_t>(n))));

  const double tight = 1e-14;
  const int tight_iter = 100000;
  const std::vector<SiconosSolver> solvers = {
      {"lemke", SICONOS_LCP_LEMKE, lcp_lexicolemke},
      {"enum", SICONOS_LCP_ENUM, lcp_enum},
      {"enum/tol:1e-14", SICONOS_LCP_ENUM, lcp_enum, tight},
      {"pgs", SICONOS_LCP_PGS, lcp_pgs},
      {"pgs/tol:1e-14", SICONOS_LCP_PGS, lcp_pgs, tight, tight_iter},
      {"newton-min", SICONOS_LCP_NEWTONMIN, lcp_newton_min},
      // Newton-min converges in 1 to 3 steps where it converges; with 1e5
      // steps allowed it ran for minutes per call on chain-256 (growing to
      // 5 GB), so it keeps its default cap (1000) at the tight tolerance.
      {"newton-min/tol:1e-14", SICONOS_LCP_NEWTONMIN, lcp_newton_min, tight},
  };
  std::map<std::string, std::string> picked;
  std::map<std::string, int> bodies;
  for (const Instance& in : all) {
    std::cerr << in.name << ": n = " << in.pd.n << ", " << in.lcp.nc << " contacts, exact case closes";
    int closed = 0;
    for (int c = 0; c < in.lcp.nc; ++c)
      if (in.closed[static_cast<std::size_t>(c)]) {
        if (in.lcp.nc <= 16) std::cerr << " " << c + 1 << "-" << c + 2;
        ++closed;
      }
    std::cerr << (closed ? "" : " none") << " (" << closed << " of " << in.lcp.nc << "), exact pivots " << in.exact_pivots
              << ", degenerate contacts " << in.degenerate << "\n";
    const std::string prefix = "peers/" + in.name + "/";
    const bool chain = numeric::solves_as_chain(in.pd);
    picked[in.name] = chain ? "ours/double-chain" : "ours/double-dense";
    bodies[in.name] = in.pd.n;
    benchmark::RegisterBenchmark((prefix + "ours/double-dense").c_str(), bm_ours<numeric::CollisionSolver<double>, double>, &in)
        ->Unit(benchmark::kNanosecond);
    benchmark::RegisterBenchmark((prefix + "ours/double-chain").c_str(), bm_ours<numeric::ChainSolver<double>, double>, &in)
        ->Unit(benchmark::kNanosecond);
    benchmark::RegisterBenchmark((prefix + "ours/exact").c_str(),
                                 chain ? bm_ours<numeric::ChainSolver<cl_RA>, cl_RA> : bm_ours<numeric::CollisionSolver<cl_RA>, cl_RA>, &in)
        ->Unit(benchmark::kNanosecond);
    benchmark::RegisterBenchmark((prefix + "ours/double-no-pivots").c_str(), bm_ours_no_pivots, &in)->Unit(benchmark::kNanosecond);
    benchmark::RegisterBenchmark((prefix + "ours/lcp-build").c_str(), bm_ours_lcp_build, &in)->Unit(benchmark::kNanosecond);
    for (const SiconosSolver& s : solvers)
      benchmark::RegisterBenchmark((prefix + "siconos/" + s.name).c_str(), bm_siconos, &in, s, false)->Unit(benchmark::kNanosecond);
    for (const SiconosSolver& s : solvers)
      benchmark::RegisterBenchmark((prefix + "siconos-end-to-end/" + s.name).c_str(), bm_siconos, &in, s, true)
          ->Unit(benchmark::kNanosecond);
  }

  SummaryReporter reporter(picked, bodies);
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  return 0;
}
