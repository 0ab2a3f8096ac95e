// The rules of numeric's settings, each in its type: SolvePrecision (auto and
// its rtol), check_threads(), MapSettings::check(), and the bits, values and
// threads of label_changes() / switch_points() / sweep().  The command and
// the Python module add no rule of their own (tests/python/test_same_refusals.py).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

#include "superball/cases/error.hpp"
#include "superball/cases/scene_file.hpp"
#include "superball/numeric/map.hpp"
#include "superball/numeric/parallel.hpp"
#include "superball/numeric/precision.hpp"
#include "superball/numeric/sweep.hpp"

#include "support/refusal.hpp"

namespace superball::numeric {
namespace {

using superball::test::refusal;

TEST(SolvePrecision, AutoTakesAnRtolFromZeroToOne) {
  const SolvePrecision automatic = SolvePrecision::parse("auto", std::nullopt);
  EXPECT_TRUE(automatic.automatic);
  EXPECT_EQ(automatic.tolerance(), default_rtol);
  EXPECT_EQ(SolvePrecision::parse("auto", 1e-3).tolerance(), 1e-3);
  EXPECT_EQ(SolvePrecision::parse("auto", 0.0).tolerance(), 0.0);
  EXPECT_EQ(SolvePrecision::parse("auto", 1.0).tolerance(), 1.0);
  EXPECT_EQ(refusal([] { SolvePrecision::parse("auto", 2.0); }), "rtol must be a number from 0 to 1, got 2");
  EXPECT_EQ(refusal([] { SolvePrecision::parse("auto", -1e-9); }), "rtol must be a number from 0 to 1, got -1e-09");
  EXPECT_EQ(refusal([] { SolvePrecision::parse("auto", std::numeric_limits<double>::quiet_NaN()); }), "rtol must be a number from 0 to 1, got nan");
}

TEST(SolvePrecision, AFixedArithmeticHasNoRtol) {
  const SolvePrecision exact = SolvePrecision::parse("exact", std::nullopt);
  EXPECT_FALSE(exact.automatic);
  EXPECT_EQ(exact.fixed.name(), "exact");
  EXPECT_EQ(SolvePrecision::parse("digits:30", std::nullopt).fixed.name(), "digits:30");
  EXPECT_EQ(refusal([] { SolvePrecision::parse("double", 1e-3); }), "rtol is the certified error of precision auto; precision double has none");
  // Said whatever the spelling of the precision: it is what was asked that is wrong.
  EXPECT_EQ(refusal([] { SolvePrecision::parse("quad", 1e-3); }), "rtol is the certified error of precision auto; precision quad has none");
  EXPECT_EQ(refusal([] { SolvePrecision::parse("quad", std::nullopt); }), "unknown precision 'quad' (expected double, long-double, digits:N or exact)");
  SolvePrecision built;
  built.automatic = false;
  built.rtol = 1e-3;
  EXPECT_EQ(refusal([&] { built.check(); }), "rtol is the certified error of precision auto; precision double has none");
}

TEST(Threads, FromZeroForAllCoresToTheMost) {
  for (int t : {0, 1, 2, max_threads}) EXPECT_EQ(refusal([&] { check_threads(t); }), "") << t;
  EXPECT_EQ(refusal([] { check_threads(-1); }), "threads must be a whole number from 0 (all cores) to 1024, got -1");
  EXPECT_EQ(refusal([] { check_threads(max_threads + 1); }), "threads must be a whole number from 0 (all cores) to 1024, got 1025");
}

TEST(MapSettings, CheckRefusesBadThreadsAndBits) {
  MapSettings s;
  EXPECT_EQ(refusal([&] { s.check(); }), "");
  s.threads = -2;
  EXPECT_EQ(refusal([&] { s.check(); }), "threads must be a whole number from 0 (all cores) to 1024, got -2");
  s.threads = 0;
  s.bits = 0;
  EXPECT_EQ(refusal([&] { s.check(); }), "bits must be a whole number from 1 to 1024, got 0");
  s.bits = max_bits + 1;
  EXPECT_EQ(refusal([&] { s.check(); }), "bits must be a whole number from 1 to 1024, got 1025");
}

TEST(Sweep, TheValuesBitsAndThreadsAreTheLibrarys) {
  const Scene scene = load_scene(std::string(SUPERBALL_CASES_DIR) + "/scenes/paper-4.4-alpha2.toml");
  const Parameter k34 = Parameter::parse("K.3-4", scene);
  const Precision dbl = Precision::parse("double");
  EXPECT_EQ(refusal([&] { sweep(scene, k34, {}, dbl, 1); }), "no value to solve");
  EXPECT_EQ(refusal([&] { sweep(scene, k34, {cln::cl_RA(1)}, dbl, -1); }), "threads must be a whole number from 0 (all cores) to 1024, got -1");
  EXPECT_EQ(refusal([&] { switch_points(scene, k34, std::vector<cln::cl_RA>{cln::cl_RA(1)}); }), "at least two values are needed");
  EXPECT_EQ(refusal([&] { switch_points(scene, k34, std::vector<cln::cl_RA>{1, 2}, 0); }), "bits must be a whole number from 1 to 1024, got 0");
  EXPECT_EQ(refusal([&] { switch_points(scene, k34, std::vector<cln::cl_RA>{1, 2}, 64, 2000); }),
            "threads must be a whole number from 0 (all cores) to 1024, got 2000");
  for (const std::vector<cln::cl_RA>& v : {std::vector<cln::cl_RA>{1, 3, 2}, {1, 1}, {3, 2, 2}})
    EXPECT_EQ(refusal([&] { switch_points(scene, k34, v); }), "the values must be strictly increasing or strictly decreasing");
  EXPECT_EQ(refusal([&] { switch_points(scene, k34, std::vector<cln::cl_RA>{3, 2, 1}); }), "");
}

}  // namespace
}  // namespace superball::numeric
