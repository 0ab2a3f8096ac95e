#include "superball/numeric/sweep.hpp"

#include <cln/rational_io.h>

#include <stdexcept>

namespace superball::numeric {
ExactPoint solve_exact_at(const Scene& scene, const Parameter& parameter, const cln::cl_RA& value) {
  auto problem = Problem<cln::cl_RA>::from(ExactScene::from(with_value(scene, parameter, value)));
  auto solution = solve(problem);
  return {std::move(problem), std::move(solution)};
}

std::vector<LabelChange> label_changes(const Scene& scene, const Parameter& parameter, const std::vector<cln::cl_RA>& values,
                                       const Label& label, int bits) {
  std::vector<LabelChange> out;
  auto at = [&](const cln::cl_RA& v) { return label(solve_exact_at(scene, parameter, v)); };
  std::string previous = values.empty() ? "" : at(values.front());
  for (std::size_t k = 1; k < values.size(); ++k) {
    LabelChange c{values[k - 1], values[k], previous, at(values[k])};
    previous = c.above;
    if (c.below == c.above) continue;
    for (int b = 0; b < bits; ++b) {
      const cln::cl_RA mid = (c.low + c.high) / 2;
      const std::string l = at(mid);
      if (l == c.below) {
        c.low = mid;
      } else {
        c.high = mid;
        c.above = l;
      }
    }
    out.push_back(c);
  }
  return out;
}

std::vector<cln::cl_RA> linspace(const cln::cl_RA& from, const cln::cl_RA& to, int steps) {
  if (steps < 2) throw std::invalid_argument("linspace(): a sweep needs at least 2 steps");
  std::vector<cln::cl_RA> v;
  v.reserve(static_cast<std::size_t>(steps));
  for (int k = 0; k < steps; ++k) v.push_back(from + (to - from) * k / (steps - 1));
  return v;
}

Scene with_value(const Scene& scene, const Parameter& parameter, const cln::cl_RA& value) {
  Scene s = scene;
  parameter.set(s, Number::parse(to_string(value)));
  return s;
}

std::vector<SweepPoint> sweep(const Scene& scene, const Parameter& parameter, const std::vector<cln::cl_RA>& values,
                              const Precision& precision) {
  std::vector<SweepPoint> out;
  out.reserve(values.size());
  for (const auto& value : values) {
    const auto exact = ExactScene::from(with_value(scene, parameter, value));
    out.push_back(with_scalar(precision, [&](auto tag) {
      using S = decltype(tag);
      using T = ScalarTraits<S>;
      const auto problem = Problem<S>::from(exact, precision.digits);
      const auto sol = solve(problem);
      SweepPoint p{value, {}, sol.closed, sol.status};
      const double unit = problem.unit_exact ? T::to_double(problem.unit) : std::sqrt(cln::double_approx(exact.unit_squared()));
      for (const auto& w : sol.velocities_after) p.velocities_after.push_back(T::to_double(w) * unit);
      return p;
    }));
  }
  return out;
}

std::vector<SwitchPoint> switch_points(const Scene& scene, const Parameter& parameter, const std::vector<SweepPoint>& points,
                                       int bits) {
  std::vector<cln::cl_RA> values;
  for (const auto& p : points) values.push_back(p.value);
  const Label by_case = [](const ExactPoint& e) { return e.solution.closed.to_string(); };
  std::vector<SwitchPoint> out;
  for (const auto& c : label_changes(scene, parameter, values, by_case, bits))
    out.push_back({c.low, c.high, solve_exact_at(scene, parameter, c.low).solution.closed,
                   solve_exact_at(scene, parameter, c.high).solution.closed});
  return out;
}

}  // namespace superball::numeric
