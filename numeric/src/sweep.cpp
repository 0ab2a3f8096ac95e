#include "superball/numeric/sweep.hpp"

#include <cln/rational_io.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>

#include "superball/cases/error.hpp"
#include "superball/numeric/certify.hpp"
#include "superball/numeric/cluster.hpp"
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

/// check_range(), returning the scenes at \p from and at \p to.
std::pair<Scene, Scene> checked_ends(const Scene& scene, const Parameter& parameter, const cln::cl_RA& from, const cln::cl_RA& to) {
  std::vector<Scene> ends;
  for (const cln::cl_RA& end : {from, to}) {
    ends.push_back(with_value(scene, parameter, end));
    const Scene& s = ends.back();
    try {
      (void)ExactScene::from(s);
    } catch (const InputError& e) {
      // "ORIGIN: field: why" -> "ORIGIN: KEY = VALUE: field: why"
      const std::string what = e.what(), prefix = scene.origin + ": ";
      throw InputError(prefix + parameter.key() + " = " + to_string(end) + ": " +
                       (what.rfind(prefix, 0) == 0 ? what.substr(prefix.size()) : what));
    }
  }
  return {std::move(ends[0]), std::move(ends[1])};
}

/// check_range() from the smallest to the largest of \p values: every value
/// a sweep sets lies between two that passed every check.
/// Returns the scenes at the smallest and the largest value (none without values).
std::optional<std::pair<Scene, Scene>> check_values(const Scene& scene, const Parameter& parameter, const std::vector<cln::cl_RA>& values) {
  if (values.empty()) return std::nullopt;
  const auto [low, high] = std::minmax_element(values.begin(), values.end());
  return checked_ends(scene, parameter, *low, *high);
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

/// A thread's copy of a line's problem in S (double or long double), for
/// the shortcut of label_changes(): converted once, only the entry of M set
/// at each value, as entry_sweep() does.
template <class S>
struct EntryProblem {
  Problem<S> problem;
  std::size_t entry;
  bool in_range;  ///< Problem::from()'s verdict on everything but the entry

  EntryProblem(const ExactScene& exact, std::size_t k) : problem(Problem<S>::from(exact, 0)), entry(k), in_range(true) {
    ExactScene one = exact;
    one.entries[k].value = 1;
    in_range = Problem<S>::from(one, 0).in_range;
  }

  /// What the solve at \p value proves about the exact solution there, or
  /// nothing when its case is not certain.  The superball verdict is proven
  /// when U₁⁺ − |U₁⁻| exceeds the certified bound on U₁⁺ plus the rounding
  /// of U₁⁻ and of the comparison (proven_verdict_rounding).
  std::optional<ProvenPoint> prove(const cln::cl_RA& value) {
    using T = ScalarTraits<S>;
    const S v = T::from(value, 0);
    if (!detail::held(v, cln::zerop(value))) return std::nullopt;
    problem.entries[entry].value = v;
    problem.in_range = in_range;
    const Solution<S> sol = solve(problem);
    const Certificate c = certify(problem, sol);
    if (!c.case_certain || !std::isfinite(c.relative_error)) return std::nullopt;
    ProvenPoint p{sol.closed, std::nullopt};
    S largest = 0;
    for (const S& w : sol.velocities_after) largest = std::max(largest, S(std::fabs(w)));
    const S after = sol.velocities_after[0], before = std::fabs(problem.u[0]);
    const S bound = S(c.relative_error) * largest + S(proven_verdict_rounding) * T::unit_roundoff(0) * (std::fabs(after) + before + largest);
    if (after - before > bound) p.superball = true;
    if (before - after > bound) p.superball = false;
    return p;
  }
};

/// The exact problem of a line, only the entry of M set at each value, for
/// the shortcut of label_changes() where floating point cannot decide: the
/// cases met last are tried in turn, each by its cluster system alone
/// (detail::ClusterSystem: one banded solve, no pivoting, no tableau).  A
/// case whose every closed contact has a reaction < 0 and every open one a
/// gap > 0, exactly, is the exact solution's case: the velocities after the
/// collision are unique and strict complementarity fixes the closed set, so
/// a solve finds the same case and the same velocities.
struct ExactCases {
  Problem<cln::cl_RA> problem;
  std::size_t entry;
  int bandwidth;
  detail::ClusterSystem<cln::cl_RA> system;
  std::vector<cln::cl_RA> W, lambda;
  std::vector<char> flags;
  std::vector<ContactSet> recent;  ///< the cases met last, the latest first

  ExactCases(const ExactScene& exact, std::size_t k)
      : problem(Problem<cln::cl_RA>::from(exact, 0)), entry(k), bandwidth(problem.bandwidth()) {}

  /// Remember \p closed as the latest case met (two are kept: a bisection's
  /// bracket has a case at each end).
  void met(const ContactSet& closed) {
    const auto at = std::find(recent.begin(), recent.end(), closed);
    if (at != recent.end()) recent.erase(at);
    recent.insert(recent.begin(), closed);
    if (recent.size() > 2) recent.pop_back();
  }

  /// The exact case and superball verdict at \p value when one of the
  /// cases met last holds there strictly, else nothing.
  std::optional<ProvenPoint> prove(const cln::cl_RA& value) {
    problem.entries[entry].value = value;
    system.assemble(problem, bandwidth);
    for (const ContactSet& closed : recent) {
      flags.assign(static_cast<std::size_t>(closed.contacts()), 0);
      for (int c = 0; c < closed.contacts(); ++c) flags[static_cast<std::size_t>(c)] = closed.closed(c);
      if (!system.solve(problem, flags, W, lambda)) continue;
      bool strict = true;
      for (int c = 0; c < closed.contacts() && strict; ++c) {
        const auto k = static_cast<std::size_t>(c);
        strict = closed.closed(c) ? cln::plusp(lambda[k]) : cln::plusp(W[k] - W[k + 1]);
      }
      if (strict) return ProvenPoint{closed, W[0] > cln::abs(problem.u[0])};
    }
    return std::nullopt;
  }
};

/// A thread's means of labelling the exact solution at a value: its own copy
/// of the scene for the exact solve, and, with a ProvenLabel along an entry
/// of M, the shortcuts tried first: floating-point solves, then the cases
/// met last checked exactly.
struct Labeller {
  Scene scene;
  const Parameter& parameter;
  const Label& label;
  const ProvenLabel& proven;
  std::optional<EntryProblem<double>> in_double;
  std::optional<EntryProblem<long double>> in_long_double;
  std::optional<ExactCases> exactly;
  std::array<std::atomic<std::size_t>, 4>& found_by;  ///< in double, in long double, by a case, solved

  Labeller(const Scene& s, const Parameter& p, const Label& l, const ProvenLabel& pl, std::optional<std::size_t> entry,
           std::array<std::atomic<std::size_t>, 4>& counts)
      : scene(s), parameter(p), label(l), proven(pl), found_by(counts) {
    if (!entry || !proven) return;
    const ExactScene exact = ExactScene::from(scene);
    in_double.emplace(exact, *entry);
    in_long_double.emplace(exact, *entry);
    exactly.emplace(exact, *entry);
  }

  /// The label of the exact solution at \p value (\p text: the same value
  /// as text): proven in double, else in long double, else by the cases met
  /// last, else from the exact solve.
  std::string operator()(const cln::cl_RA& value, const std::string& text) {
    if (exactly) {
      std::optional<std::string> l;
      std::optional<ProvenPoint> p;
      std::size_t by = 0;
      for (; by < 3 && !l; ++by) {
        p = by == 0 ? in_double->prove(value) : by == 1 ? in_long_double->prove(value) : exactly->prove(value);
        if (p) l = proven(*p);
      }
      if (l) {
        ++found_by[by - 1];
        exactly->met(p->closed);
        return std::move(*l);
      }
    }
    ++found_by[3];
    const ExactPoint e = solve_exact(set_value(scene, parameter, text));
    if (exactly) exactly->met(e.solution.closed);
    return label(e);
  }
};

/// Every change of label inside \p c (c.below at c.low, c.above at
/// c.high, different), found by \p bits halvings, appended to \p out from
/// c.low to c.high: where the midpoint's label is neither end's, both halves
/// hold a change and both are searched.
void bisect(Labeller& label_at, LabelChange c, int bits, std::vector<LabelChange>& out) {
  for (; bits > 0; --bits) {
    const cln::cl_RA mid = (c.low + c.high) / 2;
    std::string l = label_at(mid, to_string(mid));
    if (l == c.below) {
      c.low = mid;
    } else if (l == c.above) {
      c.high = mid;
    } else {
      bisect(label_at, {c.low, mid, c.below, l}, bits - 1, out);
      c.low = mid;
      c.below = std::move(l);
    }
  }
  out.push_back(std::move(c));
}

}  // namespace

