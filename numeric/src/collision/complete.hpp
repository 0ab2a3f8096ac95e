#pragma once
// Internal: what every solver does once it has the velocities after the
// collision and the contact reactions — the derived quantities and the
// independent residual check.

#include <vector>

#include "superball/numeric/collision.hpp"
#include "collision/cluster.hpp"
#include "collision/magnitude.hpp"

namespace superball::numeric::detail {

/// A sum and the sum of the magnitudes of its terms, side by side, so that
/// adding a term updates both with one store (the residual check scatters
/// over M's entries, and there the stores are the bottleneck).
template <class S>
class Sized {
 public:
  using Size = SizeOf<S>;
  void add(const S& term, const Size& magnitude) { value_ += term, size_ += magnitude; }
  /// add(−term, magnitude), without forming −term (x − t and x + (−t) round alike).
  void subtract(const S& term, const Size& magnitude) { value_ -= term, size_ += magnitude; }
  const S& value() const { return value_; }
  const Size& size() const { return size_; }
  void set(const S& value, const Size& size) { value_ = value, size_ = size; }

 private:
  S value_ = S(0);
  Size size_ = Size{};
};
/// In double both live in one 16-byte vector (GCC/Clang vector extension).
template <>
class Sized<double> {
  using Pair = double __attribute__((vector_size(16)));

 public:
  void add(double term, double magnitude) { v_ += Pair{term, magnitude}; }
  void subtract(double term, double magnitude) { v_ += Pair{-term, magnitude}; }
  double value() const { return v_[0]; }
  double size() const { return v_[1]; }
  void set(double value, double size) { v_ = Pair{value, size}; }

 private:
  Pair v_ = {0, 0};
};
/// Scratch space of the residual check, kept by a solver between solves so
/// that a solve does not allocate.
template <class S>
struct CheckWorkspace {
  std::vector<Sized<S>> y;     ///< per body: W + u and |W| + |u|
  std::vector<Sized<S>> rows;  ///< per body: the residual of its equation of motion and the sum of |terms|
  std::vector<int> group;      ///< per body: union-find parent over the bodies M and the closed contacts join
  std::vector<Sized<S>> momentum;  ///< per group: Σ m (W − u) and Σ m (|W| + |u|)
  /// per free body: m u, m W and m (W − u), computed once for the energies,
  /// the momenta, the rows of the equations of motion and the groups' balance
  std::vector<S> mu, mw, change;
  /// The union-find after M's joins, which depend only on n and on the
  /// bodies and zero-ness of M's entries: kept with those (entry_key: i, j,
  /// k, l and value ≠ 0 per entry) and reused while the next problem has the
  /// same (a reused solver, a sweep or a map varying values only).
  std::vector<int> entry_key, entry_group;
  int entry_bodies = -1;
};

template <class S>
double to_double(const S& x) {
  return ScalarTraits<S>::to_double(x);
}

/// Fill \p out from W = out.velocities_after (size n, already set) and
/// λ = −R on contacts (\p lambda, 0 where open; \p active marks the contacts
/// solved as closed): gaps, reactions, the case, energies, momentum,
/// dissipation P·X, and the residual check computed from the problem data
/// alone (the declared entries of M, not the solver's matrices):
///   m(W − u) + DᵀMD(W + u) − Cᵀλ = 0 on the free bodies, and complementarity
/// (skipped where \p imposed: the case was imposed, not solved for).
/// Sets out.status to NumericalIssue when a residual exceeds settings.residual
/// or is NaN, when a value of the answer is not finite or the problem's data
/// are not held by S (Problem::in_range),
/// or when A = diag(m) + DᵀMD (\p system, assembled for \p p) is not positive
/// definite in S: the residual check measures a backward error, which a
/// solution of the rounded problem passes even when rounding has made that
/// problem a different one (hard-eps-1e-8.toml in double: A₁₁ = 2e-16
/// exactly, 1e-24 after the O(1) terms of DᵀMD cancel in double; the answer
/// satisfies the rounded equations to 1e-17 and is off by 2e8).
/// Every solver calls this, so every path runs the same checks.
template <class S>
void complete_solution(const Problem<S>& p, ClusterSystem<S>& system, const std::vector<S>& lambda,
                       const std::vector<char>& active, bool imposed, const Settings<S>& settings, CheckWorkspace<S>& work,
                       Solution<S>& out);

/// Whether every value of \p s (velocities, reactions, energies, momenta) is finite.
template <class S>
bool all_finite(const Solution<S>& s);

/// Scale \p s from the units of Problem::scaled(k) to those of the original
/// problem (\p direction = 1) or back (−1): velocities and gaps by
/// 2^±velocity, reactions and momenta by 2^±(mass + velocity), energies and
/// dissipation by 2^±(mass + 2·velocity).  False when some value does not
/// scale exactly (it overflows, or underflows into the subnormals or to 0):
/// S cannot represent that answer.
template <class S>
bool scale_solution(Solution<S>& s, const Scaling& k, int direction);

}  // namespace superball::numeric::detail
