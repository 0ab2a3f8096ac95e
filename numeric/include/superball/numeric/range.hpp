#pragma once
/// \file range.hpp
/// The range of one parameter as text, KEY=FROM:TO:STEPS, as `sweep --vary`
/// and `map --x/--y` take it.

#include <cln/rational.h>

#include <string>

#include "superball/cases/parameter.hpp"
#include "superball/numeric/export.hpp"
SUPERBALL_NUMERIC_API_BEGIN

namespace superball::numeric {

/// A parameter and \p steps exact values from \p from to \p to, ends included.
struct Range {
  /// The parameter varied.
  Parameter parameter;
  ///@{
  /// The first and the last value (exact).
  cln::cl_RA from, to;
  ///@}
  /// The number of values, ends included (>= 2).
  int steps;
};

/// Most values of a sweep's range (`sweep --vary`).
inline constexpr int sweep_max_steps = 10000000;

/// Parse \p text, given to \p option, as KEY=FROM:TO:STEPS for \p scene
/// (e.g. K.3-4=0:20:401): KEY through Parameter::parse() (any of its
/// spellings), FROM and TO any two different numbers a scene file accepts
/// (Number::parse(): integers, decimals with an exponent, fractions; kept
/// exact), STEPS a whole number from 2 to \p max_steps.  Throws std::invalid_argument("OPTION TEXT: what is wrong
/// (expected KEY=FROM:TO:STEPS, …)").
Range parse_range(const std::string& option, const std::string& text, const Scene& scene, int max_steps);

}  // namespace superball::numeric

SUPERBALL_NUMERIC_API_END
