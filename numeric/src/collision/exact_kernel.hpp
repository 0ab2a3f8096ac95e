#pragma once
// Internal: the exact (cln::cl_RA) solve by fraction-free integer elimination.
//
// The collision is homogeneous in the masses and M (degree 1) and in the
// velocities: over common denominators L_m (masses and entries of M) and L_u
// (velocities) the data become integers, m̂ = L_m m, v̂ = L_m v, û = L_u u.
// The system of an evolution case, ZᵀÂZ V = Zᵀb̂ (cluster.hpp), then has
// integer entries and is solved by Bareiss' fraction-free elimination (band
// storage, one exact division per update, by the previous pivot), which gives
// the Cramer numerators X and the determinant d: W = X / (d L_u), and the
// reactions λ = Λ / (L_m d L_u) with Λ the running sums of the integer row
// residuals ÂŴ − d b̂.  No gcd is taken until the answer is written out;
// there the velocities' common factor gcd(d L_u, Ŵ) is taken out first, then
// each fraction is reduced in native integers where they hold it (word by
// word, 64-bit binary gcds; 128 bits; else CLN's division), and CLN makes the
// rational from parts already coprime.
//
// Integers live in 128 bits, computed modulo 2^128, wherever Hadamard's bound
// on the minors of the case's system (and a bound on every later sum and
// product) proves the true values smaller than 2^126; exact divisions there
// multiply by the inverse of the divisor's odd part modulo 2^128.  Otherwise
// the same code runs on CLN integers (cln::cl_I).  The pivoting rules are the
// solvers' own, with the same exact sign decisions, so the cases visited and
// the pivot counts are theirs; the answer is checked exactly (equations of
// motion from the declared entries of M, complementarity) before it is
// written.  Where the kernel declines (NoConvergence, a pivot that is not
// positive, a feasibility tolerance that is not 0, a failed check), the caller
// runs its rational path, which then decides the outcome.

#include <cln/rational.h>

#include "superball/numeric/collision.hpp"

namespace superball::numeric::detail {

/// The pivoting rule whose case sequence the kernel follows.
enum class ExactPivoting {
  Murty,  ///< CollisionSolver: from every contact open, flip the least-index contact of wrong sign (Murty's rule)
  Block   ///< ChainSolver: from every contact closed, flip every wrong sign (Júdice & Pires), Murty after 10 stalls
};

/// Solve \p p exactly by fraction-free integer elimination (see the file
/// comment), following \p rule with at most \p max_iterations pivots or
/// iterations, into \p out: velocities, reactions, gaps, the case, energies,
/// momenta, dissipation, the pivot count, residuals 0 and Status::Success, the
/// same fractions as the rational path.  Returns false, with \p out
/// unspecified, where it declines; the caller then solves in rationals.
/// \p settings must have feasibility 0 (exact sign decisions).
bool exact_integer_solve(const Problem<cln::cl_RA>& p, ExactPivoting rule, int max_iterations,
                         const Settings<cln::cl_RA>& settings, Solution<cln::cl_RA>& out);

}  // namespace superball::numeric::detail
