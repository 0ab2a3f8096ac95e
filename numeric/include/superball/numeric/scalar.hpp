#pragma once
/// \file scalar.hpp
/// The scalar types the numeric backend is instantiated with, and what it
/// needs to know of each: double, long double, MPFR floats of N decimal
/// digits (MpFloat, the arithmetic of `digits:N`), CLN floats of N decimal
/// digits (cln::cl_R holding floats of one precision: the reference MpFloat
/// replaced, kept for the tests and benchmarks that compare the two) and CLN
/// exact rationals (cln::cl_RA).  Eigen needs NumTraits for the CLN types and
/// MpFloat; they are here.

#include <cln/floatformat.h>
#include <cln/rational.h>
#include <cln/real.h>

#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <string>
#include <type_traits>
#include "superball/numeric/export.hpp"
#include "superball/numeric/mpfloat.hpp"
SUPERBALL_NUMERIC_API_BEGIN

namespace Eigen {

/// Eigen traits shared by the two CLN types (heap-allocated, slow, exact-ish).
template <class T>
struct ClnNumTraits : GenericNumTraits<T> {
  using Real = T;
  using NonInteger = T;
  using Literal = T;
  using Nested = T;
  enum { IsInteger = 0, IsSigned = 1, IsComplex = 0, RequireInitialization = 1, ReadCost = 20, AddCost = 200, MulCost = 400 };
  static inline int digits10() { return 0; }
};
template <>
struct NumTraits<cln::cl_RA> : ClnNumTraits<cln::cl_RA> {};
template <>
struct NumTraits<cln::cl_R> : ClnNumTraits<cln::cl_R> {};
/// MpFloat: no heap below 114 digits, each operation a call into MPFR.
template <>
struct NumTraits<superball::numeric::MpFloat> : GenericNumTraits<superball::numeric::MpFloat> {
  using Real = superball::numeric::MpFloat;        ///< itself
  using NonInteger = superball::numeric::MpFloat;  ///< itself
  using Literal = superball::numeric::MpFloat;     ///< itself
  using Nested = superball::numeric::MpFloat;      ///< itself
  enum { IsInteger = 0, IsSigned = 1, IsComplex = 0, RequireInitialization = 1, ReadCost = 2, AddCost = 20, MulCost = 30 };
  /// Not a fixed number of digits.
  static inline int digits10() { return 0; }
};

}  // namespace Eigen

