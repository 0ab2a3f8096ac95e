// With a finite obstacle the asymptotic conditions are the dominant balance
// of the conditions with m_n (m_n ~ 1/ε in the paper's regime, like K_1n):
// at points of the regime with small ε they agree with the exact solution
// (and so with the exact finite-m_n forms) on a large majority of the drawn
// points, and not less than at a larger ε.
#include <gtest/gtest.h>

#include "superball/cases/vocabulary.hpp"
#include "superball/present/verification.hpp"
#include "superball/verify/verification.hpp"

namespace superball::verify {
namespace {

using cln::cl_RA;
using present::to_text;
using symbolic::Deriver;
using symbolic::Obstacle;
using symbolic::Pattern;

/// "A large majority": the share of drawn points, at the smallest ε, where an
/// asymptotic form must agree with the exact solution.
constexpr double large_majority = 0.95;

double rate(long long part, long long whole) { return whole == 0 ? 1.0 : static_cast<double>(part) / static_cast<double>(whole); }

TEST(AsymptoticFinite, check_FiniteObstacleAsymptoticFormsAgreeAtSmallEpsilon) {
  VerifyOptions o;
  o.epsilons = {cl_RA(1) / 100, cl_RA(1) / 1000000};
  o.samples = 400;
  o.boundary_pairs = 4;
  o.threads = 2;
  for (const auto& [alphas, name] : std::vector<std::pair<std::vector<int>, std::string>>{{{2}, "1"}, {{2}, "3.2"}, {{2}, "0"}, {{1, 6}, "2.1"}}) {
    const Deriver d(Pattern::paper(alphas), Obstacle::Finite);
    const Verification v = verify_case(d, Vocabulary::paper().named_case(name).closed, o);
    SCOPED_TRACE(v.pattern + " case " + name + "\n" + to_text(v));
    ASSERT_EQ(v.obstacle, "finite");
    EXPECT_TRUE(v.exact_agrees());
    const Tally &coarse = v.epsilons[0].drawn, &fine = v.epsilons[1].drawn;
    ASSERT_EQ(fine.exact.total(), o.samples);
    EXPECT_GE(rate(fine.asymptotic.agree(), fine.asymptotic.total()), large_majority);
    EXPECT_GE(rate(fine.asymptotic.agree(), fine.asymptotic.total()), rate(coarse.asymptotic.agree(), coarse.asymptotic.total()));
    for (std::size_t c = 0; c < v.conditions.size(); ++c) {
      const ConditionTally& t = fine.conditions[c];
      EXPECT_GE(rate(t.asymptotic_agree, t.points()), large_majority) << v.conditions[c].about;
      EXPECT_EQ(t.exact_agree, t.points()) << v.conditions[c].about;
    }
  }
}

}  // namespace
}  // namespace superball::verify
