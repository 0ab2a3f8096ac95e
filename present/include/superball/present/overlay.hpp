#pragma once
/// \file overlay.hpp
/// The overlay of a map (verify/overlay.hpp) as people and programs read
/// it: the summary of `superball map --overlay` and its JSON.  Shared by the
/// command and the Python module.

#include <nlohmann/json.hpp>

#include <string>

#include "superball/numeric/map.hpp"
#include "superball/verify/overlay.hpp"
#include "superball/present/export.hpp"
SUPERBALL_PRESENT_API_BEGIN

namespace superball::present {

/// The overlay's summary for people: the conditions derived, the zeros
/// found, the largest distance against the allowed one, each disagreement.
std::string to_text(const verify::Overlay& o, const numeric::Map& map);

/// Every zero and match, for programs.
nlohmann::ordered_json to_json(const verify::Overlay& o, const numeric::Map& map);

}  // namespace superball::present

SUPERBALL_PRESENT_API_END