namespace superball::numeric {

/// What the solver needs to know about a scalar type \p S.
template <class S>
struct ScalarTraits;

template <>
/// double: IEEE binary64, rounded.
struct ScalarTraits<double> {
  /// Whether S holds exact values (no rounding).
  static constexpr bool exact = false;
  /// The precision's name, as `--precision` spells it.
  static std::string name() { return "double"; }
  /// The value of the exact rational \p r in this type (\p digits is ignored).
  static double from(const cln::cl_RA& r, int digits);
  /// \p x as a double.
  static double to_double(double x) { return x; }
  /// The unit roundoff u of S (\p digits: the decimal digits of a CLN float).
  static double unit_roundoff(int) { return std::numeric_limits<double>::epsilon() / 2; }
  /// The square root of the exact \p square, rounded, into \p out; false when it does not fit in S.
  static bool sqrt(const cln::cl_RA& square, int digits, double& out);
};

template <>
/// long double: x87 extended precision, rounded.
struct ScalarTraits<long double> {
  /// Whether S holds exact values (no rounding).
  static constexpr bool exact = false;
  /// The precision's name, as `--precision` spells it.
  static std::string name() { return "long-double"; }
  /// The value of the exact rational \p r in this type (\p digits is ignored).
  static long double from(const cln::cl_RA& r, int digits);
  /// \p x as a double.
  static double to_double(long double x) { return static_cast<double>(x); }
  /// The unit roundoff u of S.
  static long double unit_roundoff(int) { return std::numeric_limits<long double>::epsilon() / 2; }
  /// The square root of the exact \p square, rounded, into \p out; false when it does not fit in S.
  static bool sqrt(const cln::cl_RA& square, int digits, long double& out);
};

/// The CLN float format of `digits:N`: at least N decimal digits, always a
/// long float of two or more 64-bit words (CLN's own float_format(N) gives
/// single and double floats, with IEEE exponent ranges, below N = 16, and a
/// one-word long float, which CLN's float_epsilon() mishandles, at N = 15 … 17).
/// Throws std::invalid_argument("digits_format(): ...") unless \p digits > 0.
cln::float_format_t digits_format(int digits);

/// CLN floats of \p digits decimal digits (digits_format()), held as
/// cln::cl_R so that the integer constants Eigen creates stay exact and
/// never lower the precision.
template <>
struct SUPERBALL_NUMERIC_EXPORT ScalarTraits<cln::cl_R> {
  /// Whether S holds exact values (no rounding).
  static constexpr bool exact = false;
  /// The precision's name, as `--precision` spells it ("digits", the N apart).
  static std::string name() { return "digits"; }
  /// The value of the exact rational \p r as a CLN float of \p digits decimal digits.
  static cln::cl_R from(const cln::cl_RA& r, int digits);
  /// \p x as a double.
  static double to_double(const cln::cl_R& x);
  /// The unit roundoff u of a CLN float of \p digits decimal digits.
  static cln::cl_R unit_roundoff(int digits);
  /// The square root of the exact \p square at \p digits digits into \p out; false when it cannot be taken.
  static bool sqrt(const cln::cl_RA& square, int digits, cln::cl_R& out);
};

/// The precision in bits of `digits:N` in MpFloat: CLN's for N digits
/// (digits_format(): at least N decimal digits, two 64-bit words or more)
/// less one bit, 127, 191, … (MPFR is fastest below a whole number of
/// words): 127 bits for N <= 37, 191 for N = 50, 383 for N = 100.
/// Throws std::invalid_argument("digits_precision(): ...") unless \p digits > 0.
long digits_precision(int digits);

/// MPFR floats of digits_precision(\p digits) bits: the arithmetic of `digits:N`.
template <>
struct SUPERBALL_NUMERIC_EXPORT ScalarTraits<MpFloat> {
  /// Whether S holds exact values (no rounding).
  static constexpr bool exact = false;
  /// The precision's name, as `--precision` spells it ("digits", the N apart).
  static std::string name() { return "digits"; }
  /// The exact rational \p r correctly rounded to digits_precision(\p digits) bits.
  static MpFloat from(const cln::cl_RA& r, int digits);
  /// \p x as a double (rounded to nearest).
  static double to_double(const MpFloat& x);
  /// The unit roundoff u = 2^−p of p = digits_precision(\p digits) bits (digits:20 when \p digits <= 0).
  static MpFloat unit_roundoff(int digits);
  /// The square root of \p square rounded to the digits' precision, into \p out; always true.
  static bool sqrt(const cln::cl_RA& square, int digits, MpFloat& out);
};

template <>
/// Exact CLN rationals: no rounding at all.
struct SUPERBALL_NUMERIC_EXPORT ScalarTraits<cln::cl_RA> {
  /// Whether S holds exact values (no rounding).
  static constexpr bool exact = true;
  /// The precision's name, as `--precision` spells it.
  static std::string name() { return "exact"; }
  /// \p r itself.
  static cln::cl_RA from(const cln::cl_RA& r, int) { return r; }
  /// \p x as a double (rounded).
  static double to_double(const cln::cl_RA& x);
  /// 0: exact arithmetic does not round.
  static cln::cl_RA unit_roundoff(int) { return 0; }
  /// True only when \p square is the square of a rational.
  static bool sqrt(const cln::cl_RA& square, int digits, cln::cl_RA& out);
};

/// x · 2^k: std::ldexp for double and long double (exact barring overflow
/// and underflow), an exact product for the CLN types.
template <class S>
S times_power_of_two(const S& x, int k) {
  if constexpr (std::is_floating_point<S>::value) {
    return std::ldexp(x, k);
  } else {
    return x * cln::expt(cln::cl_RA(2), k);
  }
}

/// x · 2^k in MpFloat, exact barring overflow.
MpFloat times_power_of_two(const MpFloat& x, int k);

/// Whether \p x is a finite number (always true for the CLN types).
template <class S>
bool finite(const S& x) {
  if constexpr (std::is_floating_point<S>::value) {
    return std::isfinite(x);
  } else {
    (void)x;
    return true;
  }
}

/// Decimal text of \p x with \p significant digits (exact rationals as "p/q";
/// CLN floats with all their digits when \p significant is 0, else rounded
/// exactly as to_decimal() does).
std::string to_string(double x, int significant = 17);
/// to_string(x, significant) appended to \p out, with no text of its own
/// made on the way (the many numbers of a map's output).
void append_to(std::string& out, double x, int significant = 17);
///@{
/// The same for long double, CLN floats and exact rationals.
std::string to_string(long double x, int significant = 21);
std::string to_string(const cln::cl_R& x, int significant = 0);
std::string to_string(const cln::cl_RA& x, int significant = 0);
///@}
/// MpFloat: the fewest digits that read back to \p x when \p significant is
/// 0 (as CLN floats print), else rounded exactly as to_decimal() does.
std::string to_string(const MpFloat& x, int significant = 0);
/// Whether \p x is a number (not infinite, not NaN).
bool finite(const MpFloat& x);
/// The exact value of the finite \p x; throws std::domain_error("rational(): ...") otherwise.
cln::cl_RA rational(const MpFloat& x);

/// \p x rounded to \p significant decimal digits, exactly (round half away
/// from zero), without trailing zeros, in scientific notation when the
/// exponent is below -4 or at least \p significant: "13.41", "-1.741e-05", "20".
std::string to_decimal(const cln::cl_RA& x, int significant);

/// Parse a rational "p/q" or integer written by superball::Number::fraction().
cln::cl_RA parse_rational(const std::string& fraction);

}  // namespace superball::numeric

SUPERBALL_NUMERIC_API_END
