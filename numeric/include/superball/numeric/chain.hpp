#pragma once
/// \file chain.hpp
/// The collision solver for chains: O(n) time and memory when M only
/// couples pairs within a band (e.g. nearest and next-nearest neighbours);
/// solve() uses it whenever DᵀMD is banded (solves_as_chain()).
///
/// Same problem as CollisionSolver (collision.hpp), another formulation:
/// for a guess of the evolution case S, closed contacts tie consecutive
/// bodies into clusters with one velocity each; with Z the cluster incidence,
///     Zᵀ A Z V = Zᵀ b̃,        W = Z V,
/// a banded system (its bandwidth is at most M's, b) solved by a banded
/// LDLᵀ in O(n b²).  The reaction on a closed contact is the running sum of
/// the residuals A W − b̃ down its cluster; the gap of an open contact is
/// W_c − W_{c+1}.  The case is found by block principal pivoting (Júdice &
/// Pires): every contact whose gap or reaction has the wrong sign flips at
/// once; when that stops reducing the number of wrong signs, one contact
/// flips at a time, the smallest index first (Murty's rule, which
/// terminates because the contact matrix is positive definite).

#include <memory>

#include "superball/numeric/collision.hpp"
#include "superball/numeric/export.hpp"
SUPERBALL_NUMERIC_API_BEGIN

namespace superball::numeric {

/// Reusable banded solver (see the file comment).  compute() does not
/// allocate once the workspace has its size.
template <class S>
class ChainSolver {
 public:
  /// A solver with the default settings.
  ChainSolver();
  /// A solver with \p settings (tolerances, iteration limit).
  explicit ChainSolver(const Settings<S>& settings);
  ///@{
  /// Copies and moves (the workspace is copied, or moved, with the solver).
  ChainSolver(const ChainSolver& other);
  ChainSolver(ChainSolver&& other) noexcept;
  ChainSolver& operator=(const ChainSolver& other);
  ChainSolver& operator=(ChainSolver&& other) noexcept;
  ///@}
  /// Frees the workspace.
  ~ChainSolver();

  /// Solve \p problem into \p out; out.pivots counts the active-set
  /// iterations.  Throws std::invalid_argument("ChainSolver::compute(): ...")
  /// on misuse; the numerical outcome is out.status.
  void compute(const Problem<S>& problem, Solution<S>& out);
  /// compute() into a new Solution.
  Solution<S> compute(const Problem<S>& problem) {
    Solution<S> out;
    compute(problem, out);
    return out;
  }
  /// The bandwidth b of DᵀMD for the last problem.
  int bandwidth() const;

 private:
  class SUPERBALL_NUMERIC_NO_EXPORT Impl;  ///< the workspace and the steps of a solve (numeric/src/collision/solvers.hpp)
  template <class T>
  friend Solution<T> solve(const Problem<T>& problem);
  std::unique_ptr<Impl> impl_;
};

/// Whether solve() uses ChainSolver for \p p: when DᵀMD is banded, 2b + 1 < n
/// (b = p.bandwidth()); otherwise the dense CollisionSolver.  On the chains
/// of bench/peers (8 to 256 bodies) the banded solve is the faster one
/// wherever the dense one pivots (docs/PERFORMANCE.md).
template <class S>
bool solves_as_chain(const Problem<S>& p) {
  return 2 * p.bandwidth() + 1 < p.n;
}

extern template class SUPERBALL_NUMERIC_EXPORT ChainSolver<double>;
extern template class SUPERBALL_NUMERIC_EXPORT ChainSolver<long double>;
extern template class SUPERBALL_NUMERIC_EXPORT ChainSolver<cln::cl_R>;
extern template class SUPERBALL_NUMERIC_EXPORT ChainSolver<MpFloat>;
extern template class SUPERBALL_NUMERIC_EXPORT ChainSolver<cln::cl_RA>;

}  // namespace superball::numeric

SUPERBALL_NUMERIC_API_END
