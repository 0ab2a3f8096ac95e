#include "superball/numeric/scalar.hpp"
#include "scalar_internal.hpp"

#include <cln/float.h>
#include <cln/integer.h>
#include <cln/float_io.h>
#include <cln/rational_io.h>
#include <cln/real_io.h>
#include <cln/rational_ring.h>
#include <cln/integer_io.h>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace superball::numeric {
namespace {

/// CLN writes floats with a type marker as exponent ("3.1L0", "2.5d-3");
/// turn that into a plain decimal exponent.
std::string plain_decimal(std::string s) {
  for (char& c : s)
    if (c == 'L' || c == 'd' || c == 'f' || c == 's' || c == 'E') c = 'e';
  if (s.size() > 2 && s.compare(s.size() - 2, 2, "e0") == 0) s.resize(s.size() - 2);
  return s;
}

std::string float_text(const cln::cl_F& x) {
  std::ostringstream os;
  cln::fprint(os, x);
  return plain_decimal(os.str());
}

/// r = p/q in lowest terms with p and q of at most \p bits bits (below
/// 2⁶³), as machine integers: the shortcuts of the conversions below.
bool small_parts(const cln::cl_RA& r, unsigned bits, long& p, long& q) {
  const cln::cl_I num = cln::numerator(r), den = cln::denominator(r);
  if (cln::integer_length(num) > bits || cln::integer_length(den) > bits) return false;
  p = cln::cl_I_to_long(num), q = cln::cl_I_to_long(den);
  return true;
}

}  // namespace

cln::float_format_t digits_format(int digits) {
  if (digits <= 0) throw std::invalid_argument("digits_format(): digits must be > 0, got " + std::to_string(digits));
  // CLN's float_format(N) is a single-float format up to N = 6 and a
  // double-float one up to N = 15: both have IEEE exponent ranges (a scene's
  // 1e-200 squared raises floating_point_underflow, 1e-320 is not held), and
  // N = 15 … 17 gives a long float of one 64-bit word, on which CLN's
  // float_epsilon() writes past the number (LF_epsilon clears len − 2
  // words: a crash).  So every N gets a long float of at least two words,
  // whose exponent range (64 bits) no scene reaches.
  const auto f = cln::float_format(static_cast<uintE>(digits));
  const auto least = static_cast<cln::float_format_t>(cln::float_format_lfloat_min + 1);
  return f < least ? least : f;
}

double ScalarTraits<double>::from(const cln::cl_RA& r, int) {
  // A numerator and denominator of at most 53 bits are doubles exactly, and
  // IEEE division rounds their quotient correctly, as double_approx() does
  // (the same double; tests/numeric/problem_test.cpp): a sweep's or a map's
  // values, p/q with small p and q, without CLN's long division.
  long p = 0, q = 1;
  if (small_parts(r, 53, p, q)) return static_cast<double>(p) / static_cast<double>(q);
  return cln::double_approx(r);
}

bool ScalarTraits<double>::sqrt(const cln::cl_RA& square, int, double& out) {
  out = std::sqrt(cln::double_approx(square));
  return true;
}

long double ScalarTraits<long double>::from(const cln::cl_RA& r, int) {
  // With x87's 64 bits of significand, a numerator and denominator of at
  // most 63 bits are long doubles exactly, and IEEE division rounds their
  // quotient correctly; the decimal route below gives the same long double
  // for them (its 40 digits are nearer p/q than any midpoint of two long
  // doubles, which lies at least 2⁻¹²⁸·|p/q| away).
  long p = 0, q = 1;
  if (std::numeric_limits<long double>::digits == 64 && small_parts(r, 63, p, q)) return static_cast<long double>(p) / static_cast<long double>(q);
  // 40 digits, then the C library's correctly rounded decimal conversion.
  return std::strtold(float_text(cln::cl_float(r, cln::float_format(40))).c_str(), nullptr);
}

