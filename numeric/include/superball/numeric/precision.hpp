#pragma once
/// \file precision.hpp
/// The arithmetic a solve runs in (`--precision`), and the dispatch from a
/// runtime choice to the scalar type the solver template is instantiated with.

#include <cln/rational.h>
#include <cln/real.h>

#include <optional>
#include <string>
#include "superball/numeric/export.hpp"
#include "superball/numeric/mpfloat.hpp"
SUPERBALL_NUMERIC_API_BEGIN

namespace superball::numeric {

/// `double`, `long-double`, `digits:N` (MPFR floats of N decimal digits, MpFloat) or `exact` (CLN rationals).
struct Precision {
  /// The arithmetic: double, long double, MPFR floats of #digits digits, exact rationals.
  enum class Kind { Double, LongDouble, Digits, Exact };
  /// The arithmetic chosen.
  Kind kind = Kind::Double;
  int digits = 0;  ///< decimal digits for Kind::Digits

  /// Parse the CLI spelling; throws std::invalid_argument("Precision::parse(): ...").
  static Precision parse(const std::string& text);
  std::string name() const;  ///< the CLI spelling
};

/// Smallest and largest digits:N accepted.
inline constexpr int min_digits = 10;
/// Largest digits:N accepted.
inline constexpr int max_digits = 10000;

/// Default rtol of auto: six significant digits of every velocity, certified.
inline constexpr double default_rtol = 1e-6;

/// What one solve is asked for (`solve --precision P --rtol R`, Python's
/// `solve(precision=P, rtol=R)`): auto, the cheapest arithmetic whose answer
/// is certified to rtol (choose_precision()), or one fixed Precision.
struct SolvePrecision {
  bool automatic = true;       ///< auto (choose_precision()), else the arithmetic \p fixed
  Precision fixed;             ///< the arithmetic when not automatic
  std::optional<double> rtol;  ///< the certified relative error asked of auto; nullopt: not given (default_rtol)

  /// \p precision spelled "auto" or as Precision::parse() reads it, with
  /// \p rtol as given; checked (check()).  Throws std::invalid_argument.
  static SolvePrecision parse(const std::string& precision, std::optional<double> rtol);
  /// Throws std::invalid_argument("SolvePrecision::check(): ...") when rtol
  /// is given without auto, or is not a number from 0 to 1 (NaN included).
  void check() const;
  /// The rtol of auto: the one given, else default_rtol.
  double tolerance() const { return rtol.value_or(default_rtol); }
};

/// Call \p f with a value-initialised scalar of the type for \p p (a tag).
template <class F>
decltype(auto) with_scalar(const Precision& p, F&& f) {
  switch (p.kind) {
    case Precision::Kind::Double: return f(double{});
    case Precision::Kind::LongDouble: return f(static_cast<long double>(0));
    case Precision::Kind::Digits: return f(MpFloat{});
    case Precision::Kind::Exact: break;
  }
  return f(cln::cl_RA{});
}

}  // namespace superball::numeric

SUPERBALL_NUMERIC_API_END
