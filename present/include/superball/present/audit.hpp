#pragma once
/// \file audit.hpp
/// The audit for programs: the JSON of `superball audit --json`, shared by
/// the command and the Python module; not installed.

#include <nlohmann/json.hpp>

#include "superball/verify/audit.hpp"

namespace superball::present {

/// Every field of \p a: the options, each printed condition with its
/// agreement, forms and witness, each claim with its verdict (exact values as "p/q").
nlohmann::ordered_json audit_json(const verify::Audit& a);

}  // namespace superball::present