std::vector<LabelChange> label_changes(const Scene& scene, const Parameter& parameter, const std::vector<cln::cl_RA>& values,
                                       const Label& label, int bits, int threads, const ProvenLabel& proven, LabelCounts* counts) {
  const auto ends = check_values(scene, parameter, values);
  // In increasing value: a descending sweep has the same brackets, read backwards.
  const bool descending = values.size() > 1 && values.back() < values.front();
  std::vector<std::string> texts = as_text(values);
  if (descending) std::reverse(texts.begin(), texts.end());
  // The shortcut needs the parameter to be one entry of M along the whole range.
  std::optional<std::size_t> entry;
  if (proven && ends && texts.front() != texts.back()) entry = detail::entry_changed(ends->first, ends->second);
  const Scene& first = ends ? ends->first : scene;
  std::array<std::atomic<std::size_t>, 4> found_by{};
  // One labeller per thread, made on it; on one thread, one for both passes
  // (the cases met at the values are the first the bisections try).
  const bool one_thread = thread_count(threads) == 1 || values.size() < 2;
  std::shared_ptr<Labeller> only;
  if (one_thread) only = std::make_shared<Labeller>(first, parameter, label, proven, entry, found_by);
  auto make_labeller = [&] { return one_thread ? only : std::make_shared<Labeller>(first, parameter, label, proven, entry, found_by); };
  using Own = std::shared_ptr<Labeller>;
  const std::vector<std::string> labels = parallel_map(texts.size(), threads, make_labeller, [&](Own& label_at, std::size_t k) {
    return (*label_at)(parse_rational(texts[k]), texts[k]);
  });
  std::vector<std::size_t> changes;  // k: the label changes between values k − 1 and k
  for (std::size_t k = 1; k < texts.size(); ++k)
    if (labels[k - 1] != labels[k]) changes.push_back(k);
  const auto found = parallel_map(changes.size(), threads, make_labeller, [&](Own& label_at, std::size_t m) {
    const std::size_t k = changes[m];
    std::vector<LabelChange> out;
    bisect(*label_at, {parse_rational(texts[k - 1]), parse_rational(texts[k]), labels[k - 1], labels[k]}, bits, out);
    return out;
  });
  std::vector<LabelChange> all;
  for (const auto& f : found) all.insert(all.end(), f.begin(), f.end());
  if (counts) *counts = {found_by[0], found_by[1], found_by[2], found_by[3]};
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
  (void)checked_ends(scene, parameter, from, to);
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
    st.problem.in_range = st.in_range && detail::held(converted[k], zero[k]);
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
  const ProvenLabel proven_case = [](const ProvenPoint& p) -> std::optional<std::string> { return p.closed.to_string(); };
  // The label back to the case: "{2-3,3-4}" without its braces.
  auto as_case = [&](const std::string& label) { return ContactSet::parse(label.substr(1, label.size() - 2), scene.size()); };
  std::vector<SwitchPoint> out;
  for (const auto& c : label_changes(scene, parameter, values, by_case, bits, threads, proven_case))
    out.push_back({c.low, c.high, as_case(c.below), as_case(c.above)});
  return out;
}

}  // namespace superball::numeric
