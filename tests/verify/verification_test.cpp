// verify_case(): the derived exact conditions agree with the exact solution
// at every sampled point (fixed and finite obstacle, several patterns, every
// case of n = 4), the asymptotic ones agree more as eps -> 0, both sides of
// every condition and points near each boundary are reached, and the result
// does not depend on the number of threads.
#include <gtest/gtest.h>

#include "superball/cases/scene_file.hpp"
#include "superball/cases/vocabulary.hpp"
#include "superball/numeric/collision.hpp"
#include "superball/verify/space.hpp"
#include "superball/present/verification.hpp"
#include "superball/verify/verification.hpp"

namespace superball::verify {
namespace {

using cln::cl_RA;
using present::describe;
using present::to_json;
using present::to_text;
using symbolic::Deriver;
using symbolic::Obstacle;
using symbolic::Pattern;

ContactSet named(const std::string& name) { return Vocabulary::paper().named_case(name).closed; }

VerifyOptions small(int samples, std::vector<cl_RA> epsilons = {cl_RA(1) / 100, cl_RA(1) / 10000}) {
  VerifyOptions o;
  o.epsilons = std::move(epsilons);
  o.samples = samples;
  o.boundary_pairs = 4;
  o.threads = 2;
  return o;
}

std::string describe_exact_disagreements(const Verification& v) {
  std::string s;
  for (const Disagreement& d : v.disagreements)
    if (d.exact_form) s += describe(v, d) + "\n";
  return s;
}

/// The exact conditions of a case are exact: with the obstacle fixed, the
/// conjunction and every condition agree with the exact solution at every point.
TEST(Verification, check_ExactConditionsAgreeOnEverySample) {
  const Deriver alpha2(Pattern::paper({2}), Obstacle::Infinite);
  for (const auto& c : Vocabulary::paper().cases()) {
    const Verification v = verify_case(alpha2, c.closed, small(60));
    EXPECT_TRUE(v.exact_agrees()) << "case " << c.name << "\n" << describe_exact_disagreements(v);
    for (const EpsilonResult& e : v.epsilons) {
      EXPECT_EQ(e.drawn.exact.total(), 60);
      EXPECT_EQ(e.all().unsolved, 0);
    }
  }
  for (const auto& [alphas, name] : std::vector<std::pair<std::vector<int>, std::string>>{{{1, 6}, "2.1"}, {{5}, "3.2"}, {{1, 2, 3}, "1"}, {{4, 7}, "3.4"}}) {
    const Deriver d(Pattern::paper(alphas), Obstacle::Infinite);
    const Verification v = verify_case(d, named(name), small(60));
    EXPECT_TRUE(v.exact_agrees()) << v.pattern << " case " << name << "\n" << describe_exact_disagreements(v);
  }
}

/// With a finite obstacle, the finite-m_n form is the exact one.
TEST(Verification, check_FiniteObstacleExactConditionsAgree) {
  const Deriver d(Pattern::paper({2}), Obstacle::Finite);
  for (const std::string name : {"1", "3.2", "0"}) {
    const Verification v = verify_case(d, named(name), small(60));
    EXPECT_EQ(v.obstacle, "finite");
    EXPECT_TRUE(v.exact_agrees()) << "case " << name << "\n" << describe_exact_disagreements(v);
  }
}

/// The asymptotic form is the limit ε → 0 of the exact one: on case 1 of the
/// paper (α₂) the agreement of the asymptotic conditions (each one and their
/// conjunction) with the exact solution on the drawn points does not
/// decrease from ε = 1e-2 to 1e-6, and is not perfect at 1e-2 (else the test
/// proves nothing).  Near a boundary they are a distance O(ε) apart: there
/// the asymptotic form agrees on one side only until ε is below the bracket.
TEST(Verification, check_AsymptoticAgreementGrowsAsEpsilonShrinks) {
  const Deriver d(Pattern::paper({2}), Obstacle::Infinite);
  VerifyOptions o = small(1000, {cl_RA(1) / 100, cl_RA(1) / 1000000, cl_RA(1) / 1000000000000});
  o.boundary_pairs = 10;
  const Verification v = verify_case(d, named("1"), o);
  auto rate = [](long long part, long long whole) { return static_cast<double>(part) / static_cast<double>(whole); };
  const Tally &coarse = v.epsilons[0].drawn, &fine = v.epsilons[1].drawn;
  EXPECT_LT(rate(coarse.asymptotic.agree(), coarse.asymptotic.total()), 1.0) << to_text(v);
  EXPECT_GE(rate(fine.asymptotic.agree(), fine.asymptotic.total()), rate(coarse.asymptotic.agree(), coarse.asymptotic.total())) << to_text(v);
  bool some_disagree = false;
  for (std::size_t c = 0; c < v.conditions.size(); ++c) {
    const ConditionTally &a = coarse.conditions[c], &b = fine.conditions[c];
    some_disagree = some_disagree || a.asymptotic_agree < a.points();
    EXPECT_GE(rate(b.asymptotic_agree, b.points()), rate(a.asymptotic_agree, a.points())) << v.conditions[c].about << "\n" << to_text(v);
    // ε = 1e-12, far below the bracket 2^-20 ≈ 1e-6: the near points are resolved too.
    const ConditionTally& n = v.epsilons[2].boundary.conditions[c];
    EXPECT_EQ(n.near_asymptotic_agree, n.near_holds + n.near_fails) << v.conditions[c].about << "\n" << to_text(v);
  }
  EXPECT_TRUE(some_disagree);
  EXPECT_TRUE(v.exact_agrees()) << describe_exact_disagreements(v);
}

/// Both sides of every condition are reached at every ε, with points near
/// each boundary on each side; a near point is one end of a bracket of
/// 2^-20 of a segment, so the other end is on the other side, close by.
TEST(Verification, check_BothSidesAndNearBoundaryPointsAreReached) {
  const Deriver d(Pattern::paper({2}), Obstacle::Infinite);
  for (const std::string name : {"1", "3.3"}) {
    const Verification v = verify_case(d, named(name), small(200));
    for (const EpsilonResult& e : v.epsilons) {
      const Tally all = e.all();
      for (std::size_t c = 0; c < v.conditions.size(); ++c) {
        // A condition whose asymptotic form always holds (case 1: evolution 1-2 reads K14 > 0, the exact
        // form m1 < K14 + alpha2 with |alpha2| <= sqrt(K12 K14) << K14) has no failing side in the regime.
        if (v.conditions[c].asymptotic_verdict != symbolic::Verdict::Depends) continue;
        const ConditionTally& t = all.conditions[c];
        const std::string what = "case " + name + " " + v.conditions[c].about + " eps " + epsilon_name(e.epsilon);
        EXPECT_GT(t.holds, 0) << what;
        EXPECT_GT(t.fails, 0) << what;
        EXPECT_GT(t.near_holds, 0) << what;
        EXPECT_GT(t.near_fails, 0) << what;
        EXPECT_EQ(t.near_holds, t.near_fails) << what;  // brackets come in pairs, one end per side
      }
    }
  }
}

TEST(Verification, check_ThreadsDoNotChangeTheResult) {
  const Deriver d(Pattern::paper({2, 5}), Obstacle::Infinite);
  VerifyOptions o = small(120);
  o.seed = 9;
  o.threads = 1;
  const Verification one = verify_case(d, named("1"), o);
  o.threads = 2;
  const Verification two = verify_case(d, named("1"), o);
  o.threads = 3;
  const Verification three = verify_case(d, named("1"), o);
  EXPECT_EQ(to_json(one).dump(), to_json(two).dump());
  EXPECT_EQ(to_json(one).dump(), to_json(three).dump());
  o.seed = 10;
  EXPECT_NE(to_json(one).dump(), to_json(verify_case(d, named("1"), o)).dump());
}

/// A disagreement's scene solves (exactly) to the case and U1+ it states.
TEST(Verification, check_DisagreementScenesReproduceTheExactSolution) {
  const Deriver d(Pattern::paper({2}), Obstacle::Infinite);
  const Verification v = verify_case(d, named("1"), small(200, {cl_RA(1) / 100}));
  ASSERT_FALSE(v.disagreements.empty());
  numeric::CollisionSolver<cl_RA> solver;
  for (const Disagreement& x : v.disagreements) {
    EXPECT_FALSE(x.exact_form);
    EXPECT_TRUE(x.asymptotic != x.truth || !x.details.empty());  // only the asymptotic forms disagree
    const Scene scene = parse_scene(write_scene(x.scene, describe(v, x)), "disagreement.toml");
    const auto problem = numeric::Problem<cl_RA>::from(numeric::ExactScene::from(scene));
    const auto sol = solver.compute(problem);
    ASSERT_EQ(sol.status, numeric::Status::Success);
    EXPECT_EQ(Vocabulary::paper().case_name(sol.closed), x.actual_case);
    EXPECT_EQ("U1 - a = " + to_string((sol.velocities_after[0] + problem.u[0]) * problem.unit), x.quantity);
  }
}

TEST(Verification, exam_BadOptionsAreRejected) {
  const Deriver d(Pattern::paper({2}), Obstacle::Infinite);
  VerifyOptions o = small(10);
  o.epsilons = {cl_RA(2)};
  EXPECT_THROW(verify_case(d, named("1"), o), std::invalid_argument);
  o.epsilons = {};
  EXPECT_THROW(verify_case(d, named("1"), o), std::invalid_argument);
  o = small(0);
  EXPECT_THROW(verify_case(d, named("1"), o), std::invalid_argument);
  EXPECT_EQ(epsilon_name(cl_RA(1) / 1000), "1e-3");
  EXPECT_EQ(epsilon_name(cl_RA(3) / 1000), "3/1000");
}

}  // namespace
}  // namespace superball::verify
