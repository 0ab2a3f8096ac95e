#pragma once
/// \file cluster.hpp
/// Internal (numeric/src): the velocities after the collision for one evolution case, by
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
#include "collision/magnitude.hpp"

namespace superball::numeric::detail {

template <class S>
class ClusterSystem {
 public:
  /// Assemble A (lower band) and b̃ for \p p, whose DᵀMD has bandwidth
  /// \p bandwidth (what p.check() returned): O(entries + n b).
  void assemble(const Problem<S>& p, int bandwidth);
  /// Solve the case \p closed (one flag per contact): velocities \p W (size
  /// n) and λ = −R on the contacts (\p lambda, 0 where open).  False when a
  /// pivot of the reduced system is not positive (rounding broke definiteness).
  bool solve(const Problem<S>& p, const std::vector<char>& closed, std::vector<S>& W, std::vector<S>& lambda);
  /// det(Zᵀ A Z) of the case of the last solve() that returned true, the
  /// fixed cluster's columns moved to the right side: the product of the
  /// pivots of its LDLᵀ (> 0), O(clusters).
  S determinant() const;
  /// Whether A = diag(m) + DᵀMD on the free bodies, as assembled in S, is
  /// positive definite (A is positive definite in exact arithmetic when M is
  /// positive semi-definite, as ExactScene::from checks; rounding of the data
  /// and of the assembly can break it when κ(A)·u ≳ 1, and then the computed
  /// problem is not the paper's — its LCP need not have one solution).
  /// definite_by_bound(), else definite_by_factor(); known without either
  /// after a solve() of the case with every contact open.  Cached until the
  /// next assemble().
  bool definite();
  /// A sufficient condition for definite(), O(n): the assembly's rounding
  /// error E, bounded term by term, has ‖E‖₂ below the smallest mass, which
  /// bounds λ_min(A) from below (Weyl's inequality, since M is positive
  /// semi-definite): γ_k · max_r scale_r < min m, k = 2·entries + 2.  Always
  /// true in exact arithmetic.
  bool definite_by_bound() const;
  /// definite() decided: every pivot of the banded LDLᵀ of A (free bodies)
  /// is positive, O(n b²).
  bool definite_by_factor();
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

  int n_ = 0, nf_ = 0, nc_ = 0, b_ = 0, digits_ = 0, entries_ = 0;
  int k_ = 0;             ///< the unknowns (free clusters) of the last solve()
  int definite_ = -1;     ///< definite(): 1 yes, 0 no, −1 not yet known for this problem
  std::vector<S> A_;      ///< lower band of diag(m) + DᵀMD over all n bodies: A(i, d) = A_{i, i−d}
  std::vector<S> rhs_;    ///< b̃ on free bodies
  /// per row of A: Σ |terms| the assembly added (mass included), its rounding scale
  std::vector<SizeOf<S>> scale_;
  S min_mass_ = S(0);        ///< the smallest mass of a free body
  std::vector<int> cluster_;
  std::vector<S> R_, y_;  ///< the reduced banded system and its right side / solution
  std::vector<S> l_;      ///< factor(): a column of L
  std::vector<S> win_;    ///< definite_by_factor(): a window of the Schur complement
};

extern template class ClusterSystem<double>;
extern template class ClusterSystem<long double>;
extern template class ClusterSystem<cln::cl_R>;
extern template class ClusterSystem<MpFloat>;
extern template class ClusterSystem<cln::cl_RA>;

}  // namespace superball::numeric::detail
