#include "superball/present/drop_limit.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "superball/numeric/scalar.hpp"

namespace superball::present {
namespace {

/// The collisions of a cascade the text lists (the JSON has them all).
constexpr std::size_t drop_limit_listed = 6;

std::string number(double x, int significant = 6) {
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  return x == 0 ? "0" : numeric::to_string(x, significant);
}

/// "1", "1e-3", …; "0" for the simultaneous drop.
std::string scale_text(double scale) {
  if (scale == 0 || scale == 1) return scale == 0 ? "0" : "1";
  return "1e" + std::to_string(static_cast<int>(std::lround(std::log10(scale))));
}

nlohmann::json step_json(const numeric::GapLimitStep& s) {
  const numeric::DropCascade& c = s.cascade;
  return {{"scale", s.scale},
          {"cascade",
           {{"events", c.events}, {"complete", c.complete}, {"collisions", c.collisions}, {"velocities", c.velocities}, {"duration", c.duration}}},
          {"deviation", std::isinf(s.deviation) ? nlohmann::json(nullptr) : nlohmann::json(s.deviation)},
          {"collisions", s.drop.events.size()},
          {"end", s.drop.end},
          {"top_apex_ratio", std::isinf(s.drop.top_apex_ratio) ? nlohmann::json(nullptr) : nlohmann::json(s.drop.top_apex_ratio)}};
}

}  // namespace

PresentedGapLimit gap_limit_scene(const Scene& scene, const std::string& precision, int decades) {
  numeric::GapLimitOptions options;
  options.decades = decades;
  return {scene.origin, scene.title, numeric::gaps_to_zero(scene, numeric::Precision::parse(precision), options)};
}

nlohmann::json to_json(const PresentedGapLimit& g) {
  const numeric::GapLimit& r = g.result;
  nlohmann::json steps = nlohmann::json::array();
  for (const auto& s : r.steps) steps.push_back(step_json(s));
  return {{"scene", g.origin},
          {"title", g.title},
          {"precision", r.simultaneous.drop.precision},
          {"landing_speed", r.landing_speed},
          {"tolerance", numeric::drop_limit_tolerance},
          {"verdict", numeric::to_string(r.verdict)},
          {"simultaneous", step_json(r.simultaneous)},
          {"steps", steps}};
}

std::string to_text(const PresentedGapLimit& g) {
  const numeric::GapLimit& r = g.result;
  const double a = r.landing_speed > 0 ? r.landing_speed : 1;
  const std::size_t n = r.simultaneous.drop.masses.size();
  std::ostringstream os;
  os << g.origin << (g.title.empty() ? "" : ": " + g.title) << '\n';
  os << "the gaps times 10^-k against every gap 0 (the simultaneous collision), precision " << r.simultaneous.drop.precision
     << "; landing speed a = " << number(r.landing_speed) << " m/s\n";
  os << "first cascade: the collisions until every body moves up at least as fast as the one below it\n\n";
  os << "  " << std::setw(6) << "gaps x" << "  " << std::setw(9) << "deviation";
  for (std::size_t i = 0; i < n; ++i)
    if (!std::isinf(r.simultaneous.drop.masses[i])) os << "  " << std::setw(10) << ("U" + std::to_string(i + 1) + "+/a");
  os << "  " << std::setw(10) << "top apex/h" << "  cascade (bodies case, ...)\n";
  auto row = [&](const numeric::GapLimitStep& s) {
    os << "  " << std::setw(6) << scale_text(s.scale) << "  " << std::setw(9) << number(s.deviation, 3);
    for (std::size_t i = 0; i < n; ++i)
      if (!std::isinf(s.drop.masses[i]))
        os << "  " << std::setw(10) << (i < s.cascade.velocities.size() ? number(s.cascade.velocities[i] / a) : std::string("-"));
    std::string collisions;  // at most drop_limit_listed of them, then how many more
    const std::size_t shown = std::min(s.cascade.collisions.size(), drop_limit_listed);
    for (std::size_t k = 0; k < shown; ++k) collisions += (collisions.empty() ? "" : ", ") + s.cascade.collisions[k];
    if (shown < s.cascade.collisions.size()) collisions += ", ... (" + std::to_string(s.cascade.collisions.size() - shown) + " more)";
    os << "  " << std::setw(10) << number(s.drop.top_apex_ratio) << "  " << s.cascade.events << ": " << collisions
       << (s.cascade.complete ? "" : " (the drop ended before the bodies separated)") << '\n';
  };
  for (const auto& s : r.steps) row(s);
  row(r.simultaneous);
  const numeric::GapLimitStep& last = r.steps.back();
  os << '\n';
  if (r.verdict == numeric::GapVerdict::Undecided) {
    const numeric::GapLimitStep* cut = &r.simultaneous;
    for (const auto& s : r.steps)
      if (!s.cascade.complete) cut = &s;
    os << "undecided: the drop with gaps x " << scale_text(cut->scale) << " ended (" << cut->drop.end << ") before its first cascade did\n";
  } else {
    os << (r.verdict == numeric::GapVerdict::Converges ? "the gapped drops converge to the simultaneous collision"
                                                       : "the gapped drops do NOT converge to the simultaneous collision")
       << ": at gaps x " << scale_text(last.scale) << " the velocities after the cascade differ from it by " << number(last.deviation, 3)
       << " a (tolerance " << number(numeric::drop_limit_tolerance) << " a)\n";
  }
  return os.str();
}

}  // namespace superball::present
