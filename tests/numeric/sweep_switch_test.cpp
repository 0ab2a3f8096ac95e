// Sweeps and their switch points (issue 12): every change of case between
// two sweep values of different case is found, the changes chain (each
// starts in the case the previous one ended in), a descending range gives
// the same brackets as the ascending one, and a range holding an
// inadmissible value is refused, whichever end holds it.
#include <gtest/gtest.h>

#include <functional>
#include <optional>
#include <utility>
#include <iostream>
#include <string>
#include <vector>

#include "superball/cases/parameter.hpp"
#include "superball/numeric/sweep.hpp"
#include "support.hpp"

namespace superball::testing {
namespace {

const std::string kPaper = std::string(SUPERBALL_CASES_DIR) + "/scenes/paper-4.4-alpha2.toml";

/// The exact case of \p scene at \p value.
ContactSet case_at(const Scene& scene, const Parameter& parameter, const cl_RA& value) {
  return numeric::solve_exact_at(scene, parameter, value).solution.closed;
}

/// The switch points of a sweep of \p steps values from \p from to \p to
/// describe the cases along the whole range: they chain from the case at the
/// low end to the case at the high end, in increasing value, each bracket
/// (narrower than 2^-64 of the step) holding its change: the exact case is
/// `below` at its low end and `above` at its high end.
std::vector<numeric::SwitchPoint> check_chain(const Scene& scene, const Parameter& parameter, const cl_RA& from, const cl_RA& to,
                                              int steps, const std::string& context) {
  SCOPED_TRACE(context + ", " + parameter.key() + " = " + text(from) + ":" + text(to) + ":" + std::to_string(steps));
  const auto switches = numeric::switch_points(scene, parameter, numeric::linspace(from, to, steps), 64, 2);
  const cl_RA low = max_q(from, to) == to ? from : to, high = low == from ? to : from;
  const cl_RA step_limit = (high - low) / (steps - 1) / cln::expt(cl_RA(2), 64);
  ContactSet current = case_at(scene, parameter, low);
  cl_RA last = low;
  for (const auto& s : switches) {
    EXPECT_EQ(s.below, current) << "a switch starts in " << s.below.to_string() << ", the case before it is " << current.to_string();
    EXPECT_NE(s.below, s.above);
    EXPECT_TRUE(last <= s.low && s.low < s.high && s.high <= high) << "[" << approx(s.low) << ", " << approx(s.high) << "]";
    EXPECT_TRUE(s.high - s.low <= step_limit) << "bracket width " << approx(s.high - s.low);
    EXPECT_EQ(case_at(scene, parameter, s.low), s.below);
    EXPECT_EQ(case_at(scene, parameter, s.high), s.above);
    current = s.above;
    last = s.high;
  }
  EXPECT_EQ(current, case_at(scene, parameter, high)) << "the switches end in " << current.to_string();
  return switches;
}

TEST(SweepSwitchPoints, PaperSceneChainsOnAnyGrid) {
  // Fig. 7: 2.2 -> 3.3 at K34 ≈ 6.4287, 3.3 -> 3.2 at K34 ≈ 13.412.  With 2
  // values both changes lie between the ends (2.2 at 0, 3.2 at 20).
  const Scene scene = load_scene(kPaper);
  const Parameter k34 = Parameter::parse("K.3-4", scene);
  for (int steps : {2, 3, 41, 401}) {
    const auto s = check_chain(scene, k34, 0, 20, steps, "paper");
    ASSERT_EQ(s.size(), 2u) << steps << " steps";
    EXPECT_NEAR(approx(s[0].low), 6.4287436235676171, 1e-12);
    EXPECT_NEAR(approx(s[1].low), 13.411993850493881, 1e-12);
  }
}

TEST(SweepSwitchPoints, DescendingRangeGivesTheSameBrackets) {
  const Scene scene = load_scene(kPaper);
  const Parameter k34 = Parameter::parse("K.3-4", scene);
  const auto up = numeric::switch_points(scene, k34, numeric::linspace(0, 20, 5));
  const auto down = check_chain(scene, k34, 20, 0, 5, "paper, descending");
  ASSERT_EQ(down.size(), up.size());
  for (std::size_t k = 0; k < up.size(); ++k) {
    EXPECT_EQ(down[k].low, up[k].low);
    EXPECT_EQ(down[k].high, up[k].high);
    EXPECT_EQ(down[k].below, up[k].below);
    EXPECT_EQ(down[k].above, up[k].above);
  }
}

/// Random scenes whose top mass is swept.
constexpr std::uint64_t kRandomScenes = 16;

TEST(SweepSwitchPoints, RandomScenesChainWhenAMassIsVaried) {
  // The top mass from 1/1000 to 1000 times its value: a light ball bounces
  // off, a heavy one stays, and the cases in between change several times on
  // many scenes.  Several changes between two values are the rule on 2 values.
  int several = 0;
  for (std::uint64_t seed = 1; seed <= kRandomScenes; ++seed) {
    const RandomScene r = random_scene(seed, {3, 6});
    const Scene scene = r.scene();
    const Parameter mass = Parameter::parse("mass.1", scene);
    const cl_RA m = numeric::parse_rational(scene.bodies[0].mass.fraction());
    for (int steps : {2, 41}) {
      const auto s = check_chain(scene, mass, m / 1000, m * 1000, steps, r.describe());
      if (steps == 2 && s.size() >= 2) ++several;
    }
  }
  std::cout << "[ info ] " << several << " of " << kRandomScenes << " random scenes change case more than once between the two ends\n";
  EXPECT_GT(several, 0) << "the test does not exercise a third case inside a bracket";
}

/// The declared K's of a random scene, as (key, value): the entries of M on
/// its diagonal, which a sweep can raise without leaving the PSD cone.
std::vector<std::pair<std::string, cl_RA>> declared_k(const RandomScene& r) {
  std::vector<std::pair<std::string, cl_RA>> out;
  const auto line = r.toml.find("K = {");
  if (line == std::string::npos) return out;
  const std::string k = r.toml.substr(line, r.toml.find('}', line) - line);
  for (std::size_t at = k.find('"'); at != std::string::npos;) {
    const std::size_t name_end = k.find('"', at + 1), value_at = k.find('"', name_end + 1), value_end = k.find('"', value_at + 1);
    out.push_back({"K." + k.substr(at + 1, name_end - at - 1), numeric::parse_rational(k.substr(value_at + 1, value_end - value_at - 1))});
    at = k.find('"', value_end + 1);
  }
  return out;
}

TEST(SweepSwitchPoints, CheckShortcutGivesTheExactBisectionBitForBit) {
  // label_changes() with a ProvenLabel skips the exact solve wherever a
  // certified double solve, or the exact check of a case met last (its signs
  // as interpolated polynomials), decides the label; the brackets must be those of the exact bisection,
  // bit for bit, for the case and for the map's region (case and superball).
  const numeric::Label by_case = [](const numeric::ExactPoint& e) { return e.solution.closed.to_string(); };
  const numeric::ProvenLabel proven_case = [](const numeric::ProvenPoint& p) -> std::optional<std::string> { return p.closed.to_string(); };
  const numeric::Label by_region = [](const numeric::ExactPoint& e) {
    return e.solution.closed.to_string() + (e.solution.velocities_after[0] > cln::abs(e.problem.u[0]) ? " superball" : "");
  };
  const numeric::ProvenLabel proven_region = [](const numeric::ProvenPoint& p) -> std::optional<std::string> {
    if (!p.superball) return std::nullopt;
    return p.closed.to_string() + (*p.superball ? " superball" : "");
  };
  numeric::LabelCounts total;
  std::size_t changes = 0;
  auto compare = [&](const Scene& scene, const Parameter& parameter, const std::vector<cl_RA>& values, const numeric::Label& label,
                     const numeric::ProvenLabel& proven, int threads, const std::string& context) {
    SCOPED_TRACE(context + ", " + parameter.key());
    numeric::LabelCounts counts;
    const auto exact = numeric::label_changes(scene, parameter, values, label, 64, 1);
    const auto fast = numeric::label_changes(scene, parameter, values, label, 64, threads, proven, &counts);
    ASSERT_EQ(fast.size(), exact.size());
    for (std::size_t k = 0; k < exact.size(); ++k) {
      EXPECT_EQ(fast[k].low, exact[k].low);
      EXPECT_EQ(fast[k].high, exact[k].high);
      EXPECT_EQ(fast[k].below, exact[k].below);
      EXPECT_EQ(fast[k].above, exact[k].above);
    }
    changes += exact.size();
    total.in_double += counts.in_double, total.by_case += counts.by_case, total.solved += counts.solved;
  };
  const Scene paper = load_scene(kPaper);
  for (const char* key : {"K.3-4", "alpha.2"}) {
    const Parameter p = Parameter::parse(key, paper);
    const auto values = std::string(key) == "K.3-4" ? numeric::linspace(0, 20, 9) : numeric::linspace(-100, 0, 9);
    compare(paper, p, values, by_case, proven_case, 1, "paper");
    compare(paper, p, values, by_region, proven_region, 2, "paper");
  }
  for (std::uint64_t seed = 1; seed <= kRandomScenes; ++seed) {
    const RandomScene r = random_scene(seed, {3, 6});
    const Scene scene = r.scene();
    for (const auto& [key, value] : declared_k(r)) {
      const Parameter p = Parameter::parse(key, scene);
      const auto values = numeric::linspace(value, value * 100 + 1, 5);  // raised only: M stays PSD
      compare(scene, p, values, by_case, proven_case, 1 + static_cast<int>(seed % 2), r.describe());
      compare(scene, p, values, by_region, proven_region, 1, r.describe());
    }
  }
  std::cout << "[ info ] " << changes << " changes; labels found in double " << total.in_double << ", by a case checked exactly "
            << total.by_case << ", by an exact solve " << total.solved << "\n";
  EXPECT_GT(changes, 20u) << "too few changes to exercise the shortcut";
  EXPECT_GT(total.in_double, 0u);
  EXPECT_GT(total.by_case, 0u);
}

TEST(SweepRange, InadmissibleValuesAreRefusedAtEitherEnd) {
  const Scene scene = load_scene(kPaper);
  struct Bad {
    const char* key;
    cl_RA from, to;
    const char* value;  // the value named in the message
    const char* why;
  };
  const Bad bad[] = {{"g", -1, 1, "g = -1", "must be > 0"},
                     {"g", 1, 0, "g = 0", "must be > 0"},
                     {"fall_speed", -1, 1, "fall_speed = -1", "must be >= 0"},
                     {"mass.1", 1, 0, "mass.1 = 0", "must be > 0"},
                     {"K.3-4", -100, 20, "K.3-4 = -100", "not positive semi-definite"},
                     {"alpha.2", 0, -1000, "alpha.2 = -1000", "not positive semi-definite"},
                     // Body 3 at -5 m/s under a body falling at -3.13: contact 2-3 opens.
                     {"velocity.3", 0, -5, "velocity.3 = -5", "opens before the collision"}};
  for (const Bad& b : bad) {
    const Parameter p = Parameter::parse(b.key, scene);
    for (const auto& run : {std::function<void()>([&] { numeric::check_range(scene, p, b.from, b.to); }),
                            std::function<void()>([&] { numeric::sweep(scene, p, numeric::linspace(b.from, b.to, 3), numeric::Precision{}); }),
                            std::function<void()>([&] { numeric::switch_points(scene, p, numeric::linspace(b.from, b.to, 3)); })}) {
      try {
        run();
        ADD_FAILURE() << b.key << " = " << text(b.from) << " .. " << text(b.to) << " accepted";
      } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_EQ(what.rfind(kPaper + ": " + b.value + ": ", 0), 0u) << what;
        EXPECT_NE(what.find(b.why), std::string::npos) << what;
      }
    }
  }
}

TEST(SweepRange, EveryValueOfAnAdmittedRangeIsAdmissible) {
  // check_range() tests the ends only: along one parameter the admissible
  // values form an interval.  Check every value of a fine grid of ranges that
  // reach the edge of admissibility.
  const Scene scene = load_scene(kPaper);
  struct Range {
    const char* key;
    cl_RA from, to;
  };
  // velocity.3 from -fall_speed (contact 2-3 at rest) to 0 (contact 3-4 at rest).
  const Range ranges[] = {{"g", cl_RA(1) / 1000, 100},
                          {"K.3-4", 0, 1000},
                          {"alpha.2", -100, 0},
                          {"velocity.3", cl_RA(-313209) / 100000, 0},
                          {"fall_speed", 0, 10},
                          {"mass.2", cl_RA(1) / 1000000, 1000000}};
  for (const Range& r : ranges) {
    const Parameter p = Parameter::parse(r.key, scene);
    ASSERT_NO_THROW(numeric::check_range(scene, p, r.from, r.to)) << r.key;
    for (const cl_RA& v : numeric::linspace(r.from, r.to, 101))
      EXPECT_NO_THROW((void)ExactScene::from(numeric::with_value(scene, p, v))) << r.key << " = " << text(v);
  }
}

TEST(SweepRange, ChunksOfTheGridAreTheGrid) {
  const auto all = numeric::linspace(cl_RA(1) / 3, -7, 11);
  std::vector<cl_RA> joined;
  for (int first = 0; first < 11; first += 4) {
    const auto part = numeric::linspace(cl_RA(1) / 3, -7, 11, first, std::min(4, 11 - first));
    joined.insert(joined.end(), part.begin(), part.end());
  }
  ASSERT_EQ(joined.size(), all.size());
  for (std::size_t k = 0; k < all.size(); ++k) EXPECT_EQ(joined[k], all[k]);
  EXPECT_EQ(all.front(), cl_RA(1) / 3);
  EXPECT_EQ(all.back(), -7);
  EXPECT_THROW(numeric::linspace(0, 1, 11, 8, 4), std::invalid_argument);
  EXPECT_THROW(numeric::linspace(0, 1, 11, -1, 2), std::invalid_argument);
}

/// Each point of a sweep is the solve of its value's scene converted on its
/// own (Parameter::set(), ExactScene::from(), Problem<S>::from()), bit for bit.
template <class S>
void expect_sweep_is_solves(const Scene& scene, const std::string& key, const cl_RA& from, const cl_RA& to, const char* precision) {
  SCOPED_TRACE(key + " in " + precision);
  const Parameter p = Parameter::parse(key, scene);
  const auto values = numeric::linspace(from, to, 9);
  const auto points = numeric::sweep(scene, p, values, numeric::Precision::parse(precision), 2);
  ASSERT_EQ(points.size(), values.size());
  for (std::size_t k = 0; k < values.size(); ++k) {
    const ExactScene exact = ExactScene::from(numeric::with_value(scene, p, values[k]));
    const auto problem = Problem<S>::from(exact);
    const auto sol = numeric::solve(problem);
    const double unit = ScalarTraits<S>::to_double(problem.unit);
    EXPECT_EQ(points[k].value, values[k]);
    EXPECT_EQ(points[k].closed, sol.closed);
    EXPECT_EQ(points[k].status, sol.status);
    ASSERT_EQ(points[k].velocities_after.size(), sol.velocities_after.size());
    for (std::size_t i = 0; i < sol.velocities_after.size(); ++i)
      EXPECT_EQ(points[k].velocities_after[i], ScalarTraits<S>::to_double(sol.velocities_after[i]) * unit) << "value " << k << ", U" << i + 1;
  }
}

TEST(SweepPoints, AreTheSolvesOfTheirScenesBitForBit) {
  // Entries of M (each thread sets only the entry), an entry the scene leaves out, and a mass (each scene converted).
  const Scene scene = load_scene(kPaper);
  expect_sweep_is_solves<double>(scene, "K.3-4", 0, 20, "double");
  expect_sweep_is_solves<long double>(scene, "K.3-4", 20, 0, "long-double");
  expect_sweep_is_solves<double>(scene, "alpha.2", -100, 0, "double");
  expect_sweep_is_solves<double>(scene, "alpha.5", -1, 1, "double");
  expect_sweep_is_solves<double>(scene, "mass.2", 5, 20, "double");
}

}  // namespace
}  // namespace superball::testing
