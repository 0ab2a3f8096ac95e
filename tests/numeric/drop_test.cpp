// The whole drop (numeric/drop.hpp) against results derived elsewhere: a ball
// bouncing on a fixed floor (heights e^(2k) h, rest at sqrt(2h/g)(1+e)/(1-e)),
// the 9h and 49h limits of light balls over heavy ones, and the conservation
// laws at every collision.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "superball/cases/error.hpp"
#include "superball/cases/scene_file.hpp"
#include "superball/numeric/collision.hpp"
#include "superball/numeric/drop.hpp"

namespace superball::numeric {
namespace {

/// Relative agreement of a closed form with the event-driven run (double).
constexpr double kClosedFormTolerance = 1e-9;
/// A collision's momentum and energy balance, relative to the momentum / energy scale.
constexpr double kBalanceTolerance = 1e-9;

Scene scene(const std::string& text) { return parse_scene(text, "t.toml"); }

TEST(Drop, OneBallBouncesToE2kHAndRestsAtTheSumOfTheSeries) {
  const Scene s = scene("drop_height = 1\n[[body]]\nmass = 1\n[[body]]\nmass = \"inf\"\n[dissipation]\nK = { \"1-2\" = 9 }\n[drop]\nuntil = 10\n");
  for (const char* p : {"double", "long-double"}) {
    const DropResult r = drop(s, Precision::parse(p));
    const double e = 0.8, h = 1, g = 9.81;
    ASSERT_GT(r.events.size(), 10u);
    for (std::size_t k = 0; k < r.events.size(); ++k) {
      const double v = r.events[k].velocities_after[0];
      EXPECT_NEAR(v * v / (2 * g), std::pow(e, 2.0 * (k + 1)) * h, kClosedFormTolerance * h) << p << " bounce " << k + 1;
    }
    ASSERT_EQ(r.rest.size(), 1u);
    EXPECT_TRUE(r.rest[0].accumulation);
    EXPECT_NEAR(r.rest[0].time, std::sqrt(2 * h / g) * (1 + e) / (1 - e), kClosedFormTolerance);
    EXPECT_EQ(r.end, "until");
  }
}

TEST(Drop, LightOverHeavyApproachesNineAndFortyNineTimesTheHeight) {
  const Scene two = scene(
      "drop_height = 1\n[[body]]\nmass = 0.001\ngap = 0.001\n[[body]]\nmass = 1\n[[body]]\nmass = \"inf\"\n"
      "[dissipation]\nK = { \"1-2\" = 1e6, \"2-3\" = 1e6 }\n[drop]\n");
  const DropResult r2 = drop(two, Precision::parse("double"));
  EXPECT_EQ(r2.end, "apex");
  // m1/m2 = 1e-3: the top speed is (3 - 4 m1/m2 ...)v; 9h within 0.5 %.
  EXPECT_NEAR(r2.apexes[0].height, 9.0, 0.05);
  const Scene three = scene(
      "drop_height = 1\n[[body]]\nmass = 0.000001\ngap = 0.001\n[[body]]\nmass = 0.001\ngap = 0.001\n[[body]]\nmass = 1\n"
      "[[body]]\nmass = \"inf\"\n[dissipation]\nK = { \"1-2\" = 1e9, \"2-3\" = 1e9, \"3-4\" = 1e9 }\n[drop]\n");
  const DropResult r3 = drop(three, Precision::parse("double"));
  EXPECT_EQ(r3.end, "apex");
  EXPECT_NEAR(r3.apexes[0].height, 49.0, 0.5);
  // The top speed after the cascade of the first fall is (2^3 - 1) v, within 0.5 % (mass ratios 1e-3).
  const double v = std::sqrt(2 * 9.81 * 1);
  EXPECT_NEAR(r3.events[2].velocities_after[0], 7 * v, 0.005 * 7 * v);
  for (const DropResult* r : {&r2, &r3})
    for (const DropEvent& ev : r->events) {
      EXPECT_NEAR(ev.momentum_after, ev.momentum_before, kBalanceTolerance * (1 + std::abs(ev.momentum_before)) + (ev.last_body == static_cast<int>(r->masses.size()) ? 1e300 : 0));
      EXPECT_LE(ev.kinetic_energy_after, ev.kinetic_energy_before * (1 + kBalanceTolerance));
    }
}

TEST(Drop, EnergyIsConstantInFlight) {
  const Scene two = scene(
      "drop_height = 1\n[[body]]\nmass = 0.5\ngap = 0.2\n[[body]]\nmass = 1\n[[body]]\nmass = \"inf\"\n"
      "[dissipation]\nK = { \"1-2\" = 30, \"2-3\" = 40 }\n[drop]\nuntil = 2\n");
  const DropResult r = drop(two, Precision::parse("double"));
  ASSERT_GT(r.events.size(), 2u);
  auto energy = [&](const std::vector<double>& z, const std::vector<double>& v) {
    double e = 0;
    for (std::size_t i = 0; i + 1 < r.masses.size(); ++i) e += r.masses[i] * (v[i] * v[i] / 2 + r.g * z[i]);
    return e;
  };
  double previous = energy(r.release_heights, r.release_velocities);
  for (const DropEvent& ev : r.events) {
    EXPECT_NEAR(energy(ev.heights, ev.velocities_before), previous, kBalanceTolerance * 20);
    previous = energy(ev.heights, ev.velocities_after);
  }
}

TEST(Drop, RefusesWhatItDoesNotRun) {
  const Scene s = scene("drop_height = 1\n[[body]]\nmass = 1\n[[body]]\nmass = \"inf\"\n[drop]\n");
  EXPECT_THROW(drop(scene("drop_height = 1\n[[body]]\nmass = 1\n[[body]]\nmass = \"inf\"\n"), Precision::parse("double")), InputError);
  EXPECT_THROW(drop(s, SolvePrecision{true, {}, 1e-6}), std::invalid_argument);
}

TEST(Drop, BadKeysAreOneLineErrors) {
  auto message = [](const std::string& text) {
    try {
      parse_scene(text, "t.toml");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string base = "[[body]]\nmass = 1\ngap = -1\n[[body]]\nmass = 1\n[[body]]\nmass = \"inf\"\n";
  EXPECT_EQ(message("drop_height = 1\n" + base), "t.toml:4:7: body[1].gap: must be >= 0 m (got -1)");
  EXPECT_NE(message("[[body]]\nmass = 1\nvelocity = 0\n[[body]]\nmass = \"inf\"\n[drop]\n").find("drop_height: a drop onto a fixed obstacle needs drop_height > 0"), std::string::npos);
  EXPECT_EQ(message("drop_height = 1\n[[body]]\nmass = 1\n[[body]]\nmass = \"inf\"\n[drop]\nmax_events = 0\n"),
            "t.toml:7:14: drop.max_events: must be a whole number from 1 to 1000000 (got 0)");
  EXPECT_EQ(message("drop_height = 1\n[[body]]\nmass = 1\n[[body]]\nmass = \"inf\"\n[drop]\nuntil = -1\n"),
            "t.toml:7:9: drop.until: must be \"apex\" or a time in seconds > 0 (got -1)");
  EXPECT_NE(message("drop_height = 1\n[[body]]\nmass = 1\n[[body]]\nmass = \"inf\"\n[drop]\nwhen = 1\n").find("drop.when: unknown key"), std::string::npos);
}

TEST(Drop, ABodyBouncingOnABodyAtRestComesToRestAtTheSumOfItsSeries) {
  // The paper's §4.4 stack released with 1 mm gaps: ball 3 sticks to the obstacle (K34 = 10 < m3 = 15),
  // then ball 2 bounces on it with a constant ratio until its bounces accumulate; each rest is said once.
  const Scene s = load_scene(std::string(SUPERBALL_CASES_DIR) + "/scenes/drop-paper-4.4.toml");
  const DropResult r = drop(s, Precision::parse("double"));
  EXPECT_EQ(r.end, "apex");
  EXPECT_LT(r.events.size(), 50u);
  ASSERT_EQ(r.rest.size(), 2u);
  EXPECT_EQ(r.rest[0].body, 3);
  EXPECT_FALSE(r.rest[0].accumulation);
  EXPECT_EQ(r.rest[1].body, 2);
  ASSERT_TRUE(r.rest[1].accumulation);
  const double e = r.rest[1].ratio, g = 9.81;
  ASSERT_GT(e, 0);
  ASSERT_LT(e, 1);
  // The last bounces of ball 2 on ball 3 have the ratio e, and the rest is their geometric sum.
  const DropEvent& last = r.events.back();
  const DropEvent& before = r.events[r.events.size() - 2];
  EXPECT_NEAR(last.velocities_after[1] / before.velocities_after[1], e, 1e-9);
  EXPECT_NEAR(r.rest[1].time, last.time + 2 * last.velocities_after[1] / g / (1 - e), kClosedFormTolerance);
  for (const DropEvent& ev : r.events) EXPECT_LE(ev.kinetic_energy_after, ev.kinetic_energy_before * (1 + kBalanceTolerance));
  EXPECT_GT(r.top_apex_ratio, 1);
}

TEST(Drop, TwoTouchingBallsBouncingAsOneComeToRestAtTheSumOfTheirSeries) {
  // Two balls released touching (no gap) bounce on the floor as one stack (case {1-2} every time): their
  // speeds are geometric too.  They were bounced until the doubles ran out (354,588 events, or the
  // scene's max_events); now both rest at the series' sum, after a few thousand bounces at most.
  const Scene s = scene(
      "drop_height = 1\n[[body]]\nmass = 0.001\n[[body]]\nmass = 1\n[[body]]\nmass = \"inf\"\n"
      "[dissipation]\nK = { \"1-2\" = 1e3, \"2-3\" = 1e3 }\n[drop]\nuntil = 1000\n");
  for (const char* p : {"double", "long-double"}) {
    const DropResult r = drop(s, Precision::parse(p));
    EXPECT_EQ(r.end, "until") << p;
    EXPECT_LT(r.events.size(), 10000u) << p;
    ASSERT_EQ(r.rest.size(), 2u) << p;
    EXPECT_EQ(r.rest[0].body, 2);
    EXPECT_EQ(r.rest[1].body, 1);
    EXPECT_TRUE(r.rest[0].accumulation && r.rest[1].accumulation);
    EXPECT_EQ(r.rest[0].time, r.rest[1].time);
    const DropEvent& last = r.events.back();
    const double e = r.rest[0].ratio, g = 9.81;
    EXPECT_NEAR(last.velocities_after[0] / r.events[r.events.size() - 2].velocities_after[0], e, 1e-9) << p;
    EXPECT_NEAR(r.rest[0].time, last.time + 2 * last.velocities_after[0] / g / (1 - e), kClosedFormTolerance * r.rest[0].time) << p;
    // At rest on the floor, not a rounding below it.
    for (const DropApex& a : r.apexes) EXPECT_GE(a.height, 0) << p;
  }
}

TEST(Drop, ABodyLeftAtRestOnTheFloorIsNotBelowIt) {
  const Scene s = scene(
      "drop_height = 1\n[[body]]\nmass = 1e70\ngap = 0.001\n[[body]]\nmass = 1e70\n[[body]]\nmass = \"inf\"\n"
      "[dissipation]\nK = { \"1-2\" = 1e3, \"2-3\" = 1e3 }\n[drop]\n");
  const DropResult r = drop(s, Precision::parse("double"));
  ASSERT_EQ(r.end, "rest");
  for (const DropApex& a : r.apexes) EXPECT_EQ(a.height, 0);
  EXPECT_EQ(r.top_apex_ratio, 0);
}

TEST(Drop, DataOutsideTheArithmeticsWindowAreRefusedNotRoundedToZeroOrInfinity) {
  // 1e308 m overflowed 2·g·h (a gap of 1e308 was "tied" with the floor impact: the top ball teleported into
  // contact), 1e-400 m became 0 (a touching stack: another drop).  Each is refused, naming the field.
  const std::string bodies = "[[body]]\nmass = 0.001\n%GAP%[[body]]\nmass = 1\n%V%[[body]]\nmass = \"inf\"\n"
                             "[dissipation]\nK = { \"1-2\" = 1e3, \"2-3\" = 1e3 }\n[drop]\n";
  auto make = [&](const std::string& root, const std::string& gap, const std::string& v, const std::string& drop_table) {
    std::string t = root + bodies + drop_table;
    t.replace(t.find("%GAP%"), 5, gap);
    t.replace(t.find("%V%"), 3, v);
    return scene(t);
  };
  const struct {
    Scene s;
    std::string field;
  } bad[] = {
      {make("drop_height = 1\n", "gap = 1e308\n", "", ""), "body[1].gap = 1e308"},
      {make("drop_height = 1\n", "gap = \"1e-400\"\n", "", ""), "body[1].gap = 1e-400"},
      {make("drop_height = 1e300\n", "", "", ""), "drop_height = 1e300"},
      {make("drop_height = 1\ng = 1e-300\n", "", "", ""), "g = 1e-300"},
      {make("drop_height = 1\n", "", "velocity = 1e200\n", ""), "body[2].velocity = 1e200"},
      {make("drop_height = 1\n", "", "", "until = 1e300\n"), "drop.until = 1e300"},
      {make("drop_height = 1e77\n", "gap = 1e77\n", "", ""), "the top body's release height = 2e+77"},
      {scene("drop_height = 1\n[[body]]\nmass = 1e300\n[[body]]\nmass = \"inf\"\n[dissipation]\nK = { \"1-2\" = 9 }\n[drop]\n"),
       "body[1].mass = 1e300"},  // its kinetic energy overflowed (null in the JSON)
  };
  for (const auto& b : bad) {
    try {
      drop(b.s, Precision::parse("double"));
      ADD_FAILURE() << b.field << ": not refused";
    } catch (const std::invalid_argument& e) {
      const std::string m = e.what();
      EXPECT_EQ(m.rfind("drop(): t.toml: " + b.field + " is outside what a drop in double computes with", 0), 0u) << m;
      EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    }
  }
  // long double's window holds 1e-400 and 1e308: the drops run there (the ball 1e308 m up falls onto the
  // lower one, at rest by then, and bounces back nearly as high: e = (K - m)/(K + m) close to 1).
  EXPECT_EQ(drop(bad[1].s, Precision::parse("long-double")).end, "apex");
  const DropResult high = drop(bad[0].s, Precision::parse("long-double"));
  EXPECT_EQ(high.end, "apex");
  EXPECT_GT(high.apexes[0].height, 0.99e308);
  EXPECT_LT(high.apexes[0].height, 1e308);
}

/// The paper's §4.4 stack with 1 mm gaps (cases/scenes/drop-paper-4.4.toml), in the view \p distant, until \p until.
Scene paper_stack(bool distant, const std::string& until) {
  Scene s = load_scene(std::string(SUPERBALL_CASES_DIR) + "/scenes/drop-paper-4.4.toml");
  s.drop.distant = distant;
  s.drop.until = Number::parse(until);
  return s;
}

/// Every velocity of every event of \p a and \p b, bit for bit.
void expect_same_events(const DropResult& a, const DropResult& b) {
  ASSERT_EQ(a.events.size(), b.events.size());
  for (std::size_t k = 0; k < a.events.size(); ++k) {
    EXPECT_EQ(a.events[k].velocities_after, b.events[k].velocities_after) << "event " << k + 1;
    EXPECT_EQ(a.events[k].time, b.events[k].time) << "event " << k + 1;
    EXPECT_EQ(a.events[k].case_name, b.events[k].case_name) << "event " << k + 1;
  }
  EXPECT_EQ(a.end, b.end);
  EXPECT_EQ(a.top_apex_ratio, b.top_apex_ratio);
}

/// The balance laws of every collision of \p r: kinetic energy never
/// increases; the momentum of the finite bodies is conserved when the
/// colliding bodies do not hold the fixed obstacle; contacts under
/// impenetrability (closed at the instant: not apart) do not interpenetrate.
void expect_balances(const DropResult& r) {
  const int n = static_cast<int>(r.masses.size());
  for (const DropEvent& ev : r.events) {
    SCOPED_TRACE("event at t = " + std::to_string(ev.time));
    EXPECT_LE(ev.kinetic_energy_after, ev.kinetic_energy_before * (1 + kBalanceTolerance));
    if (!(r.fixed_bottom && ev.last_body == n)) {
      EXPECT_NEAR(ev.momentum_after, ev.momentum_before, kBalanceTolerance * (1 + std::abs(ev.momentum_before)));
    }
    double speed = 0;
    for (double v : ev.velocities_before) speed = std::max(speed, std::abs(v));
    for (int c = ev.first_body - 1; c + 1 < ev.last_body; ++c) {
      const std::string name = std::to_string(c + 1) + "-" + std::to_string(c + 2);
      if (std::find(ev.apart.begin(), ev.apart.end(), name) != ev.apart.end()) continue;
      EXPECT_GE(ev.velocities_after[c] - ev.velocities_after[c + 1], -kBalanceTolerance * speed) << "contact " << name;
    }
  }
}

TEST(DropDistant, AStackWithEveryContactClosedCollidesAsInTheTouchingView) {
  // Every contact closed at the impact: the colliding system and its problem are the touching view's, bit for bit.
  Scene s = scene("drop_height = 1\n[[body]]\nmass = 0.5\n[[body]]\nmass = 2\n[[body]]\nmass = 3\n[[body]]\nmass = \"inf\"\n"
                  "[dissipation]\nK = { \"1-2\" = 3, \"2-3\" = 5, \"3-4\" = 7, \"1-4\" = 2 }\n[drop]\nmax_events = 1\n");
  const DropResult touching = drop(s, Precision::parse("double"));
  s.drop.distant = true;
  const DropResult distant = drop(s, Precision::parse("double"));
  ASSERT_EQ(distant.events.size(), 1u);
  EXPECT_TRUE(distant.events[0].apart.empty());
  expect_same_events(touching, distant);
  EXPECT_TRUE(distant.distant);
}

TEST(DropDistant, NoPairOfMAcrossAnOpenGapGivesTheSameDrop) {
  // One ball on the floor (bounces, then rest), and two free bodies meeting
  // (finite bottom): M's only pair is the contact that closes.
  for (const char* text :
       {"drop_height = 1\n[[body]]\nmass = 1\n[[body]]\nmass = \"inf\"\n[dissipation]\nK = { \"1-2\" = 9 }\n[drop]\nuntil = 10\n",
        "drop_height = 0.5\n[[body]]\nmass = 1\nvelocity = -1\n[[body]]\nmass = 4\nvelocity = 1\n[dissipation]\nK = { \"1-2\" = 2 }\n[drop]\nuntil = 3\n"}) {
    Scene s = scene(text);
    const DropResult touching = drop(s, Precision::parse("double"));
    s.drop.distant = true;
    const DropResult distant = drop(s, Precision::parse("double"));
    ASSERT_GT(distant.events.size(), 0u);
    expect_same_events(touching, distant);
    EXPECT_EQ(touching.rest.size(), distant.rest.size());
    expect_balances(distant);
  }
}

TEST(DropDistant, ThePaperStackBouncesAtTheFirstImpactAsTheSimultaneousCollision) {
  // §4.4 with 1 mm gaps: all three balls reach the obstacle at the same speed
  // a = sqrt(2 g 0.5), 3-4 closing first.  Touching view: ball 3 alone hits
  // the obstacle, balls 1 and 2 fly on.  Distant view: every pair of M acts
  // at that instant (K14 = 1500 couples ball 1 and the obstacle through the
  // stack); the simultaneous collision of the paper ends in case 3.3 (every
  // contact opens: no reaction), so impenetrability on 1-2 and 2-3 plays no
  // part there, and the distant first impact is that collision.
  const DropResult touching = drop(paper_stack(false, "0.5"), Precision::parse("double"));
  const DropResult distant = drop(paper_stack(true, "0.5"), Precision::parse("double"));
  ASSERT_GT(touching.events.size(), 1u);
  ASSERT_GT(distant.events.size(), 1u);
  const DropEvent &t1 = touching.events[0], &d1 = distant.events[0];
  EXPECT_EQ(t1.contacts, std::vector<std::string>{"3-4"});
  EXPECT_EQ(d1.contacts, std::vector<std::string>{"3-4"});
  EXPECT_EQ(t1.first_body, 3);
  EXPECT_EQ(d1.first_body, 1);
  EXPECT_EQ(d1.apart, (std::vector<std::string>{"1-2", "2-3"}));
  EXPECT_EQ(t1.velocities_after[0], t1.velocities_before[0]);  // ball 1 not in the touching cluster
  EXPECT_GT(d1.velocities_after[0], 0);                         // ball 1 bounces at a distance
  // The simultaneous collision of the same stack (no gaps), at the same speed.
  Scene together = paper_stack(false, "0.5");
  for (Body& b : together.bodies) b.gap.reset();
  together.drop.requested = false;
  const double a = -d1.velocities_before[2];
  const Problem<double> p = Problem<double>::from(ExactScene::from(together));
  const Solution<double> sim = solve(p);
  ASSERT_EQ(sim.status, Status::Success);
  for (int c = 0; c < 3; ++c) EXPECT_FALSE(sim.closed.closed(c)) << "case 3.3: every contact opens";
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(d1.velocities_after[i], sim.velocities_after[i] * p.unit, 1e-9 * a) << "ball " << i + 1;
  expect_balances(touching);
  expect_balances(distant);
}

TEST(DropDistant, AFiniteBottomMassConservesTheMomentumOfEveryCollision) {
  // No fixed obstacle: every collision at a distance is internal to the stack.
  Scene s = scene("drop_height = 0.02\n[[body]]\nmass = 0.2\nvelocity = 0\ngap = 0.05\n[[body]]\nmass = 1\nvelocity = 0\ngap = 0.1\n[[body]]\nmass = 2\n"
                  "velocity = 0\n[[body]]\nmass = 5\nvelocity = 3\n[dissipation]\n"
                  "K = { \"1-2\" = 4, \"2-3\" = 6, \"3-4\" = 8, \"1-4\" = 3, \"2-4\" = 1 }\n[drop]\ndistant = true\nuntil = 1.5\n");
  for (const char* p : {"double", "long-double"}) {
    const DropResult r = drop(s, Precision::parse(p));
    ASSERT_GE(r.events.size(), 3u) << p;
    for (const DropEvent& ev : r.events) {
      EXPECT_EQ(ev.first_body, 1);  // M joins every body: the whole stack collides each time
      EXPECT_EQ(ev.last_body, 4);
    }
    expect_balances(r);
  }
}

TEST(DropDistant, AHugeKAtADistanceIsSolvedAndReversesTheLightBall) {
  // K14 = 1e12 against m1 = 1e-3: the double solve fails its residual check
  // and the collision is solved again in exact rationals, with the contacts
  // left open there too; ball 1 leaves at minus its velocity, to 2 m1/K14.
  Scene s = paper_stack(true, "0.35");
  for (MatrixEntry& e : s.entries)
    if (e.diagonal() && e.first.name() == "1-4") e.value = Number::parse("1e12");
  const DropResult r = drop(s, Precision::parse("double"));
  EXPECT_EQ(r.end, "until");
  ASSERT_EQ(r.events.size(), 1u);
  EXPECT_NEAR(r.events[0].velocities_after[0], -r.events[0].velocities_before[0], 1e-9);
  expect_balances(r);
}

TEST(DropDistant, ThePaperStackChattersBecauseBallOneReversesAtEveryCollision) {
  // Found by running it to the apex: with every pair of M in every
  // collision and K14 = 1500 >> m1 = 1e-3, ball 1 reverses (U1+ ~ -U1-) at
  // each collision of the stack below, however far it is, and each
  // reversal kicks balls 2 and 3 through K12, K13 (about 1e-6 m/s): their
  // bounces on the obstacle never die out, and the run ends on max_events.
  Scene s = paper_stack(true, "1");
  s.drop.until.reset();
  s.drop.max_events = 60;
  const DropResult r = drop(s, Precision::parse("double"));
  EXPECT_EQ(r.end, "max-events");
  ASSERT_EQ(r.events.size(), 60u);
  for (std::size_t k = 1; k < r.events.size(); ++k) {
    const DropEvent& ev = r.events[k];
    EXPECT_LT(ev.velocities_before[0] * ev.velocities_after[0], 0) << "event " << k + 1;
    EXPECT_NEAR(std::abs(ev.velocities_after[0]), std::abs(ev.velocities_before[0]), 0.05 * std::abs(ev.velocities_before[0])) << "event " << k + 1;
  }
  expect_balances(r);
}

TEST(DropDistant, OneBodyIsRefusedAndTwoBodiesAtRestTogetherNeverCollide) {
  EXPECT_THROW(drop(scene("drop_height = 1\n[[body]]\nmass = 1\n[drop]\ndistant = true\n"), Precision::parse("double")), InputError);
  const DropResult r = drop(scene("[[body]]\nmass = 1\nvelocity = 0\n[[body]]\nmass = 2\nvelocity = 0\n[dissipation]\nK = { \"1-2\" = 1 }\n"
                                  "[drop]\ndistant = true\n"),
                            SolvePrecision::parse("auto", std::nullopt));
  EXPECT_TRUE(r.events.empty());
  EXPECT_EQ(r.end, "no-more-events");
  EXPECT_TRUE(r.orders_certified);
  EXPECT_FALSE(r.escalated);
}

/// Three balls over a fixed floor, 1-2 and 2-3 closing at 0.1 s and 0.1 s + \p late.
Scene two_contacts_at_once(const std::string& late) {
  return scene("drop_height = 1\n[[body]]\nmass = 1\ngap = 0.1\nvelocity = -1\n[[body]]\nmass = 1\ngap = 0.1" + late +
               "\nvelocity = 0\n[[body]]\nmass = 1\nvelocity = 1\n[[body]]\nmass = \"inf\"\n"
               "[dissipation]\nK = { \"1-2\" = 5, \"2-3\" = 5, \"3-4\" = 5 }\n[drop]\nuntil = 0.3\n");
}

TEST(DropOrder, AnExactTieCollidesTogetherAndOnlyExactArithmeticCertifiesIt) {
  const Scene s = two_contacts_at_once("");
  for (const char* p : {"double", "long-double", "digits:40"}) {
    const DropResult r = drop(s, Precision::parse(p));
    ASSERT_GE(r.events.size(), 1u) << p;
    EXPECT_EQ(r.events[0].contacts, (std::vector<std::string>{"1-2", "2-3"})) << p;
    EXPECT_EQ(r.ties, 1) << p;
    EXPECT_FALSE(r.orders_certified) << p;
  }
  // Auto: double and long double cannot order the two contacts; exact
  // rationals (every time here is rational: no body flies over the floor)
  // find them equal, a certified tie.
  const DropResult r = drop(s, SolvePrecision::parse("auto", std::nullopt));
  ASSERT_GE(r.events.size(), 1u);
  EXPECT_EQ(r.events[0].contacts, (std::vector<std::string>{"1-2", "2-3"}));
  EXPECT_EQ(r.ties, 1);
  EXPECT_TRUE(r.events[0].order_certified);
  EXPECT_TRUE(r.orders_certified);
  EXPECT_TRUE(r.escalated);
  EXPECT_EQ(r.precision, "exact");
  EXPECT_EQ(r.precision_asked, "auto");
  EXPECT_TRUE(r.sequences_agree);
  EXPECT_EQ(r.end, "until");
  EXPECT_EQ(r.end_time, 0.3);
  // Momentum of the three balls conserved: the floor is not in the cluster 1-3.
  expect_balances(r);
}

TEST(DropOrder, AutoRunsANearTieAgainInLongDoubleWhichCertifiesIt) {
  // 1e-12 s apart: within the doubt bound of double (2^20 u t ~ 6e-11 s),
  // outside long double's (~3e-14 s).
  const Scene s = two_contacts_at_once("00000000001");
  const DropResult d = drop(s, Precision::parse("double"));
  EXPECT_EQ(d.near_ties, 1);
  EXPECT_FALSE(d.orders_certified);
  EXPECT_EQ(d.precision_asked, "double");
  EXPECT_FALSE(d.escalated);
  const DropResult r = drop(s, SolvePrecision::parse("auto", std::nullopt));
  EXPECT_TRUE(r.escalated);
  EXPECT_EQ(r.precision, "long-double");
  EXPECT_TRUE(r.orders_certified);
  EXPECT_EQ(r.near_ties, 0);
  EXPECT_TRUE(r.sequences_agree);
  EXPECT_EQ(r.double_events, static_cast<int>(d.events.size()));
  EXPECT_EQ(r.events[0].contacts, std::vector<std::string>{"1-2"});
  // A run whose orders are all certified in double stays in double.
  const DropResult plain = drop(load_scene(std::string(SUPERBALL_CASES_DIR) + "/scenes/drop-two-balls.toml"), SolvePrecision::parse("auto", std::nullopt));
  EXPECT_TRUE(plain.orders_certified);
  EXPECT_FALSE(plain.escalated);
  EXPECT_EQ(plain.precision, "double");
}

/// A drop in \p p of the scene file \p name (cases/scenes).
DropResult drop_file(const std::string& name, const char* p) {
  return drop(load_scene(std::string(SUPERBALL_CASES_DIR) + "/scenes/" + name), Precision::parse(p));
}

/// Whether \p a and \p b have the same events (contacts, bodies, case, in
/// order) with times, velocities and the top apex ratio within \p rel.
void expect_same_drop(const DropResult& a, const DropResult& b, double rel) {
  ASSERT_EQ(a.events.size(), b.events.size());
  for (std::size_t k = 0; k < a.events.size(); ++k) {
    SCOPED_TRACE("event " + std::to_string(k + 1));
    EXPECT_EQ(a.events[k].contacts, b.events[k].contacts);
    EXPECT_EQ(a.events[k].case_name, b.events[k].case_name);
    EXPECT_NEAR(a.events[k].time, b.events[k].time, rel * b.events[k].time);
    for (std::size_t i = 0; i < a.events[k].velocities_after.size(); ++i)
      EXPECT_NEAR(a.events[k].velocities_after[i], b.events[k].velocities_after[i], rel * (1 + std::abs(b.events[k].velocities_after[i])));
  }
  EXPECT_EQ(a.end, b.end);
  EXPECT_NEAR(a.top_apex_ratio, b.top_apex_ratio, rel * b.top_apex_ratio);
}

TEST(DropPrecision, DigitsRunsTheSameDropsAsDoubleAndLongDouble) {
  // The classical scenes (stiff contacts included: K/m = 10^15 in the three
  // balls, re-solved exactly from the rounded data as in double) in MPFR
  // floats of 30 and 100 digits: the same sequences; 30 digits against 100
  // to double's last bits, long double against 100 digits to 1e-9 (the
  // 25 collisions of the 1:2:4 stack amplify long double's roundoff to 1e-12).
  for (const char* name : {"drop-two-balls.toml", "drop-three-balls.toml", "drop-paper-4.4.toml", "drop-three-balls-1-2-4.toml", "drop-one-ball.toml"}) {
    SCOPED_TRACE(name);
    const DropResult hundred = drop_file(name, "digits:100"), thirty = drop_file(name, "digits:30");
    EXPECT_EQ(hundred.precision, "digits:100");
    expect_same_drop(thirty, hundred, 1e-14);
    expect_same_drop(drop_file(name, "long-double"), hundred, 1e-9);
    expect_balances(thirty);
    expect_balances(hundred);
  }
}

TEST(DropExact, TheBounceSequenceIsExactToItsRestTime) {
  // One ball over a fixed floor, released at rest: in units of its landing
  // speed every time and velocity is rational, its bounces to the rest are
  // exact; the rest time is t∞ = √(2h/g)(1 + e)/(1 − e) to double's
  // rounding, where double's own run is 1e-9 (drop_one_ball: e = 0.8).
  const DropResult r = drop_file("drop-one-ball.toml", "exact");
  EXPECT_EQ(r.precision, "exact");
  EXPECT_TRUE(r.orders_certified);
  ASSERT_EQ(r.rest.size(), 1u);
  const double h = r.release_heights[0], e = r.rest[0].ratio, g = r.g;
  EXPECT_EQ(e, 0.8);
  EXPECT_NEAR(r.rest[0].time, std::sqrt(2 * h / g) * (1 + e) / (1 - e), 4e-15 * r.rest[0].time);
  const double a = std::sqrt(2 * g * h);
  for (std::size_t k = 0; k < r.events.size(); ++k) {
    const double up = r.events[k].velocities_after[0];  // e^(k+1) a
    EXPECT_NEAR(up, std::pow(e, static_cast<double>(k + 1)) * a, 1e-14 * a) << "bounce " << k + 1;
  }
  expect_same_drop(r, drop_file("drop-one-ball.toml", "double"), 1e-9);
}

TEST(DropExact, EndsWhereAnEventTimeIsNotRational) {
  // Two balls with a gap: the lower one lands at 2h (rational in units of
  // a), the upper one meets it at a rational time, and then the lower one
  // falls back onto the floor from a height: the root of a quadratic whose
  // discriminant is not a square.  Exact goes that far and says so; its
  // events are those of 100 digits to double's last bits.
  const DropResult r = drop_file("drop-two-balls.toml", "exact");
  const DropResult d = drop_file("drop-two-balls.toml", "digits:100");
  EXPECT_EQ(r.end, "inexact");
  ASSERT_GE(r.events.size(), 2u);
  ASSERT_GT(d.events.size(), r.events.size());
  for (std::size_t k = 0; k < r.events.size(); ++k) {
    SCOPED_TRACE("event " + std::to_string(k + 1));
    EXPECT_EQ(r.events[k].contacts, d.events[k].contacts);
    EXPECT_NEAR(r.events[k].time, d.events[k].time, 1e-15 * d.events[k].time);
    for (std::size_t i = 0; i < d.events[k].velocities_after.size(); ++i)
      EXPECT_NEAR(r.events[k].velocities_after[i], d.events[k].velocities_after[i], 1e-15 * (1 + std::abs(d.events[k].velocities_after[i])));
  }
  EXPECT_EQ(r.end_time, r.events.back().time);  // (it ends at its last collision)
  expect_balances(r);
}

}  // namespace
}  // namespace superball::numeric
