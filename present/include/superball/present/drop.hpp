#pragma once
/// \file drop.hpp
/// A whole drop (numeric/drop.hpp) as people and programs read it: the
/// event list, the apexes after the last collisions and the rest times, as
/// text and as JSON (`superball drop`, Python's `superball.drop`).

#include <nlohmann/json.hpp>

#include <string>

#include "superball/numeric/drop.hpp"
#include "superball/present/export.hpp"
SUPERBALL_PRESENT_API_BEGIN

namespace superball::present {

/// A drop and the scene it came from, for output.
struct PresentedDrop {
  ///@{
  /// The scene's file (or label) and title.
  std::string origin, title;
  ///@}
  /// The drop itself.
  numeric::DropResult result;
};

/// The drop of \p scene in \p precision ("double", the default,
/// "long-double" or "auto": numeric::drop() with a SolvePrecision).  Throws std::invalid_argument
/// for another arithmetic and superball::InputError for a scene without [drop].
PresentedDrop drop_scene(const Scene& scene, const std::string& precision = "double");

/// Every field of \p d, for programs (`superball drop --json`): `events`
/// (time, contacts, bodies, case, closed, velocities_before,
/// velocities_after, heights, kinetic energies, momenta), `apexes` (body,
/// height, time), `rest` (body, time, accumulation, ratio), `end`,
/// `top_apex_ratio`, `near_ties`, `ties`, `orders_certified`,
/// `precision_asked`, `escalated`, `sequences_agree`, `distant` (and per
/// event `apart`, `order_certified`).
nlohmann::json to_json(const PresentedDrop& d);
/// \p d for people (`superball drop`).
std::string to_text(const PresentedDrop& d);

}  // namespace superball::present

SUPERBALL_PRESENT_API_END
