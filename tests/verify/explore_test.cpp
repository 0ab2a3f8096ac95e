// The exploration of α-patterns: every witness is an admissible point where
// an exact solve (case not imposed) gives the case with U₁⁺ > a, its scene
// file solves to the same, the derived velocity formula agrees there; the
// paper's claims (§4.1, §4.3 remarks) come out; {α₁, α₆} in case 1 is proved
// impossible and the proof is sound on sampled points; same seed, same result.
#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "superball/cases/scene_file.hpp"
#include "superball/cases/vocabulary.hpp"
#include "superball/numeric/collision.hpp"
#include "superball/present/explore.hpp"
#include "superball/verify/explore.hpp"
#include "superball/verify/space.hpp"

namespace superball::verify {
namespace {

using cln::cl_RA;
using present::cell_text;
using present::to_json;
using present::to_text;
using present::witness_file;
using symbolic::Deriver;
using symbolic::Obstacle;
using symbolic::Pattern;

/// A smaller budget than the command's default: the claims do not need the largest U₁⁺/a.
ExploreOptions quick() {
  ExploreOptions o;
  o.starts = 6;
  o.evaluations = 300;
  return o;
}

ContactSet named(const std::string& name) { return Vocabulary::paper().named_case(name).closed; }

/// The witness of \p r as a point of \p space (the names come in coordinate order).
Point point_of(const ExploreResult& r, const ParameterSpace& space) {
  Point x;
  for (const auto& [name, value] : r.witness) {
    EXPECT_EQ(space.coordinates()[x.size()].ascii, name);
    x.push_back(value);
  }
  return x;
}

/// Everything a witness must satisfy, checked independently of the search.
void expect_confirmed_witness(const Deriver& d, const ExploreResult& r) {
  ASSERT_EQ(r.reach, Reach::Yes) << to_text(r);
  const ParameterSpace space(d);
  const Point x = point_of(r, space);
  EXPECT_TRUE(space.admissible(x)) << "M must be positive semi-definite";
  const numeric::Problem<cl_RA> problem = space.problem(x);
  numeric::CollisionSolver<cl_RA> solver;
  const numeric::Solution<cl_RA> sol = solver.compute(problem);
  ASSERT_EQ(sol.status, numeric::Status::Success);
  EXPECT_EQ(sol.closed, r.closed) << "the case must be the actual evolution";
  const cl_RA a = -problem.u.front();
  EXPECT_GT(sol.velocities_after[0], a);
  EXPECT_EQ(sol.velocities_after[0], r.u1);
  EXPECT_EQ(r.ratio, r.u1 / a);
  EXPECT_LE(sol.kinetic_energy_after, sol.kinetic_energy_before);
  // The derived velocity formula of the case gives the same U1+ exactly.
  const symbolic::Derivation c = d.derive(r.closed);
  GiNaC::exmap at;
  for (std::size_t k = 0; k < x.size(); ++k) at[d.symbols().all()[k].symbol] = GiNaC::numeric(cln::cl_N(x[k]));
  const GiNaC::ex u1 = c.velocities.front().value().subs(at, GiNaC::subs_options::no_pattern);
  EXPECT_TRUE((u1 - GiNaC::numeric(cln::cl_N(r.u1))).is_zero());
  // The witness file reads back to the same collision.
  const Scene scene = parse_scene(witness_file(r, "test"), "witness.toml");
  const auto from_file = numeric::Problem<cl_RA>::from(numeric::ExactScene::from(scene));
  const numeric::Solution<cl_RA> again = solver.compute(from_file);
  EXPECT_EQ(again.closed, r.closed);
  EXPECT_EQ(again.velocities_after[0] * from_file.unit, r.u1);
}

TEST(Explore, exam_PaperClaimsSuperballReachable) {
  struct Claim {
    std::vector<int> alphas;
    std::string case_name;
  };
  // §4.1: α₂ (the paper's analysis) and α₃ (remark) in case 1; §4.3: α₅ and α₇ (remark) in case 3.2;
  // §4.4: α₄ in case 3.3.
  for (const Claim& c : {Claim{{2}, "1"}, Claim{{3}, "1"}, Claim{{5}, "3.2"}, Claim{{7}, "3.2"}, Claim{{4}, "3.3"}}) {
    SCOPED_TRACE("alpha " + std::to_string(c.alphas.front()) + " case " + c.case_name);
    const Deriver d(Pattern::paper(c.alphas), Obstacle::Infinite);
    const ExploreResult r = explore_case(d, named(c.case_name), quick());
    expect_confirmed_witness(d, r);
    EXPECT_FALSE(r.clash);
  }
}

/// §4.1's remark: with α₁ and α₆ the superball is impossible in case 1.  The
/// clash is the superball condition against the quadratic form of M, and no
/// sampled point with case 1 actual has U₁⁺ > a.
TEST(Explore, exam_Alpha1Alpha6Case1IsProvedImpossible) {
  const Deriver d(Pattern::paper({1, 6}), Obstacle::Infinite);
  const ExploreResult r = explore_case(d, named("1"), quick());
  ASSERT_EQ(r.reach, Reach::Impossible) << to_text(r);
  ASSERT_TRUE(r.clash);
  EXPECT_TRUE(r.clash->superball);
  ASSERT_EQ(r.clash->conditions.size(), 1u);
  EXPECT_NE(r.clash->conditions[0].find("superball"), std::string::npos);
  EXPECT_NE(r.clash->identity.find("xᵀMx"), std::string::npos);
  ASSERT_TRUE(r.asymptotic_clash);
  EXPECT_NE(to_text(r).find("clash of the exact conditions"), std::string::npos);
  if (!r.witness.empty()) {
    EXPECT_LE(r.ratio, 1);
  }
  EXPECT_EQ(cell_text(r), "no (proved)");
}

/// Every proof of the table's first rows is sound: at sampled admissible
/// points where the case is the actual evolution (exact solve), U₁⁺ <= a.
TEST(Explore, check_ProofsHoldAtSampledPoints) {
  for (const std::vector<int>& alphas : {std::vector<int>{1}, std::vector<int>{1, 6}, std::vector<int>{4}, std::vector<int>{7}}) {
    const Deriver d(Pattern::paper(alphas), Obstacle::Infinite);
    const ParameterSpace space(d);
    numeric::CollisionSolver<cl_RA> solver;
    for (const NamedCase& c : Vocabulary::paper().cases()) {
      const ExploreResult r = explore_case(d, c.closed, quick());
      if (r.reach == Reach::Yes) {
        expect_confirmed_witness(d, r);
        continue;
      }
      if (r.reach != Reach::Impossible && r.reach != Reach::CaseImpossible) continue;
      RegimeSampler sampler(space, cl_RA(1) / 100, 3);
      for (int k = 0; k < 150; ++k) {
        const auto x = sampler.draw();
        ASSERT_TRUE(x);
        const auto problem = space.problem(*x);
        const numeric::Solution<cl_RA> sol = solver.compute(problem);
        if (sol.closed != c.closed) continue;
        EXPECT_NE(r.reach, Reach::CaseImpossible) << "case " << c.name << " is actual at a sampled point";
        EXPECT_LE(sol.velocities_after[0], -problem.u.front()) << "case " << c.name << ": " << to_text(r);
      }
    }
  }
}

/// A clash that needs polynomial multipliers (the linear programme): α₇ in
/// case 2.1, the superball against R₁₂ <= 0 and the opening of contact 2-3.
TEST(Explore, exam_Alpha7Case2_1NeedsPolynomialMultipliers) {
  const Deriver d(Pattern::paper({7}), Obstacle::Infinite);
  const ExploreResult r = explore_case(d, named("2.1"), quick());
  ASSERT_EQ(r.reach, Reach::Impossible) << to_text(r);
  ASSERT_TRUE(r.clash);
  EXPECT_TRUE(r.clash->superball);
  EXPECT_GE(r.clash->conditions.size(), 2u);
  EXPECT_NE(r.clash->identity.find(")·N"), std::string::npos) << r.clash->identity;
}

/// The table's shape (rows: α₁..α₇ and {α₁, α₆}; columns: the paper's 8
/// cases) and its cells: a proof wherever it says so, a witness wherever it
/// says yes, whatever the (here tiny) budget; its progress counts every cell.
TEST(Explore, exam_TableOfAllPatterns) {
  ExploreOptions o;
  o.starts = 2;
  o.evaluations = 60;
  std::vector<std::pair<long long, long long>> calls;  // the table's progress: every cell's steps, one after the other
  o.progress = [&](long long done, long long planned) { calls.emplace_back(done, planned); };
  const PatternTable t = explore_all_patterns(o);
  EXPECT_FALSE(t.options.progress);
  const long long planned = 64 * (2 * 60 + 1);
  ASSERT_FALSE(calls.empty());
  for (std::size_t k = 1; k < calls.size(); ++k) {
    EXPECT_EQ(calls[k].second, planned);
    EXPECT_GE(calls[k].first, calls[k - 1].first);
  }
  EXPECT_EQ(calls.back(), std::make_pair(planned, planned));
  ASSERT_EQ(t.patterns.size(), 8u);
  EXPECT_EQ(t.patterns.back(), (std::vector<int>{1, 6}));
  ASSERT_EQ(t.cases.size(), 8u);
  ASSERT_EQ(t.cells.size(), 8u);
  for (const auto& row : t.cells) {
    ASSERT_EQ(row.size(), 8u);
    for (const ExploreResult& c : row) {
      if (c.reach == Reach::Impossible || c.reach == Reach::CaseImpossible) {
        EXPECT_TRUE(c.clash);
      }
      if (c.reach == Reach::Yes) {
        EXPECT_GT(c.ratio, 1);
        EXPECT_TRUE(c.scene);
      }
    }
  }
  // Case 0 (nothing bounces) never gives the superball: U1+ = 0.
  for (const auto& row : t.cells) EXPECT_EQ(row.back().reach, Reach::Impossible) << row.back().pattern;
  const std::string text = to_text(t);
  EXPECT_NE(text.find("| α₁, α₆ |"), std::string::npos) << text;
  EXPECT_EQ(to_json(t)["rows"].size(), 8u);
}

TEST(Explore, exam_SameSeedSameResult) {
  const Deriver d(Pattern::paper({5}), Obstacle::Infinite);
  const ExploreResult a = explore_case(d, named("3.2"), quick()), b = explore_case(d, named("3.2"), quick());
  EXPECT_EQ(to_json(a).dump(), to_json(b).dump());
  EXPECT_EQ(to_text(a), to_text(b));
}

// Issue 26: the search reports its steps through ExploreOptions::progress,
// from 0 to starts × evaluations + 1, and the result is the same with it.
TEST(Explore, ProgressCountsTheStepsAndChangesNothing) {
  const Deriver d(Pattern::paper({5}), Obstacle::Infinite);
  for (const char* name : {"3.2", "1"}) {  // a witness; no witness, then the proofs
    ExploreOptions o = quick();
    std::vector<std::pair<long long, long long>> calls;
    o.progress = [&](long long done, long long planned) { calls.emplace_back(done, planned); };
    const ExploreResult with = explore_case(d, named(name), o), without = explore_case(d, named(name), quick());
    EXPECT_EQ(to_json(with).dump(), to_json(without).dump()) << name;
    EXPECT_EQ(to_text(with), to_text(without)) << name;
    const long long planned = 6LL * 300 + 1;
    ASSERT_GE(calls.size(), 7u) << name;  // one after each local search, and the end
    for (std::size_t k = 0; k < calls.size(); ++k) {
      EXPECT_EQ(calls[k].second, planned);
      EXPECT_LE(calls[k].first, k + 1 < calls.size() ? planned - 1 : planned);
      if (k) {
        EXPECT_GE(calls[k].first, calls[k - 1].first) << name << ", call " << k;
      }
    }
    EXPECT_EQ(calls.back().first, planned) << name;
  }
}

// A progress that throws (Ctrl-C) stops the search: the exception leaves
// explore_case() at once, within explore_progress_evaluations evaluations.
TEST(Explore, ProgressThatThrowsStopsTheSearch) {
  struct Stop {};
  const Deriver d(Pattern::paper({2}), Obstacle::Infinite);
  ExploreOptions o;
  o.evaluations = 1000000;  // one local search alone would take seconds
  long long last = 0;
  int calls = 0;
  o.progress = [&](long long done, long long) {
    ++calls;
    last = done;
    throw Stop{};
  };
  EXPECT_THROW(explore_case(d, named("1"), o), Stop);
  EXPECT_EQ(calls, 1);
  EXPECT_LE(last, explore_progress_evaluations);
}

TEST(Explore, exam_BadOptionsAreRejected) {
  const Deriver d(Pattern::paper({2}), Obstacle::Infinite);
  ExploreOptions o = quick();
  o.starts = 0;
  EXPECT_THROW(explore_case(d, named("1"), o), std::invalid_argument);
  o = quick();
  o.box_low = 10;
  o.box_high = 1;
  EXPECT_THROW(explore_case(d, named("1"), o), std::invalid_argument);
  const Deriver finite(Pattern::paper({2}), Obstacle::Finite);
  EXPECT_THROW(explore_case(finite, named("1"), quick()), std::invalid_argument);
  EXPECT_THROW(explore_case(d, ContactSet::parse("2-3", 3), quick()), std::invalid_argument);
  ExploreResult none;
  EXPECT_THROW(witness_file(none, "x"), std::invalid_argument);
}

// Issue 25: the box's rule is ExploreOptions::check()'s, the same for the
// command and Python: 0 < LOW < HIGH, both normal doubles; 1e-300:1e300 is a box.
TEST(Explore, TheBoxIsAnyIntervalOfNormalDoubles) {
  ExploreOptions o;
  for (const auto& [low, high] : {std::pair{1e-300, 1e300}, {std::numeric_limits<double>::min(), std::numeric_limits<double>::max()}, {1.0, 2.0}}) {
    o.box_low = low;
    o.box_high = high;
    EXPECT_NO_THROW(o.check()) << low << ":" << high;
  }
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  for (const auto& [low, high] : {std::pair{5.0, 1.0}, {1.0, 1.0}, {0.0, 1.0}, {-1.0, 1.0}, {1e-320, 1.0}, {1.0, inf}, {nan, 1.0}, {1.0, nan}}) {
    o.box_low = low;
    o.box_high = high;
    try {
      o.check();
      ADD_FAILURE() << low << ":" << high << " accepted";
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind("ExploreOptions::check(): box ", 0), 0u) << what;
      EXPECT_NE(what.find(": needs 0 < LOW < HIGH with LOW >= 2.2250738585072014e-308 and HIGH finite (normal doubles)"), std::string::npos) << what;
    }
  }
}

}  // namespace
}  // namespace superball::verify
