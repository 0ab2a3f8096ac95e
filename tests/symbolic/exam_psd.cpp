// The positive semi-definiteness conditions of M (paper §3): every
// condition the paper lists is among the derived principal minors, and the
// derived list is exactly the connected minors of the coupling graph.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "superball/symbolic/derivation.hpp"

namespace superball::symbolic {
namespace {

struct Listed {
  const char* about;
  const char* minor;  // >= 0 (> 0 for a single pair)
};

// §3, verbatim: K_ij > 0, α₁² ≤ K₁₂K₁₃, …, the two 3×3 minors.
const std::vector<Listed>& paper_list() {
  static const std::vector<Listed> list = {
      {"1-2", "K12"}, {"1-3", "K13"}, {"1-4", "K14"}, {"2-3", "K23"}, {"2-4", "K24"}, {"3-4", "K34"},
      {"1-2,1-3", "K12*K13-alpha1^2"},
      {"1-2,1-4", "K12*K14-alpha2^2"},
      {"1-3,1-4", "K13*K14-alpha3^2"},
      {"1-4,2-3", "K14*K23-alpha4^2"},
      {"1-4,2-4", "K14*K24-alpha5^2"},
      {"2-3,2-4", "K23*K24-alpha6^2"},
      {"1-4,3-4", "K14*K34-alpha7^2"},
      {"1-2,1-3,1-4", "K12*K13*K14+2*alpha1*alpha2*alpha3-K12*alpha3^2-K13*alpha2^2-K14*alpha1^2"},
      {"1-4,2-3,2-4", "K14*K23*K24+2*alpha4*alpha5*alpha6-K14*alpha6^2-K23*alpha5^2-K24*alpha4^2"},
  };
  return list;
}

TEST(ExamPsd, EveryConditionOfSection3IsDerived) {
  const Deriver deriver(Pattern::paper({1, 2, 3, 4, 5, 6, 7}), Obstacle::Infinite);
  const Symbols& s = deriver.symbols();
  GiNaC::parser reader(s.table(), true);
  for (const Listed& l : paper_list()) {
    SCOPED_TRACE(l.about);
    const Condition* found = nullptr;
    for (const Condition& c : deriver.psd())
      if (c.about == l.about) found = &c;
    ASSERT_NE(found, nullptr);
    EXPECT_TRUE(same_condition(found->exact.numerator, reader(l.minor), s));
    EXPECT_EQ(found->relation, std::string(l.about).find(',') == std::string::npos ? Relation::Greater : Relation::GreaterEqual);
  }
}

TEST(ExamPsd, ConnectedSetsOnly) {
  // α₂ alone: the coupling graph has one edge 1-2 — 1-4; the minors are the
  // six K's and K₁₂K₁₄ − α₂²; the other 2×2 minors are products and are not listed.
  const Deriver deriver(Pattern::paper({2}), Obstacle::Infinite);
  ASSERT_EQ(deriver.psd().size(), 7u);
  EXPECT_EQ(deriver.psd().back().about, "1-2,1-4");
  // All seven α's: pairs 1-2, 1-3, 1-4, 2-3, 2-4, 3-4 with 1-4 coupled to all; count the
  // connected sets by brute force over the 63 subsets.
  const Deriver full(Pattern::paper({1, 2, 3, 4, 5, 6, 7}), Obstacle::Infinite);
  const std::vector<std::pair<int, int>> edges = {{0, 1}, {0, 2}, {1, 2}, {2, 3}, {2, 4}, {3, 4}, {2, 5}};
  int connected = 0;
  for (int mask = 1; mask < 64; ++mask) {
    int reached = mask & -mask;
    for (bool grew = true; grew;) {
      grew = false;
      for (auto [x, y] : edges)
        if ((mask >> x & 1) && (mask >> y & 1) && ((reached >> x & 1) != (reached >> y & 1))) reached |= (1 << x) | (1 << y), grew = true;
    }
    connected += reached == mask;
  }
  EXPECT_EQ(static_cast<int>(full.psd().size()), connected);
}

TEST(ExamPsd, FullMinorIsTheDeterminantOfM) {
  const Deriver deriver(Pattern::paper({1, 2, 3, 4, 5, 6, 7}), Obstacle::Infinite);
  const Symbols& s = deriver.symbols();
  const std::vector<Pair> pairs = s.pattern().pairs();
  GiNaC::matrix M(6, 6);
  for (unsigned r = 0; r < 6; ++r)
    for (unsigned c = 0; c < 6; ++c) M(r, c) = s.entry(pairs[r], pairs[c]);
  const Condition& last = deriver.psd().back();
  EXPECT_EQ(last.about, "1-2,1-3,1-4,2-3,2-4,3-4");
  EXPECT_TRUE(GiNaC::normal(last.exact.numerator - M.determinant()).is_zero());
}

}  // namespace
}  // namespace superball::symbolic
