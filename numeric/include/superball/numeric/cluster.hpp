#pragma once
/// \file cluster.hpp
/// Internal: the velocities after the collision for one evolution case, by
/// clusters.  Closed contacts tie consecutive bodies into clusters with one
/// velocity each; with Z the cluster incidence the velocities solve
///     Zᵀ A Z V = Zᵀ b̃,   W = Z V,   A = diag(m) + DᵀMD,
/// a banded system (bandwidth ≤ b, that of DᵀMD) solved by banded LDLᵀ in
/// O(n b²).  Bodies of a cluster get the same velocity (a closed gap is
/// exactly 0 in every arithmetic), and the reaction on a closed contact is
/// the running sum of the row residuals A W − b̃ down its cluster.  Used by
/// ChainSolver at every active-set step and by CollisionSolver for its final
/// answer.

#include <vector>

#include "superball/numeric/problem.hpp"

namespace superball::numeric::detail {

template <class S>
class ClusterSystem {
 public:
  /// Assemble A (lower band) and b̃ for \p p: O(entries + n b).
  void assemble(const Problem<S>& p);
  /// Solve the case \p closed (one flag per contact): velocities \p W (size
  /// n) and λ = −R on the contacts (\p lambda, 0 where open).  False when a
  /// pivot of the reduced system is not positive (rounding broke definiteness).
  bool solve(const Problem<S>& p, const std::vector<char>& closed, std::vector<S>& W, std::vector<S>& lambda);
  /// Whether A = diag(m) + DᵀMD on the free bodies, as assembled in S, is
  /// positive definite: every pivot of its banded LDLᵀ is positive (A is
  /// positive definite in exact arithmetic; rounding of the data and of the
  /// assembly can break it when κ(A)·u ≳ 1, and then the computed problem is
  /// not the paper's — its LCP need not have one solution).  O(n b²), free
  /// after a solve() of the case with every contact open.
  bool definite();
  int bandwidth() const { return b_; }
  /// A_{i, i−d} (0 <= d <= bandwidth(), d <= i), as assembled.
  const S& band(int i, int d) const {
    return A_[static_cast<std::size_t>(i) * static_cast<std::size_t>(b_ + 1) + static_cast<std::size_t>(d)];
  }
  /// b̃ on the free bodies, as assembled.
  const std::vector<S>& rhs() const { return rhs_; }

 private:
  S& A(int i, int d) { return A_[static_cast<std::size_t>(i) * static_cast<std::size_t>(b_ + 1) + static_cast<std::size_t>(d)]; }
  /// Banded LDLᵀ of the first \p k rows of R_ in place; false at a pivot that is not positive.
  bool factor(int k);
  S& R(int i, int d) { return R_[static_cast<std::size_t>(i) * static_cast<std::size_t>(b_ + 1) + static_cast<std::size_t>(d)]; }

  int n_ = 0, nf_ = 0, nc_ = 0, b_ = 0;
  int definite_ = -1;     ///< definite(): 1 yes, 0 no, −1 not yet known for this problem
  std::vector<S> A_;      ///< lower band of diag(m) + DᵀMD over all n bodies: A(i, d) = A_{i, i−d}
  std::vector<S> rhs_;    ///< b̃ on free bodies
  std::vector<S> row_size_;  ///< Σ_j |A_ij| per row
  std::vector<int> cluster_;
  std::vector<S> R_, y_;  ///< the reduced banded system and its right side / solution
  std::vector<S> win_;    ///< definite(): a window of the Schur complement
};

extern template class ClusterSystem<double>;
extern template class ClusterSystem<long double>;
extern template class ClusterSystem<cln::cl_R>;
extern template class ClusterSystem<cln::cl_RA>;

}  // namespace superball::numeric::detail
