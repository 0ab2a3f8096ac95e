#pragma once
/// \file drop.hpp
/// A whole drop (numeric/drop.hpp) as people and programs read it: the
/// event list, the apexes after the last collisions and the rest times, as
/// text and as JSON (`superball drop`, Python's `superball.drop`).

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

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

/// Points of a flight arc drawn by drop_trace() (a parabola, so a few dozen
/// are smooth at a figure's size).
inline constexpr int drop_trace_samples = 64;
/// A bounce sequence that accumulates (DropRest::accumulation) is drawn
/// bounce by bounce until its apex is below this fraction of the run's
/// highest point, then flat to its rest time and beyond: a few thousand
/// points however many bounces the series sums.
inline constexpr double drop_trace_resolution = 1e-4;

/// Every body's height against time over a drop, sampled for a figure
/// (`superball drop --plot`, Python's DropResult.plot()): between events
/// each free body flies a parabola under g from its height and velocity
/// after the last event (drop_trace_samples points per arc, fewer for
/// short arcs), a body at rest on the obstacle stays there, and a bounce
/// sequence that accumulates is drawn to drop_trace_resolution of the
/// highest point and then at rest from its rest time.
struct DropTrace {
  ///@{
  /// Each body's samples (top to bottom; the fixed obstacle's too, at 0), from the release to the run's end.
  std::vector<std::vector<double>> time, height;
  ///@}
  ///@{
  /// Each contact closing at a collision: the time and the contact's height.
  std::vector<double> collision_time, collision_height;
  ///@}
  ///@{
  /// Each body coming to rest (DropResult::rest): the time and its height.
  std::vector<double> rest_time, rest_height;
  ///@}
};

/// The trajectories of \p r (see DropTrace).  O(events × bodies × samples).
DropTrace drop_trace(const numeric::DropResult& r);

}  // namespace superball::present

SUPERBALL_PRESENT_API_END
