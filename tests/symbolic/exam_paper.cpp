// Known answers from the paper (§4.1, case 1 with α₂) and from hand
// derivations of the same model, checked as expressions (normal(a − b) = 0)
// and as conditions (same sign for every admissible parameter).
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "superball/cases/vocabulary.hpp"
#include "superball/symbolic/derivation.hpp"
#include "superball/symbolic/format.hpp"

namespace superball::symbolic {
namespace {

GiNaC::ex parse(const Symbols& s, const std::string& text) {
  GiNaC::parser reader(s.table(), true);
  return reader(text);
}

const Condition& find(const Derivation& d, ConditionKind kind, const std::string& about) {
  for (const Condition& c : d.conditions)
    if (c.kind == kind && c.about == about) return c;
  throw std::runtime_error("no condition " + std::string(to_string(kind)) + " " + about);
}

ContactSet named(const std::string& name) { return Vocabulary::paper().named_case(name).closed; }

bool equal(const GiNaC::ex& a, const GiNaC::ex& b) { return GiNaC::normal(a - b).is_zero(); }

TEST(ExamPaper, Case1Alpha2Velocity) {
  const Deriver deriver(Pattern::paper({2}), Obstacle::Infinite);
  const Derivation d = deriver.derive(named("1"));
  const Symbols& s = deriver.symbols();
  EXPECT_TRUE(equal(d.velocities[0].value(), parse(s, "a*(K14+alpha2-m1)/(m1+K12+K13+K14+2*alpha2)")));
  for (int i = 1; i < 4; ++i) EXPECT_TRUE(d.velocities[static_cast<std::size_t>(i)].value().is_zero()) << "U" << i + 1;
  EXPECT_TRUE(equal(d.determinant, parse(s, "m1+K12+K13+K14+2*alpha2")));
  EXPECT_EQ(d.free_clusters, 1);
}

TEST(ExamPaper, Case1Alpha2Conditions) {
  const Deriver deriver(Pattern::paper({2}), Obstacle::Infinite);
  const Derivation d = deriver.derive(named("1"));
  const Symbols& s = deriver.symbols();
  // §4.1: -α₂ > 2m₁ + K₁₂ + K₁₃ (the paper's "asymptotic" superball condition is exact).
  const Condition& superball = find(d, ConditionKind::Superball, "U1 > a");
  EXPECT_TRUE(superball.exact.sign_proved());
  EXPECT_TRUE(same_condition(superball.exact.numerator, parse(s, "-alpha2-2*m1-K12-K13"), s));
  EXPECT_EQ(superball.relation, Relation::Greater);
  // Dominant balance: the ε⁻¹ terms (K₁₄) cancel, -α₂ > K₁₂ + K₁₃ at order ε⁰.
  EXPECT_TRUE(same_condition(superball.asymptotic.numerator, parse(s, "-alpha2-K12-K13"), s));
  EXPECT_EQ(superball.leading_order, 0);
  EXPECT_EQ(superball.descended, 1);
  // m₁ < K₁₄ + α₂ (actual evolution).
  EXPECT_TRUE(same_condition(find(d, ConditionKind::Evolution, "1-2").exact.numerator, parse(s, "K14+alpha2-m1"), s));
  // m₂ + m₃ >= K₁₂ + K₁₃ + K₂₄ + K₃₄ (no interpenetration 3-4) at the dominant order.
  const Condition& c34 = find(d, ConditionKind::Contact, "3-4");
  EXPECT_EQ(c34.relation, Relation::GreaterEqual);
  EXPECT_TRUE(same_condition(c34.asymptotic.numerator, parse(s, "m2+m3-K12-K13-K24-K34"), s));
  // 2-3 at the dominant order: m₂ >= K₁₂ + K₂₄ (hand derivation; the paper prints another condition).
  EXPECT_TRUE(same_condition(find(d, ConditionKind::Contact, "2-3").asymptotic.numerator, parse(s, "m2-K12-K24"), s));
}

TEST(ExamPaper, Case1Alpha2Reactions) {
  const Deriver deriver(Pattern::paper({2}), Obstacle::Infinite);
  const Derivation d = deriver.derive(named("1"));
  const Symbols& s = deriver.symbols();
  // λ = -R from the running sums of the equations of motion of bodies 2 and 3 (hand derivation).
  const GiNaC::ex U1 = parse(s, "a*(K14+alpha2-m1)/(m1+K12+K13+K14+2*alpha2)");
  const GiNaC::ex lambda23 = parse(s, "-(K12+alpha2)") * U1 + parse(s, "a*(m2-K24+alpha2)");
  const GiNaC::ex lambda34 = lambda23 + parse(s, "-K13") * U1 + parse(s, "a*(m3-K34)");
  EXPECT_TRUE(equal(d.reactions[1].value(), -lambda23));
  EXPECT_TRUE(equal(d.reactions[2].value(), -lambda34));
  EXPECT_TRUE(d.reactions[0].value().is_zero());
}

TEST(ExamPaper, EpsilonFamilyGivesAOverTwoEpsilon) {
  // §4.1: K₁₂ = -α₂(1-ε+ε²), K₁₃ = -α₂ε², K₁₄ = -α₂(1+ε), m₁ = -α₂ε³ give U₁⁺ = a/(2ε) + O(1).
  const Deriver deriver(Pattern::paper({2}), Obstacle::Infinite);
  const Derivation d = deriver.derive(named("1"));
  const Symbols& s = deriver.symbols();
  const GiNaC::symbol eps("eps");
  const GiNaC::ex al = s.by_name("alpha2");
  GiNaC::exmap family{{s.by_name("K12"), -al * (1 - eps + eps * eps)},
                      {s.by_name("K13"), -al * eps * eps},
                      {s.by_name("K14"), -al * (1 + eps)},
                      {s.by_name("m1"), -al * eps * eps * eps}};
  const GiNaC::ex U1 = GiNaC::normal(d.velocities[0].value().subs(family));
  EXPECT_TRUE(equal(GiNaC::normal(U1 * eps).subs(eps == 0), s.fall_speed() / 2));
}

TEST(ExamPaper, Alpha3BehavesLikeAlpha2InCase1) {
  const Deriver d3(Pattern::paper({3}), Obstacle::Infinite);
  const Derivation r3 = d3.derive(named("1"));
  const GiNaC::ex u3 = GiNaC::parser(d3.symbols().table(), true)("a*(K14+alpha3-m1)/(m1+K12+K13+K14+2*alpha3)");
  EXPECT_TRUE(equal(r3.velocities[0].value(), u3));
  EXPECT_TRUE(same_condition(find(r3, ConditionKind::Superball, "U1 > a").exact.numerator,
                             GiNaC::parser(d3.symbols().table(), true)("-alpha3-2*m1-K12-K13"), d3.symbols()));
}

TEST(ExamPaper, Alpha1Alpha6SuperballConditionInCase1) {
  // U₁⁺ = a(K₁₄ − m₁)/(m₁ + K₁₂ + K₁₃ + K₁₄ + 2α₁): U₁⁺ > a ⇔ −2α₁ > 2m₁ + K₁₂ + K₁₃, which M ⪰ 0
  // (α₁² ≤ K₁₂K₁₃, so −2α₁ ≤ 2√(K₁₂K₁₃) ≤ K₁₂ + K₁₃) forbids: the paper's claim.
  const Deriver deriver(Pattern::paper({1, 6}), Obstacle::Infinite);
  const Derivation d = deriver.derive(named("1"));
  const Symbols& s = deriver.symbols();
  EXPECT_TRUE(equal(d.velocities[0].value(), parse(s, "a*(K14-m1)/(m1+K12+K13+K14+2*alpha1)")));
  EXPECT_TRUE(same_condition(find(d, ConditionKind::Superball, "U1 > a").exact.numerator, parse(s, "-2*alpha1-2*m1-K12-K13"), s));
}

TEST(ExamPaper, FiniteObstacleTendsToTheFixedOne) {
  // m₄ → ∞ of the finite-obstacle conditions equals the fixed-obstacle derivation, every case.
  for (const std::vector<int>& alphas : {std::vector<int>{2}, std::vector<int>{1, 6}, std::vector<int>{5}}) {
    const Deriver finite(Pattern::paper(alphas), Obstacle::Finite), fixed(Pattern::paper(alphas), Obstacle::Infinite);
    const auto a = finite.derive_all(), b = fixed.derive_all();
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t k = 0; k < a.size(); ++k) {
      ASSERT_EQ(a[k].conditions.size(), b[k].conditions.size());
      for (std::size_t c = 0; c < a[k].conditions.size(); ++c) {
        const Condition &x = a[k].conditions[c], &y = b[k].conditions[c];
        SCOPED_TRACE("case " + a[k].case_name + " " + to_string(x.kind) + " " + x.about);
        ASSERT_EQ(x.about, y.about);
        ASSERT_TRUE(x.finite.has_value());
        // Same names in both symbol sets: compare the printed polynomials.
        std::ostringstream px, py;
        px << x.exact.numerator;
        py << y.exact.numerator;
        const GiNaC::ex ex = GiNaC::parser(fixed.symbols().table(), true)(px.str());
        EXPECT_TRUE(same_condition(ex, y.exact.numerator, fixed.symbols())) << px.str() << " vs " << py.str();
      }
    }
  }
}

/// A finite obstacle in the paper's regime (m₄ ~ 1/ε like K₁₄): the
/// asymptotic form is the dominant balance of the condition with m₄, not
/// that of its limit m₄ → ∞.
TEST(ExamPaper, FiniteObstacleAsymptoticKeepsTheObstacleMass) {
  const Deriver deriver(Pattern::paper({2}), Obstacle::Finite);
  const Derivation d = deriver.derive(named("1"));
  const Symbols& s = deriver.symbols();
  const Condition& superball = find(d, ConditionKind::Superball, "U1 > a");
  ASSERT_TRUE(superball.finite.has_value());
  ASSERT_TRUE(superball.asymptotic.sign_proved());
  // m₄(−α₂ − K₁₂ − K₁₃) > (m₂ + m₃)K₁₄, not the limit −α₂ > K₁₂ + K₁₃.
  EXPECT_TRUE(same_condition(superball.asymptotic.numerator, parse(s, "m4*(-alpha2-K12-K13)-(m2+m3)*K14"), s))
      << superball.asymptotic.numerator;
  EXPECT_FALSE(same_condition(superball.asymptotic.numerator, parse(s, "-alpha2-K12-K13"), s));
  // m₄α₂ and m₂K₁₄ are of order ε^-1 (m₁m₄, m₁K₁₄ of order ε⁰ are dropped).
  EXPECT_EQ(superball.leading_order, -1);
  EXPECT_EQ(format_condition(superball.asymptotic, superball.relation, s, Style::Text), "−m₄α₂ > m₂K₁₄ + m₃K₁₄ + m₄K₁₂ + m₄K₁₃");
  // The limit form is unchanged: the fixed-obstacle condition.
  EXPECT_TRUE(same_condition(superball.exact.numerator, parse(s, "-alpha2-2*m1-K12-K13"), s));
  // The finite form is of the same order as its dominant balance; the limit form is not.
  EXPECT_EQ(epsilon_order(superball.finite->numerator, s, deriver.scaling()), superball.leading_order);
  EXPECT_EQ(epsilon_order(superball.exact.numerator, s, deriver.scaling()), 0);
}

}  // namespace
}  // namespace superball::symbolic
