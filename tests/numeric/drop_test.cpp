// The whole drop (numeric/drop.hpp) against results derived elsewhere: a ball
// bouncing on a fixed floor (heights e^(2k) h, rest at sqrt(2h/g)(1+e)/(1-e)),
// the 9h and 49h limits of light balls over heavy ones, and the conservation
// laws at every collision.
#include <gtest/gtest.h>

#include <cmath>

#include "superball/cases/error.hpp"
#include "superball/cases/scene_file.hpp"
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
  EXPECT_THROW(drop(s, Precision::parse("exact")), std::invalid_argument);
  EXPECT_THROW(drop(scene("drop_height = 1\n[[body]]\nmass = 1\n[[body]]\nmass = \"inf\"\n"), Precision::parse("double")), InputError);
  EXPECT_THROW(drop(scene("drop_height = 1\n[[body]]\nmass = 1\n[[body]]\nmass = \"inf\"\n[drop]\ndistant = true\n"), Precision::parse("double")),
               std::invalid_argument);
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
            "t.toml:7:14: drop.max_events: must be a whole number from 1 to 100000000 (got 0)");
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

}  // namespace
}  // namespace superball::numeric
