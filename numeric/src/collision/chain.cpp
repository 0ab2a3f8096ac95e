#include "superball/numeric/chain.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "collision/complete.hpp"
#include "collision/exact_kernel.hpp"
#include "collision/solvers.hpp"

namespace superball::numeric {
namespace {
/// Block pivots that do not reduce the number of wrong signs before the
/// solver falls back to one Murty pivot (Júdice & Pires' p).
constexpr int block_pivot_patience = 10;
}  // namespace

template <class S>
void ChainSolver<S>::Impl::compute(const Problem<S>& p, Solution<S>& out) {
  const int b = p.check("ChainSolver::compute()");
  const int nc = p.n - 1, nf = p.fixed_bottom ? p.n - 1 : p.n;
  if constexpr (ScalarTraits<S>::exact)  // the integer kernel, the same pivoting (exact_kernel.hpp), when every contact is constrained
    if (settings_.integer_kernel && p.constrained.empty() &&
        detail::exact_integer_solve(p, detail::ExactPivoting::Block, settings_.max_pivots_per_contact * std::max(nc, 1), settings_, out))
      return;
  system_.assemble(p, b);
  lambda_.resize(static_cast<std::size_t>(nc));
  // Start from every contact closed: the pivoting then opens the ones that
  // separate, all at once.  (From all-open, or from the contacts approaching
  // before the collision, closing travels up a chain one band per iteration:
  // O(n) iterations, measured in bench/bench_chain.cpp's history.)
  // Contacts that are not constrained (Problem::constrained) stay open throughout.
  closed_.assign(static_cast<std::size_t>(nc), 1);
  if (!p.constrained.empty()) closed_.assign(p.constrained.begin(), p.constrained.end());
  out.velocities_after.resize(static_cast<std::size_t>(p.n));
  auto& W = out.velocities_after;

  S vscale = S(0), lscale = S(0);
  for (int i = 0; i < p.n; ++i) vscale = std::max(vscale, detail::abs_value(p.u[i]));
  for (int i = 0; i < nf; ++i) lscale = std::max(lscale, detail::abs_value(S(p.mass[i] * p.u[i])));
  const S wtol = settings_.feasibility * vscale, ltol = settings_.feasibility * lscale;
  const int cap = settings_.max_pivots_per_contact * std::max(nc, 1);
  int best = std::numeric_limits<int>::max(), stall = 0, iterations = 0;
  out.status = Status::Success;
  for (;;) {
    if (!system_.solve(p, closed_, W, lambda_)) {
      out.status = Status::NumericalIssue;
      break;
    }
    int wrong = 0, first = -1;
    for (int c = 0; c < nc; ++c) {
      const bool bad = closed_[c] ? lambda_[c] < -ltol : p.constrained_contact(c) && S(W[c] - W[c + 1]) < -wtol;
      if (bad) {
        ++wrong;
        if (first < 0) first = c;
      }
    }
    if (wrong == 0) break;
    if (++iterations > cap) {
      out.status = Status::NoConvergence;
      break;
    }
    if (wrong < best) {
      best = wrong;
      stall = 0;
    } else {
      ++stall;
    }
    if (stall < block_pivot_patience) {  // block pivot: flip every wrong sign
      for (int c = 0; c < nc; ++c) {
        const bool bad = closed_[c] ? lambda_[c] < -ltol : p.constrained_contact(c) && S(W[c] - W[c + 1]) < -wtol;
        if (bad) closed_[c] ^= 1;
      }
    } else {  // Murty: the smallest index only
      closed_[first] ^= 1;
    }
  }
  out.pivots = iterations;
  // The checks every solver shares, including the definiteness of A: this
  // path factors only the reduced systems ZᵀAZ of the cases it visits, which
  // can be positive definite when A is not in S (hard-eps-1e-8.toml in
  // double: the case {2-3, 3-4} leaves the 1×1 system A₁₁ = 1e-24, rounded
  // from 2e-16, and W₁ off by 2e8 with residuals of 1e-17).  The dense
  // solver factors A itself first and met the failed pivot there.
  detail::complete_solution(p, system_, lambda_, closed_, false, settings_, check_, out);
}

template <class S>
Solution<S> solve(const Problem<S>& problem) {
  const Settings<S> settings = Settings<S>::defaults(problem.digits);
  auto solve_as_given = [&settings](const Problem<S>& p) {
    // The solvers' workspaces, not the solvers: no allocation for a pimpl.
    Solution<S> out;
    if (solves_as_chain(p)) {
      typename ChainSolver<S>::Impl chain(settings);
      chain.compute(p, out);
    } else {
      typename CollisionSolver<S>::Impl dense(settings);
      dense.compute(p, out);
    }
    return out;
  };
  // Data outside the safe window of S are solved scaled by powers of two
  // (scaling_of()) and the answer scaled back exactly; an answer S cannot
  // represent, or data whose magnitudes no scaling fits, are a numerical issue.
  const Scaling scaling = scaling_of(problem);
  if (scaling.identity() && scaling.fits) return solve_as_given(problem);
  Solution<S> out = solve_as_given(problem.scaled(scaling));
  if (!detail::scale_solution(out, scaling, 1) || !scaling.fits) out.status = Status::NumericalIssue;
  return out;
}

template <class S>
ChainSolver<S>::ChainSolver() : impl_(std::make_unique<Impl>(Settings<S>::defaults())) {}
template <class S>
ChainSolver<S>::ChainSolver(const Settings<S>& settings) : impl_(std::make_unique<Impl>(settings)) {}
template <class S>
ChainSolver<S>::ChainSolver(const ChainSolver& other) : impl_(std::make_unique<Impl>(*other.impl_)) {}
template <class S>
ChainSolver<S>::ChainSolver(ChainSolver&& other) noexcept = default;
template <class S>
ChainSolver<S>& ChainSolver<S>::operator=(const ChainSolver& other) {
  if (this != &other) impl_ = std::make_unique<Impl>(*other.impl_);
  return *this;
}
template <class S>
ChainSolver<S>& ChainSolver<S>::operator=(ChainSolver&& other) noexcept = default;
template <class S>
ChainSolver<S>::~ChainSolver() = default;
template <class S>
void ChainSolver<S>::compute(const Problem<S>& problem, Solution<S>& out) {
  impl_->compute(problem, out);
}
template <class S>
int ChainSolver<S>::bandwidth() const {
  return impl_->bandwidth();
}

template SUPERBALL_NUMERIC_EXPORT Solution<double> solve(const Problem<double>&);
template SUPERBALL_NUMERIC_EXPORT Solution<long double> solve(const Problem<long double>&);
template SUPERBALL_NUMERIC_EXPORT Solution<cln::cl_R> solve(const Problem<cln::cl_R>&);
template SUPERBALL_NUMERIC_EXPORT Solution<MpFloat> solve(const Problem<MpFloat>&);
template SUPERBALL_NUMERIC_EXPORT Solution<cln::cl_RA> solve(const Problem<cln::cl_RA>&);

template class ChainSolver<double>;
template class ChainSolver<long double>;
template class ChainSolver<cln::cl_R>;
template class ChainSolver<MpFloat>;
template class ChainSolver<cln::cl_RA>;

}  // namespace superball::numeric
