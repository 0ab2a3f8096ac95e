// `superball sweep` (issue 12): a range holding an inadmissible value is
// refused before any output; a descending range works throughout; every
// option pair is honoured or refused; rows written chunk by chunk are the
// rows of a single solve.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "support/run.hpp"

namespace {

using superball::test::describe;
using superball::test::expect_bad_input;
using superball::test::run;
using superball::test::csv_fields;
using superball::test::lines_of;
using superball::test::RunResult;

const std::string kPaper = std::string(SUPERBALL_CASES_DIR) + "/scenes/paper-4.4-alpha2.toml";
const std::string kThreeBalls = std::string(SUPERBALL_TEST_DATA_DIR) + "/hard/mass-ratio-light-on-heavy.toml";

TEST(SweepCli, InadmissibleValuesAreRefusedBeforeAnyOutput) {
  const struct {
    std::string vary, named, why;
  } bad[] = {{"g=-1:1:3", "g = -1", "must be > 0"},
             {"g=1:0:3", "g = 0", "must be > 0"},
             {"fall_speed=-1:1:3", "fall_speed = -1", "must be >= 0"},
             {"K.3-4=20:-100:1000001", "K.3-4 = -100", "not positive semi-definite"},
             {"velocity.3=0:-5:3", "velocity.3 = -5", "opens before the collision"}};
  for (const auto& b : bad)
    for (const std::vector<std::string>& extra : {std::vector<std::string>{}, {"--csv"}, {"--switch-points"}}) {
      std::vector<std::string> args = {"sweep", kPaper, "--vary", b.vary};
      args.insert(args.end(), extra.begin(), extra.end());
      expect_bad_input(run(args), {kPaper, b.named, b.why});
    }
  // A mass crossing 0, on a scene of three bodies.
  expect_bad_input(run({"sweep", kThreeBalls, "--vary", "mass.2=1:-1:3"}), {"mass.2 = -1", "must be > 0"});
}

TEST(SweepCli, ADescendingRangeWorksThroughout) {
  // The rows in the order asked for; the switch points in increasing value,
  // the same as for the ascending range, with positive bracket widths.
  const RunResult up = run({"sweep", kPaper, "--vary", "K.3-4=0:20:5", "--switch-points"});
  const RunResult down = run({"sweep", kPaper, "--vary", "K.3-4=20:0:5", "--switch-points"});
  ASSERT_EQ(down.exit_code, 0) << describe(down);
  EXPECT_EQ(down.out, up.out);
  for (const std::string& line : lines_of(down.out)) {
    const auto at = line.find("(bracket width ");
    ASSERT_NE(at, std::string::npos) << line;
    EXPECT_GT(std::stod(line.substr(at + 15)), 0) << line;
  }
  const RunResult rows_up = run({"sweep", kPaper, "--vary", "K.3-4=0:20:5", "--csv"});
  const RunResult rows_down = run({"sweep", kPaper, "--vary", "K.3-4=20:0:5", "--csv"});
  ASSERT_EQ(rows_down.exit_code, 0) << describe(rows_down);
  auto a = lines_of(rows_up.out), b = lines_of(rows_down.out);
  ASSERT_EQ(a.size(), 6u);
  ASSERT_EQ(b.size(), 6u);
  for (std::size_t k = 1; k < 6; ++k) EXPECT_EQ(b[k], a[6 - k]);
}

TEST(SweepCli, SwitchPointsAsCsv) {
  // --csv with --switch-points: the switch points as CSV, every change
  // between the two ends of a two-value sweep.
  const RunResult r = run({"sweep", kPaper, "--vary", "K.3-4=0:20:2", "--switch-points", "--csv"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const auto lines = lines_of(r.out);
  ASSERT_EQ(lines.size(), 3u) << r.out;
  EXPECT_EQ(lines[0], "K.3-4,bracket_width,case_below,case_above");
  const auto first = csv_fields(lines[1]), second = csv_fields(lines[2]);
  ASSERT_EQ(first.size(), 4u);
  ASSERT_EQ(second.size(), 4u);
  EXPECT_NEAR(std::stod(first[0]), 6.4287436235676171, 1e-12);
  EXPECT_NEAR(std::stod(second[0]), 13.411993850493881, 1e-12);
  EXPECT_GT(std::stod(first[1]), 0);
  EXPECT_LT(std::stod(first[1]), 20 * 0x1p-64);
  EXPECT_EQ(first[2], "2.2");
  EXPECT_EQ(first[3], "3.3");
  EXPECT_EQ(second[2], first[3]) << "the switches chain";
  EXPECT_EQ(second[3], "3.2");
}

TEST(SweepCli, PrecisionDoesNotApplyToSwitchPoints) {
  expect_bad_input(run({"sweep", kPaper, "--vary", "K.3-4=0:20:3", "--switch-points", "--precision", "double"}),
                   {"--switch-points", "--precision"});
}

TEST(SweepCli, CsvQuotesTheCaseOfOtherThanFourBodies) {
  // Three bodies: the case is the set of closed contacts, "{1-2,2-3}", one field.
  const RunResult r = run({"sweep", kThreeBalls, "--vary", "mass.1=1:2:11", "--csv"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const auto lines = lines_of(r.out);
  ASSERT_EQ(lines.size(), 12u);
  EXPECT_EQ(lines[0], "mass.1,U1,U2,U3,case,status");
  bool both_closed = false;
  for (std::size_t k = 1; k < lines.size(); ++k) {
    const auto f = csv_fields(lines[k]);
    ASSERT_EQ(f.size(), 6u) << lines[k];  // every row has the header's fields
    EXPECT_EQ(f[4].front(), '{') << lines[k];
    both_closed = both_closed || f[4] == "{1-2,2-3}";
  }
  EXPECT_TRUE(both_closed) << r.out;
}

TEST(SweepCli, RowsAcrossChunksAreTheRowsOfOneSolve) {
  // 8193 values: rows are written 4096 at a time.  Values 0, 10, 20 are rows
  // 0, 4096 (the first of the second chunk) and 8192 (the last, alone in the
  // third); each row is the row a sweep of 3 values gives, byte for byte, on
  // any number of threads.
  const RunResult three = run({"sweep", kPaper, "--vary", "K.3-4=0:20:3", "--csv"});
  ASSERT_EQ(three.exit_code, 0) << describe(three);
  const auto small = lines_of(three.out);
  for (const std::string threads : {"1", "2"}) {
    const RunResult r = run({"sweep", kPaper, "--vary", "K.3-4=0:20:8193", "--csv", "--threads", threads});
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    const auto lines = lines_of(r.out);
    ASSERT_EQ(lines.size(), 8194u);
    EXPECT_EQ(lines[0], small[0]);
    EXPECT_EQ(lines[1], small[1]);
    EXPECT_EQ(lines[1 + 4096], small[2]);
    EXPECT_EQ(lines[1 + 8192], small[3]);
  }
}

TEST(SweepCli, RangeEndsAreEveryNumberASceneAccepts) {
  // Issue 25: range ends past 64 bits were refused ("not representable in 64
  // bits") though a scene file takes them; they are exact numbers like any other.
  for (const std::string vary : {"K.1-4=1e18:1e19:3", "K.1-4=10000000000000000000:1e18:3", "K.1-4=1e4000:1e3999:3"}) {
    const RunResult r = run({"sweep", kPaper, "--vary", vary, "--csv", "--precision", "exact"});
    ASSERT_EQ(r.exit_code, 0) << vary << ": " << describe(r);
    const auto lines = lines_of(r.out);
    ASSERT_EQ(lines.size(), 4u) << r.out;
    for (std::size_t k = 1; k < lines.size(); ++k) EXPECT_EQ(csv_fields(lines[k]).back(), "success") << lines[k];
  }
  const RunResult s = run({"sweep", kPaper, "--vary", "K.1-4=1e18:1e19:3", "--switch-points"});
  ASSERT_EQ(s.exit_code, 0) << describe(s);
  EXPECT_EQ(s.out, "no change of evolution case for K.1-4 in the range\n");
}

TEST(SweepCli, OutputNamesTheParameterByItsCanonicalKey) {
  // Any spelling of the entry; the output says K.3-4 (issue 25).
  const RunResult a = run({"sweep", kPaper, "--vary", "K.3-4=0:20:3", "--csv"});
  const RunResult b = run({"sweep", kPaper, "--vary", "K.03-04=0:20:3", "--csv"});
  ASSERT_EQ(a.exit_code, 0) << describe(a);
  ASSERT_EQ(b.exit_code, 0) << describe(b);
  EXPECT_EQ(a.out, b.out);
  const RunResult c = run({"sweep", kPaper, "--vary", "coupling.1-4/1-2=-100:-50:3", "--csv"});
  ASSERT_EQ(c.exit_code, 0) << describe(c);
  EXPECT_EQ(lines_of(c.out).at(0), "alpha.2,U1,U2,U3,U4,case,status");
}

}  // namespace
