#pragma once
/// \file printed_conditions.hpp
/// The conditions the paper prints in §4.1–§4.3 and its claims in words
/// (cases/paper/printed-conditions.toml), as plain text: no arithmetic
/// backend reads them here; `superball audit` compares them with the
/// derivation.

#include <string>
#include <vector>
#include "superball/cases/export.hpp"
SUPERBALL_CASES_API_BEGIN

namespace superball {

/// One printed condition (or formula) of the paper.
struct PrintedCondition {
  std::string section;    ///< "4.1"
  std::string case_name;  ///< the paper's case, "1"
  std::vector<int> alphas;  ///< the couplings α_k assumed non-zero
  std::string kind;       ///< superball | evolution | contact | psd | velocity
  std::string about;      ///< "U1 > a", a contact "2-3", or "U1" for a velocity
  std::string printed;    ///< the paper's LaTeX, verbatim
  ///@{
  /// The condition as ASCII expressions: left-hand side, relation, right-hand side.
  std::string lhs, relation, rhs;  ///< ASCII expressions (m1, K12, alpha2, a); relation > >= < <= =
  ///@}
  std::string words;      ///< the paper's words for it
  std::string note;       ///< transcription remarks, may be empty
};

/// A claim of the paper in words about a pattern and a case.
struct PaperClaim {
  ///@{
  /// The claim's identifier, the paper's section, and the paper's name of the case.
  std::string id, section, case_name;
  ///@}
  std::vector<int> alphas;  ///< the claim's pattern
  std::vector<int> like;    ///< the pattern it is compared with (may be empty)
  std::string claim;        ///< "superball possible" or "superball impossible"
  std::string text;         ///< the paper's words
};

/// The transcription.
struct PrintedConditions {
  /// The printed conditions, in the file's order.
  std::vector<PrintedCondition> conditions;
  /// The claims in words, in the file's order.
  std::vector<PaperClaim> claims;

  /// Parse the text of a printed-conditions file; \p origin names it in
  /// messages.  Throws std::invalid_argument("PrintedConditions::parse(): ...")
  /// naming the entry and the field that is missing or malformed.
  static PrintedConditions parse(const std::string& text, const std::string& origin);
  /// The file compiled into the library (cases/paper/printed-conditions.toml).
  static const PrintedConditions& paper();
};

}  // namespace superball

SUPERBALL_CASES_API_END
