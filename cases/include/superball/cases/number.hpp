#pragma once
/// \file number.hpp
/// Exact numbers as the user wrote them.  The cases library knows no arithmetic
/// backend: a Number keeps the exact rational value as decimal digit strings,
/// and each backend (CLN rationals, doubles, GiNaC) converts it itself.

#include <string>
#include <string_view>
#include "superball/cases/export.hpp"
SUPERBALL_CASES_API_BEGIN

namespace superball {

/// An exact rational number p/q written in a scene or a data file.
///
/// Accepted spellings: integers (`15`, `-3`), decimals with an optional
/// exponent (`0.001`, `5e6`, `1.5E-3`) and fractions of integers (`1/3`,
/// `-2/7`).  The digits of a decimal may be grouped by `_` as in TOML, only
/// between two digits (`1_000`; not `_1`, `1_`, `1__0`).  The value is kept
/// exactly: `0.001` is 1/1000, not the nearest double.  The fraction is not
/// reduced (no big-integer arithmetic here).
struct Number {
  std::string numerator = "0";    ///< optional '-' then decimal digits
  std::string denominator = "1";  ///< decimal digits, never zero
  std::string text = "0";         ///< the spelling the user gave, for messages

  /// Parse a spelling; throws std::invalid_argument("Number::parse(): ...")
  /// with the reason (bad character, zero denominator, exponent out of range).
  static Number parse(std::string_view text);
  /// The integer \p value.
  static Number integer(long long value);

  /// `p/q`, readable by CLN, GiNaC and any CAS.
  std::string fraction() const { return numerator + "/" + denominator; }
  bool is_zero() const;      ///< exactly 0
  bool is_negative() const;  ///< exactly < 0
  /// The nearest double, good to a few ulps (for messages and quick checks;
  /// computations convert the exact fraction themselves).
  double approx() const;
};

/// Largest decimal exponent accepted in a Number (|e| <= this): 1e4000 already
/// has 4001 digits; larger ones are surely typing errors and would cost memory.
inline constexpr int max_decimal_exponent = 4000;

}  // namespace superball

SUPERBALL_CASES_API_END
