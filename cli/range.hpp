#pragma once
/// \file range.hpp
/// The range of one parameter on the command line, KEY=FROM:TO:STEPS, as
/// `sweep --vary` and `map --x/--y` take it.

#include <cln/rational.h>

#include <string>

#include "superball/cases/parameter.hpp"

namespace superball::cli {

/// A parameter and \p steps exact values from \p from to \p to, ends included.
struct Range {
  Parameter parameter;
  cln::cl_RA from, to;
  int steps;
};

/// Parse \p text, given to \p option, as KEY=FROM:TO:STEPS for \p scene
/// (e.g. K.3-4=0:20:401): KEY through Parameter::parse(), FROM and TO exact
/// numbers or fractions (different), STEPS a whole number from 2 to
/// \p max_steps.  Throws std::invalid_argument("OPTION TEXT: what is wrong
/// (expected KEY=FROM:TO:STEPS, …)").
Range parse_range(const std::string& option, const std::string& text, const Scene& scene, int max_steps);

}  // namespace superball::cli
