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
  ///@{
  /// Where the paper reports it ("4.4, Fig. 7"), the parameter's key ("K.3-4"),
  /// the paper's words, and the paper's name of the case it reports ("3.2").
  std::string section, parameter, text, case_name;
  ///@}
  /// The parameter value printed.
  Number value;
};

/// The paper's printed numbers.
struct PrintedNumbers {
  ///@{
  /// Equation (16): where it is, its description, and the paper's name of its case ("3.3").
  std::string eq16_section, eq16_text, eq16_case;
  ///@}
  std::vector<Number> eq16_velocities;  ///< U1+ .. U4+ as printed
  /// The case changes the paper reports along a parameter (Fig. 7).
  std::vector<PrintedSwitch> switches;
  ///@{
  /// The ε family of §4.1: where it is, its description, and the claim ("U1+ = a/(2 eps)").
  std::string epsilon_section, epsilon_text, epsilon_claim;
  ///@}

  /// The compiled-in transcription; throws std::runtime_error("PrintedNumbers::paper(): ...") if it is malformed.
  static const PrintedNumbers& paper();
};

}  // namespace superball

SUPERBALL_CASES_API_END
