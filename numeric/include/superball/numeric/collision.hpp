#pragma once
/// \file collision.hpp
/// The collision solver (paper §2–§3, n bodies), one template over the scalar.
///
/// Unknowns: the velocities after the collision W = U⁺ of the free bodies and
/// the impenetrability reactions on the n−1 adjacent contacts.  With
/// K = DᵀMD (D the pair incidence matrix), A = diag(m) + K, the equations of
/// motion (5) with P = 2MX + R, X = D(W+U⁻)/2 read
///     A W = diag(m) U⁻ − K U⁻ + Cᵀλ,      λ = −R ≥ 0 on contacts,
/// C the contact incidence matrix.  Eliminating W gives the linear
/// complementarity problem on the contact gaps w = C W:
///     w = q + N λ,  w ≥ 0,  λ ≥ 0,  wᵀλ = 0,   N = C A⁻¹ Cᵀ (positive definite),
/// which has exactly one solution.  It is solved by Murty's least-index
/// principal pivoting, each pivot an O(n²) update of the tableau (no
/// refactorisation), then checked independently against the equations of
/// motion and the complementarity conditions.  The tableau N is formed only
/// when a pivot is needed: the case with every contact open is solved first
/// (A W = b̃, by the banded cluster system); its gaps are q, and when q ≥ 0
/// it is the answer, without forming N.
///
/// Contacts that Problem::constrained leaves out (open at the instant of a
/// collision at a distance) have no λ: the LCP is the principal block of the
/// constrained contacts, and their gaps take any sign.

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "superball/cases/model.hpp"
#include "superball/numeric/problem.hpp"
#include "superball/numeric/export.hpp"
SUPERBALL_NUMERIC_API_BEGIN

namespace superball::numeric {

/// How a solve ended (Eigen style: numerical outcomes are a status).
enum class Status {
  Success,         ///< converged, A = diag(m) + DᵀMD positive definite in the solve's arithmetic, and the independent residual check passed
  NumericalIssue,  ///< A not positive definite once rounded, or the residual check failed at the stated tolerances
  NoConvergence,   ///< the pivoting did not terminate within Settings::max_pivots
};
/// The status's name: "success", "numerical-issue", "no-convergence".
const char* to_string(Status s);

/// Named tolerances of a solve, in units of the scalar's unit roundoff u.
template <class S>
struct Settings {
  /// A tableau value counts as negative when below −feasibility·|q|∞ (0 in exact arithmetic).
  S feasibility = S(0);
  /// The residual check passes when every relative residual is at most this.
  S residual = S(0);
  /// Pivot cap, per contact (Murty's rule terminates; the cap guards rounding cycles).
  int max_pivots_per_contact = 16;
  /// In double and long double, CollisionSolver::compute() solves problems of
  /// at most 8 bodies on a path whose sizes are known at compile time (no
  /// heap allocation, loops of fixed length), with the operations of the
  /// general path in the same order: the same results bit for bit.  False
  /// takes the general path at every size (for comparing the two).
  bool small_sizes = true;
  /// Exact rationals only: solve by fraction-free elimination on integers
  /// (the data over common denominators, 128-bit arithmetic where bounds
  /// prove it exact, CLN integers elsewhere), the same pivoting and the same
  /// fractions and pivot counts as in rationals, about 13× (paper scene) and 22×
  /// (chain-32) faster (docs/PERFORMANCE.md); false solves in CLN rationals
  /// throughout (the reference the tests compare with).
  bool integer_kernel = true;

  /// Defaults for S at \p digits: feasibility = 64u, residual = 1e6·u (u the unit roundoff).
  static Settings defaults(int digits = 0);
};

/// The outcome of one collision (velocities in units of Problem::unit).
template <class S>
struct Solution {
  /// Whether the solve succeeded; the fields below are meaningful only on Status::Success.
  Status status = Status::Success;
  std::vector<S> velocities_after;   ///< U⁺, size n, top to bottom
  std::vector<S> reactions;          ///< R on contact c = (c+1, c+2), ≤ 0; 0 where open
  std::vector<S> gaps;               ///< D_{c,c+1}(U⁺), ≥ 0 on constrained contacts (Problem::constrained)
  ContactSet closed;                 ///< the evolution case
  S kinetic_energy_before = S(0);    ///< finite bodies only
  /// ½ Σ m (U⁺)² over finite bodies.
  S kinetic_energy_after = S(0);
  S dissipation = S(0);              ///< P·X = 2XᵀMX + R·X
  S momentum_before = S(0);          ///< Σ m U⁻ over finite bodies
  /// Σ m U⁺ over finite bodies.
  S momentum_after = S(0);
  double residual_motion = 0;        ///< max relative residual of the equations of motion
  double residual_complementarity = 0;  ///< max relative violation of w ≥ 0, λ ≥ 0, wλ = 0
  /// The active-set pivots taken.
  int pivots = 0;
};

/// Reusable solver: construct once per problem size, then compute() any
/// problem of that size; compute() does not allocate for double and long
/// double once the workspace has its size.
template <class S>
class CollisionSolver {
 public:
  /// A dense matrix of S.
  using Matrix = Eigen::Matrix<S, Eigen::Dynamic, Eigen::Dynamic>;
  /// A dense column vector of S.
  using Vector = Eigen::Matrix<S, Eigen::Dynamic, 1>;

