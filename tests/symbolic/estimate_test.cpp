// symbolic::estimate_derivation() (estimate.hpp): the width of a pattern and
// the estimate against the measured points it is fitted on and the real runs
// of docs/SYMBOLIC.md ("Limits"), within the factor of 3 it promises.
#include "superball/symbolic/estimate.hpp"

#include <gtest/gtest.h>

namespace superball::symbolic {
namespace {

TEST(Estimate, TheWidthOfAPattern) {
  EXPECT_EQ(pattern_width(Pattern::near(8, 1)), 1);
  EXPECT_EQ(pattern_width(Pattern::near(8, 2)), 2);
  EXPECT_EQ(pattern_width(Pattern::nearest_and_next_nearest(8)), 3);
  EXPECT_EQ(pattern_width(Pattern::all_pairs(6)), 5);
}

/// Within a factor of 3 of \p measured.
void near(double estimated, double measured, const char* what) {
  EXPECT_GT(estimated, measured / 3) << what;
  EXPECT_LT(estimated, measured * 3) << what;
}

TEST(Estimate, WithinAFactorOfThreeOfTheMeasuredRuns) {
  // Times on one core and peak resident memory of the real runs (docs/SYMBOLIC.md, Limits; near2 with
  // couplings: CPU seconds of the tasks, `derive --task-cpu -j 2`, and the largest process).
  const Estimate w3_all_7 = estimate_derivation(Pattern::nearest_and_next_nearest(7), Obstacle::Infinite, 64, true);
  near(w3_all_7.seconds, 7.05, "near2 with couplings, every case of 7 bodies: 7.05 s");
  near(w3_all_7.process_bytes, 174e6, "… 174 MB the largest worker");
  const Estimate w3_all_8 = estimate_derivation(Pattern::nearest_and_next_nearest(8), Obstacle::Infinite, 128, true);
  near(w3_all_8.seconds, 66.9, "every case of 8 bodies: 66.9 s");
  near(w3_all_8.process_bytes, 1.44e9, "… 1.44 GB the largest worker");
  near(estimate_derivation(Pattern::near(11, 1), Obstacle::Infinite, 1, false).seconds, 0.86, "near, one case of 11 bodies: 0.86 s");
  near(estimate_derivation(Pattern::near(11, 1), Obstacle::Infinite, 1, false).process_bytes, 76.8e6, "… 76.8 MB");
  near(estimate_derivation(Pattern::near(9, 1), Obstacle::Infinite, 256, true).seconds, 3.92, "near, every case of 9 bodies: 3.92 s");
  near(estimate_derivation(Pattern::near(8, 2), Obstacle::Infinite, 1, false).seconds, 0.75, "near2, one case of 8 bodies: 0.75 s");
  near(estimate_derivation(Pattern::near(8, 2), Obstacle::Infinite, 1, false).process_bytes, 64.5e6, "… 64.5 MB");
  near(estimate_derivation(Pattern::near(8, 2), Obstacle::Infinite, 128, true).seconds, 13.2, "near2, every case of 8 bodies: 13.2 s");
  near(estimate_derivation(Pattern::all_pairs(6), Obstacle::Infinite, 32, true).seconds, 0.98, "all pairs, every case of 6 bodies: 0.98 s");
  near(estimate_derivation(Pattern::all_pairs(7), Obstacle::Infinite, 1, false).process_bytes, 251e6, "all pairs, one case of 7 bodies: 251 MB");
  // The steps: a body more costs more, a finite obstacle more, a wider pattern more.
  const Estimate w3_one_8 = estimate_derivation(Pattern::nearest_and_next_nearest(8), Obstacle::Infinite, 1, false);
  EXPECT_GT(w3_one_8.seconds, estimate_derivation(Pattern::nearest_and_next_nearest(7), Obstacle::Infinite, 1, false).seconds * 5);
  EXPECT_GT(estimate_derivation(Pattern::nearest_and_next_nearest(8), Obstacle::Finite, 1, false).seconds, w3_one_8.seconds * 2);
  EXPECT_GT(w3_one_8.seconds, estimate_derivation(Pattern::near(8, 2), Obstacle::Infinite, 1, false).seconds);
}

TEST(Estimate, DurationsForPeople) {
  EXPECT_EQ(duration_text(0.42), "0.4 s");
  EXPECT_EQ(duration_text(26.2), "26 s");
  EXPECT_EQ(duration_text(256), "4 min 16 s");
  EXPECT_EQ(duration_text(3 * 3600 + 300), "3 h 5 min");
  EXPECT_EQ(duration_text(12 * 86400), "12 days");
  EXPECT_EQ(duration_text(1e300), "longer than anyone can wait");
}

}  // namespace
}  // namespace superball::symbolic
