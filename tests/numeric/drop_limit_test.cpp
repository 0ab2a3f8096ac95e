// A drop as its gaps go to 0 against the simultaneous collision
// (numeric/drop_limit.hpp): the drop with every gap 0 is the Frémond
// collision of the whole stack (numeric::solve at the landing speed); the
// gapped cascades have a limit, reached at the rate of the gaps; that limit
// is the classical sequence of binary impacts (closed form below), which is
// not Frémond's simultaneous answer for the superball, and is for plastic
// contacts.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "superball/cases/error.hpp"
#include "superball/cases/scene_file.hpp"
#include "superball/numeric/collision.hpp"
#include "superball/numeric/drop_limit.hpp"
#include "superball/numeric/problem.hpp"

namespace superball::numeric {
namespace {

/// Velocities of two double computations of the same collision, relative to the landing speed.
constexpr double kSameCollisionTolerance = 1e-12;

Scene stack(const std::string& text) { return parse_scene(text, "t.toml"); }

/// A light ball over a heavy one over a fixed floor, gaps 1 mm, contacts of stiffness K.
std::string two_balls(const std::string& k12, const std::string& k23) {
  return "drop_height = 1\n[[body]]\nmass = 0.001\ngap = 0.001\n[[body]]\nmass = 1\n[[body]]\nmass = \"inf\"\n"
         "[dissipation]\nK = { \"1-2\" = " + k12 + ", \"2-3\" = " + k23 + " }\n";
}

TEST(GapsToZero, TheDropWithoutGapsIsTheSolveOfTheWholeStack) {
  // The paper's §4.4 stack: the simultaneous drop's one collision is numeric::solve of the scene at a = sqrt(2 g h).
  const Scene gapped = load_scene(std::string(SUPERBALL_CASES_DIR) + "/scenes/drop-paper-4.4.toml");
  const GapLimit limit = gaps_to_zero(gapped, Precision::parse("double"), GapLimitOptions{2});
  Scene still = gapped;
  still.drop = Drop{};
  for (Body& b : still.bodies) b.gap.reset();
  const Problem<double> p = Problem<double>::from(ExactScene::from(still));
  const Solution<double> sol = solve(p);
  ASSERT_EQ(sol.status, Status::Success);
  const DropEvent& first = limit.simultaneous.drop.events.at(0);
  EXPECT_EQ(first.first_body, 1);
  EXPECT_EQ(first.last_body, 4);
  EXPECT_EQ(first.closed.size(), static_cast<std::size_t>(sol.closed.closed_names().size()));
  EXPECT_NEAR(limit.landing_speed, p.unit, kSameCollisionTolerance * p.unit);
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(first.velocities_after[i], sol.velocities_after[i] * p.unit, kSameCollisionTolerance * p.unit) << "body " << i + 1;
  EXPECT_EQ(limit.simultaneous.cascade.events, 1);
  EXPECT_TRUE(limit.simultaneous.cascade.complete);
}

TEST(GapsToZero, TheCascadesConvergeAtTheRateOfTheGaps) {
  const GapLimit limit = gaps_to_zero(load_scene(std::string(SUPERBALL_CASES_DIR) + "/scenes/drop-paper-4.4.toml"),
                                      Precision::parse("double"), GapLimitOptions{6});
  ASSERT_EQ(limit.steps.size(), 7u);
  // |U(k) - U(k+1)| shrinks about tenfold a decade (gravity acts during the cascade for a time of the order of the gaps).
  for (std::size_t k = 0; k + 2 < limit.steps.size(); ++k) {
    double d0 = 0, d1 = 0;
    for (int i = 0; i < 3; ++i) {
      d0 = std::max(d0, std::fabs(limit.steps[k].cascade.velocities[i] - limit.steps[k + 1].cascade.velocities[i]));
      d1 = std::max(d1, std::fabs(limit.steps[k + 1].cascade.velocities[i] - limit.steps[k + 2].cascade.velocities[i]));
    }
    if (d0 < 1e-12 * limit.landing_speed) break;  // roundoff from here on
    EXPECT_LT(d1, d0 / 5) << "decade " << k;
  }
  for (const GapLimitStep& s : limit.steps) EXPECT_TRUE(s.cascade.complete);
  // ... and the limit is not the simultaneous collision: ball 1 leaves at 1.79 a after three binary collisions, 1.00 a after one collision of the stack.
  EXPECT_EQ(limit.verdict, GapVerdict::Differs);
  EXPECT_GT(limit.steps.back().deviation, 0.5);
  EXPECT_EQ(limit.steps.back().cascade.events, 3);
  EXPECT_EQ(limit.simultaneous.cascade.collisions.at(0), "1-4 3.3");
}

TEST(GapsToZero, TwoBallsTendToTheSequenceOfBinaryImpactsNotToTheSimultaneousCollision) {
  const Scene s = stack(two_balls("1e6", "1e6") + "[drop]\n");
  const GapLimit limit = gaps_to_zero(s, Precision::parse("double"), GapLimitOptions{8});
  // Binary impacts with the restitutions the contacts' K give (e = (K - mu)/(K + mu), mu the reduced mass):
  // ball 2 leaves the floor at e23 a, then meets ball 1 (falling at a).
  const double a = std::sqrt(2 * 9.81), m1 = 0.001, m2 = 1, k = 1e6;
  const double e23 = (k - m2) / (k + m2), mu = m1 * m2 / (m1 + m2), e12 = (k - mu) / (k + mu);
  const double u1 = -a, u2 = e23 * a;
  const double v1 = (m1 * u1 + m2 * u2 + m2 * e12 * (u2 - u1)) / (m1 + m2), v2 = (m1 * u1 + m2 * u2 - m1 * e12 * (u2 - u1)) / (m1 + m2);
  const DropCascade& c = limit.steps.back().cascade;
  ASSERT_EQ(c.events, 2);
  EXPECT_NEAR(c.velocities[0], v1, 1e-6 * a);
  EXPECT_NEAR(c.velocities[1], v2, 1e-6 * a);
  // Frémond's collision of the touching stack keeps the two balls together: both leave at e a (no superball without
  // a coupling at a distance, paper §4).
  const DropCascade& sim = limit.simultaneous.cascade;
  EXPECT_EQ(limit.simultaneous.drop.events.at(0).case_name, "{1-2}");
  EXPECT_NEAR(sim.velocities[0], sim.velocities[1], 1e-9 * a);
  EXPECT_NEAR(sim.velocities[0], a, 1e-5 * a);
  EXPECT_EQ(limit.verdict, GapVerdict::Differs);
}

TEST(GapsToZero, NBallsTendToTwoToTheNMinusOneTimesTheLandingSpeed) {
  // n balls, each 1000 times lighter than the one below, nearly elastic: the limit of the cascade is one binary impact per
  // contact, bottom up, (its closed form to 1e-6 a), and the top ball's speed approaches (2^n - 1) a.
  for (int n = 2; n <= 4; ++n) {
    std::string text = "drop_height = 1\n";
    std::vector<double> m;
    for (int i = 0; i < n; ++i) {
      m.push_back(std::pow(1e-3, n - 1 - i));
      text += "[[body]]\nmass = 1e-" + std::to_string(3 * (n - 1 - i)) + "\n" + (i + 1 < n ? "gap = 0.001\n" : "");
    }
    text += "[[body]]\nmass = \"inf\"\n[dissipation]\nK = { ";
    for (int i = 1; i <= n; ++i) text += (i > 1 ? ", " : "") + ("\"" + std::to_string(i) + "-" + std::to_string(i + 1) + "\" = 1e9");
    text += " }\n[drop]\n";
    const GapLimit limit = gaps_to_zero(stack(text), Precision::parse("double"), GapLimitOptions{6});
    const double a = limit.landing_speed, k = 1e9;
    std::vector<double> u(static_cast<std::size_t>(n), -a);
    u[n - 1] = (k - m[n - 1]) / (k + m[n - 1]) * a;  // the bottom ball off the floor
    for (int i = n - 2; i >= 0; --i) {  // then each ball meets the one below it, once
      const double mu = m[i] * m[i + 1] / (m[i] + m[i + 1]), e = (k - mu) / (k + mu), p = m[i] * u[i] + m[i + 1] * u[i + 1], w = u[i + 1] - u[i];
      u[i] = (p + m[i + 1] * e * w) / (m[i] + m[i + 1]);
      u[i + 1] = (p - m[i] * e * w) / (m[i] + m[i + 1]);
    }
    const DropCascade& c = limit.steps.back().cascade;
    ASSERT_EQ(c.events, n) << n << " balls";
    for (int i = 0; i < n; ++i) EXPECT_NEAR(c.velocities[i], u[i], 1e-6 * a) << n << " balls, ball " << i + 1;
    EXPECT_NEAR(c.velocities[0] / a, std::pow(2.0, n) - 1, 0.005 * (std::pow(2.0, n) - 1)) << n << " balls";
  }
}

TEST(GapsToZero, PlasticContactsConvergeToTheSimultaneousCollision) {
  // K = m on the floor and K = mu between the balls: restitution 0, every body stops whatever the order.
  const Scene s = stack(
      "drop_height = 1\n[[body]]\nmass = 1\ngap = 0.001\n[[body]]\nmass = 1\n[[body]]\nmass = \"inf\"\n"
      "[dissipation]\nK = { \"1-2\" = 0.5, \"2-3\" = 1 }\n[drop]\n");
  const GapLimit limit = gaps_to_zero(s, Precision::parse("long-double"), GapLimitOptions{3});
  EXPECT_EQ(limit.verdict, GapVerdict::Converges);
  for (const GapLimitStep& st : limit.steps) EXPECT_LE(st.deviation, drop_limit_tolerance);
}

TEST(GapsToZero, RefusesScenesWithoutGapsAndDecadesOutOfRange) {
  EXPECT_THROW(gaps_to_zero(stack("drop_height = 1\n[[body]]\nmass = 1\n[[body]]\nmass = \"inf\"\n[dissipation]\nK = { \"1-2\" = 9 }\n[drop]\n"),
                            Precision::parse("double")),
               InputError);
  const Scene s = stack(two_balls("9", "9") + "[drop]\n");
  for (int d : {0, -1, GapLimitOptions::max_decades + 1}) {
    try {
      gaps_to_zero(s, Precision::parse("double"), GapLimitOptions{d});
      ADD_FAILURE() << d;
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()), "GapLimitOptions::check(): decades must be a whole number from 1 to 12, got " + std::to_string(d));
    }
  }
  // Exact rationals reach each drop's first cascade (its times are rational): the verdict of double.
  EXPECT_EQ(gaps_to_zero(s, Precision::parse("exact"), GapLimitOptions{3}).verdict,
            gaps_to_zero(s, Precision::parse("double"), GapLimitOptions{3}).verdict);
  EXPECT_THROW(gaps_to_zero(stack(two_balls("9", "9")), Precision::parse("double")), InputError);  // no [drop]
}

