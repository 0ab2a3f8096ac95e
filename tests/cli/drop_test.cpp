// `superball drop` (issue 27) as a user runs it: the JSON's keys and its
// physics (time order, momentum of each cluster, kinetic energy never
// increasing at a collision, the 9 h of a light ball over a heavy one), the
// text's last line, and bad input as one line, exit 2.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "support/run.hpp"

namespace {

using superball::test::describe;
using superball::test::expect_bad_input;
using superball::test::expect_output_error;
using superball::test::fresh_folder;
using superball::test::run;
using superball::test::RunResult;
using superball::test::slurp;

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
  expect_bad_input(run({"drop", kScenes + "drop-two-balls.toml", "--precision", "quad"}), {"precision"});
  const std::string dir = ::testing::TempDir();
  const struct {
    std::string text, expected;
  } bad[] = {
      {"drop_height = 1\n[[body]]\nmass = 1\n[[body]]\nmass = \"inf\"\n[dissipation]\nK = { \"1-2\" = 9 }\n[drop]\nmax_events = 0\n",
       "drop.max_events: must be a whole number from 1 to 1000000 (got 0)"},
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

/// The blocks of a figure's data file (gnuplot's `index`): each its title and its (x, y) points.
struct Block {
  std::string title;
  std::vector<double> x, y;
};
std::vector<Block> blocks(const std::string& dat) {
  std::vector<Block> out;
  std::istringstream in(dat);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("# ", 0) == 0) {
      out.push_back({line.substr(2), {}, {}});
    } else if (!line.empty() && !out.empty()) {
      std::istringstream xy(line);
      double x = 0, y = 0;
      xy >> x >> y;
      out.back().x.push_back(x);
      out.back().y.push_back(y);
    }
  }
  return out;
}

