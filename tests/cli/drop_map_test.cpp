// `superball sweep` and `superball map` of drop scenes (a [drop] table), as a
// user runs them: each value's top apex ratio is that of `superball drop` on
// the scene with the value written in, bit for bit; each label is the
// sequence of that drop's collisions, so labels change exactly where the
// sequence does; the fronts' options that need one collision's exact
// solution or another process are refused with one line; so are bad keys,
// bad ranges and arithmetics a drop does not run in.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "support/run.hpp"

namespace {

using superball::test::describe;
using superball::test::expect_bad_input;
using superball::test::run;
using superball::test::RunResult;

const std::string kScenes = std::string(SUPERBALL_CASES_DIR) + "/scenes/";
const std::string kTwo = kScenes + "drop-two-balls.toml";
const std::string kThree = kScenes + "drop-three-balls.toml";

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The fields of a CSV row whose last field may be quoted (the label).
std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::string> f;
  std::string cur;
  bool quoted = false;
  for (char c : line) {
    if (c == '"') quoted = !quoted;
    else if (c == ',' && !quoted) f.push_back(cur), cur.clear();
    else cur += c;
  }
  f.push_back(cur);
  return f;
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

/// \p scene's text with \p line (a whole line, e.g. "gap = 0.001 ...") replaced by \p with, written to a temporary file.
std::string scene_with(const std::string& scene, const std::string& line_start, const std::string& with, const std::string& name) {
  std::string text = slurp(scene);
  const std::size_t at = text.find(line_start);
  EXPECT_NE(at, std::string::npos) << line_start;
  text.replace(at, text.find('\n', at) - at, with);
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

/// The label of `superball drop --json`'s events, as the docs define it: CONTACTS:CASE per collision, a run of k as *k.
std::string label_of(const nlohmann::json& drop) {
  std::vector<std::string> tokens;
  for (const auto& e : drop["events"]) {
    std::string t;
    for (const auto& c : e["contacts"]) t += (t.empty() ? "" : ",") + c.get<std::string>();
    tokens.push_back(t + ":" + e["case"].get<std::string>());
  }
  std::string label;
  for (std::size_t k = 0; k < tokens.size();) {
    std::size_t run = 1;
    while (k + run < tokens.size() && tokens[k + run] == tokens[k]) ++run;
    label += (label.empty() ? "" : " ") + tokens[k] + (run > 1 ? "*" + std::to_string(run) : "");
    k += run;
  }
  return label.empty() ? "none" : label;
}

TEST(DropSweepCli, EachValueIsTheDropOfTheSceneWithTheValueWrittenInBitForBit) {
  for (const char* precision : {"double", "long-double"}) {
    const RunResult r = run({"sweep", kThree, "--vary", "gap.1=0:0.004:5", "--csv", "--precision", precision});
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    const auto rows = lines(r.out);
    ASSERT_EQ(rows.size(), 6u) << r.out;
    EXPECT_EQ(rows[0], "gap.1,top_apex_ratio,events,end,label");
    for (std::size_t k = 1; k < rows.size(); ++k) {
      const auto f = csv_fields(rows[k]);
      ASSERT_EQ(f.size(), 5u) << rows[k];
      const std::string path = scene_with(kThree, "gap = 0.001", "gap = " + f[0], "drop-map-sweep-" + std::to_string(k) + ".toml");
      const RunResult d = run({"drop", path, "--json", "--precision", precision});
      ASSERT_EQ(d.exit_code, 0) << describe(d);
      const auto j = nlohmann::json::parse(d.out);
      // 17 significant digits read back to the same double.
      EXPECT_EQ(std::strtod(f[1].c_str(), nullptr), j["top_apex_ratio"].get<double>()) << rows[k];
      EXPECT_EQ(f[2], std::to_string(j["events"].size()));
      EXPECT_EQ(f[3], j["end"].get<std::string>());
      EXPECT_EQ(f[4], label_of(j)) << rows[k];
    }
  }
}

TEST(DropSweepCli, TheTableSaysTheSameAndDoesNotDependOnTheThreads) {
  const RunResult one = run({"sweep", kTwo, "--vary", "gap.1=0:0.01:6", "-j", "1"});
  const RunResult two = run({"sweep", kTwo, "--vary", "gap.1=0:0.01:6", "-j", "2"});
  ASSERT_EQ(one.exit_code, 0) << describe(one);
  EXPECT_EQ(one.out, two.out);
  const auto rows = lines(one.out);
  ASSERT_EQ(rows.size(), 7u);
  EXPECT_EQ(rows[0], "gap.1  top_apex_ratio  events  end  label");
  // No gap: the two balls touch, 1-2 stays closed, and the light ball only follows the heavy one (ratio ~1);
  // a gap: three collisions, floor, balls, floor, and nearly 9 h.
  EXPECT_EQ(rows[1].rfind("0  0.99999", 0), 0u) << rows[1];
  EXPECT_NE(rows[1].find("  1  apex  2-3:{1-2}"), std::string::npos) << rows[1];
  EXPECT_NE(rows[2].find("  3  apex  2-3:{} 1-2:{} 2-3:{}"), std::string::npos) << rows[2];
}

TEST(DropMapCli, LabelsChangeExactlyWhereTheSequenceOfCollisionsChanges) {
  const RunResult r = run({"map", kTwo, "--x", "gap.1=0:0.01:3", "--y", "mass.1=1/1000:1/2:3", "--csv"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const auto rows = lines(r.out);
  ASSERT_EQ(rows.size(), 10u) << r.out;
  EXPECT_EQ(rows[0], "gap.1,mass.1,top_apex_ratio,events,end,label");
  std::vector<std::string> labels, sequences;
  for (std::size_t k = 1; k < rows.size(); ++k) {
    const auto f = csv_fields(rows[k]);
    ASSERT_EQ(f.size(), 6u) << rows[k];
    std::string text = slurp(kTwo);
    text.replace(text.find("gap = 0.001"), std::string("gap = 0.001").size(), "gap = " + f[0]);
    text.replace(text.find("mass = 0.001"), std::string("mass = 0.001").size(), "mass = " + f[1]);
    const std::string path = ::testing::TempDir() + "drop-map-point-" + std::to_string(k) + ".toml";
    std::ofstream(path) << text;
    const auto j = nlohmann::json::parse(run({"drop", path, "--json"}).out);
    EXPECT_EQ(std::strtod(f[2].c_str(), nullptr), j["top_apex_ratio"].get<double>()) << rows[k];
    labels.push_back(f[5]);
    std::string sequence;  // the contacts and the case of each collision, times and velocities aside
    for (const auto& e : j["events"]) sequence += e["contacts"].dump() + e["case"].get<std::string>() + ";";
    sequences.push_back(sequence);
  }
  // Equal labels exactly where the sequences of contacts and cases are equal.
  bool some_differ = false;
  for (std::size_t a = 0; a < labels.size(); ++a)
    for (std::size_t b = 0; b < labels.size(); ++b) {
      EXPECT_EQ(labels[a] == labels[b], sequences[a] == sequences[b]) << labels[a] << " / " << labels[b];
      some_differ = some_differ || labels[a] != labels[b];
    }
  EXPECT_TRUE(some_differ) << r.out;
  // Along gap.1 at each mass, the touching start (gap 0) differs from the gapped ones.
  for (int row = 0; row < 3; ++row) EXPECT_NE(labels[static_cast<std::size_t>(row * 3)], labels[static_cast<std::size_t>(row * 3 + 1)]);
}

TEST(DropMapCli, SummaryJsonAndFigureOfOneMap) {
  const std::vector<std::string> args = {"map", kTwo, "--x", "gap.1=0:0.01:3", "--y", "drop_height=1/2:1:2"};
  const RunResult text = run(args);
  ASSERT_EQ(text.exit_code, 0) << describe(text);
  EXPECT_EQ(text.out.rfind("drop map of " + kTwo + ": gap.1 from 0 to 1/100 (3 values) by drop_height from 1/2 to 1 (2 values), in double\n", 0), 0u)
      << text.out;
  EXPECT_NE(text.out.find("boundaries: none bisected"), std::string::npos) << text.out;
  std::vector<std::string> json_args = args;
  json_args.push_back("--json");
  const RunResult json = run(json_args);
  ASSERT_EQ(json.exit_code, 0) << describe(json);
  const auto j = nlohmann::json::parse(json.out);
  ASSERT_EQ(j["points"].size(), 6u);
  EXPECT_EQ(j["x"]["key"], "gap.1");
  EXPECT_EQ(j["y"]["to"], "1");
  for (const auto& p : j["points"]) {
    EXPECT_LT(p["label"].get<std::size_t>(), j["labels"].size());
    EXPECT_EQ(p["end"], "apex");
  }
  EXPECT_EQ(j["labels"][0], "2-3:{1-2}");
  const std::string prefix = ::testing::TempDir() + "drop-map-figure";
  std::vector<std::string> plot_args = args;
  plot_args.insert(plot_args.end(), {"--plot", prefix});
  const RunResult plot = run(plot_args);
  ASSERT_EQ(plot.exit_code, 0) << describe(plot);
  EXPECT_EQ(plot.out, text.out);
  for (const char* ext : {".dat", ".gp", ".png", ".svg"}) EXPECT_FALSE(slurp(prefix + ext).empty()) << ext;
  EXPECT_NE(slurp(prefix + ".gp").find("L1: 2-3:{1-2}"), std::string::npos);
}

TEST(DropMapCli, ARunEndedByMaxEventsIsPrintedAsSuchAndExitsOne) {
  // A gap of 1 km: the lower bodies bounce for as long as the top one falls, until max_events (here 5).
  const std::string path = scene_with(kThree, "[drop]", "[drop]\nmax_events = 5", "drop-map-max-events.toml");
  const RunResult sweep = run({"sweep", path, "--vary", "gap.1=0:1000:2", "--csv"});
  EXPECT_EQ(sweep.exit_code, 1) << describe(sweep);
  EXPECT_EQ(sweep.err, "");
  const auto rows = lines(sweep.out);
  ASSERT_EQ(rows.size(), 3u) << sweep.out;
  EXPECT_EQ(csv_fields(rows[1])[3], "apex");
  EXPECT_EQ(csv_fields(rows[2])[2], "5");
  EXPECT_EQ(csv_fields(rows[2])[3], "max-events");
  const RunResult map = run({"map", path, "--x", "gap.1=0:1000:2", "--y", "mass.1=1/1000:1:2"});
  EXPECT_EQ(map.exit_code, 1) << describe(map);
  EXPECT_NE(map.out.find("runs ended by max-events or an unsolved collision: 2 points"), std::string::npos) << map.out;
}

TEST(DropMapCli, HostileInputIsRefusedWithOneLine) {
  const std::string paper = kScenes + "paper-4.4-alpha2.toml";
  // A gap on a scene without [drop]; the bottom body's; body n - 1's (its distance is drop_height); not a body.
  expect_bad_input(run({"sweep", paper, "--vary", "gap.1=0:1:3"}), {"'gap.1'", "no [drop] table"});
  expect_bad_input(run({"map", paper, "--x", "gap.1=0:1:3", "--y", "K.3-4=1:2:3"}), {"'gap.1'", "no [drop] table"});
  expect_bad_input(run({"sweep", kTwo, "--vary", "gap.3=0:1:3"}), {"'gap.3'", "body must be 1..1"});
  expect_bad_input(run({"sweep", kTwo, "--vary", "gap.2=0:1:3"}), {"'gap.2'", "body 2's is drop_height"});
  expect_bad_input(run({"sweep", kTwo, "--vary", "gap.x=0:1:3"}), {"'gap.x'", "body must be"});
  expect_bad_input(run({"sweep", kScenes + "drop-one-ball.toml", "--vary", "gap.1=0:1:3"}), {"no gap to vary with 2 bodies"});
  // Negative gaps along an axis, a drop height reaching 0, M not PSD at an end.
  expect_bad_input(run({"sweep", kTwo, "--vary", "gap.1=-0.01:0.01:3"}), {"gap.1 = -1/100", "must be >= 0"});
  expect_bad_input(run({"map", kTwo, "--x", "gap.1=0:0.01:3", "--y", "gap.2=-1:0:3"}), {"'gap.2'"});
  expect_bad_input(run({"map", kThree, "--x", "gap.1=0:0.01:3", "--y", "gap.2=-1:0:3"}), {"gap.2 = -1", "must be >= 0"});
  expect_bad_input(run({"sweep", kTwo, "--vary", "drop_height=0:1:3"}), {"drop_height = 0", "needs drop_height > 0"});
  expect_bad_input(run({"sweep", kTwo, "--vary", "K.1-2=-1:1:3"}), {"K.1-2 = -1", "not positive semi-definite"});
  // Steps 1 and huge.
  expect_bad_input(run({"sweep", kTwo, "--vary", "gap.1=0:0.01:1"}), {"STEPS"});
  expect_bad_input(run({"sweep", kTwo, "--vary", "gap.1=0:0.01:100000000"}), {"STEPS"});
  expect_bad_input(run({"map", kTwo, "--x", "gap.1=0:0.01:10001", "--y", "mass.1=1:2:3"}), {"STEPS"});
  expect_bad_input(run({"map", kTwo, "--x", "gap.1=0:0.01:3", "--y", "gap.01=0:1:3"}), {"same parameter (gap.1)"});
  // An arithmetic that does not exist.
  expect_bad_input(run({"sweep", kTwo, "--vary", "gap.1=0:0.01:3", "--precision", "quad"}), {"precision"});
  // What needs one collision's exact solution, or another process.
  expect_bad_input(run({"sweep", kTwo, "--vary", "gap.1=0:0.01:3", "--switch-points"}), {"has a [drop] table", "no exact solution"});
  expect_bad_input(run({"map", kTwo, "--x", "gap.1=0:0.01:3", "--y", "mass.1=1:2:3", "--overlay"}), {"overlay", "has a [drop] table"});
  expect_bad_input(run({"map", kTwo, "--x", "gap.1=0:0.01:3", "--y", "mass.1=1:2:3", "--boundary-points"}), {"boundary_points", "has a [drop] table"});
  const std::string folder = ::testing::TempDir() + "drop-map-checkpoint";
  expect_bad_input(run({"map", kTwo, "--x", "gap.1=0:0.01:3", "--y", "mass.1=1:2:3", "--checkpoint", folder}), {"no checkpoint"});
  expect_bad_input(run({"sweep", kTwo, "--vary", "gap.1=0:0.01:3", "--checkpoint", folder}), {"no checkpoint"});
  expect_bad_input(run({"sweep", kTwo, "--vary", "gap.1=0:0.01:3", "--shard", "1/2"}), {"no --shard"});
  EXPECT_FALSE(std::ifstream(folder).good()) << "a refused checkpoint made its folder";
}

}  // namespace
