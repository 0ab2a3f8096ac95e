#pragma once
/// \file drop_limit.hpp
/// A drop as its gaps go to 0 against the simultaneous collision
/// (numeric/drop_limit.hpp), as people and programs read it
/// (`superball drop --gaps-to-zero`, Python's `superball.gaps_to_zero`).

#include <nlohmann/json.hpp>

#include <string>

#include "superball/numeric/drop_limit.hpp"
#include "superball/present/export.hpp"
SUPERBALL_PRESENT_API_BEGIN

namespace superball::present {

/// The comparison and the scene it came from, for output.
struct PresentedGapLimit {
  ///@{
  /// The scene's file (or label) and title.
  std::string origin, title;
  ///@}
  /// The comparison itself.
  numeric::GapLimit result;
};

/// gaps_to_zero() of \p scene in \p precision ("double" or "long-double";
/// Precision::parse() spellings) over \p decades decades.  Throws what
/// numeric::gaps_to_zero() throws.
PresentedGapLimit gap_limit_scene(const Scene& scene, const std::string& precision = "double", int decades = 8);

/// Every field of \p g, for programs: `landing_speed`, `tolerance`,
/// `verdict` (converges, differs, undecided), `simultaneous` and `steps` (each: `scale`, `cascade` with
/// `events`, `complete`, `collisions`, `velocities`, `duration`;
/// `deviation`, `collisions`, `end`, `top_apex_ratio`).
nlohmann::json to_json(const PresentedGapLimit& g);
/// \p g for people: a table of the cascades, the simultaneous collision
/// last, and the verdict.
std::string to_text(const PresentedGapLimit& g);

}  // namespace superball::present

SUPERBALL_PRESENT_API_END
