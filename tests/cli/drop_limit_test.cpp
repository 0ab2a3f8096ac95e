// `superball drop --gaps-to-zero` as a user runs it: the JSON's keys, the
// series of gaps, the cascades' physics (kinetic energy after a cascade no
// more than before the drop's first collision), and bad input as one line, exit 2.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "support/run.hpp"

namespace {

using superball::test::expect_bad_input;
using superball::test::run;
using superball::test::RunResult;

const std::string kScenes = std::string(SUPERBALL_CASES_DIR) + "/scenes/";

TEST(DropGapsToZeroCli, ThePaperStacksSeriesAndItsVerdict) {
  const RunResult r = run({"drop", kScenes + "drop-paper-4.4.toml", "--gaps-to-zero", "--decades", "4", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* key : {"landing_speed", "tolerance", "verdict", "simultaneous", "steps", "precision"}) EXPECT_TRUE(j.contains(key)) << key;
  ASSERT_EQ(j["steps"].size(), 5u);
  const double a = j["landing_speed"], masses[] = {0.001, 10, 15};
  EXPECT_NEAR(a, std::sqrt(2 * 9.81 * 0.5), 1e-12 * a);
  for (std::size_t k = 0; k < 5; ++k) {
    const auto& step = j["steps"][k];
    EXPECT_DOUBLE_EQ(step["scale"].get<double>(), std::pow(10.0, -static_cast<double>(k)));
    EXPECT_TRUE(step["cascade"]["complete"].get<bool>());
    // Released from rest with gaps of at most 1 mm: the energy after the cascade is at most that of the stack landing at a
    // (plus what the 2 mm of extra fall of ball 1 gives it).
    double energy = 0;
    for (int i = 0; i < 3; ++i) energy += masses[i] * std::pow(step["cascade"]["velocities"][i].get<double>(), 2) / 2;
    EXPECT_LE(energy, (masses[0] + masses[1] + masses[2]) * a * a / 2 + masses[0] * 9.81 * 0.002 + masses[1] * 9.81 * 0.001);
  }
  EXPECT_EQ(j["verdict"], "differs");
  EXPECT_EQ(j["simultaneous"]["cascade"]["collisions"][0], "1-4 3.3");
  const RunResult text = run({"drop", kScenes + "drop-paper-4.4.toml", "--gaps-to-zero", "--decades", "4"});
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("the gapped drops do NOT converge to the simultaneous collision: at gaps x 1e-4"), std::string::npos) << text.out;
}

TEST(DropGapsToZeroCli, BadInputIsOneLine) {
  expect_bad_input(run({"drop", kScenes + "drop-two-balls.toml", "--gaps-to-zero", "--decades", "0"}), {"decades must be a whole number from 1 to 12, got 0"});
  expect_bad_input(run({"drop", kScenes + "drop-two-balls.toml", "--gaps-to-zero", "--decades", "13"}), {"decades must be a whole number from 1 to 12, got 13"});
  expect_bad_input(run({"drop", kScenes + "drop-one-ball.toml", "--gaps-to-zero"}), {"no body has a gap > 0"});
  expect_bad_input(run({"drop", kScenes + "drop-two-balls.toml", "--decades", "3"}), {"--decades requires --gaps-to-zero"});
  expect_bad_input(run({"drop", kScenes + "drop-two-balls.toml", "--gaps-to-zero", "--precision", "quad"}), {"precision"});
}

}  // namespace
