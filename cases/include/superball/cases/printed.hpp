#pragma once
/// \file printed.hpp
/// The numbers the paper prints (cases/paper/printed-numbers.toml), for
/// comparison only: nothing the tool computes reads them.

#include <string>
#include <vector>

#include "superball/cases/number.hpp"
#include "superball/cases/export.hpp"
SUPERBALL_CASES_API_BEGIN

namespace superball {

/// A case change the paper reports along a parameter (Fig. 7).
struct PrintedSwitch {
  std::string section, parameter, text, case_name;
  Number value;
};

/// The paper's printed numbers.
struct PrintedNumbers {
  std::string eq16_section, eq16_text, eq16_case;
  std::vector<Number> eq16_velocities;  ///< U1+ .. U4+ as printed
  std::vector<PrintedSwitch> switches;
  std::string epsilon_section, epsilon_text, epsilon_claim;

  /// The compiled-in transcription; throws std::runtime_error("PrintedNumbers::paper(): ...") if it is malformed.
  static const PrintedNumbers& paper();
};

}  // namespace superball

SUPERBALL_CASES_API_END
