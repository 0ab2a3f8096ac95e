#include "superball/present/drop.hpp"

#include <algorithm>
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

/// Most bounces of an accumulating sequence drawn one by one (the rest is drawn at rest).
constexpr int max_drawn_bounces = 10000;

/// One body's samples, arc after arc.
struct Track {
  std::vector<double>& t;
  std::vector<double>& z;
  double run;  ///< the run's duration: an arc spanning an eighth of it gets every sample

  /// The arc z0 + v·τ − a·τ²/2, τ from 0 to t1 − t0 (a flat line when v = a = 0).
  void arc(double t0, double t1, double z0, double v, double a) {
    if (!t.empty() && t.back() == t0 && !(t1 > t0)) return;
    const double span = std::max(t1 - t0, 0.0);
    const int k = v == 0 && a == 0 ? 1 : std::clamp(static_cast<int>(std::ceil(drop_trace_samples * 8 * span / run)), 4, drop_trace_samples);
    for (int s = !t.empty() && t.back() == t0 ? 1 : 0; s <= k; ++s) {
      const double tau = span * s / k;
      t.push_back(s == k ? t0 + span : t0 + tau);
      z.push_back(z0 + v * tau - a * tau * tau / 2);
    }
  }
};

}  // namespace

DropTrace drop_trace(const numeric::DropResult& r) {
  const std::size_t n = r.masses.size();
  DropTrace out;
  out.time.resize(n);
  out.height.resize(n);
  // The states the flights start from: the release, then every collision solved (a failed one ends the run).
  std::vector<double> at{0};
  std::vector<const std::vector<double>*> z{&r.release_heights}, v{&r.release_velocities};
  std::vector<const numeric::DropEvent*> by;
  by.push_back(nullptr);
  for (const numeric::DropEvent& e : r.events) {
    if (e.velocities_after.size() != n || e.heights.size() != n) break;
    at.push_back(e.time);
    z.push_back(&e.heights);
    v.push_back(&e.velocities_after);
    by.push_back(&e);
    for (const std::string& c : e.contacts) {
      out.collision_time.push_back(e.time);
      out.collision_height.push_back(e.heights[static_cast<std::size_t>(Pair::parse(c).j - 1)]);
    }
  }
  const double end = std::max(r.end_time, at.back());
  // The highest point of any arc: the scale of what a figure shows.
  double top = 0;
  for (std::size_t k = 0; k < at.size(); ++k)
    for (std::size_t i = 0; i < n; ++i) top = std::max(top, (*z[k])[i] + std::pow(std::max((*v[k])[i], 0.0), 2) / (2 * r.g));
  std::vector<std::vector<const numeric::DropRest*>> rests(n);
  for (const numeric::DropRest& s : r.rest)
    if (s.body >= 1 && static_cast<std::size_t>(s.body) <= n) rests[static_cast<std::size_t>(s.body - 1)].push_back(&s);
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t next = 0;
    Track track{out.time[i], out.height[i], end > 0 ? end : 1};
    bool held = r.fixed_bottom && i + 1 == n;  // at rest on the fixed obstacle (or on bodies at rest there)
    for (std::size_t k = 0; k < at.size(); ++k) {
      const double t0 = at[k], t1 = k + 1 < at.size() ? at[k + 1] : end, z0 = (*z[k])[i], v0 = (*v[k])[i];
      const double floor = (*z[k])[n - 1];  // where a body at rest lies: on the obstacle (bodies are points)
      const numeric::DropEvent* e = by[k];
      if (e && static_cast<int>(i) + 1 >= e->first_body && static_cast<int>(i) + 1 <= e->last_body) held = held && v0 == 0;
      // This body's rests (in time order) up to the end of this flight: left at rest now, or accumulating during it.
      const numeric::DropRest* accumulation = nullptr;
      for (; next < rests[i].size() && rests[i][next]->time <= (rests[i][next]->accumulation ? t1 : t0); ++next) {
        const numeric::DropRest& s = *rests[i][next];
        if (s.accumulation) {
          accumulation = &s;
        } else if (!held) {
          held = true;
          out.rest_time.push_back(s.time);
          out.rest_height.push_back(floor);
        }
      }
      if (held) {
        track.arc(t0, t1, floor, 0, 0);
      } else if (accumulation) {
        // Bounces from the floor with speeds v0·eʲ, drawn down to the figure's resolution, then at rest.
        double t = t0, speed = v0;
        for (int j = 0; j < max_drawn_bounces && speed > 0 && speed * speed / (2 * r.g) >= drop_trace_resolution * top; ++j) {
          const double flight = 2 * speed / r.g;
          if (t + flight > accumulation->time) break;
          track.arc(t, t + flight, floor, speed, r.g);
          t += flight;
          speed *= accumulation->ratio;
        }
        track.arc(t, t1, floor, 0, 0);
        held = true;
        out.rest_time.push_back(accumulation->time);
        out.rest_height.push_back(floor);
      } else {
        track.arc(t0, t1, z0, v0, r.g);
      }
    }
  }
  return out;
}

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
  if (r.end == "inexact")
    os << "\nexact: the next event's time is an irrational square root (a body meeting the obstacle, or bodies at rest on it, from a "
          "height): exact rationals end here; digits:N goes on";
  if (r.distant) os << "\ndistant: every pair of M takes part in every collision";
  os << "\norder of events: " << (r.orders_certified ? "every order certified" : "not every order certified") << " (ties " << r.ties << ", near ties "
     << r.near_ties << ")";
  if (r.escalated)
    os << "; auto: double could not certify every order, " << r.precision << " decided; the " << r.double_events << " events in double "
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
