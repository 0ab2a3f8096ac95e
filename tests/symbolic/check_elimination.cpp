// check_: the forms written through a case's elimination (derivation.hpp,
// Elimination, EliminatedForm) are the velocities, reactions and conditions.
// The printed ASCII definitions (p, l, y, V) are read back with GiNaC's
// parser at random exact rational points, independently of the derivation's
// own check, and
//   1. the cluster velocities V equal the expanded velocity fractions, the
//      product of the pivots equals det(ZᵀAZ), each reaction written through
//      the V's equals its fraction (exact rational equality);
//   2. each condition written through the V's has the truth value of its
//      expanded polynomial at admissible points; an asymptotic form marked
//      `limit` (the scaling's small parameters at 0 in the definitions) has
//      the truth value of the expanded dominant balance.
// For n = 5 every case, for n = 6 and 7 the all-open case (the longest
// forms) and random others.
#include <gtest/gtest.h>

#include <random>

#include "superball/symbolic/derivation.hpp"
#include "superball/symbolic/format.hpp"
#include "random_point.hpp"
#include "support/scale.hpp"

namespace superball::symbolic {
namespace {

using test::random_point;

GiNaC::numeric value(const GiNaC::ex& e, const GiNaC::exmap& at) { return GiNaC::ex_to<GiNaC::numeric>(GiNaC::ex(e.subs(at)).evalm()); }

/// The numbers of the symbols at \p at and of every definition of \p e, read back from its ASCII text.
GiNaC::symtab definitions_at(const Elimination& e, const Symbols& s, const GiNaC::exmap& at) {
  GiNaC::symtab table;
  for (const SymbolInfo& info : s.all()) table[info.ascii] = at.at(info.symbol);
  for (const auto& [name, text] : elimination_definitions(e, s, Style::Ascii)) {
    GiNaC::parser read(table, true);  // strict: an unknown name is an error
    table[name] = read(text);
    EXPECT_TRUE(GiNaC::is_a<GiNaC::numeric>(table[name])) << name << " = " << text;
  }
  return table;
}

GiNaC::numeric read_at(const std::string& text, const GiNaC::symtab& table) {
  GiNaC::parser read(table, true);
  return GiNaC::ex_to<GiNaC::numeric>(read(text));
}

/// "LHS > RHS" or "LHS >= RHS" (ASCII) at the point: LHS − RHS, and the relation.
GiNaC::numeric difference_at(const std::string& inequality, const GiNaC::symtab& table) {
  for (const std::string rel : {" >= ", " > "}) {
    const std::size_t at = inequality.find(rel);
    if (at != std::string::npos) return read_at(inequality.substr(0, at), table) - read_at(inequality.substr(at + rel.size()), table);
  }
  ADD_FAILURE() << "no relation in " << inequality;
  return 0;
}

bool holds(const GiNaC::numeric& v, Relation r) { return r == Relation::Greater ? v.is_positive() : !v.is_negative(); }

/// Checks \p d at three random points; returns the number of forms written through the elimination.
int check_derivation(const Derivation& d, std::mt19937_64& rng) {
  if (!d.elimination) return 0;
  const Symbols& s = *d.symbols;
  const Elimination& e = *d.elimination;
  const std::string where = "case " + d.closed.to_string();
  int forms = 0;
  for (int k = 0; k < 3; ++k) {
    const GiNaC::exmap at = random_point(s, rng);
    GiNaC::exmap zeroed = at;
    for (const GiNaC::ex& x : e.small) zeroed[x] = 0;
    const GiNaC::symtab table = definitions_at(e, s, at), limit = definitions_at(e, s, zeroed);
    // 1. Velocities, det(ZᵀAZ), reactions.
    GiNaC::numeric pivots = 1;
    for (int c = 1; c <= e.size; ++c) pivots *= GiNaC::ex_to<GiNaC::numeric>(table.at("p" + std::to_string(c)));
    EXPECT_EQ(pivots, value(d.determinant, at)) << where << ": det(Z^T A Z) is not the product of the pivots";
    for (int i = 1, c = 1; i <= s.bodies(); ++i) {
      const GiNaC::numeric u = value(d.velocities[static_cast<std::size_t>(i - 1)].value(), at);
      if (c <= e.size) {
        EXPECT_EQ(u, GiNaC::ex_to<GiNaC::numeric>(table.at("V" + std::to_string(c)))) << where << ": U" << i;
      }
      if (i < s.bodies() && !d.closed.closed(i - 1)) ++c;
    }
    for (int c = 0; c + 1 < s.bodies(); ++c) {
      if (!d.closed.closed(c)) continue;
      const std::string r = format_linear(d.reactions_eliminated.at(static_cast<std::size_t>(c)), s, Style::Ascii, true);
      EXPECT_EQ(read_at(r, table), value(d.reactions[static_cast<std::size_t>(c)].value(), at)) << where << ": R on " << c + 1;
    }
    // 2. Conditions.
    for (const Condition& c : d.conditions) {
      const std::string about = where + ", " + to_string(c.kind) + " " + c.about;
      for (const ConditionForm* form : {&c.exact, &c.asymptotic}) {
        if (!form->eliminated) continue;
        ++forms;
        const bool lim = form->eliminated->limit;
        EXPECT_EQ(lim, form == &c.asymptotic) << about << ": only an asymptotic form takes the limit";
        const GiNaC::numeric through = difference_at(format_eliminated(*form->eliminated, c.relation, s, Style::Ascii), lim ? limit : table);
        const GiNaC::numeric expanded = value(form->numerator, lim ? zeroed : at);
        EXPECT_EQ(holds(through, c.relation), holds(expanded, c.relation))
            << about << (lim ? " (asymptotic)" : " (exact)") << ": " << through << " vs " << expanded;
        EXPECT_EQ(through.csgn(), expanded.csgn()) << about;
      }
    }
  }
  return forms;
}

TEST(CheckElimination, FiveBodiesNearAndNextNearestEveryCase) {
  std::mt19937_64 rng(55);
  const Deriver deriver(Pattern::nearest_and_next_nearest(5), Obstacle::Infinite);
  int forms = 0;
  for (std::uint64_t mask = 0; mask < 16; ++mask) forms += check_derivation(deriver.derive(ContactSet::from_mask(mask, 5)), rng);
  EXPECT_GT(forms, 10);
}

TEST(CheckElimination, SixAndSevenBodiesAllOpenAndRandomCases) {
  std::mt19937_64 rng(76);
  for (int n : {6, 7}) {
    // At a small scale (scripts/test.sh under the sanitizers) 6 bodies only: 7 take the same paths, longer.
    if (n == 7 && superball::test::small_scale()) continue;
    const Deriver deriver(Pattern::nearest_and_next_nearest(n), Obstacle::Infinite);
    std::vector<std::uint64_t> masks{0};
    while (masks.size() < 3) masks.push_back(rng() % (std::uint64_t{1} << (n - 1)));
    int forms = 0;
    for (std::uint64_t mask : masks) forms += check_derivation(deriver.derive(ContactSet::from_mask(mask, n)), rng);
    EXPECT_GT(forms, n) << n << " bodies";
  }
}

TEST(ExamElimination, AllOpenFiveBodies) {
  // The top cluster's velocity is the last one eliminated: V₁ = y₁/p₁, and the
  // superball condition of the all-open case reads V₁ > a.
  const Deriver deriver(Pattern::nearest_and_next_nearest(5), Obstacle::Infinite);
  const Derivation d = deriver.derive(ContactSet::from_mask(0, 5));
  ASSERT_TRUE(d.elimination);
  const auto defs = elimination_definitions(*d.elimination, *d.symbols, Style::Text);
  EXPECT_EQ(defs.front().first, "p₄");
  EXPECT_EQ(defs.front().second, "m₄ + K₂₄ + K₃₄ + K₄₅ + 2c₂₄,₃₄");
  const auto v1 = std::find_if(defs.begin(), defs.end(), [](const auto& def) { return def.first == "V₁"; });
  ASSERT_NE(v1, defs.end());
  EXPECT_EQ(v1->second, "y₁/p₁");
  const Condition& superball = d.conditions.front();
  ASSERT_TRUE(superball.exact.eliminated);
  EXPECT_EQ(format_form(superball.exact, superball.relation, *d.symbols, Style::Text), "V₁ > a");
  ASSERT_TRUE(superball.asymptotic.eliminated);
  EXPECT_TRUE(superball.asymptotic.eliminated->limit);
  ASSERT_EQ(d.elimination->small.size(), 1u);
  EXPECT_TRUE(d.elimination->small.front().is_equal(d.symbols->mass(1)));
  // The paper's four bodies with any one coupling α_k: every form stays
  // expanded.  With all seven, the exact forms of more than
  // max_inline_exact_terms terms are written through the elimination, the
  // asymptotic ones never (K₁₄ ~ 1/ε has a negative order, so no asymptotic
  // form is the ε⁰ part of the elimination).
  for (int k = 1; k <= 8; ++k) {
    const Deriver paper(Pattern::paper(k <= 7 ? std::vector<int>{k} : std::vector<int>{1, 2, 3, 4, 5, 6, 7}), Obstacle::Infinite);
    for (std::uint64_t mask = 0; mask < 8; ++mask) {
      const Derivation p = paper.derive(ContactSet::from_mask(mask, 4));
      for (const Condition& c : p.conditions) {
        EXPECT_FALSE(c.asymptotic.eliminated) << k << ": " << p.case_name << " " << c.about;
        if (k <= 7) {
          EXPECT_FALSE(c.exact.eliminated) << "alpha" << k << ": " << p.case_name << " " << c.about;
        } else {
          EXPECT_EQ(c.exact.eliminated.has_value(), GiNaC::expand(c.exact.numerator).nops() > max_inline_exact_terms) << p.case_name << " " << c.about;
        }
      }
    }
  }
}

}  // namespace
}  // namespace superball::symbolic