bool ScalarTraits<long double>::sqrt(const cln::cl_RA& square, int, long double& out) {
  out = std::sqrt(from(square, 0));
  return true;
}

cln::cl_R ScalarTraits<cln::cl_R>::from(const cln::cl_RA& r, int digits) {
  if (digits <= 0) throw std::invalid_argument("ScalarTraits<cl_R>::from(): digits must be > 0");
  return cln::cl_float(r, digits_format(digits));
}

double ScalarTraits<cln::cl_R>::to_double(const cln::cl_R& x) { return cln::double_approx(x); }

cln::cl_R ScalarTraits<cln::cl_R>::unit_roundoff(int digits) {
  return cln::float_epsilon(digits_format(digits > 0 ? digits : 20));
}

bool ScalarTraits<cln::cl_R>::sqrt(const cln::cl_RA& square, int digits, cln::cl_R& out) {
  out = cln::sqrt(from(square, digits));
  return true;
}

double ScalarTraits<cln::cl_RA>::to_double(const cln::cl_RA& x) { return cln::double_approx(x); }

bool ScalarTraits<cln::cl_RA>::sqrt(const cln::cl_RA& square, int, cln::cl_RA& out) {
  return cln::sqrtp(square, &out);
}

std::string to_string(double x, int significant) {
  std::string out;
  append_to(out, x, significant);
  return out;
}

void append_to(std::string& out, double x, int significant) {
  // std::to_chars with a precision writes what printf's "%.*g" writes (C++17
  // [charconv.to.chars]), several times faster than glibc's printf; the
  // text is the same (tests/numeric/certify_test.cpp compares the two).
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, x, std::chars_format::general, significant);
  if (r.ec != std::errc()) {
    std::snprintf(buf, sizeof buf, "%.*g", significant, x);
    out += buf;
    return;
  }
  out.append(buf, r.ptr);
}

std::string to_string(long double x, int significant) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%.*Lg", significant, x);
  return buf;
}

std::string to_string(const cln::cl_R& x, int significant) {
  // Rounded exactly: a float of `significant` digits would be a single or
  // double float, whose range does not hold 1e400.
  if (significant > 0) return to_decimal(cln::rational(x), significant);
  if (cln::instanceof(x, cln::cl_RA_ring)) {
    std::ostringstream os;
    cln::fprint(os, cln::the<cln::cl_RA>(x));
    return os.str();
  }
  return float_text(cln::the<cln::cl_F>(x));
}

std::string to_string(const cln::cl_RA& x, int) {
  std::ostringstream os;
  cln::fprint(os, x);
  return os.str();
}

