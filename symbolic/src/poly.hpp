#pragma once
/// \file poly.hpp (private)
/// A sparse polynomial with integer coefficients in the symbols of one
/// pattern, for the heavy arithmetic of a derivation (determinants, Cramer
/// numerators, reactions, the substitution check, term classification).
///
/// Why not GiNaC::ex: a derivation multiplies polynomials of thousands of
/// terms by small matrix entries and adds them up, and GiNaC's expand()
/// rebuilds and re-sorts sums of expression trees at every step; measured on
/// `derive --bodies 6 --pairs near2 --coupling near2 --all`, expand() was 64 %
/// of the run (docs/SYMBOLIC.md, "Representation").  Here a term is a packed
/// exponent vector (8 bits a symbol, 8 symbols a 64-bit word) and a CLN
/// integer; sums are merges of sorted term lists, products accumulate in a
/// hash table.  Results go back to GiNaC (to_ex()) once, for the public types.

#include <cln/integer.h>
#include <ginac/ginac.h>

#include <cstdint>
#include <string>
#include <vector>

#include "superball/symbolic/symbols.hpp"

namespace superball::symbolic::detail {

/// A polynomial in the symbols x_0 … x_{V−1} of a Symbols (x_k = Symbols::all()[k]),
/// with integer coefficients.  Terms are kept sorted (lexicographic on the
/// exponent vector, x_0 first, descending) without zero coefficients, so two
/// polynomials are equal exactly when their term lists are.
class Poly {
 public:
  /// The zero polynomial in \p vars symbols.
  explicit Poly(int vars = 0);
  /// The constant \p c.
  static Poly constant(int vars, const cln::cl_I& c);
  /// The symbol x_k.
  static Poly variable(int vars, int k);
  /// The expanded polynomial \p p (integer coefficients) in \p symbols.  Throws
  /// std::invalid_argument("Poly::from_ex(): ...") for a non-integer coefficient
  /// or an exponent above max_exponent.
  static Poly from_ex(const GiNaC::ex& p, const Symbols& symbols);

  /// Exponents must stay at or below this (8 bits a symbol, one spare bit to detect overflow).
  static constexpr int max_exponent = 127;

  int vars() const { return vars_; }
  std::size_t size() const { return coef_.size(); }
  bool is_zero() const { return coef_.empty(); }
  /// Whether the polynomial is a constant (zero included).
  bool is_constant() const;

  /// Coefficient of term \p t.
  const cln::cl_I& coefficient(std::size_t t) const { return coef_[t]; }
  /// Exponent of x_k in term \p t.
  int exponent(std::size_t t, int k) const;
  /// Highest exponent of x_k over the terms (0 for the zero polynomial).
  int degree(int k) const;
  /// Whether x_k occurs.
  bool has(int k) const { return degree(k) > 0; }

  Poly operator-() const;
  Poly operator+(const Poly& q) const;
  Poly operator-(const Poly& q) const;
  Poly operator*(const Poly& q) const;
  Poly& operator+=(const Poly& q) { return *this = *this + q; }
  Poly& operator-=(const Poly& q) { return *this = *this - q; }
  /// The polynomial times the integer \p c.
  Poly scaled(const cln::cl_I& c) const;
  bool operator==(const Poly& q) const;
  bool operator!=(const Poly& q) const { return !(*this == q); }

  /// The gcd of the coefficients (0 for the zero polynomial), positive.
  cln::cl_I content() const;
  /// The polynomial divided term by term by the integer \p c, which must divide every coefficient.
  Poly divided(const cln::cl_I& c) const;

  /// The exponent of each symbol in the gcd of the terms' monomials (all 0 for the zero polynomial).
  std::vector<int> common_exponents() const;
  /// The polynomial divided by the monomial Π x_k^e[k], which must divide every term.
  Poly divided_by_monomial(const std::vector<int>& e) const;
  /// The leading coefficient in x_k: the terms of highest degree in x_k, with x_k removed.
  Poly leading_coefficient(int k) const;
  /// The coefficient of x_k^d: the terms of degree d in x_k, with x_k removed.
  Poly coefficient_of(int k, int d) const;
  /// The polynomial times x_k^d.
  Poly times_power(int k, int d) const;
  /// The terms whose indices are listed (ascending).
  Poly subset(const std::vector<std::size_t>& terms) const;

