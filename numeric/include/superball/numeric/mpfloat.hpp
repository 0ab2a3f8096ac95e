#pragma once
/// \file mpfloat.hpp
/// MpFloat: the scalar of `digits:N`, a binary floating-point number of a
/// precision chosen at run time, correctly rounded to nearest as MPFR rounds:
/// computed by MPFR, except sums, differences and products of 2 to 6 words,
/// quotients of 3 to 6 words, scalings by a constant ±2^k, sums and
/// differences with a zero, and comparisons, which numeric/src/mpfloat.cpp
/// computes on the words with the same results bit for bit.  This header does not include mpfr.h: the number holds MPFR's
/// variable by value, with its significand in the object itself up to
/// MpFloat::inline_limbs 64-bit words (N <= 113 digits), so that a solve in
/// that precision allocates nothing; larger precisions keep it on the heap.
///
/// Every value carries its precision.  A result is rounded to the larger
/// precision of its operands; integers and doubles convert exactly (at 64
/// bits), as CLN's exact integers did, so that the constants of the solver
/// never lower the precision of the data.

#include <cstdint>
#include "superball/numeric/export.hpp"
SUPERBALL_NUMERIC_API_BEGIN

namespace superball::numeric {

/// A floating-point number of run-time precision (MPFR), round to nearest.
class SUPERBALL_NUMERIC_EXPORT MpFloat {
 public:
  /// Significand words held in the object; more go to the heap.
  static constexpr int inline_limbs = 6;

  /// +0 (64 bits).
  MpFloat() noexcept : raw_{kIntegerBits, 1, kZeroExp, limbs_} {}
  ///@{
  /// \p x exactly (64 bits), without a call into MPFR.
  MpFloat(long x) noexcept : raw_{kIntegerBits, x < 0 ? -1 : 1, kZeroExp, limbs_} {  // NOLINT(google-explicit-constructor): a number, as double's
    if (x == 0) return;
    const unsigned long m = x < 0 ? 0ul - static_cast<unsigned long>(x) : static_cast<unsigned long>(x);
    const int shift = __builtin_clzl(m);
    limbs_[0] = m << shift;  // normalised: the top bit set
    raw_.exp = 64 - shift;   // x = 0.limb × 2^exp
  }
  MpFloat(int x) noexcept : MpFloat(static_cast<long>(x)) {}  // NOLINT(google-explicit-constructor)
  MpFloat(long long x) noexcept : MpFloat(static_cast<long>(x)) {}  // NOLINT(google-explicit-constructor)
  MpFloat(double x) noexcept;  // NOLINT(google-explicit-constructor)
  ///@}
  /// +0 with a precision of \p bits (at least 2).
  static MpFloat zero(long bits);
  ///@{
  /// Copies take the precision of the source; moves steal a heap significand.
  MpFloat(const MpFloat& other) : raw_{other.raw_.prec, other.raw_.sign, other.raw_.exp, limbs_} {
    if (words(raw_.prec) > inline_limbs) grow(raw_.prec);
    copy_significand(other);
  }
  MpFloat(MpFloat&& other) noexcept;
  MpFloat& operator=(const MpFloat& other) {
    if (words(other.raw_.prec) > capacity_) grow(other.raw_.prec);
    raw_.prec = other.raw_.prec, raw_.sign = other.raw_.sign, raw_.exp = other.raw_.exp;
    copy_significand(other);
    return *this;
  }
  MpFloat& operator=(MpFloat&& other) noexcept {
    if (other.raw_.d == other.limbs_ || capacity_ >= other.capacity_) {  // room enough: a copy
      if (this != &other) *this = static_cast<const MpFloat&>(other);
      return *this;
    }
    return steal(other);
  }
  ///@}
  /// Frees a heap significand.
  ~MpFloat() {
    if (raw_.d != limbs_) release();
  }

  /// Whether the value is ±0.
  bool is_zero() const { return raw_.exp == kZeroExp; }
  /// Whether \p x is ±0 or a regular number (not NaN, not ±inf).
  static bool zero_or_regular(const MpFloat& x) { return x.raw_.exp == kZeroExp || x.raw_.exp > kInfExp; }
  /// The precision in bits.
  long precision() const { return raw_.prec; }
  /// x = m·2^e with 1/2 ≤ |m| < 1, as std::frexp: m is x's leading word
  /// rounded to a double (within one unit of its last place, 2⁻⁵³|m|) and e
  /// any exponent MPFR holds; ±0 gives ±0 and e = 0, NaN and ±∞ give
  /// themselves.  A magnitude for sizes and ratios, not a rounding of x.
  friend double frexp(const MpFloat& x, long* e) {
    *e = 0;
    const double sign = x.raw_.sign < 0 ? -1.0 : 1.0;
    if (x.raw_.exp == kZeroExp) return sign * 0.0;
    if (x.raw_.exp <= kInfExp) return x.raw_.exp == kInfExp ? sign * __builtin_inf() : __builtin_nan("");
    const double top = static_cast<double>(x.raw_.d[words(x.raw_.prec) - 1]) * 0x1p-64;  // in [1/2, 1]
    *e = x.raw_.exp + (top == 1.0 ? 1 : 0);  // a word of 64 ones rounds up to 1 = (1/2)·2
    return sign * (top == 1.0 ? 0.5 : top);
  }

