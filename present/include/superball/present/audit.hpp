#pragma once
/// \file audit.hpp
/// The audit of the paper's printed conditions (verify/audit.hpp) as people
/// and programs read it: the report of `superball audit` and its JSON.
/// Shared by the command and the Python module.

#include <nlohmann/json.hpp>

#include <string>

#include "superball/verify/audit.hpp"
#include "superball/present/export.hpp"
SUPERBALL_PRESENT_API_BEGIN

namespace superball::present {

/// Every field of \p a: the options, each printed condition with its
/// agreement, forms and witness, each claim with its verdict (exact values as "p/q").
nlohmann::ordered_json audit_json(const verify::Audit& a);

/// The audit as text for people (Unicode notation): each printed condition
/// with its derived forms, verdict and disagreeing point, each claim, a summary.
std::string to_text(const verify::Audit& audit);

}  // namespace superball::present

SUPERBALL_PRESENT_API_END
