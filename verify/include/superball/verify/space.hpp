#pragma once
/// \file space.hpp
/// The parameter space of a pattern as plain data, for the code that samples
/// and searches it (the audit, `verify`, `explore`): its coordinates (the
/// pattern's symbols: masses, K's, couplings, the fall speed a), polynomials
/// in them compiled out of GiNaC, the exact collision problem and the scene
/// at a point, and the random points of the paper's asymptotic regime.
///
/// Nothing here holds a GiNaC object once built, and clone() gives a copy
/// that shares no CLN object with the original: GiNaC and CLN count
/// references without atomics, so parallel code gives each thread its own
/// clone and never shares a number.

#include <cln/rational.h>
#include <ginac/ginac.h>

#include <cstdint>
#include <optional>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "superball/cases/model.hpp"
#include "superball/cases/number.hpp"
#include "superball/numeric/collision.hpp"
#include "superball/numeric/problem.hpp"
#include "superball/symbolic/derivation.hpp"
#include "superball/verify/export.hpp"
SUPERBALL_VERIFY_API_BEGIN

namespace superball::verify {

/// A point of the parameter space: one exact value per coordinate.
using Point = std::vector<cln::cl_RA>;

/// An expanded polynomial in the coordinates, evaluated without GiNaC.
class Polynomial {
 public:
  Polynomial() = default;
  /// Compile \p p, a polynomial in the symbols of \p symbols.  Throws
  /// std::invalid_argument("Polynomial::Polynomial(): ...") otherwise.
  Polynomial(const GiNaC::ex& p, const symbolic::Symbols& symbols);

  /// The exact value at \p x (one value per coordinate).
  cln::cl_RA operator()(const Point& x) const;
  /// The value in double at \p x (coefficients rounded once).
  double operator()(const std::vector<double>& x) const;
  /// The sign of the exact value at \p x: −1, 0 or 1.  Decided in double
  /// where that is a proof: each term c·∏ x_k^e is computed from the
  /// coordinates and the coefficient rounded to double (each within 2u of
  /// its exact value, u = 2⁻⁵³) by E = Σe products (each within u), so
  /// within γ(2 + 3E) of its exact value, where γ(k) = ku/(1 − ku); the
  /// sum of T terms adds γ(T − 1)·Σ|t̃|.  Where |Σ t̃| exceeds twice the sum
  /// of the two bounds (and no product leaves [2⁻¹⁰⁰⁰, 2¹⁰⁰⁰]), its sign is
  /// the exact one; elsewhere (near a zero of the polynomial) the exact value
  /// decides.  The same answer as the sign of operator()(x), faster.
  int sign(const Point& x) const;
  /// Whether it is the zero polynomial.
  bool is_zero() const { return terms_.empty(); }
  /// A copy sharing no CLN object with this one (for another thread).
  Polynomial clone() const;

 private:
  struct Term {
    cln::cl_RA coefficient;
    double approx = 0;
    std::vector<std::pair<int, int>> powers;  ///< (coordinate, exponent)
  };
  std::vector<Term> terms_;
  std::vector<int> used_;  ///< the coordinates the terms use, increasing
  int degree_ = 0;         ///< the largest Σe of a term
  bool filter_ = true;     ///< sign() may decide in double (exponents ≥ 0, coefficients normal doubles)
  void prepare();          ///< used_, degree_ and filter_ from terms_
};

/// A condition "numerator / denominator REL 0" (symbolic::ConditionForm) compiled.
struct CompiledCondition {
  /// The kind of the condition compiled.
  symbolic::ConditionKind kind = symbolic::ConditionKind::Superball;
  std::string about;      ///< as in symbolic::Condition
  bool strict = true;     ///< > (else >=)
  /// The numerator, over the coordinates.
  Polynomial numerator;
  Polynomial denominator; ///< the zero polynomial stands for 1 (sign proved and cleared)

  /// Compile \p form of \p condition.
  CompiledCondition(const symbolic::Condition& condition, const symbolic::ConditionForm& form, const symbolic::Symbols& symbols);
  /// Whether the condition holds exactly at \p x (false where the denominator vanishes).
  bool holds(const Point& x) const;
  /// The signed value numerator/denominator at \p x in double (NaN where the
  /// denominator vanishes): > 0 (>= 0) where the condition holds.
  double value(const std::vector<double>& x) const;
  /// A copy sharing no CLN object with this one.
  CompiledCondition clone() const;

