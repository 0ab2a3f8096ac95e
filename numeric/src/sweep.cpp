#include "superball/numeric/sweep.hpp"

#include <cln/rational_io.h>

#include <stdexcept>

#include "superball/numeric/parallel.hpp"

namespace superball::numeric {
namespace {

/// The values as text, written on the calling thread: tasks on other threads
/// parse their own copies and never touch the caller's CLN objects.
std::vector<std::string> as_text(const std::vector<cln::cl_RA>& values) {
  std::vector<std::string> texts;
  texts.reserve(values.size());
  for (const auto& v : values) texts.push_back(to_string(v));
  return texts;
}

/// A thread's own copy of the scene, with the parameter set to \p text.
const Scene& set_value(Scene& copy, const Parameter& parameter, const std::string& text) {
  parameter.set(copy, Number::parse(text));
  return copy;
}

ExactPoint solve_exact(const Scene& scene) {
  auto problem = Problem<cln::cl_RA>::from(ExactScene::from(scene));
  auto solution = solve(problem);
  return {std::move(problem), std::move(solution)};
}

}  // namespace

ExactPoint solve_exact_at(const Scene& scene, const Parameter& parameter, const cln::cl_RA& value) {
  return solve_exact(with_value(scene, parameter, value));
}

std::vector<LabelChange> label_changes(const Scene& scene, const Parameter& parameter, const std::vector<cln::cl_RA>& values,
                                       const Label& label, int bits, int threads) {
  const std::vector<std::string> texts = as_text(values);
  auto own_scene = [&scene] { return scene; };
  const std::vector<std::string> labels = parallel_map(values.size(), threads, own_scene, [&](Scene& s, std::size_t k) {
    return label(solve_exact(set_value(s, parameter, texts[k])));
  });
  std::vector<std::size_t> changes;  // k: the label changes between values k − 1 and k
  for (std::size_t k = 1; k < values.size(); ++k)
    if (labels[k - 1] != labels[k]) changes.push_back(k);
  return parallel_map(changes.size(), threads, own_scene, [&](Scene& s, std::size_t m) {
    const std::size_t k = changes[m];
    LabelChange c{parse_rational(texts[k - 1]), parse_rational(texts[k]), labels[k - 1], labels[k]};
    for (int b = 0; b < bits; ++b) {
      const cln::cl_RA mid = (c.low + c.high) / 2;
      const std::string l = label(solve_exact(set_value(s, parameter, to_string(mid))));
      if (l == c.below) {
        c.low = mid;
      } else {
        c.high = mid;
        c.above = l;
      }
    }
    return c;
  });
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
                              const Precision& precision, int threads) {
  const std::vector<std::string> texts = as_text(values);
  return parallel_map(values.size(), threads, [&scene] { return scene; }, [&](Scene& s, std::size_t k) {
    const auto exact = ExactScene::from(set_value(s, parameter, texts[k]));
    return with_scalar(precision, [&](auto tag) {
      using S = decltype(tag);
      using T = ScalarTraits<S>;
      const auto problem = Problem<S>::from(exact, precision.digits);
      const auto sol = solve(problem);
      SweepPoint p{parse_rational(texts[k]), {}, sol.closed, sol.status};
      const double unit = problem.unit_exact ? T::to_double(problem.unit) : std::sqrt(cln::double_approx(exact.unit_squared()));
      for (const auto& w : sol.velocities_after) p.velocities_after.push_back(T::to_double(w) * unit);
      return p;
    });
  });
}

std::vector<SwitchPoint> switch_points(const Scene& scene, const Parameter& parameter, const std::vector<SweepPoint>& points,
                                       int bits, int threads) {
  std::vector<cln::cl_RA> values;
  for (const auto& p : points) values.push_back(p.value);
  const Label by_case = [](const ExactPoint& e) { return e.solution.closed.to_string(); };
  // The label back to the case: "{2-3,3-4}" without its braces.
  auto as_case = [&](const std::string& label) { return ContactSet::parse(label.substr(1, label.size() - 2), scene.size()); };
  std::vector<SwitchPoint> out;
  for (const auto& c : label_changes(scene, parameter, values, by_case, bits, threads))
    out.push_back({c.low, c.high, as_case(c.below), as_case(c.above)});
  return out;
}

}  // namespace superball::numeric
