#include "superball/numeric/drop_limit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "superball/cases/error.hpp"
#include "superball/numeric/scalar.hpp"

namespace superball::numeric {
namespace {

/// Whether every body moves up at least as fast as the one below it (within \p tolerance m/s).
bool separating(const std::vector<double>& v, double tolerance) {
  for (std::size_t i = 0; i + 1 < v.size(); ++i)
    if (v[i] - v[i + 1] < -tolerance) return false;
  return true;
}

/// \p scene with every body's gap divided by 10^k, exactly (the gap's fraction with k more zeros under it); every gap 0 for k < 0.
Scene scaled_gaps(const Scene& scene, int k) {
  Scene out = scene;
  for (Body& b : out.bodies) {
    if (!b.gap) continue;
    if (k < 0) {
      b.gap = Number::integer(0);
    } else {
      b.gap = Number::parse(b.gap->numerator + "/" + b.gap->denominator + std::string(static_cast<std::size_t>(k), '0'));
      b.gap->text = to_string(b.gap->approx(), 6);  // for messages: 1e-308, not its fraction
    }
  }
  return out;
}

/// The first contact of the first collision of \p drop that had a gap > 0 at release in \p scene (0-based), or -1;
/// -1 in the distant view, where a collision takes in bodies across open gaps.
int gapped_contact_in_first_collision(const Scene& scene, const DropResult& drop) {
  if (drop.events.empty() || scene.drop.distant) return -1;
  const DropEvent& e = drop.events.front();
  for (int c = e.first_body - 1; c + 1 < e.last_body; ++c) {
    const auto& gap = scene.bodies[static_cast<std::size_t>(c)].gap;
    if (c + 2 < scene.size() && gap && !gap->is_zero()) return c;  // (the lowest free body's distance to the obstacle is drop_height)
  }
  return -1;
}

}  // namespace

const char* to_string(GapVerdict v) {
  switch (v) {
    case GapVerdict::Converges: return "converges";
    case GapVerdict::Differs: return "differs";
    case GapVerdict::Undecided: break;
  }
  return "undecided";
}

DropCascade first_cascade(const DropResult& drop, double speed) {
  DropCascade c;
  if (drop.events.empty()) return c;
  const double tolerance = drop_cascade_tolerance * speed;
  for (const DropEvent& e : drop.events) {
    ++c.events;
    c.collisions.push_back(std::to_string(e.first_body) + "-" + std::to_string(e.last_body) + " " + e.case_name);
    c.velocities = e.velocities_after;
    c.duration = e.time - drop.events.front().time;
    if (separating(e.velocities_after, tolerance)) {
      c.complete = true;
      break;
    }
  }
  return c;
}

void GapLimitOptions::check() const {
  if (decades < 1 || decades > max_decades)
    throw std::invalid_argument("GapLimitOptions::check(): decades must be a whole number from 1 to " + std::to_string(max_decades) +
                                ", got " + std::to_string(decades));
}

GapLimit gaps_to_zero(const Scene& scene, const Precision& precision, const GapLimitOptions& options) {
  options.check();
  if (std::none_of(scene.bodies.begin(), scene.bodies.end(), [](const Body& b) { return b.gap && !b.gap->is_zero(); }))
    throw InputError(scene.origin + ": no body has a gap > 0: its drop is the simultaneous collision already");
  GapLimit limit;
  limit.simultaneous.scale = 0;
  limit.simultaneous.drop = drop(scaled_gaps(scene, -1), precision);
  const DropResult& sim = limit.simultaneous.drop;
  if (!sim.events.empty()) {
    const DropEvent& first = sim.events.front();
    for (int i = first.first_body - 1; i < first.last_body; ++i)
      if (!std::isinf(sim.masses[static_cast<std::size_t>(i)]))
        limit.landing_speed = std::max(limit.landing_speed, std::fabs(first.velocities_before[static_cast<std::size_t>(i)]));
  }
  const double speed = limit.landing_speed > 0 ? limit.landing_speed : 1;
  limit.simultaneous.cascade = first_cascade(sim, speed);
  const std::vector<double>& reference = limit.simultaneous.cascade.velocities;
  for (int k = 0; k <= options.decades; ++k) {
    GapLimitStep step;
    step.scale = std::pow(10.0, -k);
    const Scene scaled = scaled_gaps(scene, k);
    const std::string fewer = k == 0 ? std::string("widen the gaps") : "take " + std::to_string(k - 1) + " decades or fewer";
    try {
      step.drop = drop(scaled, precision);
    } catch (const std::invalid_argument& e) {  // a gap below the arithmetic's window
      if (k == 0) throw;
      std::string why = without_function_prefix(e.what());
      if (why.rfind(scene.origin + ": ", 0) == 0) why.erase(0, scene.origin.size() + 2);
      throw InputError(scene.origin + ": gaps x 1e-" + std::to_string(k) + ": " + why + "; " + fewer);
    }
    if (const int c = gapped_contact_in_first_collision(scaled, step.drop); c >= 0)
      throw InputError(scene.origin + ": gaps x 1e-" + std::to_string(k) + ": the gap of contact " + std::to_string(c + 1) + "-" +
                       std::to_string(c + 2) + " (" + scaled.bodies[static_cast<std::size_t>(c)].gap->text + " m) is below what " +
                       precision.name() + " resolves: the contact collides as if it touched; " + fewer);
    step.cascade = first_cascade(step.drop, speed);
    if (step.cascade.complete && limit.simultaneous.cascade.complete && step.cascade.velocities.size() == reference.size()) {
      for (std::size_t i = 0; i < reference.size(); ++i)
        if (!std::isinf(sim.masses[i])) step.deviation = std::max(step.deviation, std::fabs(step.cascade.velocities[i] - reference[i]) / speed);
    } else {
      step.deviation = std::numeric_limits<double>::infinity();  // a cascade that did not end, or a drop without collision
    }
    limit.steps.push_back(std::move(step));
  }
  const bool complete = limit.simultaneous.cascade.complete &&
                        std::all_of(limit.steps.begin(), limit.steps.end(), [](const GapLimitStep& s) { return s.cascade.complete; });
  limit.verdict = !complete ? GapVerdict::Undecided
                  : limit.steps.back().deviation <= drop_limit_tolerance ? GapVerdict::Converges
                                                                          : GapVerdict::Differs;
  return limit;
}

}  // namespace superball::numeric
