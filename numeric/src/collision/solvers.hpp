#pragma once
// Internal: the state and the steps of the two solvers of the public headers
// (CollisionSolver in collision.hpp, ChainSolver in chain.hpp), which hold
// one of these each (pimpl), so that no workspace type of the solve is in an
// installed header.  solve() builds them directly, on the stack.

#include <vector>

#include "superball/numeric/chain.hpp"
#include "superball/numeric/collision.hpp"
#include "collision/cluster.hpp"
#include "collision/complete.hpp"
#include "collision/small_solver.hpp"
#include "superball/numeric/export.hpp"

namespace superball::numeric {

/// The dense solver: Murty's principal pivoting on the tableau N = C A⁻¹ Cᵀ
/// (collision.hpp), the fixed-size path for small n in double and long
/// double, the integer kernel in rationals (collision.cpp).
template <class S>
class SUPERBALL_NUMERIC_NO_EXPORT CollisionSolver<S>::Impl {
 public:
  using Matrix = typename CollisionSolver<S>::Matrix;
  using Vector = typename CollisionSolver<S>::Vector;

  explicit Impl(const Settings<S>& settings) : settings_(settings) {}
  void compute(const Problem<S>& p, Solution<S>& out);
  void compute_case(const Problem<S>& p, const ContactSet& closed, Solution<S>& out);
  typename CollisionSolver<S>::Lcp lcp(const Problem<S>& p);
  const Settings<S>& settings() const { return settings_; }

 private:
  void start(const Problem<S>& p, int bandwidth, Solution<S>& out);
  bool factorize();  ///< false (and singular_) at a pivot of A that is not positive
  void form_tableau();
  int check(const Problem<S>& p) const;  ///< Problem::check and the size limit; returns the bandwidth
  int pivot(const Problem<S>& problem);  ///< Murty on the constrained contacts; the pivots taken, −1 over the cap, −2 at a pivot not positive
  bool pivot_on(int p);
  void finish(const Problem<S>& p, Solution<S>& out, bool imposed);

  Settings<S> settings_;
  int n_ = 0, nf_ = 0, nc_ = 0;
  Matrix A_;          ///< LDLᵀ factors of diag(m) + DᵀMD on free bodies (lower triangle; formed at the first pivot)
  Matrix G_;          ///< A⁻¹ C_Fᵀ, nf × nc
  Vector W0_;         ///< A⁻¹ b̃, b̃ = diag(m)u − K u − K_{·,fixed} u_fixed on free bodies: every contact open
  Matrix T_;          ///< the pivoting tableau (starts as N; formed at the first pivot)
  bool factorized_ = false;  ///< whether A_ holds the factors for the current problem
  bool tableau_ = false;     ///< whether G_ and T_ are formed for the current problem
  bool answered_ = false;    ///< whether the output holds the cluster answer of the current case
  bool singular_ = false;    ///< whether factorize() met a pivot that is not positive (no A⁻¹ in S)
  Vector t_;          ///< its constant column (starts as q)
  std::vector<char> basic_lambda_;  ///< contact c: λ_c basic (closed)
  std::vector<S> lambda_;           ///< λ on every contact, 0 where open
  detail::CheckWorkspace<S> check_;  ///< scratch of the residual check
  detail::ClusterSystem<S> system_;  ///< A and b̃ (band), and the answer by clusters of a case
  int small_n_ = 0;                   ///< the n small_ was chosen for (0: none yet)
  detail::SmallSolve<S> small_ = nullptr;  ///< the fixed-size path for small_n_ bodies, if any
};

/// The banded solver: block principal pivoting over the cluster systems of
/// the cases it visits (chain.hpp, chain.cpp).
template <class S>
class SUPERBALL_NUMERIC_NO_EXPORT ChainSolver<S>::Impl {
 public:
  explicit Impl(const Settings<S>& settings) : settings_(settings) {}
  void compute(const Problem<S>& p, Solution<S>& out);
  int bandwidth() const { return system_.bandwidth(); }

 private:
  Settings<S> settings_;
  detail::ClusterSystem<S> system_;
  std::vector<S> lambda_;  ///< λ on closed contacts, 0 on open ones
  std::vector<char> closed_;
  detail::CheckWorkspace<S> check_;
};

}  // namespace superball::numeric
