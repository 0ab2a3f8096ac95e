#pragma once
/// \file polynomial.hpp (private)
/// Small tools on expanded polynomials with rational coefficients.

#include <ginac/ginac.h>

#include <utility>
#include <vector>

#include "superball/symbolic/symbols.hpp"

namespace superball::symbolic::detail {

/// One term c · Π s^e of an expanded polynomial.
struct Term {
  GiNaC::numeric coefficient = 1;
  std::vector<std::pair<GiNaC::ex, int>> powers;  ///< (symbol, exponent > 0)
  GiNaC::ex monomial() const;                     ///< Π s^e
};

/// The terms of the expanded polynomial \p p (none for 0).  Throws
/// std::invalid_argument("terms(): ...") when a term is not a rational
/// coefficient times powers of symbols with positive integer exponents.
std::vector<Term> terms(const GiNaC::ex& p);

/// The determinant of the square matrix \p m of polynomials, expanded
/// (fraction-free: minor expansion for small or sparse matrices, Bareiss's
/// exact-division elimination otherwise, as GiNaC chooses).
GiNaC::ex determinant(const GiNaC::matrix& m);

/// The value of \p p at the point \p point, which must give a number.
/// Throws std::logic_error("evaluate(): ...") otherwise.
GiNaC::numeric evaluate(const GiNaC::ex& p, const GiNaC::exmap& point);

/// Whether every term has a positive coefficient and even powers of the
/// couplings (then p >= 0 for every admissible point).
bool certainly_nonnegative(const GiNaC::ex& p, const Symbols& symbols);

/// A fixed denominator q (det(ZᵀAZ) of a case) prepared for many
/// coprimality tests: for every symbol x of q, a point for the other symbols
/// where the leading coefficient of q in x does not vanish, and q there.
class Denominator {
 public:
  Denominator(const GiNaC::ex& q, const Symbols& symbols);
  /// q, expanded.
  const GiNaC::ex& value() const { return q_; }
  /// Whether gcd(p, q) is a constant, proved by specialisation: for every
  /// symbol x of both, the univariate gcd at the probe point is a constant,
  /// so a common factor cannot involve x (it would keep its degree in x
  /// there, its leading coefficient dividing q's).  False means "not proved".
  bool coprime_with(const GiNaC::ex& p) const;
  /// \p num / q in lowest terms, both expanded: common polynomial factors
  /// cancelled (GiNaC::numer_denom, once, unless coprime_with() proves there
  /// are none) and the common rational content divided out.
  std::pair<GiNaC::ex, GiNaC::ex> lowest_terms(const GiNaC::ex& num) const;

 private:
  struct Probe {
    GiNaC::ex x;
    GiNaC::exmap point;
    GiNaC::ex q_at;  ///< q at the point: a polynomial in x only
  };
  GiNaC::ex q_;
  std::vector<Probe> probes_;
  std::vector<GiNaC::ex> unprobed_;  ///< symbols of q without a usable point
};

}  // namespace superball::symbolic::detail
