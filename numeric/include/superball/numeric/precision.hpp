#pragma once
/// \file precision.hpp
/// The arithmetic a solve runs in (`--precision`), and the dispatch from a
/// runtime choice to the scalar type the solver template is instantiated with.

#include <cln/rational.h>
#include <cln/real.h>

#include <string>
#include "superball/numeric/export.hpp"
SUPERBALL_NUMERIC_API_BEGIN

namespace superball::numeric {

/// `double`, `long-double`, `digits:N` (CLN floats, N decimal digits) or `exact` (CLN rationals).
struct Precision {
  enum class Kind { Double, LongDouble, Digits, Exact };
  Kind kind = Kind::Double;
  int digits = 0;  ///< decimal digits for Kind::Digits

  /// Parse the CLI spelling; throws std::invalid_argument("Precision::parse(): ...").
  static Precision parse(const std::string& text);
  std::string name() const;  ///< the CLI spelling
};

/// Smallest and largest digits:N accepted.
inline constexpr int min_digits = 10;
inline constexpr int max_digits = 10000;

/// Call \p f with a value-initialised scalar of the type for \p p (a tag).
template <class F>
decltype(auto) with_scalar(const Precision& p, F&& f) {
  switch (p.kind) {
    case Precision::Kind::Double: return f(double{});
    case Precision::Kind::LongDouble: return f(static_cast<long double>(0));
    case Precision::Kind::Digits: return f(cln::cl_R{});
    case Precision::Kind::Exact: break;
  }
  return f(cln::cl_RA{});
}

}  // namespace superball::numeric

SUPERBALL_NUMERIC_API_END