 private:
  CompiledCondition() = default;
};

/// One coordinate of the space: a symbol of the pattern, as plain data.
struct Coordinate {
  /// What the coordinate stands for: a mass, a diagonal K, a coupling, the fall speed.
  symbolic::SymbolKind kind = symbolic::SymbolKind::Mass;
  ///@{
  /// The names in ASCII and in text (m1, K12, alpha2, c_12_14, a).
  std::string ascii, text;   ///< names (m1, K12, alpha2, c_12_14, a)
  ///@}
  int body = 0;              ///< Mass: the body, 1-based
  ///@{
  /// Diagonal: first == second; Coupling: the two pairs.
  Pair first, second;        ///< Diagonal: first == second; Coupling: the two pairs
  ///@}
  int order = 0;             ///< the parameter behaves like ε^order in the regime
  int first_diagonal = -1;   ///< Coupling: the coordinate of K_first (-1 when not declared)
  int second_diagonal = -1;  ///< Coupling: the coordinate of K_second
};

/// Largest |order| in ε of a coordinate that sampling takes (ParameterSpace
/// refuses a scaling beyond it; RegimeSampler refuses an ε whose power
/// leaves the numbers a scene holds).
inline constexpr int max_sampling_order = max_decimal_exponent;

/// The parameters of a pattern (symbolic::Symbols, in the same order) and
/// the positive semi-definiteness of M on them (paper §3).
class ParameterSpace {
 public:
  /// The coordinates of \p deriver's symbols, their orders in ε from its
  /// scaling (integers), the PSD minors from Deriver::psd().  Throws
  /// std::invalid_argument("ParameterSpace::ParameterSpace(): ...") for a
  /// non-integer order or one beyond ±max_sampling_order.
  explicit ParameterSpace(const symbolic::Deriver& deriver);

  /// The coordinates, in the pattern's printing order.
  const std::vector<Coordinate>& coordinates() const { return coordinates_; }
  /// The number of coordinates.
  int size() const { return static_cast<int>(coordinates_.size()); }
  /// The number of bodies n.
  int bodies() const { return bodies_; }
  /// True when body n is a fixed obstacle (infinite mass).
  bool fixed_bottom() const { return fixed_bottom_; }
  /// The coordinate of the fall speed a.
  int fall_speed() const { return fall_speed_; }
  /// The coordinate called \p ascii; throws std::invalid_argument("ParameterSpace::index(): ...").
  int index(const std::string& ascii) const;

  /// Whether \p x is admissible: masses, K's and a > 0 and M positive
  /// semi-definite (every PSD minor of the pattern >= 0, exactly).
  bool admissible(const Point& x) const;
  /// The collision at \p x for the numeric backend: bodies 1..n−1 fall at −a,
  /// the bottom body is at rest (fixed when the obstacle is infinite);
  /// velocities in m/s (unit 1).
  numeric::Problem<cln::cl_RA> problem(const Point& x) const;
  /// The scene file of \p x (`superball solve` reproduces problem(x)).
  Scene scene(const Point& x, const std::string& title) const;
  /// (ASCII name, value) of every coordinate.
  std::vector<std::pair<std::string, cln::cl_RA>> named(const Point& x) const;
  /// A copy sharing no CLN object with this one (for another thread).
  ParameterSpace clone() const;

 private:
  ParameterSpace() = default;
  std::vector<Coordinate> coordinates_;
  std::vector<Polynomial> psd_;
  int bodies_ = 0, fall_speed_ = -1;
  bool fixed_bottom_ = true;
};

/// Random points of the paper's asymptotic regime (§4: m₁ small, K₁ₙ and
/// m_n large): every coordinate is an O(1) value times ε^order — masses in
/// 0.1..30, K's in 0.1..20, a in 1..5 (steps of 0.1), couplings in
/// [−b, b] (steps of b/20) with b = min(20, √(K_p K_q)/ε^order) so the 2×2
/// minors hold — and a point is kept only when M is positive semi-definite.
class RegimeSampler {
 public:
  /// \p epsilon in (0, 1); the points are a function of \p seed only.
  /// Throws std::invalid_argument("RegimeSampler::RegimeSampler(): ...")
  /// otherwise, or when \p epsilon to the largest |order| of the space is
  /// below 10^-(max_decimal_exponent − 2) (values no scene holds).
  RegimeSampler(const ParameterSpace& space, const cln::cl_RA& epsilon, std::uint64_t seed);
  /// An admissible point, or nullopt when 1000 draws in a row were not.
  std::optional<Point> draw();

 private:
  Point candidate();
  const ParameterSpace& space_;
  cln::cl_RA epsilon_;
  std::mt19937_64 rng_;
};

/// What the exact solution \p forced of the case (numeric compute_case at
/// the point of \p problem) says about the condition (\p kind, \p about) of
/// that case: U₁⁺ > a (superball), U_i⁺ > U_j⁺ (evolution of the open
/// contact i-j), R_ij <= 0 (contact).  \p quantity receives the decided
/// quantity, e.g. "R2_3 = -13/7".  Throws std::invalid_argument(
/// "condition_truth(): ...") for a PSD condition (not a property of the solution).
bool condition_truth(symbolic::ConditionKind kind, const std::string& about, const numeric::Problem<cln::cl_RA>& problem,
                     const numeric::Solution<cln::cl_RA>& forced, std::string* quantity = nullptr);

/// A copy of \p x that shares no heap object with it (a CLN copy shares its
/// bignum and counts the reference without atomics): for another thread.
cln::cl_RA deep_copy(const cln::cl_RA& x);
/// The same for every value of a point.
Point deep_copy(const Point& x);

/// Exact decimal-free spelling of a rational ("-13/7").
std::string to_string(const cln::cl_RA& x);

}  // namespace superball::verify

SUPERBALL_VERIFY_API_END