  ///@{
  /// Arithmetic in place, rounded to the larger precision of the two.
  MpFloat& operator+=(const MpFloat& x);
  MpFloat& operator-=(const MpFloat& x);
  MpFloat& operator*=(const MpFloat& x);
  MpFloat& operator/=(const MpFloat& x);
  ///@}

  /// The layout of MPFR's __mpfr_struct (checked in mpfloat.cpp).
  struct Raw {
    long prec;          ///< mpfr_prec_t
    int sign;           ///< mpfr_sign_t
    long exp;           ///< mpfr_exp_t
    std::uint64_t* d;   ///< mp_limb_t*, the significand
  };
  /// MPFR's variable (an mpfr_ptr once cast; numeric/src only).
  Raw* raw() { return &raw_; }
  /// MPFR's variable, read only (an mpfr_srcptr once cast; numeric/src only).
  const Raw* raw() const { return &raw_; }

 private:
  static constexpr long kIntegerBits = 64;  ///< holds every long and double exactly
  static constexpr long kZeroExp = -0x7fffffffffffffffL;  ///< MPFR's exponent of ±0 (checked in mpfloat.cpp)
  static constexpr long kInfExp = kZeroExp + 2;           ///< of ±inf; NaN's is between: regular numbers' are above
  static constexpr long words(long bits) { return (bits + 63) / 64; }
  struct Uninitialised {};
  MpFloat(Uninitialised, long bits);
  void grow(long bits);  ///< a heap significand of room for \p bits (the value is lost)
  void release();        ///< frees the heap significand
  MpFloat& steal(MpFloat& other) noexcept;  ///< takes \p other's heap significand, larger than ours
  /// The significand of \p other into ours (room made): only a regular number has one.
  void copy_significand(const MpFloat& other) {
    if (raw_.exp <= kInfExp) return;
    for (long k = 0, n = words(raw_.prec); k < n; ++k) raw_.d[k] = other.raw_.d[k];
  }

  Raw raw_;
  int capacity_ = inline_limbs;  ///< words d can hold
  std::uint64_t limbs_[inline_limbs];
};

///@{
/// Arithmetic, rounded to the larger precision of the operands.
SUPERBALL_NUMERIC_EXPORT MpFloat operator+(const MpFloat& a, const MpFloat& b);
SUPERBALL_NUMERIC_EXPORT MpFloat operator-(const MpFloat& a, const MpFloat& b);
SUPERBALL_NUMERIC_EXPORT MpFloat operator*(const MpFloat& a, const MpFloat& b);
SUPERBALL_NUMERIC_EXPORT MpFloat operator/(const MpFloat& a, const MpFloat& b);
/// −a, exact.
inline MpFloat operator-(const MpFloat& a) {
  MpFloat r = a;
  r.raw()->sign = -r.raw()->sign;
  return r;
}
/// √x, rounded to the precision of \p x.
SUPERBALL_NUMERIC_EXPORT MpFloat sqrt(const MpFloat& x);
/// |x|, exact.
inline MpFloat abs(const MpFloat& x) {
  MpFloat r = x;
  r.raw()->sign = 1;
  return r;
}
///@}
///@{
/// Comparisons (false when either is NaN, as for double).
SUPERBALL_NUMERIC_EXPORT bool operator==(const MpFloat& a, const MpFloat& b);
SUPERBALL_NUMERIC_EXPORT bool operator!=(const MpFloat& a, const MpFloat& b);
/// a < b in general (operator< decides comparisons with ±0 inline).
SUPERBALL_NUMERIC_EXPORT bool less(const MpFloat& a, const MpFloat& b);
/// a < b; against a zero, from the sign of a regular number.
inline bool operator<(const MpFloat& a, const MpFloat& b) {
  if (MpFloat::zero_or_regular(a) && MpFloat::zero_or_regular(b)) {
    if (b.is_zero()) return !a.is_zero() && a.raw()->sign < 0;
    if (a.is_zero()) return b.raw()->sign > 0;
  }
  return less(a, b);
}
SUPERBALL_NUMERIC_EXPORT bool operator<=(const MpFloat& a, const MpFloat& b);
/// a > b: b < a.
inline bool operator>(const MpFloat& a, const MpFloat& b) { return b < a; }
SUPERBALL_NUMERIC_EXPORT bool operator>=(const MpFloat& a, const MpFloat& b);
///@}

}  // namespace superball::numeric

SUPERBALL_NUMERIC_API_END
