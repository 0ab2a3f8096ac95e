#include "superball/present/solution.hpp"

#include <cln/float.h>
#include <cln/real.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "superball/numeric/certify.hpp"
#include "superball/cases/vocabulary.hpp"

namespace superball::present {
namespace {

using numeric::ScalarTraits;

template <class S>
Presented present(const Scene& scene, const numeric::ExactScene& exact, const numeric::Precision& precision, S) {
  using T = ScalarTraits<S>;
  const int digits = precision.digits;
  const auto problem = numeric::Problem<S>::from(exact, digits);
  const auto sol = numeric::solve(problem);
  Presented p;
  p.origin = scene.origin;
  p.title = scene.title;
  p.precision = precision.name();
  p.status = numeric::to_string(sol.status);
  p.n = problem.n;
  p.fixed_bottom = problem.fixed_bottom;
  p.pivots = sol.pivots;
  p.exact = T::exact;
  p.case_name = Vocabulary::paper().case_name(sol.closed);
  p.closed = sol.closed.closed_names();
  // The unit: exact and rational, or irrational (exact runs print "x*sqrt(a²)").
  const std::string sqrt_text = problem.unit_exact ? "" : "*sqrt(" + numeric::to_string(exact.unit_squared()) + ")";
  const double unit = problem.unit_exact ? T::to_double(problem.unit) : std::sqrt(cln::double_approx(exact.unit_squared()));
  const S unit_s = problem.unit;  // 1 when irrational in exact arithmetic
  auto text = [&](const S& x) { return x == S(0) ? std::string("0") : numeric::to_string(S(x * unit_s)) + sqrt_text; };
  // x times the irrational unit in double: 0 stays 0 when the unit overflows.
  auto times_unit = [&](double x, double power) { return x == 0 ? 0.0 : x * power; };
  // x·unit^power to \p significant digits from S, for the text: the
  // doubles above overflow where S holds the value (−1e400 in long double).
  auto shown = [&](const S& x, int power, int significant = 6) -> std::string {
    const S v = power == 0 ? x : power == 2 ? S(x * unit_s * unit_s) : S(x * unit_s);
    if (v == S(0)) return "0";  // not "-0"
    if constexpr (T::exact) {
      if (problem.unit_exact) return numeric::to_decimal(v, significant);
      if (power != 1) return numeric::to_decimal(power == 2 ? cln::cl_RA(v * exact.unit_squared()) : v, significant);
      const auto f = numeric::digits_format(20);  // x·sqrt(a²), a irrational
      return numeric::to_string(cln::cl_R(cln::cl_float(v, f) * cln::sqrt(cln::cl_float(exact.unit_squared(), f))), significant);
    } else {
      return numeric::to_string(v, significant);
    }
  };
  for (int i = 0; i < p.n; ++i) {
    p.masses.push_back(problem.fixed_bottom && i == p.n - 1 ? INFINITY : T::to_double(problem.mass[i]));
    p.before.push_back(times_unit(T::to_double(problem.u[i]), unit));
    p.after.push_back(times_unit(T::to_double(S(sol.velocities_after[i] * unit_s)), problem.unit_exact ? 1.0 : unit));
    p.after_text.push_back(text(sol.velocities_after[i]));
    p.shown.masses.push_back(problem.fixed_bottom && i == p.n - 1 ? "inf" : shown(problem.mass[i], 0));
    p.shown.before.push_back(shown(problem.u[i], 1));
    p.shown.after.push_back(shown(sol.velocities_after[i], 1));
  }
  for (int c = 0; c + 1 < p.n; ++c) {
    p.reactions.push_back(times_unit(T::to_double(S(sol.reactions[c] * unit_s)), problem.unit_exact ? 1.0 : unit));
    p.reaction_text.push_back(text(sol.reactions[c]));
    p.shown.reactions.push_back(shown(sol.reactions[c], 1));
  }
  p.shown.ke_before = shown(sol.kinetic_energy_before, 2, 8);
  p.shown.ke_after = shown(sol.kinetic_energy_after, 2, 8);
  p.shown.dissipation = shown(sol.dissipation, 2, 8);
  p.warnings = numeric::trust_warnings(problem, sol);
  const double unit2 = problem.unit_exact ? 1.0 : unit * unit;
  const S u2 = unit_s * unit_s;
  p.ke_before = times_unit(T::to_double(S(sol.kinetic_energy_before * u2)), unit2);
  p.ke_after = times_unit(T::to_double(S(sol.kinetic_energy_after * u2)), unit2);
  p.dissipation = times_unit(T::to_double(S(sol.dissipation * u2)), unit2);
  p.momentum_before = times_unit(T::to_double(S(sol.momentum_before * unit_s)), problem.unit_exact ? 1.0 : unit);
  p.momentum_after = times_unit(T::to_double(S(sol.momentum_after * unit_s)), problem.unit_exact ? 1.0 : unit);
  p.residual_motion = sol.residual_motion;
  p.residual_complementarity = sol.residual_complementarity;
  // Superball: the top body's velocity after exceeds its speed before.
  const S top_after = sol.velocities_after[0], top_before = problem.u[0];
  p.superball = top_after > (top_before < S(0) ? S(-top_before) : top_before);
  return p;
}

}  // namespace

Presented solve_scene(const Scene& scene, const numeric::Precision& precision) {
  const auto exact = numeric::ExactScene::from(scene);
  Presented p = numeric::with_scalar(precision, [&](auto tag) { return present(scene, exact, precision, tag); });
  if (scene.flight.requested) {  // only the effects a scene calls for
    p.g = scene.g.approx();
    p.flight = numeric::free_flight(p.after, p.g);
    double last = 0;
    for (const auto& f : p.flight) last = std::max(last, f.landing_time);
    p.flight_duration = scene.flight.duration ? scene.flight.duration->approx() : (last > 0 ? last : 1.0);
  }
  return p;
}

Presented solve_scene_auto(const Scene& scene, double rtol) {
  const numeric::AutoChoice choice = numeric::choose_precision(numeric::ExactScene::from(scene), rtol);
  Presented p = solve_scene(scene, choice.precision);
  p.requested = "auto";
  p.error_bound = choice.relative_error;
  p.escalation = choice.tried;
  return p;
}

nlohmann::json to_json(const Presented& p) {
  nlohmann::json j;
  j["scene"] = p.origin;
  j["title"] = p.title;
  j["precision"] = p.precision;
  if (!p.requested.empty()) {
    j["precision_requested"] = p.requested;
    j["error_bound"] = p.error_bound;
    j["escalation"] = p.escalation;
  }
  j["warnings"] = p.warnings;
  j["status"] = p.status;
  j["bodies"] = p.n;
  j["fixed_obstacle"] = p.fixed_bottom;
  j["velocities_before"] = p.before;
  j["velocities_after"] = p.after;
  (p.exact ? j["velocities_after_exact"] : j["velocities_after_text"]) = p.after_text;
  j["closed_contacts"] = p.closed;
  j["case"] = p.case_name;
  nlohmann::json r = nlohmann::json::object(), rt = nlohmann::json::object();
  for (int c = 0; c + 1 < p.n; ++c) {
    const std::string name = Pair{c + 1, c + 2}.name();
    r[name] = p.reactions[static_cast<std::size_t>(c)];
    rt[name] = p.reaction_text[static_cast<std::size_t>(c)];
  }
  j["reactions"] = r;
  j[p.exact ? "reactions_exact" : "reactions_text"] = rt;
  j["kinetic_energy_before"] = p.ke_before;
  j["kinetic_energy_after"] = p.ke_after;
  j["dissipation"] = p.dissipation;
  j["momentum_before"] = p.momentum_before;
  j["momentum_after"] = p.momentum_after;
  j["superball"] = p.superball;
  j["pivots"] = p.pivots;
  j["residuals"] = {{"motion", p.residual_motion}, {"complementarity", p.residual_complementarity}};
  if (!p.flight.empty()) {
    nlohmann::json f = nlohmann::json::array();
    for (std::size_t i = 0; i < p.flight.size(); ++i)
      f.push_back({{"body", i + 1}, {"velocity_after", p.flight[i].velocity}, {"apex_height", p.flight[i].apex_height},
                   {"apex_time", p.flight[i].apex_time}, {"landing_time", p.flight[i].landing_time}});
    j["flight"] = {{"g", p.g}, {"bodies", f}};
  }
  return j;
}

std::string to_text(const Presented& p) {
  std::ostringstream os;
  os << p.origin << (p.title.empty() ? "" : ": " + p.title) << '\n';
  os << "precision " << p.precision;
  if (!p.requested.empty()) os << " (chosen by auto: certified relative velocity error <= " << numeric::to_string(p.error_bound, 3) << ")";
  os << ", status " << p.status << " (" << p.pivots << " pivots)\n\n";
  os << "  body        mass (kg)      U- (m/s)      U+ (m/s)\n";
  for (int i = 0; i < p.n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    os << "  " << std::setw(4) << i + 1 << "  " << std::setw(15) << p.shown.masses[k] << "  " << std::setw(12) << p.shown.before[k] << "  "
       << std::setw(12) << p.shown.after[k];
    if (p.exact || p.precision != "double") os << "   " << p.after_text[k];
    os << '\n';
  }
  const std::string set = p.closed.empty() ? "none" : [&] {
    std::string s;
    for (const auto& c : p.closed) s += (s.empty() ? "" : ", ") + c;
    return s;
  }();
  os << "\ncase " << p.case_name << " (closed contacts: " << set << ")";
  for (const auto& c : Vocabulary::paper().cases())
    if (c.name == p.case_name && p.n == Vocabulary::paper().bodies()) os << ": " << c.description;
  os << "\nreactions (N s):";
  for (int c = 0; c + 1 < p.n; ++c) os << "  " << Pair{c + 1, c + 2}.name() << " = " << p.shown.reactions[static_cast<std::size_t>(c)];
  os << "\nkinetic energy (J): before " << p.shown.ke_before << ", after " << p.shown.ke_after << ", dissipated " << p.shown.dissipation << '\n';
  const std::string& top_before = p.shown.before[0];
  os << "superball: " << (p.superball ? "yes" : "no") << " (U1+ = " << p.shown.after[0]
     << ", |U1-| = " << (top_before[0] == '-' ? top_before.substr(1) : top_before) << ")\n";
  if (!p.flight.empty()) {
    os << "\nflight after the collision (g = " << numeric::to_string(p.g, 6) << " m/s^2; bodies fly freely, later collisions not modelled):\n"
       << "  body    U+ (m/s)   apex height (m)   apex time (s)\n";
    for (std::size_t i = 0; i < p.flight.size(); ++i)
      os << "  " << std::setw(4) << i + 1 << "  " << std::setw(10) << numeric::to_string(p.flight[i].velocity, 6) << "  " << std::setw(16)
         << numeric::to_string(p.flight[i].apex_height, 6) << "  " << std::setw(14) << numeric::to_string(p.flight[i].apex_time, 6) << '\n';
  }
  return os.str();
}

}  // namespace superball::present
