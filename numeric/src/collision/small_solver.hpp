#pragma once
// Internal: the fixed-size path of CollisionSolver for stacks of at most
// small_max_bodies bodies in double and long double (small_solver.cpp).

#include "superball/numeric/collision.hpp"

namespace superball::numeric::detail {

/// A solve of CollisionSolver's fixed-size path for one number of bodies
/// (problem, bandwidth of DᵀMD, settings, output); false hands the problem
/// over to the general path.
template <class S>
using SmallSolve = bool (*)(const Problem<S>&, int, const Settings<S>&, Solution<S>&);

/// The largest n that CollisionSolver solves on the fixed-size path.
inline constexpr int small_max_bodies = 8;

/// The fixed-size solve for \p n bodies (2 <= n <= small_max_bodies), or
/// nullptr for any other n.  Defined for double and long double.
///
/// The function it returns performs, for a problem of exactly n bodies whose
/// DᵀMD has bandwidth b (what Problem::check() returned), the operations of
/// CollisionSolver::compute() in the same order: the assembly of
/// A = diag(m) + DᵀMD and b̃ in band storage, the case with every contact
/// open by banded LDLᵀ (its gaps are q of w = q + Nλ), Murty's least-index
/// principal pivoting on N = C A⁻¹ Cᵀ (formed by the dense LDLᵀ of A at the
/// first pivot), the answer by clusters of the case found, and the
/// independent residual check of complete_solution() (paper §2–§3).  Every
/// array has its size fixed at compile time (no heap allocation, loops of
/// known length), so the results are those of the general path bit for bit.
/// It returns false, leaving \p out to be overwritten, where the general
/// path takes a branch it does not copy: a pivot of A that is not positive
/// in S, a pivot of the tableau that is not positive, the pivot cap.
template <class S>
SmallSolve<S> small_solver_for(int n);

extern template SmallSolve<double> small_solver_for<double>(int);
extern template SmallSolve<long double> small_solver_for<long double>(int);

}  // namespace superball::numeric::detail
