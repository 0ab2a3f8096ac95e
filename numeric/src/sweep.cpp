#include "superball/numeric/sweep.hpp"

#include <cln/rational_io.h>

#include <stdexcept>

namespace superball::numeric {
namespace {

/// The evolution case of the exact solution at \p value.
ContactSet exact_case(const Scene& scene, const Parameter& parameter, const cln::cl_RA& value) {
  const auto exact = ExactScene::from(with_value(scene, parameter, value));
  return solve(Problem<cln::cl_RA>::from(exact)).closed;
}

}  // namespace

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
  std::vector<SwitchPoint> out;
  for (std::size_t k = 1; k < points.size(); ++k) {
    SwitchPoint s{points[k - 1].value, points[k].value, exact_case(scene, parameter, points[k - 1].value),
                  exact_case(scene, parameter, points[k].value)};
    if (s.below == s.above) continue;
    for (int b = 0; b < bits; ++b) {
      const cln::cl_RA mid = (s.low + s.high) / 2;
      const ContactSet c = exact_case(scene, parameter, mid);
      if (c == s.below) {
        s.low = mid;
      } else if (c == s.above) {
        s.high = mid;
      } else {  // a third case in between: keep the nearer change
        s.high = mid;
        s.above = c;
      }
    }
    out.push_back(s);
  }
  return out;
}

}  // namespace superball::numeric
