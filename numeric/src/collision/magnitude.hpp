#pragma once
// Internal: sizes.  The residual check and the assembly's rounding scale sum
// magnitudes of terms; in double and long double they are S itself, and
// where S's arithmetic is costly (MpFloat, exact rationals) they are a
// Magnitude of 53 bits and any exponent.

#include <cln/rational.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "superball/numeric/mpfloat.hpp"

namespace superball::numeric::detail {

/// A size (of the residual check, or of the assembly's rounding scale) where
/// S's own arithmetic is costly (MpFloat, and exact rationals, whose sums of
/// magnitudes grow their denominators): a number m·2^e ≥ 0 with m a double
/// in [1/2, 1) and e a long, so about 53 bits over any range of exponents S
/// has.  A size (a sum of
/// the magnitudes of a row's terms) only scales a residual to compare it
/// with a tolerance given as a double, so 53 bits are more than it needs;
/// what it must keep is the range (an MpFloat's values go far beyond
/// double's) and NaN and +∞, so that a size that is not a number fails the
/// check as it did in S.  Zero is m = 0 with the lowest e, +∞ m = ∞ with the
/// highest, so that (e, m) orders every value but NaN.
class Magnitude {
 public:
  /// 0.
  Magnitude() = default;
  /// |x|, from the leading 62 bits of its numerator and of its denominator.
  explicit Magnitude(const cln::cl_RA& x);
  /// |x|.
  explicit Magnitude(const MpFloat& x) {
    long e = 0;
    const double m = std::fabs(frexp(x, &e));
    set(m, e);
  }
  friend Magnitude operator+(const Magnitude& a, const Magnitude& b) {
    if (a.m_ == 0) return b;
    if (b.m_ == 0) return a;
    if (!regular(a) || !regular(b)) return special(a.m_ + b.m_);
    const bool a_larger = a.e_ >= b.e_;
    Magnitude r = a_larger ? a : b;
    const Magnitude& y = a_larger ? b : a;
    r.m_ += y.m_ * power_of_two(y.e_ - r.e_);  // in [1/2, 2)
    if (r.m_ >= 1) r.m_ *= 0.5, ++r.e_;
    return r;
  }
  Magnitude& operator+=(const Magnitude& b) { return *this = *this + b; }
  friend Magnitude operator*(Magnitude a, const Magnitude& b) {
    if (!regular(a) || !regular(b)) return special(a.m_ * b.m_);
    a.m_ *= b.m_, a.e_ += b.e_;  // m in [1/4, 1)
    if (a.m_ < 0.5) a.m_ *= 2, --a.e_;
    return a;
  }
  friend Magnitude operator/(Magnitude a, const Magnitude& b) {
    if (!regular(a) || !regular(b)) return special(a.m_ / b.m_);
    a.m_ /= b.m_, a.e_ -= b.e_;  // m in (1/2, 2)
    if (a.m_ >= 1) a.m_ *= 0.5, ++a.e_;
    return a;
  }
  /// a < b; false when either is NaN.
  friend bool operator<(const Magnitude& a, const Magnitude& b) {
    return !std::isnan(a.m_) && !std::isnan(b.m_) && (a.e_ < b.e_ || (a.e_ == b.e_ && a.m_ < b.m_));
  }
  friend bool operator>(const Magnitude& a, const Magnitude& b) { return b < a; }
  /// The value as a double: 0 below double's range, +∞ above it.
  double to_double() const { return std::ldexp(m_, static_cast<int>(std::clamp(e_, -2000L, 2000L))); }

 private:
  static constexpr long kZeroE = -(1L << 60), kInfE = 1L << 60;
  /// m·2^e from std::frexp's form (m 0, +∞, NaN or in [1/2, 1)).
  void set(double m, long e) {
    m_ = m;
    e_ = m == 0 ? kZeroE : std::isinf(m) ? kInfE : e;
  }
  static bool regular(const Magnitude& x) { return x.m_ != 0 && std::isfinite(x.m_); }
  /// 2^k for k ≤ 0, from its bits (0 below 2^−1022, where a term is far
  /// below the rounding of a sum of 53 bits).
  static double power_of_two(long k) {
    if (k < -1022) return 0;
    const std::uint64_t bits = static_cast<std::uint64_t>(1023 + k) << 52;
    double x;
    std::memcpy(&x, &bits, sizeof x);
    return x;
  }
  /// The value of an operation with 0, +∞ or NaN, from that of m alone.
  static Magnitude special(double m) {
    Magnitude r;
    r.set(m, 0);
    return r;
  }

  double m_ = 0;
  long e_ = kZeroE;
};

/// The type of a size (the residual check's, the assembly's rounding scale):
/// S itself, or Magnitude where S's arithmetic is costly and a size needs
/// none of its precision.
template <class S>
struct SizeType {
  using type = S;
};
template <>
struct SizeType<MpFloat> {
  using type = Magnitude;
};
/// Exact: a correct answer's residuals are exactly 0 whatever the sizes, and
/// a wrong one's are not, so the sizes need no exact arithmetic either.
template <>
struct SizeType<cln::cl_RA> {
  using type = Magnitude;
};
template <class S>
using SizeOf = typename SizeType<S>::type;

template <class S>
S abs_value(const S& x) {
  return x < S(0) ? S(-x) : x;
}
/// The same for MpFloat with one copy: a negative number's sign flipped
/// (±0 and NaN kept as they are, as x < 0 ? −x : x keeps them).
template <>
inline MpFloat abs_value<MpFloat>(const MpFloat& x) {
  MpFloat r = x;
  if (MpFloat::zero_or_regular(x) && !x.is_zero() && x.raw()->sign < 0) r.raw()->sign = 1;
  return r;
}
/// |x| as a size.
template <class S>
SizeOf<S> size_of(const S& x) {
  return abs_value<S>(x);
}
template <>
inline Magnitude size_of<MpFloat>(const MpFloat& x) {
  return Magnitude(x);
}
template <>
inline Magnitude size_of<cln::cl_RA>(const cln::cl_RA& x) {
  return Magnitude(x);
}
inline double to_double(const Magnitude& x) { return x.to_double(); }

}  // namespace superball::numeric::detail