TEST(GapsToZero, ADropEndedBeforeItsCascadeLeavesTheVerdictUndecided) {
  const GapLimit limit = gaps_to_zero(stack(two_balls("1e6", "1e6") + "[drop]\nmax_events = 1\n"), Precision::parse("double"), GapLimitOptions{2});
  EXPECT_EQ(limit.verdict, GapVerdict::Undecided);
  for (const GapLimitStep& s : limit.steps) {
    EXPECT_FALSE(s.cascade.complete);
    EXPECT_TRUE(std::isinf(s.deviation));
  }
}

TEST(GapsToZero, GapsTheArithmeticCannotTellFromContactAreRefusedWithTheDecadesThatCanBeTaken) {
  // 1e-70 m is in double's window; eight decades down, 1e-78 m is not (drop() refuses it): the message says so, and how
  // many decades can be taken.
  const Scene s = stack("drop_height = 1\n[[body]]\nmass = 0.001\ngap = 1e-70\n[[body]]\nmass = 1\n[[body]]\nmass = \"inf\"\n"
                        "[dissipation]\nK = { \"1-2\" = 1e6, \"2-3\" = 1e6 }\n[drop]\n");
  EXPECT_EQ(gaps_to_zero(s, Precision::parse("double"), GapLimitOptions{7}).verdict, GapVerdict::Differs);
  try {
    gaps_to_zero(s, Precision::parse("double"), GapLimitOptions{12});
    ADD_FAILURE() << "1e-78 m taken as a gap";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("t.toml: gaps x 1e-8: body[1].gap = 1e-78 is outside what a drop in double computes with", 0), 0u)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("; take 7 decades or fewer"), std::string::npos) << e.what();
  }
  // long double's window is wider: there the gaps go down to 1e-82 m.
  EXPECT_EQ(gaps_to_zero(s, Precision::parse("long-double"), GapLimitOptions{12}).verdict, GapVerdict::Differs);
}

}  // namespace
}  // namespace superball::numeric
