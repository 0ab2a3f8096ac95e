#include "superball/numeric/sweep.hpp"

#include <cln/rational_io.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "superball/cases/error.hpp"
#include "superball/numeric/map.hpp"
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

/// A thread's own copy of the scene, with the parameter set to \p text, a
/// value inside a range that check_values() has passed.
const Scene& set_value(Scene& copy, const Parameter& parameter, const std::string& text) {
  parameter.assign(copy, Number::parse(text));
  return copy;
}

/// check_range() from the smallest to the largest of \p values: every value
/// a sweep sets lies between two that passed every check.
void check_values(const Scene& scene, const Parameter& parameter, const std::vector<cln::cl_RA>& values) {
  if (values.empty()) return;
  const auto [low, high] = std::minmax_element(values.begin(), values.end());
  check_range(scene, parameter, *low, *high);
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

namespace {

/// Every change of \p label inside \p c (c.below at c.low, c.above at
/// c.high, different), found by \p bits halvings, appended to \p out from
/// c.low to c.high: where the midpoint's label is neither end's, both halves
/// hold a change and both are searched.
void bisect(Scene& s, const Parameter& parameter, const Label& label, LabelChange c, int bits, std::vector<LabelChange>& out) {
  for (; bits > 0; --bits) {
    const cln::cl_RA mid = (c.low + c.high) / 2;
    std::string l = label(solve_exact(set_value(s, parameter, to_string(mid))));
    if (l == c.below) {
      c.low = mid;
    } else if (l == c.above) {
      c.high = mid;
    } else {
      bisect(s, parameter, label, {c.low, mid, c.below, l}, bits - 1, out);
      c.low = mid;
      c.below = std::move(l);
    }
  }
  out.push_back(std::move(c));
}

}  // namespace

std::vector<LabelChange> label_changes(const Scene& scene, const Parameter& parameter, const std::vector<cln::cl_RA>& values,
                                       const Label& label, int bits, int threads) {
  check_values(scene, parameter, values);
  // In increasing value: a descending sweep has the same brackets, read backwards.
  const bool descending = values.size() > 1 && values.back() < values.front();
  std::vector<std::string> texts = as_text(values);
  if (descending) std::reverse(texts.begin(), texts.end());
  auto own_scene = [&scene] { return scene; };
  const std::vector<std::string> labels = parallel_map(texts.size(), threads, own_scene, [&](Scene& s, std::size_t k) {
    return label(solve_exact(set_value(s, parameter, texts[k])));
  });
  std::vector<std::size_t> changes;  // k: the label changes between values k − 1 and k
  for (std::size_t k = 1; k < texts.size(); ++k)
    if (labels[k - 1] != labels[k]) changes.push_back(k);
  const auto found = parallel_map(changes.size(), threads, own_scene, [&](Scene& s, std::size_t m) {
    const std::size_t k = changes[m];
    std::vector<LabelChange> out;
    bisect(s, parameter, label, {parse_rational(texts[k - 1]), parse_rational(texts[k]), labels[k - 1], labels[k]}, bits, out);
    return out;
  });
  std::vector<LabelChange> all;
  for (const auto& f : found) all.insert(all.end(), f.begin(), f.end());
  return all;
}

std::vector<cln::cl_RA> linspace(const cln::cl_RA& from, const cln::cl_RA& to, int steps, int first, int count) {
  if (steps < 2) throw std::invalid_argument("linspace(): a sweep needs at least 2 steps");
  if (count < 0) count = steps - first;
  if (first < 0 || count < 0 || first > steps - count)
    throw std::invalid_argument("linspace(): values " + std::to_string(first) + " .. " + std::to_string(first + count - 1) +
                                " are not among the " + std::to_string(steps));
  std::vector<cln::cl_RA> v;
  v.reserve(static_cast<std::size_t>(count));
  for (int k = first; k < first + count; ++k) v.push_back(from + (to - from) * k / (steps - 1));
  return v;
}

Scene with_value(const Scene& scene, const Parameter& parameter, const cln::cl_RA& value) {
  Scene s = scene;
  parameter.set(s, Number::parse(to_string(value)));
  return s;
}

void check_range(const Scene& scene, const Parameter& parameter, const cln::cl_RA& from, const cln::cl_RA& to) {
  for (const cln::cl_RA& end : {from, to}) {
    const Scene s = with_value(scene, parameter, end);
    try {
      (void)ExactScene::from(s);
    } catch (const InputError& e) {
      // "ORIGIN: field: why" -> "ORIGIN: KEY = VALUE: field: why"
      const std::string what = e.what(), prefix = scene.origin + ": ";
      throw InputError(prefix + parameter.key() + " = " + to_string(end) + ": " +
                       (what.rfind(prefix, 0) == 0 ? what.substr(prefix.size()) : what));
    }
  }
}

namespace {

/// sweep() of a parameter that is the entry \p entry of M of \p first (the
/// scene at the first value), in S (double or long double): each thread
/// converts \p first once and sets only that entry at each value.  The
/// problem solved is Problem<S>::from() of the value's scene, so the points
/// are those of converting each scene, bit for bit; M stays positive
/// semi-definite between the checked ends (check_range()).
template <class S>
std::vector<SweepPoint> entry_sweep(const Scene& first, std::size_t entry, const std::vector<cln::cl_RA>& values,
                                    const Precision& precision, int threads) {
  using T = ScalarTraits<S>;
  std::vector<S> converted;
  std::vector<char> zero;
  for (const auto& v : values) converted.push_back(T::from(v, precision.digits)), zero.push_back(cln::zerop(v));
  // As Problem::from(): finite, and a nonzero value not rounded to zero or a subnormal number.
  auto held = [](const S& v, bool is_zero) { return std::isfinite(v) && (is_zero || std::fabs(v) >= std::numeric_limits<S>::min()); };
  struct State {
    Problem<S> problem;
    bool in_range = true;  ///< Problem::from()'s verdict on everything but the entry
    double unit = 1;
  };
  auto make_state = [&] {
    const ExactScene exact = ExactScene::from(first);
    ExactScene one = exact;
    one.entries[entry].value = 1;
    State st{Problem<S>::from(exact, precision.digits), Problem<S>::from(one, precision.digits).in_range, 1};
    st.unit = st.problem.unit_exact ? T::to_double(st.problem.unit) : std::sqrt(cln::double_approx(exact.unit_squared()));
    return st;
  };
  auto points = parallel_map(values.size(), threads, make_state, [&](State& st, std::size_t k) {
    st.problem.entries[entry].value = converted[k];
    st.problem.in_range = st.in_range && held(converted[k], zero[k]);
    const auto sol = solve(st.problem);
    SweepPoint p{0, {}, sol.closed, sol.status};
    for (const auto& w : sol.velocities_after) p.velocities_after.push_back(T::to_double(w) * st.unit);
    return p;
  });
  // The values, copied on the calling thread (the workers never touch the caller's CLN objects).
  for (std::size_t k = 0; k < points.size(); ++k) points[k].value = values[k];
  return points;
}

}  // namespace

std::vector<SweepPoint> sweep(const Scene& scene, const Parameter& parameter, const std::vector<cln::cl_RA>& values,
                              const Precision& precision, int threads) {
  check_values(scene, parameter, values);
  if (values.size() > 1 && (precision.kind == Precision::Kind::Double || precision.kind == Precision::Kind::LongDouble)) {
    const Scene first = with_value(scene, parameter, values.front());
    const auto other = std::find_if(values.begin(), values.end(), [&](const cln::cl_RA& v) { return v != values.front(); });
    const auto entry = other == values.end() ? std::nullopt : detail::entry_changed(first, with_value(scene, parameter, *other));
    if (entry && precision.kind == Precision::Kind::Double) return entry_sweep<double>(first, *entry, values, precision, threads);
    if (entry) return entry_sweep<long double>(first, *entry, values, precision, threads);
  }
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
  return switch_points(scene, parameter, values, bits, threads);
}

std::vector<SwitchPoint> switch_points(const Scene& scene, const Parameter& parameter, const std::vector<cln::cl_RA>& values,
                                       int bits, int threads) {
  const Label by_case = [](const ExactPoint& e) { return e.solution.closed.to_string(); };
  // The label back to the case: "{2-3,3-4}" without its braces.
  auto as_case = [&](const std::string& label) { return ContactSet::parse(label.substr(1, label.size() - 2), scene.size()); };
  std::vector<SwitchPoint> out;
  for (const auto& c : label_changes(scene, parameter, values, by_case, bits, threads))
    out.push_back({c.low, c.high, as_case(c.below), as_case(c.above)});
  return out;
}

}  // namespace superball::numeric
