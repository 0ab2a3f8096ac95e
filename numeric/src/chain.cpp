#include "superball/numeric/chain.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "detail/complete.hpp"

namespace superball::numeric {
namespace {
/// Block pivots that do not reduce the number of wrong signs before the
/// solver falls back to one Murty pivot (Júdice & Pires' p).
constexpr int block_pivot_patience = 10;
}  // namespace

template <class S>
void ChainSolver<S>::assemble(const Problem<S>& p) {
  n_ = p.n;
  nf_ = p.fixed_bottom ? n_ - 1 : n_;
  nc_ = n_ - 1;
  b_ = 0;
  for (const Entry<S>& e : p.entries) b_ = std::max(b_, std::max({e.i, e.j, e.k, e.l}) - std::min({e.i, e.j, e.k, e.l}));
  A_.assign(static_cast<std::size_t>(n_) * static_cast<std::size_t>(b_ + 1), S(0));
  // Symmetric lower-band storage: add(r, c, v) adds v to A_rc and A_cr.
  auto add = [&](int r, int c, const S& v) {
    if (r < c) std::swap(r, c);
    A(r, r - c) += v;
  };
  for (const Entry<S>& e : p.entries) {
    if (e.diagonal()) {  // v (e_i − e_j)(e_i − e_j)ᵀ
      A(e.i, 0) += e.value;
      A(e.j, 0) += e.value;
      add(e.j, e.i, -e.value);
      continue;
    }
    // v [(e_i − e_j)(e_k − e_l)ᵀ + transpose]
    const int rows[2] = {e.i, e.j}, cols[2] = {e.k, e.l};
    for (int a = 0; a < 2; ++a)
      for (int c = 0; c < 2; ++c) {
        const S v = (a == c) ? e.value : S(-e.value);
        if (rows[a] == cols[c])
          A(rows[a], 0) += S(2) * v;
        else
          add(rows[a], cols[c], v);
      }
  }
  // b̃ = m u − K u − [fixed] K_{·,n} u_n on free bodies (K u before the masses enter A).
  rhs_.assign(static_cast<std::size_t>(nf_), S(0));
  for (int i = 0; i < n_; ++i)
    for (int d = 0; d <= b_ && d <= i; ++d) {
      const int j = i - d;
      const S a = A(i, d);
      if (i < nf_) rhs_[i] -= a * p.u[j];
      if (d > 0 && j < nf_) rhs_[j] -= a * p.u[i];
    }
  if (p.fixed_bottom)
    for (int d = 1; d <= b_ && d <= n_ - 1; ++d) rhs_[n_ - 1 - d] -= A(n_ - 1, d) * p.u[n_ - 1];
  for (int i = 0; i < nf_; ++i) {
    rhs_[i] += p.mass[i] * p.u[i];
    A(i, 0) += p.mass[i];
  }
}

template <class S>
bool ChainSolver<S>::solve_case(const Problem<S>& p, std::vector<S>& W) {
  // Clusters: consecutive bodies joined by closed contacts; the one holding
  // a fixed bottom body (if any) is last and has the known velocity u_n.
  cluster_[0] = 0;
  for (int c = 0; c < nc_; ++c) cluster_[c + 1] = cluster_[c] + (closed_[c] ? 0 : 1);
  const int fixed = p.fixed_bottom ? cluster_[n_ - 1] : -1;
  const int k = p.fixed_bottom ? fixed : cluster_[n_ - 1] + 1;
  const S u_fixed = p.fixed_bottom ? p.u[n_ - 1] : S(0);
  std::fill(R_.begin(), R_.begin() + static_cast<std::ptrdiff_t>(k) * (b_ + 1), S(0));
  std::fill(y_.begin(), y_.begin() + k, S(0));
  for (int i = 0; i < nf_; ++i) {
    const int ci = cluster_[i];
    if (ci == fixed) {  // columns of the fixed cluster move to the right side
      for (int d = 1; d <= b_ && d <= i; ++d)
        if (cluster_[i - d] != fixed) y_[cluster_[i - d]] -= A(i, d) * u_fixed;
      continue;
    }
    y_[ci] += rhs_[i];
    for (int d = 0; d <= b_ && d <= i; ++d) {
      const int cj = cluster_[i - d];
      R(ci, ci - cj) += A(i, d);
      if (d > 0 && ci == cj) R(ci, 0) += A(i, d);
    }
  }
  // Banded LDLᵀ in place, then the three triangular/diagonal solves.
  for (int j = 0; j < k; ++j) {
    const S dj = R(j, 0);
    if (!(dj > S(0))) return false;
    const int last = std::min(k - 1, j + b_);
    for (int r = j + 1; r <= last; ++r) {
      const S lrj = R(r, r - j) / dj;
      for (int i = r; i <= last; ++i) R(i, i - r) -= R(i, i - j) * lrj;
    }
    for (int i = j + 1; i <= last; ++i) R(i, i - j) /= dj;
  }
  for (int i = 0; i < k; ++i)
    for (int j = std::max(0, i - b_); j < i; ++j) y_[i] -= R(i, i - j) * y_[j];
  for (int i = 0; i < k; ++i) y_[i] /= R(i, 0);
  for (int i = k - 1; i >= 0; --i)
    for (int j = i + 1; j <= std::min(k - 1, i + b_); ++j) y_[i] -= R(j, j - i) * y_[j];
  for (int i = 0; i < n_; ++i) W[i] = cluster_[i] == fixed ? u_fixed : y_[cluster_[i]];
  // Reactions: running sums of (A W − b̃) down each cluster.
  S above = S(0);
  for (int c = 0; c < nc_; ++c) {
    if (!closed_[c]) {
      lambda_[c] = S(0);
      above = S(0);
      continue;
    }
    S r = -rhs_[c];
    for (int d = 0; d <= b_ && d <= c; ++d) r += A(c, d) * W[c - d];
    for (int d = 1; d <= b_ && c + d < nf_; ++d) r += A(c + d, d) * W[c + d];
    lambda_[c] = above + r;
    above = lambda_[c];
  }
  return true;
}

template <class S>
void ChainSolver<S>::compute(const Problem<S>& p, Solution<S>& out) {
  if (p.n < 2) throw std::invalid_argument("ChainSolver::compute(): a problem needs at least 2 bodies");
  if (static_cast<int>(p.mass.size()) != p.n || static_cast<int>(p.u.size()) != p.n)
    throw std::invalid_argument("ChainSolver::compute(): masses and velocities must have one entry per body");
  for (const Entry<S>& e : p.entries)
    if (std::min({e.i, e.j, e.k, e.l}) < 0 || std::max({e.i, e.j, e.k, e.l}) >= p.n || e.i >= e.j || e.k >= e.l)
      throw std::invalid_argument("ChainSolver::compute(): an entry of M names a pair outside the bodies");
  assemble(p);
  cluster_.resize(static_cast<std::size_t>(n_));
  R_.resize(static_cast<std::size_t>(n_) * static_cast<std::size_t>(b_ + 1));
  y_.resize(static_cast<std::size_t>(n_));
  lambda_.resize(static_cast<std::size_t>(nc_));
  // Start from every contact closed: the pivoting then opens the ones that
  // separate, all at once.  (From all-open, or from the contacts approaching
  // before the collision, closing travels up a chain one band per iteration:
  // O(n) iterations, measured in bench/bench_chain.cpp's history.)
  closed_.assign(static_cast<std::size_t>(nc_), 1);
  out.velocities_after.resize(static_cast<std::size_t>(n_));
  auto& W = out.velocities_after;

  S vscale = S(0), lscale = S(0);
  for (int i = 0; i < n_; ++i) vscale = std::max(vscale, detail::abs_value(p.u[i]));
  for (int i = 0; i < nf_; ++i) lscale = std::max(lscale, detail::abs_value(S(p.mass[i] * p.u[i])));
  const S wtol = settings_.feasibility * vscale, ltol = settings_.feasibility * lscale;
  const int cap = settings_.max_pivots_per_contact * std::max(nc_, 1);
  int best = std::numeric_limits<int>::max(), stall = 0, iterations = 0;
  out.status = Status::Success;
  for (;;) {
    if (!solve_case(p, W)) {
      out.status = Status::NumericalIssue;
      break;
    }
    int wrong = 0, first = -1;
    for (int c = 0; c < nc_; ++c) {
      const bool bad = closed_[c] ? lambda_[c] < -ltol : S(W[c] - W[c + 1]) < -wtol;
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
      for (int c = 0; c < nc_; ++c) {
        const bool bad = closed_[c] ? lambda_[c] < -ltol : S(W[c] - W[c + 1]) < -wtol;
        if (bad) closed_[c] ^= 1;
      }
    } else {  // Murty: the smallest index only
      closed_[first] ^= 1;
    }
  }
  out.pivots = iterations;
  detail::complete_solution(p, lambda_, closed_, false, settings_, check_, out);
}

template <class S>
Solution<S> solve(const Problem<S>& problem) {
  const Settings<S> settings = Settings<S>::defaults(problem.digits);
  int b = 0;
  for (const Entry<S>& e : problem.entries) b = std::max(b, std::max({e.i, e.j, e.k, e.l}) - std::min({e.i, e.j, e.k, e.l}));
  if (problem.n > dense_max_bodies && 2 * b + 1 < problem.n) return ChainSolver<S>(settings).compute(problem);
  return CollisionSolver<S>(settings).compute(problem);
}

template Solution<double> solve(const Problem<double>&);
template Solution<long double> solve(const Problem<long double>&);
template Solution<cln::cl_R> solve(const Problem<cln::cl_R>&);
template Solution<cln::cl_RA> solve(const Problem<cln::cl_RA>&);

template class ChainSolver<double>;
template class ChainSolver<long double>;
template class ChainSolver<cln::cl_R>;
template class ChainSolver<cln::cl_RA>;

}  // namespace superball::numeric