  /// The value with x_k = point[k] for every k except \p keep, as the
  /// coefficients c_0 … c_d of a polynomial in x_keep.
  std::vector<cln::cl_I> univariate(int keep, const std::vector<cln::cl_I>& point) const;
  /// univariate() modulo the prime 2⁶¹ − 1 (\p point already reduced):
  /// coefficients c_0 … c_d in [0, 2⁶¹ − 1), trailing zeros dropped.
  std::vector<std::uint64_t> univariate_mod(int keep, const std::vector<std::uint64_t>& point) const;
  /// The polynomial on the line x = a + b·t, modulo the prime 2⁶¹ − 1
  /// (\p a, \p b already reduced, one entry a symbol): the coefficients
  /// c_0 … c_d of p(a + b·t) in [0, 2⁶¹ − 1), trailing zeros dropped.
  std::vector<std::uint64_t> on_line_mod(const std::vector<std::uint64_t>& a, const std::vector<std::uint64_t>& b) const;
  /// The total degree: the largest sum of exponents over the terms (0 for the zero polynomial).
  int total_degree() const;
  /// The value at \p point (one integer a symbol).
  cln::cl_I evaluate(const std::vector<cln::cl_I>& point) const;
  /// The value at \p point modulo the prime 2⁶¹ − 1 (\p point already reduced).
  std::uint64_t evaluate_mod(const std::vector<std::uint64_t>& point) const;

  /// The same polynomial as a GiNaC expression in \p symbols (an add of
  /// products, built without re-expanding).
  GiNaC::ex to_ex(const Symbols& symbols) const;

  /// Appends the polynomial to \p out in a compact binary form (its packed
  /// exponents and coefficients), read back by read(), for a polynomial that
  /// crosses processes (Deriver::prepare()).
  void write(std::string& out) const;
  /// The polynomial write() put at \p at in \p in, in \p vars symbols;
  /// \p at moves past it.  Throws std::invalid_argument("Poly::read(): ...")
  /// on a truncated or malformed record.
  static Poly read(const std::string& in, std::size_t& at, int vars);

 private:
  int vars_ = 0, words_ = 0;
  std::vector<std::uint64_t> mono_;  ///< size() × words_ packed exponents
  std::vector<cln::cl_I> coef_;
  const std::uint64_t* mono(std::size_t t) const { return mono_.data() + t * static_cast<std::size_t>(words_); }
  void push(const std::uint64_t* m, const cln::cl_I& c);
  /// Calls f(k, e) for each symbol x_k of term \p t with its exponent e > 0,
  /// reading the packed words (a term has few symbols, most bytes are 0),
  /// until f returns false.
  template <class F>
  void for_each_power(std::size_t t, F f) const;
  /// The product with \p q of few terms, as a merge of this polynomial's terms shifted by each of q's.
  Poly times_small(const Poly& q) const;
  friend Poly from_terms(int vars, std::vector<std::uint64_t>&& mono, std::vector<cln::cl_I>&& coef);
};

/// Arithmetic modulo the Mersenne prime 2⁶¹ − 1, for the fast coprimality proof (polynomial.hpp).
namespace mod61 {
constexpr std::uint64_t prime = (std::uint64_t{1} << 61) - 1;
/// \p x reduced into [0, prime).
std::uint64_t reduce(const cln::cl_I& x);
std::uint64_t multiply(std::uint64_t a, std::uint64_t b);
std::uint64_t add(std::uint64_t a, std::uint64_t b);
/// a − b.
std::uint64_t subtract(std::uint64_t a, std::uint64_t b);
/// 1 / a, for a ≠ 0.
std::uint64_t inverse(std::uint64_t a);
/// The degree of gcd(a, b) of two polynomials modulo the prime (coefficients low to high,
/// no trailing zeros, neither zero).
int gcd_degree(std::vector<std::uint64_t> a, std::vector<std::uint64_t> b);
}  // namespace mod61

/// det of the square matrix \p m of polynomials (row-major, \p n × \p n, n ≤ max_moving_clusters):
/// Laplace expansion along the rows with every minor of the bottom rows
/// memoised by its column set; zero entries (the band of a banded matrix)
/// are skipped, so a banded matrix costs a few products per minor.
Poly determinant(const std::vector<Poly>& m, int n, int vars);

}  // namespace superball::symbolic::detail
