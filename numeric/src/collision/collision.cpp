#include "superball/numeric/collision.hpp"

#include "collision/complete.hpp"
#include "collision/dense_steps.hpp"
#include "collision/exact_kernel.hpp"
#include "collision/small_solver.hpp"
#include "collision/solvers.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <type_traits>

namespace superball::numeric {

const char* to_string(Status s) {
  switch (s) {
    case Status::Success: return "success";
    case Status::NumericalIssue: return "numerical-issue";
    case Status::NoConvergence: break;
  }
  return "no-convergence";
}

template <class S>
Settings<S> Settings<S>::defaults(int digits) {
  Settings<S> s;
  const S u = ScalarTraits<S>::unit_roundoff(digits);
  s.feasibility = S(64) * u;
  s.residual = S(1000000) * u;
  return s;
}

template <class S>
void CollisionSolver<S>::Impl::start(const Problem<S>& p, int bandwidth, Solution<S>& out) {
  // A = diag(m) + DᵀMD and b̃, once, in the band storage of the cluster
  // system; then the case with every contact open (one cluster per body,
  // A W = b̃), whose gaps are the constant column q of the LCP.
  n_ = p.n;
  nf_ = p.fixed_bottom ? n_ - 1 : n_;
  nc_ = n_ - 1;
  system_.assemble(p, bandwidth);
  basic_lambda_.assign(static_cast<std::size_t>(nc_), 0);
  A_.resize(nf_, nf_);  // sized now, so that forming N later does not allocate
  G_.resize(nf_, nc_);
  T_.resize(nc_, nc_);
  W0_.resize(nf_);
  t_.resize(nc_);
  factorized_ = tableau_ = singular_ = false;
  answered_ = system_.solve(p, basic_lambda_, out.velocities_after, lambda_);
  if (answered_) {
    for (int i = 0; i < nf_; ++i) W0_(i) = out.velocities_after[static_cast<std::size_t>(i)];
  } else if (factorize()) {  // rounding broke the definiteness of A: the dense factors say what they can
    for (int i = 0; i < nf_; ++i) W0_(i) = system_.rhs()[static_cast<std::size_t>(i)];
    detail::ldlt_solve_in_place(A_, nf_, W0_);
  } else {  // a pivot of A is not positive in S: nothing to pivot on (compute() says so)
    W0_.setZero();
  }
  for (int c = 0; c < nc_; ++c) t_(c) = c + 1 < nf_ ? S(W0_(c) - W0_(c + 1)) : S(W0_(c) - p.u[n_ - 1]);
}

template <class S>
bool CollisionSolver<S>::Impl::factorize() {
  // The lower triangle of A on the free bodies from the band, then its LDLᵀ
  // in place, no pivoting (A is symmetric positive definite: positive
  // masses plus DᵀMD with M positive semi-definite).
  const int b = system_.bandwidth();
  for (int i = 0; i < nf_; ++i)
    for (int j = 0; j <= i; ++j) A_(i, j) = i - j <= b ? system_.band(i, i - j) : S(0);
  singular_ = !detail::ldlt_in_place<S>(A_, nf_);
  factorized_ = true;
  return !singular_;
}

template <class S>
void CollisionSolver<S>::Impl::form_tableau() {
  // G = A⁻¹ C_Fᵀ, one solve per contact, and the tableau T = N = C G.
  if (!factorized_) factorize();
  if (singular_) return;  // no A⁻¹ in S: pivot_on() declines
  G_.setZero();
  for (int c = 0; c < nc_; ++c) {
    G_(c, c) = S(1);
    if (c + 1 < nf_) G_(c + 1, c) = S(-1);
    detail::ldlt_solve_in_place(A_, nf_, G_.col(c));
  }
  for (int c = 0; c < nc_; ++c) {
    if (c + 1 < nf_)
      T_.row(c) = G_.row(c) - G_.row(c + 1);
    else
      T_.row(c) = G_.row(c);
  }
  tableau_ = true;
}

template <class S>
typename CollisionSolver<S>::Lcp CollisionSolver<S>::Impl::lcp(const Problem<S>& p) {
  const int b = check(p);
  Solution<S> open;
  start(p, b, open);
  form_tableau();
  if (singular_) throw std::domain_error("CollisionSolver::lcp(): A = diag(m) + DᵀMD is not positive definite in this arithmetic");
  return {T_, t_, G_, W0_};
}

template <class S>
int CollisionSolver<S>::Impl::pivot(const Problem<S>& problem) {
  // Murty's least-index principal pivoting: exchange w_p and λ_p for the
  // smallest p whose basic variable is negative.  Terminates for P-matrices.
  // Only constrained contacts are pivoted (Problem::constrained): the others
  // keep λ = 0 and any gap, and the pivots on the constrained ones act on
  // their principal block as on the LCP of those contacts alone (a principal
  // block of a P-matrix is one), so this is Murty's pivoting on that LCP.
  S scale = S(0);
  for (int c = 0; c < nc_; ++c) scale = std::max(scale, detail::abs_value<S>(t_(c)));
  const S tol = settings_.feasibility * scale;
  const int cap = settings_.max_pivots_per_contact * std::max(nc_, 1);
  int pivots = 0;
  for (;;) {
    int p = -1;
    for (int c = 0; c < nc_ && p < 0; ++c)
      if (t_(c) < -tol && problem.constrained_contact(c)) p = c;
    if (p < 0) return pivots;
    if (++pivots > cap) return -1;
    if (!pivot_on(p)) return -2;
  }
}

template <class S>
bool CollisionSolver<S>::Impl::pivot_on(int p) {
  // Principal pivot transform on (p, p): exchange the basic and non-basic
  // variables of contact p, an O(nc²) update of the tableau.
  if (!tableau_) form_tableau();
  if (singular_) return false;
  answered_ = false;
  if (!detail::principal_pivot<S>(T_, t_, nc_, p)) return false;
  basic_lambda_[static_cast<std::size_t>(p)] ^= 1;
  return true;
}

template <class S>
void CollisionSolver<S>::Impl::finish(const Problem<S>& p, Solution<S>& out, bool imposed) {
  // The pivoting decided the case; the answer comes from the cluster system
  // of that case, so that bodies in contact share one velocity exactly and
  // the accuracy does not depend on the conditioning of the tableau.  With
  // no pivot the case is every contact open, solved already by start().
  if (!answered_ && !system_.solve(p, basic_lambda_, out.velocities_after, lambda_)) out.status = Status::NumericalIssue;
  detail::complete_solution(p, system_, lambda_, basic_lambda_, imposed, settings_, check_, out);
}

template <class S>
int CollisionSolver<S>::Impl::check(const Problem<S>& p) const {
  const int b = p.check("CollisionSolver::compute()");
  if (p.n > dense_solver_max_bodies)
    throw std::invalid_argument("CollisionSolver::compute(): " + std::to_string(p.n) + " bodies: the dense solver takes at most " +
                                std::to_string(dense_solver_max_bodies) + " (ExactScene::from() refuses such scenes by name; use ChainSolver for chains whose M is banded)");
  return b;
}

template <class S>
void CollisionSolver<S>::Impl::compute(const Problem<S>& p, Solution<S>& out) {
  const int bandwidth = check(p);
  // A problem with contacts that are not constrained takes the general path
  // (the fixed-size path and the integer kernel pivot on every contact).
  const bool every_contact = p.constrained.empty();
  if constexpr (std::is_floating_point<S>::value) {  // n <= 8: sizes known at compile time (small_solver.cpp)
    if (settings_.small_sizes && every_contact) {
      if (p.n != small_n_) small_n_ = p.n, small_ = detail::small_solver_for<S>(p.n);
      if (small_ && small_(p, bandwidth, settings_, out)) return;
    }
  }
  if constexpr (ScalarTraits<S>::exact)  // the integer kernel, the same pivoting (exact_kernel.hpp)
    if (settings_.integer_kernel && every_contact &&
        detail::exact_integer_solve(p, detail::ExactPivoting::Murty, settings_.max_pivots_per_contact * std::max(p.n - 1, 1), settings_, out))
      return;
  start(p, bandwidth, out);
  const int pivots = singular_ ? -2 : pivot(p);
  out.status = pivots == -1 ? Status::NoConvergence : pivots == -2 ? Status::NumericalIssue : Status::Success;
  out.pivots = std::max(pivots, 0);
  finish(p, out, false);
}

template <class S>
void CollisionSolver<S>::Impl::compute_case(const Problem<S>& p, const ContactSet& closed, Solution<S>& out) {
  const int b = check(p);
  if (closed.bodies() != p.n)
    throw std::invalid_argument("CollisionSolver::compute_case(): the case is for " + std::to_string(closed.bodies()) +
                                " bodies, the problem has " + std::to_string(p.n));
  start(p, b, out);
  out.status = Status::Success;
  out.pivots = 0;
  for (int c = 0; c < nc_; ++c)
    if (closed.closed(c)) {
      ++out.pivots;
      if (!pivot_on(c)) out.status = Status::NumericalIssue;
    }
  finish(p, out, true);
}

template <class S>
CollisionSolver<S>::CollisionSolver() : impl_(std::make_unique<Impl>(Settings<S>::defaults())) {}
template <class S>
CollisionSolver<S>::CollisionSolver(const Settings<S>& settings) : impl_(std::make_unique<Impl>(settings)) {}
template <class S>
CollisionSolver<S>::CollisionSolver(const CollisionSolver& other) : impl_(std::make_unique<Impl>(*other.impl_)) {}
template <class S>
CollisionSolver<S>::CollisionSolver(CollisionSolver&& other) noexcept = default;
template <class S>
CollisionSolver<S>& CollisionSolver<S>::operator=(const CollisionSolver& other) {
  if (this != &other) impl_ = std::make_unique<Impl>(*other.impl_);
  return *this;
}
template <class S>
CollisionSolver<S>& CollisionSolver<S>::operator=(CollisionSolver&& other) noexcept = default;
template <class S>
CollisionSolver<S>::~CollisionSolver() = default;

template <class S>
void CollisionSolver<S>::compute(const Problem<S>& problem, Solution<S>& out) {
  impl_->compute(problem, out);
}
template <class S>
void CollisionSolver<S>::compute_case(const Problem<S>& problem, const ContactSet& closed, Solution<S>& out) {
  impl_->compute_case(problem, closed, out);
}
template <class S>
const Settings<S>& CollisionSolver<S>::settings() const {
  return impl_->settings();
}
template <class S>
typename CollisionSolver<S>::Lcp CollisionSolver<S>::lcp(const Problem<S>& problem) {
  return impl_->lcp(problem);
}

template struct Settings<double>;
template struct Settings<long double>;
template struct Settings<cln::cl_R>;
template struct Settings<MpFloat>;
template struct Settings<cln::cl_RA>;
template class CollisionSolver<double>;
template class CollisionSolver<long double>;
template class CollisionSolver<cln::cl_R>;
template class CollisionSolver<MpFloat>;
template class CollisionSolver<cln::cl_RA>;

}  // namespace superball::numeric
