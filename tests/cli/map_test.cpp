// `superball map` (issue 15): every bad input is one line and exit 2 with
// nothing written, not even the figure's files; the CSV has one row per
// grid point and matches `solve` of the same scene; the output does not
// depend on --threads; the boundary points as CSV bracket changes of region;
// --plot draws the figure.
#include <gtest/gtest.h>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include <chrono>
#include <sstream>
#include <string>
#include <vector>

#include "support/run.hpp"

namespace {

using superball::test::kAddressSanitizer;
using superball::test::describe;
using superball::test::expect_bad_input;
using superball::test::run;
using superball::test::csv_fields;
using superball::test::lines_of;
using superball::test::RunResult;
using superball::test::slurp;

const std::string kPaper = std::string(SUPERBALL_CASES_DIR) + "/scenes/paper-4.4-alpha2.toml";

bool exists(const std::string& path) { return ::access(path.c_str(), F_OK) == 0; }

TEST(MapCli, BadInputIsOneLineAndWritesNothing) {
  const std::string prefix = ::testing::TempDir() + "map-bad-" + std::to_string(::getpid());
  const struct {
    std::string x, y, expected;
  } bad[] = {{"K.5-6=0:20:5", "alpha.2=-100:0:5", "K.5-6"},                                     // not in a scene of 4 bodies
             {"K.3-4=0:20:5", "K.3-4=1:2:5", "--x K.3-4 and --y K.3-4 name the same parameter (K.3-4)"},  // the same key twice
             // One entry under two spellings (issue 25).
             {"K.3-4=0:20:3", "K.03-4=0:20:3", "--x K.3-4 and --y K.03-4 name the same parameter (K.3-4); a map needs two different parameters"},
             {"alpha.2=-100:0:3", "coupling.1-2/1-4=-100:0:3", "--x alpha.2 and --y coupling.1-2/1-4 name the same parameter (alpha.2)"},
             {"coupling.1-4/1-2=-100:0:3", "coupling.1-2/1-4=-100:0:3", "--x coupling.1-4/1-2 and --y coupling.1-2/1-4 name the same parameter"},
             {"K.3-4=0:20:1", "alpha.2=-100:0:5", "STEPS must be a whole number from 2 to 10000"},  // N < 2
             {"K.3-4=0:20:5", "alpha.2=-100:0:10001", "from 2 to 10000"},                          // N > 10⁴
             {"K.3-4=0:20:5", "alpha.2=-400:-200:5", "not positive semi-definite at any point"},   // M nowhere PSD
             {"K.3-4=0:20:5", "g=-1:10:5", "g = -1"},                                              // a corner a file could not hold
             {"K.3-4=0:0:5", "alpha.2=-100:0:5", "FROM and TO are equal"}};
  for (const auto& b : bad)
    for (const std::vector<std::string>& extra : {std::vector<std::string>{}, {"--csv"}, {"--json"}, {"--plot", prefix}}) {
      std::vector<std::string> args = {"map", kPaper, "--x", b.x, "--y", b.y};
      args.insert(args.end(), extra.begin(), extra.end());
      SCOPED_TRACE(b.x + " " + b.y);
      expect_bad_input(run(args), {b.expected});
      for (const char* ext : {".png", ".svg", ".dat", ".gp"}) EXPECT_FALSE(exists(prefix + ext)) << prefix + ext;
    }
}

TEST(MapCli, AxisEndsAreEveryNumberASceneAccepts) {
  // Issue 25: an end past 64 bits was refused ("not representable in 64 bits").
  const RunResult r = run({"map", kPaper, "--x", "K.1-4=1e18:1e19:3", "--y", "K.3-4=0:20:3", "--csv", "--precision", "exact"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_EQ(lines_of(r.out).size(), 10u) << r.out;
}

/// superball \p args under `ulimit -v KB` (address space), through /bin/sh.
RunResult run_limited(long kb, const std::vector<std::string>& args) {
  std::vector<std::string> sh = {"-c", "ulimit -v " + std::to_string(kb) + " && exec \"$0\" \"$@\"", SUPERBALL_EXE};
  sh.insert(sh.end(), args.begin(), args.end());
  return superball::test::run_program("/bin/sh", sh);
}

TEST(MapCli, AGridTooLargeForTheMemoryIsRefusedAtOnce) {
  // The reproducer: 10⁴ × 10⁴ points under 4 GB grew to bad_alloc (exit 4).  Every output that holds the
  // whole grid is refused with the estimate in under a second, before anything is written.
  if (kAddressSanitizer) GTEST_SKIP() << "AddressSanitizer's shadow memory does not fit under ulimit -v";
  const std::string prefix = ::testing::TempDir() + "map-memory-" + std::to_string(::getpid());
  for (const std::vector<std::string>& extra :
       {std::vector<std::string>{}, {"--json"}, {"--plot", prefix}, {"--boundary-points", "--csv"}, {"--csv", "--checkpoint", prefix}}) {
    std::vector<std::string> args = {"map", kPaper, "--x", "K.3-4=0:20:10000", "--y", "alpha.2=-110:0:10000"};
    args.insert(args.end(), extra.begin(), extra.end());
    SCOPED_TRACE(extra.empty() ? "summary" : extra[0]);
    const auto start = std::chrono::steady_clock::now();
    const RunResult r = run_limited(4000000, args);
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
    expect_bad_input(r, {"a 10000 x 10000 grid holds about ", " GB available (", "use a coarser grid"});
    for (const char* ext : {".png", ".svg", ".dat", ".gp", ""}) EXPECT_FALSE(exists(prefix + ext)) << prefix + ext;
  }
}

TEST(MapCli, ACsvGridTooLargeToHoldIsStreamed) {
  // 600 × 400 points held whole (about 228 bytes each) do not fit in the 40 MB that `ulimit -v 60000` leaves
  // beside the program: the summary is refused, the grid as CSV is written as it is computed, the same bytes.
  if (kAddressSanitizer) GTEST_SKIP() << "AddressSanitizer's shadow memory does not fit under ulimit -v";
  const std::vector<std::string> args = {"map", kPaper, "--x", "K.3-4=0:20:600", "--y", "alpha.2=-110:0:400", "--threads", "2"};
  std::vector<std::string> csv = args;
  csv.push_back("--csv");
  const RunResult whole = run(csv), streamed = run_limited(60000, csv);
  ASSERT_EQ(whole.exit_code, 0) << describe(whole);
  ASSERT_EQ(streamed.exit_code, 0) << describe(streamed);
  EXPECT_EQ(streamed.err, "");
  EXPECT_EQ(lines_of(streamed.out).size(), 1u + 600 * 400);
  EXPECT_TRUE(streamed.out == whole.out) << "the streamed CSV differs from the CSV held whole";
  expect_bad_input(run_limited(60000, args), {"a 600 x 400 grid holds about", "(ulimit -v)"});
}

TEST(MapCli, CsvRowsAreTheSweepsSolves) {
  // The row α₂ = −100 of the map is the scene as written: its points are those of `sweep` along K₃₄.
  const RunResult r = run({"map", kPaper, "--x", "K.3-4=0:20:5", "--y", "alpha.2=-150:0:4", "--csv"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const auto lines = lines_of(r.out);
  ASSERT_EQ(lines.size(), 1u + 5 * 4);
  EXPECT_EQ(lines[0], "K.3-4,alpha.2,psd,case,closed,U1_over_a,superball,status");
  const RunResult sweep = run({"sweep", kPaper, "--vary", "K.3-4=0:20:5", "--csv"});
  ASSERT_EQ(sweep.exit_code, 0) << describe(sweep);
  const auto rows = lines_of(sweep.out);
  ASSERT_EQ(rows.size(), 6u);
  const double a = 3.13209;  // the scene's fall speed
  int not_psd = 0, compared = 0;
  for (std::size_t k = 1; k < lines.size(); ++k) {
    const auto f = csv_fields(lines[k]);
    ASSERT_EQ(f.size(), 8u) << lines[k];
    if (f[1] == "-150") {  // beyond the edge of the PSD cone at α₂ ≈ −102.5
      EXPECT_EQ(f[2], "0") << lines[k];
      EXPECT_EQ(f[3], "") << lines[k];
      ++not_psd;
      continue;
    }
    EXPECT_EQ(f[2], "1") << lines[k];
    EXPECT_EQ(f[7], "success") << lines[k];
    if (f[1] != "-100") continue;
    const auto s = csv_fields(rows[static_cast<std::size_t>(compared + 1)]);
    ++compared;
    EXPECT_EQ(std::stod(s[0]), std::stod(f[0]));
    EXPECT_EQ(f[3], s[5]) << lines[k] << " / " << rows[static_cast<std::size_t>(compared)];
    const double u1 = std::stod(s[1]);
    EXPECT_NEAR(std::stod(f[5]), u1 / a, 1e-14) << lines[k];
    EXPECT_EQ(f[6], u1 > a ? "1" : "0") << lines[k];
  }
  EXPECT_EQ(not_psd, 5);
  EXPECT_EQ(compared, 5);
}

TEST(MapCli, OutputDoesNotDependOnThreads) {
  for (const std::vector<std::string>& extra : {std::vector<std::string>{}, {"--csv"}, {"--json"}, {"--boundary-points", "--csv"}}) {
    std::vector<std::string> args = {"map", kPaper, "--x", "K.3-4=0:20:9", "--y", "alpha.2=-150:0:9"};
    args.insert(args.end(), extra.begin(), extra.end());
    auto with = [&](const std::string& threads) {
      auto a = args;
      a.insert(a.end(), {"--threads", threads});
      return run(a);
    };
    const RunResult one = with("1"), two = with("2");
    ASSERT_EQ(one.exit_code, 0) << describe(one);
    EXPECT_EQ(one.out, two.out);
  }
}

TEST(MapCli, AGridOfSeveralBlocksIsTheSameOnAnyThreads) {
  // 101 x 90 points: the CSV and JSON rows are formatted in three blocks, on the threads.
  for (const std::vector<std::string>& extra : {std::vector<std::string>{}, {"--csv"}, {"--json"}}) {
    std::vector<std::string> args = {"map", kPaper, "--x", "K.3-4=0:20:101", "--y", "alpha.2=-110:0:90"};
    args.insert(args.end(), extra.begin(), extra.end());
    auto with = [&](const std::string& threads) {
      auto a = args;
      a.insert(a.end(), {"--threads", threads});
      return run(a);
    };
    const RunResult one = with("1");
    ASSERT_EQ(one.exit_code, 0) << describe(one);
    EXPECT_EQ(one.err, "");
    for (const std::string threads : {"2", "3"}) {
      const RunResult more = with(threads);
      EXPECT_TRUE(one.out == more.out) << (extra.empty() ? "summary" : extra[0]) << " on " << threads << " threads";
    }
  }
}

TEST(MapCli, StageTimesAreOneLineEachOnStandardError) {
  const RunResult r = run({"map", kPaper, "--x", "K.3-4=0:20:9", "--y", "alpha.2=-150:0:9", "--stage-times"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const auto lines = lines_of(r.err);
  std::vector<std::string> stages;
  for (const std::string& line : lines) {
    ASSERT_EQ(line.rfind("map: stage ", 0), 0u) << line;
    stages.push_back(line.substr(11, line.find(' ', 11) - 11));
  }
  EXPECT_EQ(stages, (std::vector<std::string>{"setup", "checks", "grid", "neighbours", "bisections", "read", "curves", "output"}));
  EXPECT_EQ(r.out, run({"map", kPaper, "--x", "K.3-4=0:20:9", "--y", "alpha.2=-150:0:9"}).out);
}

TEST(MapCli, BoundaryPointsAsCsv) {
  const RunResult r = run({"map", kPaper, "--x", "K.3-4=0:20:5", "--y", "alpha.2=-100:0:5", "--boundary-points", "--csv"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const auto lines = lines_of(r.out);
  ASSERT_GT(lines.size(), 1u);
  EXPECT_EQ(lines[0], "along,K.3-4,alpha.2,bracket_width,psd_low,case_low,superball_low,psd_high,case_high,superball_high");
  for (std::size_t k = 1; k < lines.size(); ++k) {
    const auto f = csv_fields(lines[k]);
    ASSERT_EQ(f.size(), 10u) << lines[k];
    EXPECT_GT(std::stod(f[3]), 0) << lines[k];
    EXPECT_LE(std::stod(f[3]), 25 * 0x1p-64 * 1.005) << lines[k];  // 2^-64 of the larger step, 25 (α₂), printed to 3 digits
    EXPECT_TRUE(f[4] != f[7] || f[5] != f[8] || f[6] != f[9]) << "no change across " << lines[k];
  }
}

TEST(MapCli, SummaryAndFigure) {
  const std::string prefix = ::testing::TempDir() + "map-figure-" + std::to_string(::getpid());
  const RunResult r = run({"map", kPaper, "--x", "K.3-4=0:20:11", "--y", "alpha.2=-150:0:11", "--plot", prefix});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  for (const char* expected : {"case 2.2 {3-4}", "case 3.3 {}", "superball (U1+ > a)", "M is not positive semi-definite at the other",
                               "superball edge (U1+ = a)", "edge of M positive semi-definite"})
    EXPECT_NE(r.out.find(expected), std::string::npos) << expected << " not in:\n" << r.out;
  EXPECT_EQ(slurp(prefix + ".png").substr(1, 3), "PNG");
  EXPECT_NE(slurp(prefix + ".svg").find("<svg"), std::string::npos);
  EXPECT_NE(slurp(prefix + ".gp").find("multiplot"), std::string::npos);
  for (const char* ext : {".png", ".svg", ".dat", ".gp"}) std::remove((prefix + ext).c_str());
}

TEST(MapCli, OverlayAgreesOnThePaperPlane) {
  const RunResult r = run({"map", kPaper, "--x", "K.3-4=0:20:9", "--y", "alpha.2=-150:0:9", "--overlay"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_NE(r.out.find("overlay: the derived conditions of cases 2.2, 3.2, 3.3"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("): agree\n"), std::string::npos) << r.out;
  // --out only with --overlay; an overlay needs keys the derivation's coordinates are affine in.
  expect_bad_input(run({"map", kPaper, "--x", "K.3-4=0:20:3", "--y", "alpha.2=-100:0:3", "--out", "somewhere"}), {"--out", "--overlay"});
  expect_bad_input(run({"map", kPaper, "--x", "K.3-4=0:20:3", "--y", "g=1:10:3", "--overlay"}), {"g: the derivation's coordinates"});
}

TEST(MapCli, JsonHasTheGridTheBoundariesTheCurvesAndTheOverlay) {
  const RunResult r = run({"map", kPaper, "--x", "K.3-4=0:20:5", "--y", "alpha.2=-150:0:4", "--json", "--overlay"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["x"]["key"], "K.3-4");
  EXPECT_EQ(j["y"]["steps"], 4);
  ASSERT_EQ(j["points"].size(), 20u);
  EXPECT_FALSE(j["points"][0]["psd"].get<bool>());  // α₂ = −150
  EXPECT_TRUE(j["points"][5]["psd"].get<bool>());   // α₂ = −100
  ASSERT_FALSE(j["boundaries"].empty());
  for (const auto& b : j["boundaries"]) {
    EXPECT_GT(b["bracket_width"].get<double>(), 0);
    EXPECT_NE(b["below"], b["above"]);
  }
  ASSERT_FALSE(j["curves"].empty());
  for (const auto& c : j["curves"]) EXPECT_EQ(c["points"].size(), c["boundaries"].size());
  EXPECT_TRUE(j["overlay"]["agrees"].get<bool>());
}

}  // namespace
