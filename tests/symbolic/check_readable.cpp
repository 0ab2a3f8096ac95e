// check_: the readable forms of the conditions (derivation.hpp, Readable)
// are the conditions.  For n = 5 to 7 bodies with nearest and next-nearest
// neighbours and their couplings, and for the paper's four bodies with the
// seven α's and a finite obstacle, every readable form is
//   1. substituted back: the expanded condition P equals σ g S x − (Q S + R)
//      (isolated) or Q S + R (grouped), S the named part, expanded by GiNaC
//      independently of the derivation's own arithmetic;
//   2. evaluated at random exact rational points: the readable inequality and
//      "P REL 0" have the same truth value, and a part the isolated form
//      divides by is positive there.
#include <gtest/gtest.h>

#include <random>

#include "superball/symbolic/derivation.hpp"
#include "superball/symbolic/format.hpp"
#include "random_point.hpp"

namespace superball::symbolic {
namespace {

using test::random_point;

bool holds(const GiNaC::numeric& v, Relation r) { return r == Relation::Greater ? v.is_positive() : !v.is_negative(); }

GiNaC::numeric value(const GiNaC::ex& e, const GiNaC::exmap& at) { return GiNaC::ex_to<GiNaC::numeric>(e.subs(at)); }

/// Checks one form; returns whether it had a readable form.
bool check_form(const ConditionForm& form, Relation rel, const Derivation& d, std::mt19937_64& rng, const std::string& where) {
  if (!form.readable) return false;
  const Readable& r = *form.readable;
  EXPECT_TRUE(form.sign_proved()) << where;
  const GiNaC::ex S = r.named == 0 ? GiNaC::ex(1) : d.named.at(static_cast<std::size_t>(r.named - 1)).value;
  const bool isolated = !r.subject.is_zero();
  const GiNaC::ex rebuilt = isolated ? r.subject * S - (r.quotient * S + r.remainder) : r.quotient * S + r.remainder;
  EXPECT_TRUE(GiNaC::expand(form.numerator - rebuilt).is_zero()) << where << ": P != the readable form's polynomial";
  if (isolated && r.named) {
    EXPECT_TRUE(d.named.at(static_cast<std::size_t>(r.named - 1)).positive) << where << ": divides by a part not proved positive";
  }
  for (int k = 0; k < 3; ++k) {
    const GiNaC::exmap at = random_point(*d.symbols, rng);
    const GiNaC::numeric s = value(S, at);
    if (isolated) {
      EXPECT_TRUE(s.is_positive()) << where;
    }
    const GiNaC::numeric p = value(form.numerator, at);
    const GiNaC::numeric readable = isolated ? value(r.subject, at) - value(r.quotient, at) - value(r.remainder, at) / s
                                             : value(r.quotient, at) * s + value(r.remainder, at);
    EXPECT_EQ(holds(p, rel), holds(readable, rel)) << where << " at a random point";
  }
  return true;
}

/// Checks every readable form of \p cases; returns how many there were.
int check_cases(const Deriver& deriver, const std::vector<ContactSet>& cases, std::mt19937_64& rng) {
  int count = 0;
  for (const ContactSet& closed : cases) {
    const Derivation d = deriver.derive(closed);
    for (const Condition& c : d.conditions) {
      const std::string where = "case " + closed.to_string() + ", " + to_string(c.kind) + " " + c.about;
      count += check_form(c.exact, c.relation, d, rng, where + " (exact)");
      if (c.finite) count += check_form(*c.finite, c.relation, d, rng, where + " (finite)");
      count += check_form(c.asymptotic, c.relation, d, rng, where + " (asymptotic)");
    }
    // Named parts are numbered 1, 2, … in order and each is used.
    for (std::size_t k = 0; k < d.named.size(); ++k) EXPECT_EQ(d.named[k].index, static_cast<int>(k) + 1);
  }
  return count;
}

std::vector<ContactSet> every_case(int n) {
  std::vector<ContactSet> out;
  for (std::uint64_t mask = 0; mask < (std::uint64_t{1} << (n - 1)); ++mask) out.push_back(ContactSet::from_mask(mask, n));
  return out;
}

TEST(CheckReadable, PaperFourBodiesSevenAlphasFiniteObstacle) {
  std::mt19937_64 rng(4);
  const Deriver deriver(Pattern::paper({1, 2, 3, 4, 5, 6, 7}), Obstacle::Finite);
  EXPECT_GT(check_cases(deriver, every_case(4), rng), 10);
}

TEST(CheckReadable, FiveBodiesNearAndNextNearestEveryCase) {
  std::mt19937_64 rng(5);
  const Deriver deriver(Pattern::nearest_and_next_nearest(5), Obstacle::Infinite);
  EXPECT_GT(check_cases(deriver, every_case(5), rng), 10);
}

TEST(CheckReadable, SixAndSevenBodiesRandomCases) {
  std::mt19937_64 rng(67);
  for (int n : {6, 7}) {
    const Deriver deriver(Pattern::nearest_and_next_nearest(n), Obstacle::Infinite);
    // Cases with at least n − 4 closed contacts (a reduced system of at most 4
    // velocities) keep the test short; the mask is random among those.
    std::vector<ContactSet> cases;
    while (cases.size() < 4) {
      const std::uint64_t mask = rng() % (std::uint64_t{1} << (n - 1));
      if (__builtin_popcountll(mask) >= n - 4) cases.push_back(ContactSet::from_mask(mask, n));
    }
    EXPECT_GT(check_cases(deriver, cases, rng), 0) << n << " bodies";
  }
}

TEST(ExamReadable, TheExpertFormOfCase22WithAlpha3) {
  // Issue 13: the analogue of the paper's α₂ condition, written as an expert writes it.
  const Deriver deriver(Pattern::paper({3}), Obstacle::Infinite);
  const Derivation d = deriver.derive(ContactSet::parse("3-4", 4));
  const Condition& superball = d.conditions.front();
  ASSERT_TRUE(superball.exact.readable);
  EXPECT_EQ(format_form(superball.exact, superball.relation, *d.symbols, Style::Text), "−α₃ > 2m₁ + K₁₃ + K₁₂(2m₂ + K₂₃)/S₁");
  ASSERT_FALSE(d.named.empty());
  EXPECT_EQ(format_polynomial(d.named.front().value, *d.symbols, Style::Text), "m₂ + K₁₂ + K₂₃ + K₂₄");
  // The paper's own §4.1 forms stay as the paper writes them.
  const Deriver paper(Pattern::paper({2}), Obstacle::Infinite);
  const Derivation case1 = paper.derive(ContactSet::parse("2-3,3-4", 4));
  EXPECT_EQ(format_form(case1.conditions[0].exact, Relation::Greater, *case1.symbols, Style::Text), "−α₂ > 2m₁ + K₁₂ + K₁₃");
  EXPECT_EQ(format_form(case1.conditions[1].exact, Relation::Greater, *case1.symbols, Style::Text), "m₁ < K₁₄ + α₂");
}

}  // namespace
}  // namespace superball::symbolic