namespace {

/// The text of to_decimal() from the digits \p d of |x| rounded to
/// \p significant digits (maybe one more, when the rounding carried into a
/// new digit) and the exponent e of |x| (10^e <= |x| < 10^(e+1)).
std::string decimal_text(bool negative, std::string d, long e, int significant) {
  if (static_cast<int>(d.size()) > significant) {  // rounding carried into a new digit
    d.pop_back();
    ++e;
  }
  while (d.size() > 1 && d.back() == '0') d.pop_back();  // trailing zeros say nothing here
  std::string out;
  if (e < -4 || e >= significant) {
    out = d.substr(0, 1) + (d.size() > 1 ? "." + d.substr(1) : "") + "e" + (e < 0 ? "-" : "+") + (std::labs(e) < 10 ? "0" : "") +
          std::to_string(std::labs(e));
  } else if (e >= 0) {
    if (static_cast<int>(d.size()) < e + 1) d += std::string(static_cast<std::size_t>(e + 1) - d.size(), '0');
    out = d.substr(0, static_cast<std::size_t>(e + 1));
    if (static_cast<int>(d.size()) > e + 1) out += "." + d.substr(static_cast<std::size_t>(e + 1));
  } else {
    out = "0." + std::string(static_cast<std::size_t>(-e - 1), '0') + d;
  }
  return (negative ? "-" : "") + out;
}

__extension__ typedef unsigned __int128 U128;  // GCC and Clang's 128-bit integer

/// to_decimal()'s digits and exponent of |x| = a/b in 128-bit integers
/// when a and b have at most 63 bits and a·10^P or b·10^−P (P the power
/// that scales |x| to \p significant digits) stays below 2¹²⁷: a sweep's or
/// a map's values.  The same digits as CLN's exact route: round(a·10^P / b)
/// half up.  False otherwise.
bool small_decimal(const cln::cl_RA& ax, int significant, std::string& d, long& e) {
  long num = 0, den = 1;
  if (!small_parts(ax, 63, num, den)) return false;
  const U128 a = static_cast<std::uint64_t>(num), b = static_cast<std::uint64_t>(den);  // ax ≥ 0
  e = 0;  // 10^e <= a/b < 10^(e+1): e in [−19, 18]
  if (a >= b) {
    for (U128 p = b; p * 10 <= a; p *= 10) ++e;
  } else {
    for (U128 p = a; p < b; p *= 10) --e;
  }
  const long P = significant - 1 - e;
  if (P > 38 || P < -38) return false;
  U128 t = 1;
  for (long k = 0; k < std::labs(P); ++k) t *= 10;
  const U128 half = ~U128(0) >> 1;  // 2¹²⁷ − 1
  if ((P >= 0 ? a : b) > half / t) return false;
  const U128 n = P >= 0 ? a * t : a, m = P >= 0 ? b : b * t;
  U128 q = n / m;
  if (n % m >= m - n % m) ++q;  // the remainder at least half of m: up
  char digits[40];
  int at = 40;
  do {
    digits[--at] = static_cast<char>('0' + static_cast<int>(q % 10));
    q /= 10;
  } while (q != 0);
  d.assign(digits + at, digits + 40);
  return true;
}

}  // namespace

namespace detail {

std::string to_decimal_by_cln(const cln::cl_RA& x, int significant) {
  if (significant < 1) throw std::invalid_argument("to_decimal(): significant digits must be >= 1");
  if (cln::zerop(x)) return "0";
  const bool negative = cln::minusp(x);
  const cln::cl_RA ax = negative ? cln::cl_RA(-x) : x;
  // e = floor(log10 |x|): 10^e <= |x| < 10^(e+1)
  long e = 0;
  cln::cl_RA p = 1;
  while (p * 10 <= ax) p = p * 10, ++e;
  while (p > ax) p = p / 10, --e;
  // digits = round(|x| / 10^(e - significant + 1)), as an integer
  cln::cl_RA scale = 1;
  for (long k = 0; k < std::labs(e - significant + 1); ++k) scale = scale * 10;
  const cln::cl_RA scaled = e - significant + 1 >= 0 ? ax / scale : ax * scale;
  cln::cl_I digits = cln::floor1(scaled + cln::cl_RA(1) / 2);
  std::ostringstream ds;
  cln::fprint(ds, digits);
  return decimal_text(negative, ds.str(), e, significant);
}

}  // namespace detail

std::string to_decimal(const cln::cl_RA& x, int significant) {
  if (significant < 1) throw std::invalid_argument("to_decimal(): significant digits must be >= 1");
  if (cln::zerop(x)) return "0";
  const bool negative = cln::minusp(x);
  std::string d;
  long e = 0;
  if (small_decimal(negative ? cln::cl_RA(-x) : x, significant, d, e)) return decimal_text(negative, d, e, significant);
  return detail::to_decimal_by_cln(x, significant);
}

cln::cl_RA parse_rational(const std::string& fraction) {
  try {
    return cln::cl_RA(fraction.c_str());
  } catch (const std::exception& e) {
    throw std::invalid_argument("parse_rational(): '" + fraction + "' is not a rational: " + e.what());
  }
}

}  // namespace superball::numeric
