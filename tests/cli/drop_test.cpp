// `superball drop` (issue 27) as a user runs it: the JSON's keys and its
// physics (time order, momentum of each cluster, kinetic energy never
// increasing at a collision, the 9 h of a light ball over a heavy one), the
// text's last line, and bad input as one line, exit 2.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "support/run.hpp"

namespace {

using superball::test::expect_bad_input;
using superball::test::run;
using superball::test::RunResult;

const std::string kScenes = std::string(SUPERBALL_CASES_DIR) + "/scenes/";
/// A collision's balance, relative to the largest momentum or energy of the run.
constexpr double kBalance = 1e-9;

TEST(DropCli, TwoBallsJsonHoldsEveryCollisionInTimeOrderAndNearlyNineTimesTheHeight) {
  const RunResult r = run({"drop", kScenes + "drop-two-balls.toml", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  const auto j = nlohmann::json::parse(r.out);
  for (const char* key : {"events", "apexes", "rest", "end", "top_apex_ratio", "precision", "g"}) EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["end"], "apex");
  ASSERT_TRUE(j["fixed_obstacle"].get<bool>());
  ASSERT_GE(j["events"].size(), 2u);
  double t = 0;
  for (const auto& e : j["events"]) {
    for (const char* key : {"time", "contacts", "case", "velocities_before", "velocities_after", "kinetic_energy_after"})
      EXPECT_TRUE(e.contains(key)) << key;
    EXPECT_GE(e["time"].get<double>(), t);
    t = e["time"];
    const double before = e["kinetic_energy_before"], after = e["kinetic_energy_after"];
    EXPECT_LE(after, before * (1 + kBalance));
    // The momentum of a cluster that does not hold the fixed floor (the last body) is conserved.
    if (e["bodies"].back().get<std::size_t>() < j["masses"].size()) {
      EXPECT_NEAR(e["momentum_after"].get<double>(), e["momentum_before"].get<double>(), kBalance * 10) << e.dump();
    }
  }
  const double ratio = j["top_apex_ratio"];
  EXPECT_GT(ratio, 8.9);
  EXPECT_LT(ratio, 9.0);
  // The text says the same ratio on its last line.
  const RunResult text = run({"drop", kScenes + "drop-two-balls.toml"});
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("ratio 8.96605\n"), std::string::npos) << text.out;
}

TEST(DropCli, TheSameInLongDoubleAgreesToTheDoubleFigures) {
  const auto d = nlohmann::json::parse(run({"drop", kScenes + "drop-three-balls.toml", "--json"}).out);
  const auto l = nlohmann::json::parse(run({"drop", kScenes + "drop-three-balls.toml", "--json", "--precision", "long-double"}).out);
  EXPECT_EQ(l["precision"], "long-double");
  ASSERT_EQ(d["events"].size(), l["events"].size());
  EXPECT_NEAR(d["top_apex_ratio"].get<double>(), l["top_apex_ratio"].get<double>(), 1e-9 * d["top_apex_ratio"].get<double>());
  EXPECT_GT(d["top_apex_ratio"].get<double>(), 48);
  EXPECT_LT(d["top_apex_ratio"].get<double>(), 49);
}

TEST(DropCli, BadInputIsOneLineExitTwo) {
  expect_bad_input(run({"drop", kScenes + "paper-4.4-alpha2.toml"}), {"paper-4.4-alpha2.toml", "has no [drop] table"});
  for (const char* p : {"exact", "digits:20"})
    expect_bad_input(run({"drop", kScenes + "drop-two-balls.toml", "--precision", p}), {"a drop runs in double or long-double"});
  const std::string dir = ::testing::TempDir();
  const struct {
    std::string text, expected;
  } bad[] = {
      {"drop_height = 1\n[[body]]\nmass = 1\n[[body]]\nmass = \"inf\"\n[dissipation]\nK = { \"1-2\" = 9 }\n[drop]\nmax_events = 0\n",
       "drop.max_events: must be a whole number from 1 to 100000000 (got 0)"},
      {"drop_height = 1\n[[body]]\nmass = 1\ngap = -1\n[[body]]\nmass = 1\n[[body]]\nmass = \"inf\"\n[dissipation]\nK = { \"1-2\" = 9, \"2-3\" = 9 }\n[drop]\n",
       "gap"},
      {"drop_height = 1\n[[body]]\nmass = 1\n[[body]]\nmass = \"inf\"\n[dissipation]\nK = { \"1-2\" = 9 }\n[drop]\nuntil = -1\n", "drop.until"},
      {"drop_height = 1\n[[body]]\nmass = 1\n[[body]]\nmass = \"inf\"\n[dissipation]\nK = { \"1-2\" = 9 }\n[drop]\nwhen = 3\n", "unknown key"},
  };
  int k = 0;
  for (const auto& b : bad) {
    const std::string file = dir + "superball-drop-bad-" + std::to_string(++k) + ".toml";
    std::ofstream(file) << b.text;
    expect_bad_input(run({"drop", file}), {file, b.expected});
    std::remove(file.c_str());
  }
}

}  // namespace
