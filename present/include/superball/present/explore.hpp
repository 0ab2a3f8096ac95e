#pragma once
/// \file explore.hpp
/// The exploration of a pattern (verify/explore.hpp) as people and programs
/// read it: one result, the table of `--all-patterns` (also from cells
/// explored one at a time elsewhere), and the witness scene file.  Shared by
/// the command and the Python module.

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "superball/verify/explore.hpp"
#include "superball/present/export.hpp"
SUPERBALL_PRESENT_API_BEGIN

namespace superball::present {

/// The cell text: "yes U₁⁺/a = 12.3", "no (proved)", "case impossible", "not found"
/// (with the best U₁⁺/a at a point where the case is actual, when there is
/// one, and whether the leading-order conditions clash).
std::string cell_text(const verify::ExploreResult& r);

/// One result for people: verdict, witness, exact U₁⁺/a, statistics, clashes.
std::string to_text(const verify::ExploreResult& r);
/// Every field, for programs (exact values as "p/q" strings).
nlohmann::ordered_json to_json(const verify::ExploreResult& r);

/// One cell of the table as the table prints it, for a table whose cells
/// were explored one at a time elsewhere (`superball explore --all-patterns`
/// as a task list over processes): plain text, no CLN object.
struct RenderedCell {
  std::string pattern;          ///< ExploreResult::pattern (the row's label)
  std::string text;             ///< cell_text()
  nlohmann::ordered_json json;  ///< to_json() of the result
};
/// The cell of \p r as the table prints it (cell_text() and to_json()).
RenderedCell render(const verify::ExploreResult& r);

/// The table as Markdown (rows patterns, columns cases) with the box and budget.
std::string to_text(const verify::PatternTable& t);
/// Every cell, for programs.
nlohmann::ordered_json to_json(const verify::PatternTable& t);
/// to_text() and to_json() of a table from its options, patterns and cases
/// (its cells left empty) and its cells rendered: \p cells[row][column].
/// The same text as from the table with its cells filled.
std::string to_text(const verify::PatternTable& t, const std::vector<std::vector<RenderedCell>>& cells);
/// The same JSON as to_json() of the table with its cells filled.
nlohmann::ordered_json to_json(const verify::PatternTable& t, const std::vector<std::vector<RenderedCell>>& cells);

/// The TOML text of the witness scene of \p r (write_scene) with a comment
/// saying how it was found (\p command) and what the exact solve gives.
/// Throws std::invalid_argument("witness_file(): ...") when r has no witness.
std::string witness_file(const verify::ExploreResult& r, const std::string& command);

}  // namespace superball::present

SUPERBALL_PRESENT_API_END
