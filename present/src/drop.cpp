#include "superball/present/drop.hpp"

#include <cmath>
#include <iomanip>
#include <sstream>

#include "superball/numeric/scalar.hpp"

namespace superball::present {
namespace {

std::string number(double x, int significant = 6) {
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  return x == 0 ? "0" : numeric::to_string(x, significant);
}

std::string joined(const std::vector<std::string>& items, const char* none) {
  std::string s;
  for (const auto& i : items) s += (s.empty() ? "" : ",") + i;
  return s.empty() ? none : s;
}

}  // namespace

PresentedDrop drop_scene(const Scene& scene, const std::string& precision) {
  return {scene.origin, scene.title, numeric::drop(scene, numeric::SolvePrecision::parse(precision, std::nullopt))};
}

nlohmann::json to_json(const PresentedDrop& d) {
  const numeric::DropResult& r = d.result;
  nlohmann::json j;
  j["scene"] = d.origin;
  j["title"] = d.title;
  j["precision"] = r.precision;
  j["g"] = r.g;
  j["fixed_obstacle"] = r.fixed_bottom;
  nlohmann::json masses = nlohmann::json::array();
  for (double m : r.masses) masses.push_back(std::isinf(m) ? nlohmann::json("inf") : nlohmann::json(m));
  j["masses"] = masses;
  j["release_heights"] = r.release_heights;
  j["release_velocities"] = r.release_velocities;
  nlohmann::json events = nlohmann::json::array();
  for (const auto& e : r.events)
    events.push_back({{"time", e.time},
                      {"contacts", e.contacts},
                      {"bodies", {e.first_body, e.last_body}},
                      {"case", e.case_name},
                      {"closed", e.closed},
                      {"apart", e.apart},
                      {"order_certified", e.order_certified},
                      {"heights", e.heights},
                      {"velocities_before", e.velocities_before},
                      {"velocities_after", e.velocities_after},
                      {"kinetic_energy_before", e.kinetic_energy_before},
                      {"kinetic_energy_after", e.kinetic_energy_after},
                      {"momentum_before", e.momentum_before},
                      {"momentum_after", e.momentum_after}});
  j["events"] = events;
  nlohmann::json apexes = nlohmann::json::array();
  for (const auto& a : r.apexes) apexes.push_back({{"body", a.body}, {"height", a.height}, {"time", a.time}});
  j["apexes"] = apexes;
  nlohmann::json rest = nlohmann::json::array();
  for (const auto& s : r.rest) {
    nlohmann::json o = {{"body", s.body}, {"time", s.time}, {"accumulation", s.accumulation}};
    if (s.accumulation) o["ratio"] = s.ratio;
    rest.push_back(o);
  }
  j["rest"] = rest;
  j["end"] = r.end;
  j["end_time"] = r.end_time;
  j["top_apex_ratio"] = std::isinf(r.top_apex_ratio) ? nlohmann::json(nullptr) : nlohmann::json(r.top_apex_ratio);
  j["near_ties"] = r.near_ties;
  j["ties"] = r.ties;
  j["orders_certified"] = r.orders_certified;
  j["precision_asked"] = r.precision_asked;
  j["escalated"] = r.escalated;
  j["sequences_agree"] = r.sequences_agree;
  j["distant"] = r.distant;
  return j;
}

std::string to_text(const PresentedDrop& d) {
  const numeric::DropResult& r = d.result;
  std::ostringstream os;
  os << d.origin << (d.title.empty() ? "" : ": " + d.title) << '\n';
  os << "precision " << r.precision << ", g = " << number(r.g) << " m/s^2, " << r.events.size() << " collisions, ended by " << r.end
     << " at t = " << number(r.end_time, 8) << " s";
  if (r.near_ties > 0) os << ", " << r.near_ties << " near ties (see docs/DROP.md)";
  if (r.distant) os << "\ndistant: every pair of M takes part in every collision";
  os << "\norder of events: " << (r.orders_certified ? "every order certified" : "not every order certified") << " (ties " << r.ties << ", near ties "
     << r.near_ties << ")";
  if (r.escalated)
    os << "; auto: double could not certify every order, long-double decided; the " << r.double_events << " events in double "
       << (r.sequences_agree ? "are the same" : "differ");
  else if (r.precision_asked == "auto")
    os << "; auto: double decided";
  os << "\n\n  body        mass (kg)   release height (m)\n";
  for (std::size_t i = 0; i < r.masses.size(); ++i)
    os << "  " << std::setw(4) << i + 1 << "  " << std::setw(15) << number(r.masses[i]) << "  " << std::setw(19) << number(r.release_heights[i])
       << '\n';
  os << "\nevents (velocities after, m/s, top to bottom):\n"
     << "  " << std::setw(4) << "#" << "  " << std::setw(12) << "time (s)" << "  " << std::setw(10) << "contacts" << "  " << std::setw(8) << "bodies"
     << "  " << std::setw(8) << "case" << "  " << std::setw(14) << "KE after (J)" << "  velocities after\n";
  for (std::size_t k = 0; k < r.events.size(); ++k) {
    const auto& e = r.events[k];
    std::string v;
    for (double x : e.velocities_after) v += (v.empty() ? "" : " ") + number(x);
    os << "  " << std::setw(4) << k + 1 << "  " << std::setw(12) << number(e.time, 8) << "  " << std::setw(10) << joined(e.contacts, "-") << "  "
       << std::setw(8) << (std::to_string(e.first_body) + "-" + std::to_string(e.last_body)) << "  " << std::setw(8) << e.case_name << "  "
       << std::setw(14) << number(e.kinetic_energy_after, 8) << "  " << v << '\n';
  }
  for (const auto& s : r.rest)
    os << "rest: body " << s.body << " at t = " << number(s.time, 8) << " s"
       << (s.accumulation ? " (its bounces accumulate, ratio e = " + number(s.ratio) + ")" : " (left at rest by a collision)") << '\n';
  os << "\napexes after the last collision:\n  body   height (m)     time (s)\n";
  for (const auto& a : r.apexes) os << "  " << std::setw(4) << a.body << "  " << std::setw(11) << number(a.height) << "  " << std::setw(11) << number(a.time) << '\n';
  if (!r.apexes.empty())
    os << "top body: apex " << number(r.apexes[0].height) << " m over release height " << number(r.release_heights[0]) << " m: ratio "
       << number(r.top_apex_ratio) << '\n';
  return os.str();
}

}  // namespace superball::present
