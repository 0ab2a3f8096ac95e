#pragma once
/// \file certify.hpp
/// Certified results (`--precision auto`): an a-posteriori bound on the
/// error of a floating-point solution with respect to the exact solution of
/// the exact scene, and the escalation double → long double → exact.
///
/// The bound.  For the case S of the solution, closed contacts tie bodies
/// into clusters (Z the cluster incidence) and the velocities solve
/// R V = Zᵀ b̃ with R = Zᵀ(diag(m) + DᵀMD)Z ⪰ Zᵀ diag(m) Z, so
/// ‖R⁻¹‖₂ ≤ 1 / (smallest free cluster mass).  With ρ the exact residual of
/// the computed V̂ (row residuals of the equations of motion summed over each
/// cluster), ‖V − V̂‖∞ ≤ ‖ρ‖₂ / m_cluster,min =: E.  ρ is evaluated in the
/// solve's arithmetic from the rounded data; the data rounding and the
/// evaluation rounding add at most γ·Σ|terms| per row, γ = 4(b + 4)u (b the
/// bandwidth of DᵀMD, u the unit roundoff), which the bound includes.  The
/// case is certain when every open contact's gap exceeds 2E and every closed
/// contact's reaction exceeds its own bound (its running sum of row bounds).
/// With a fixed obstacle, E is at least u·|u_n|: the bodies it carries move
/// with its velocity as rounded to S.

#include <string>
#include <vector>

#include "superball/numeric/collision.hpp"
#include "superball/numeric/precision.hpp"
#include "superball/numeric/export.hpp"
SUPERBALL_NUMERIC_API_BEGIN

namespace superball::numeric {

/// What certify() proved about a floating-point solution.
struct Certificate {
  bool case_certain = false;   ///< the evolution case is that of the exact solution
  double velocity_error = 0;   ///< bound on max_i |U_i⁺ − exact U_i⁺| (solver units), rounded up to a double
  double relative_error = 0;   ///< velocity_error / max_i |U_i⁺|
};

/// Bound the error of \p solution of \p problem (see the file comment).
/// Defined for double, long double and CLN floats (digits:N, with u their
/// unit roundoff at Problem::digits).  Nothing is certain (case_certain
/// false) when the status is not Success, a value of the solution is not
/// finite, or the data are not held by S or fit no scaling (Problem::in_range,
/// Scaling::fits); data outside the safe window are certified in the units
/// of the scaled problem that solve() solves.
template <class S>
Certificate certify(const Problem<S>& problem, const Solution<S>& solution);

/// Why an answer of an explicitly chosen arithmetic (`--precision double`,
/// `long-double`, `digits:N`) cannot be trusted, by the certificate `auto`
/// certifies with: one line when \p solution has status Success and certify()
/// does not prove its evolution case, or proves it only with a velocity bound
/// at least as large as the velocities (relative error >= 1); none otherwise,
/// and none in exact arithmetic.  An answer with another status is declined
/// by its status already.  Each line names the arithmetic and suggests
/// `--precision auto` or `exact`.
template <class S>
std::vector<std::string> trust_warnings(const Problem<S>& problem, const Solution<S>& solution);

/// The outcome of `--precision auto`.
struct AutoChoice {
  Precision precision;               ///< the arithmetic whose result is certified
  double relative_error = 0;         ///< its bound (0 for exact)
  std::vector<std::string> tried;    ///< e.g. {"double: case not certain", "exact"}
};

/// Solve \p scene in double, then long double, then exact rationals, and
/// stop at the first whose case is certain and whose velocity bound is at
/// most \p rtol (relative to the largest velocity).  Exact always qualifies.
/// Throws std::invalid_argument (SolvePrecision::check()) unless 0 <= rtol <= 1
/// (NaN included).
AutoChoice choose_precision(const ExactScene& scene, double rtol);

///@{
/// The explicit instantiations of certify() and trust_warnings() compiled into
/// the library, one per scalar type (certify() has none for exact rationals:
/// an exact solution needs no certificate).
extern template SUPERBALL_NUMERIC_EXPORT Certificate certify(const Problem<double>&, const Solution<double>&);
extern template SUPERBALL_NUMERIC_EXPORT Certificate certify(const Problem<long double>&, const Solution<long double>&);
extern template SUPERBALL_NUMERIC_EXPORT Certificate certify(const Problem<cln::cl_R>&, const Solution<cln::cl_R>&);
extern template SUPERBALL_NUMERIC_EXPORT Certificate certify(const Problem<MpFloat>&, const Solution<MpFloat>&);
extern template SUPERBALL_NUMERIC_EXPORT std::vector<std::string> trust_warnings(const Problem<double>&, const Solution<double>&);
extern template SUPERBALL_NUMERIC_EXPORT std::vector<std::string> trust_warnings(const Problem<long double>&, const Solution<long double>&);
extern template SUPERBALL_NUMERIC_EXPORT std::vector<std::string> trust_warnings(const Problem<cln::cl_R>&, const Solution<cln::cl_R>&);
extern template SUPERBALL_NUMERIC_EXPORT std::vector<std::string> trust_warnings(const Problem<MpFloat>&, const Solution<MpFloat>&);
extern template SUPERBALL_NUMERIC_EXPORT std::vector<std::string> trust_warnings(const Problem<cln::cl_RA>&, const Solution<cln::cl_RA>&);
///@}

}  // namespace superball::numeric

SUPERBALL_NUMERIC_API_END
