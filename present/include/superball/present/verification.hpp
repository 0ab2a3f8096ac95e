#pragma once
/// \file verification.hpp
/// The verification of a case (verify/verification.hpp) as people and
/// programs read it: the tables of `superball verify`, its JSON, and the
/// comment of a disagreement's scene file.  Shared by the command and the
/// Python module.

#include <nlohmann/json.hpp>

#include <string>

#include "superball/verify/verification.hpp"
#include "superball/present/export.hpp"
SUPERBALL_PRESENT_API_BEGIN

namespace superball::present {

/// The tables for people: per ε the samples, the agreement of the exact and
/// asymptotic conjunctions and their confusion cells; per condition the
/// sides reached and the agreement of each form; the disagreements.
std::string to_text(const verify::Verification& v);

/// Every field, for programs (exact values as fractions).
nlohmann::ordered_json to_json(const verify::Verification& v);

/// The comment of a disagreement's scene file: the case, ε, what disagreed
/// and what the exact solution says (several lines, no '#').
std::string describe(const verify::Verification& v, const verify::Disagreement& d);

}  // namespace superball::present

SUPERBALL_PRESENT_API_END
