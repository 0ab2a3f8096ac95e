#pragma once
/// \file polynomial.hpp (private)
/// Small tools on expanded polynomials with rational coefficients.

#include <ginac/ginac.h>

#include <utility>
#include <vector>

#include "poly.hpp"
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
/// coprimality tests: for every symbol x of q, an integer point for the other
/// symbols where the leading coefficient of q in x does not vanish, and q there.
class Denominator {
 public:
  /// \p probe false: no probe points (coprime_with() is then not to be
  /// called; lowest_terms() is told whether a numerator is coprime).
  Denominator(const Poly& q, const Symbols& symbols, bool probe = true);
  /// q.
  const Poly& poly() const { return q_; }
  /// q as a GiNaC expression.
  const GiNaC::ex& value() const;
  /// The sign (−1, 0, 1) of q at reference_point() (masses, K's, a = 1, couplings 0).
  int sign_at_reference() const { return sign_; }
  /// Whether gcd(p, q) is a constant, proved by specialisation.  First on
  /// one line x = a + b·t modulo the prime ℓ = 2⁶¹ − 1: a common factor g
  /// (q = g·h) has top homogeneous part g_top dividing q's, so when
  /// q_top(b) ≢ 0 (mod ℓ), g(a + b·t) keeps the degree of g and divides
  /// both p(a + b·t) and q(a + b·t); their gcd of degree 0 modulo ℓ proves
  /// g constant (one pass over p's terms).  When that does not prove it:
  /// for every symbol x of both, the univariate gcd at a probe point is a
  /// constant, so a common factor cannot involve x (it would keep its degree
  /// in x there, its leading coefficient dividing q's), modulo ℓ first, over
  /// the integers only where q's leading coefficient vanishes modulo ℓ.
  /// False means "not proved".  Not thread-safe (the probe points are made
  /// on first need).
  bool coprime_with(const Poly& p) const;

  /// A fraction p / q in lowest terms.
  struct Reduced {
    GiNaC::ex numerator, denominator;  ///< expanded, the common rational content divided out
    bool whole = false;                ///< the denominator is q / content (no polynomial factor cancelled)
    cln::cl_I content = 1;             ///< when whole: numerator = p / content, denominator = q / content
  };
  /// \p num / q in lowest terms: common polynomial factors cancelled
  /// (GiNaC::numer_denom, once, unless coprime_with() proves there are none)
  /// and the common rational content divided out.
  /// \p with_numerator false leaves Reduced::numerator unset when whole
  /// (the caller keeps num / content as a Poly).  \p coprime: what
  /// coprime_with(num) answers, when already known (Deriver::prepare()).
  Reduced lowest_terms(const Poly& num, bool with_numerator = true, const bool* coprime = nullptr) const;

 private:
  struct Probe {
    int x = 0;                    ///< index of the symbol kept
    std::vector<cln::cl_I> point; ///< one integer a symbol (x's entry unused)
    GiNaC::ex q_at;               ///< q at the point: a polynomial in x only
    std::vector<std::uint64_t> point_mod, q_mod;  ///< the same modulo 2⁶¹ − 1 (q_mod empty when its leading coefficient vanishes there)
  };
  /// The probes of coprime_with()'s second test, made on first need.
  void make_probes() const;
  const Symbols* symbols_;
  Poly q_;
  bool probe_ = true;
  std::vector<std::uint64_t> line_a_, line_b_, line_q_;  ///< the line and q on it modulo ℓ (line_q_ empty: q_top(b) ≡ 0, not used)
  mutable GiNaC::ex q_ex_;      ///< q as GiNaC, made on first use
  mutable bool have_ex_ = false;
  int sign_ = 0;
  mutable bool probed_ = false;
  mutable std::vector<Probe> probes_;
  mutable std::vector<int> unprobed_;  ///< symbols of q without a usable point
};

}  // namespace superball::symbolic::detail