TEST(DropCli, PlotDrawsEveryBodysHeightAgainstTimeWithTheCollisionsAndTheRest) {
  const std::string dir = fresh_folder("drop", "plot-one-ball");
  const RunResult r = run({"drop", kScenes + "drop-one-ball.toml", "--plot", dir, "--json"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const auto j = nlohmann::json::parse(r.out);  // the output is the command's without --plot
  EXPECT_EQ(r.out, run({"drop", kScenes + "drop-one-ball.toml", "--json"}).out);
  EXPECT_EQ(slurp(dir + "/trajectories.png").substr(1, 3), "PNG");
  EXPECT_NE(slurp(dir + "/trajectories.svg").find("<svg"), std::string::npos);
  EXPECT_NE(slurp(dir + "/trajectories.gp").find("\"trajectories.dat\" index 0"), std::string::npos);
  const std::vector<Block> b = blocks(slurp(dir + "/trajectories.dat"));
  ASSERT_EQ(b.size(), 4u);
  EXPECT_EQ(b[0].title, "body 1");
  EXPECT_EQ(b[1].title, "obstacle");
  EXPECT_EQ(b[2].title, "collisions");
  EXPECT_EQ(b[3].title, "at rest");
  // One ball from 1 m, e = 0.8: parabolas between the bounces, never below the floor nor above 1 m, at rest
  // (height 0) from the sum of the series to the end (until = 10 s); a few hundred points, not one per bounce.
  const double rest = j["rest"][0]["time"], g = 9.81;
  ASSERT_EQ(b[0].x.front(), 0);
  EXPECT_EQ(b[0].y.front(), 1);
  EXPECT_EQ(b[0].x.back(), 10);
  EXPECT_LT(b[0].x.size(), 2000u);
  for (std::size_t k = 0; k < b[0].x.size(); ++k) {
    EXPECT_GE(b[0].y[k], -1e-12) << b[0].x[k];
    EXPECT_LE(b[0].y[k], 1 + 1e-12) << b[0].x[k];
    if (b[0].x[k] >= rest) {
      EXPECT_EQ(b[0].y[k], 0) << b[0].x[k];
    }
    if (k > 0) {
      EXPECT_GE(b[0].x[k], b[0].x[k - 1]);
    }
  }
  // The first fall is the closed form h − g t²/2.
  for (std::size_t k = 0; k < b[0].x.size() && b[0].x[k] <= std::sqrt(2 / g); ++k)
    EXPECT_NEAR(b[0].y[k], 1 - g * b[0].x[k] * b[0].x[k] / 2, 1e-12);
  // The highest point between the first and the second bounce is the first apex e² h.
  const double t1 = j["events"][0]["time"], t2 = j["events"][1]["time"];
  double top = 0;
  for (std::size_t k = 0; k < b[0].x.size(); ++k)
    if (b[0].x[k] > t1 && b[0].x[k] < t2) top = std::max(top, b[0].y[k]);
  EXPECT_NEAR(top, 0.64, 0.64 * 1e-3);
  EXPECT_EQ(b[2].x.size(), j["events"].size());
  for (double y : b[2].y) EXPECT_NEAR(y, 0, 1e-12);
  ASSERT_EQ(b[3].x.size(), 1u);
  EXPECT_EQ(b[3].x[0], rest);
  EXPECT_EQ(b[3].y[0], 0);
  std::filesystem::remove_all(dir);
}

TEST(DropCli, PlotOfAStackBouncingAsOneEndsAtRestNotInThousandsOfBounces) {
  // Two touching balls bounce on the floor as one stack (e = 0.998): their rest is drawn, the figure stays small.
  const std::string dir = fresh_folder("drop", "plot-stack");
  const std::string scene = dir + "/stack.toml";
  std::ofstream(scene) << "drop_height = 1\n[[body]]\nmass = 0.001\n[[body]]\nmass = 1\n[[body]]\nmass = \"inf\"\n"
                          "[dissipation]\nK = { \"1-2\" = 1e3, \"2-3\" = 1e3 }\n[drop]\nuntil = 1000\n";
  const RunResult r = run({"drop", scene, "--plot", dir, "--json"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["rest"].size(), 2u);
  const double rest = j["rest"][0]["time"];
  const std::vector<Block> b = blocks(slurp(dir + "/trajectories.dat"));
  ASSERT_EQ(b.size(), 5u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_LT(b[i].x.size(), 100000u);
    EXPECT_EQ(b[i].x.back(), 1000);
    for (std::size_t k = 0; k < b[i].x.size(); ++k)
      if (b[i].x[k] >= rest) {
        EXPECT_EQ(b[i].y[k], 0) << b[i].x[k];
      }
  }
  std::filesystem::remove_all(dir);
}

TEST(DropCli, PlotRefusalsAreThoseOfSolveAndWriteNothing) {
  const std::string dir = fresh_folder("drop", "plot-refusals");
  const std::string one = kScenes + "drop-one-ball.toml";
  // A folder that does not exist: exit 3 naming the first file, as solve --plot.
  expect_output_error(run({"drop", one, "--plot", dir + "/missing"}), {dir + "/missing/trajectories.dat", "No such file or directory"});
  expect_bad_input(run({"drop", one, "--plot", ""}), {"--plot: is empty"});
  // A scene that is one of the figure's files, or the folder's name itself: refused before anything is written.
  const std::string scene = dir + "/trajectories.png", before = slurp(one);
  std::ofstream(scene) << before;
  expect_bad_input(run({"drop", scene, "--plot", dir}), {"--plot " + dir + " (trajectories.png)", "which this command reads"});
  expect_bad_input(run({"drop", scene, "--plot", scene}), {"which this command reads"});
  EXPECT_EQ(slurp(scene), before);
  // A bad scene: one line, and the folder stays as it was.
  const std::string bad = dir + "/bad.toml";
  std::ofstream(bad) << "drop_height = 1\n[[body]]\nmass = 1\ngap = 1e308\n[[body]]\nmass = 1\n[[body]]\nmass = \"inf\"\n[drop]\n";
  expect_bad_input(run({"drop", bad, "--plot", dir}), {bad + ": body[1].gap = 1e308 is outside what a drop in double computes with"});
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"bad.toml", "trajectories.png"}));
  std::filesystem::remove_all(dir);
}

}  // namespace