  /// A solver with the default settings.
  CollisionSolver();
  /// A solver with \p settings (tolerances, iteration limit).
  explicit CollisionSolver(const Settings<S>& settings);
  ///@{
  /// Copies and moves (the workspace is copied, or moved, with the solver).
  CollisionSolver(const CollisionSolver& other);
  CollisionSolver(CollisionSolver&& other) noexcept;
  CollisionSolver& operator=(const CollisionSolver& other);
  CollisionSolver& operator=(CollisionSolver&& other) noexcept;
  ///@}
  /// Frees the workspace.
  ~CollisionSolver();

  /// Solve \p problem into \p out (reusing out's storage).  Throws
  /// std::invalid_argument("CollisionSolver::compute(): ...") on misuse
  /// (sizes inconsistent); the numerical outcome is out.status.
  void compute(const Problem<S>& problem, Solution<S>& out);
  /// compute() into a new Solution.
  Solution<S> compute(const Problem<S>& problem) {
    Solution<S> out;
    compute(problem, out);
    return out;
  }
  /// Solve with the evolution case imposed: the contacts in \p closed are
  /// kept closed (their gaps are 0, their reactions whatever they come out)
  /// and the others open (reaction 0, gap whatever it comes out), without
  /// any sign condition.  This is the paper's way of solving "an assumed
  /// evolution case" (§4.1); out.closed is \p closed, and the residual check
  /// covers the equations of motion and the imposed gaps only
  /// (Problem::constrained plays no part: the case is imposed).
  void compute_case(const Problem<S>& problem, const ContactSet& closed, Solution<S>& out);
  /// The settings the solver was made with.
  const Settings<S>& settings() const;

  /// The linear complementarity problem w = q + Nλ of \p problem exactly
  /// as compute() builds it (same operations, same rounding), before any
  /// pivot: N = C A⁻¹ Cᵀ, q = C A⁻¹ b̃ (minus the obstacle's velocity on the
  /// last contact when it is fixed), and the map back to the velocities of
  /// the free bodies, W = W0 + Gλ with G = A⁻¹ C_Fᵀ, W0 = A⁻¹ b̃, on every
  /// contact (Problem::constrained selects a principal block of it).  For
  /// comparing other LCP solvers on the same instance.
  struct Lcp {
    /// The matrix N = C A⁻¹ Cᵀ of w = q + Nλ.
    Matrix N;
    /// The vector q = C A⁻¹ b̃ of w = q + Nλ.
    Vector q;
    /// G = A⁻¹ C_Fᵀ: the velocities of the free bodies are W = W0 + Gλ.
    Matrix G;
    /// W0 = A⁻¹ b̃, the velocities of the free bodies at λ = 0.
    Vector W0;
  };
  /// The LCP of \p problem (see Lcp).
  Lcp lcp(const Problem<S>& problem);

 private:
  class SUPERBALL_NUMERIC_NO_EXPORT Impl;  ///< the workspace and the steps of a solve (numeric/src/collision/solvers.hpp)
  template <class T>
  friend Solution<T> solve(const Problem<T>& problem);
  std::unique_ptr<Impl> impl_;
};

/// The solution of \p problem with default settings, by the formulation that
/// suits it: the banded ChainSolver (chain.hpp) when M couples only nearby
/// pairs (solves_as_chain()), else the dense CollisionSolver.  In double and
/// long double, data outside the safe window of S are solved scaled by powers
/// of two (scaling_of(), Problem::scaled()) and the answer is scaled back
/// exactly; the status is NumericalIssue when that answer is not
/// representable in S or when no scaling fits the data (Scaling::fits).
template <class S>
Solution<S> solve(const Problem<S>& problem);

extern template struct SUPERBALL_NUMERIC_EXPORT Settings<double>;
extern template struct SUPERBALL_NUMERIC_EXPORT Settings<long double>;
extern template struct SUPERBALL_NUMERIC_EXPORT Settings<cln::cl_R>;
extern template struct SUPERBALL_NUMERIC_EXPORT Settings<MpFloat>;
extern template struct SUPERBALL_NUMERIC_EXPORT Settings<cln::cl_RA>;
extern template class SUPERBALL_NUMERIC_EXPORT CollisionSolver<double>;
extern template class SUPERBALL_NUMERIC_EXPORT CollisionSolver<long double>;
extern template class SUPERBALL_NUMERIC_EXPORT CollisionSolver<cln::cl_R>;
extern template class SUPERBALL_NUMERIC_EXPORT CollisionSolver<MpFloat>;
extern template class SUPERBALL_NUMERIC_EXPORT CollisionSolver<cln::cl_RA>;
///@{
/// The explicit instantiations of solve() compiled into the library, one per scalar type.
extern template SUPERBALL_NUMERIC_EXPORT Solution<double> solve(const Problem<double>&);
extern template SUPERBALL_NUMERIC_EXPORT Solution<long double> solve(const Problem<long double>&);
extern template SUPERBALL_NUMERIC_EXPORT Solution<cln::cl_R> solve(const Problem<cln::cl_R>&);
extern template SUPERBALL_NUMERIC_EXPORT Solution<MpFloat> solve(const Problem<MpFloat>&);
extern template SUPERBALL_NUMERIC_EXPORT Solution<cln::cl_RA> solve(const Problem<cln::cl_RA>&);
///@}

}  // namespace superball::numeric

SUPERBALL_NUMERIC_API_END
