// The library's contract: declared entries only become symbols, misuse is
// reported with standard exceptions prefixed by the function name, the
// asymptotic order is honoured, and every derivation of several patterns
// passes its own substitution check.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "superball/cases/vocabulary.hpp"
#include "superball/symbolic/derivation.hpp"

namespace superball::symbolic {
namespace {

template <class F>
std::string message_of(F&& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

bool starts_with(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

TEST(ExamApi, OnlyDeclaredEntriesAreSymbols) {
  const Symbols s(Pattern::paper({2}), Obstacle::Infinite);
  int masses = 0, diagonal = 0, couplings = 0;
  for (const SymbolInfo& i : s.all()) {
    masses += i.kind == SymbolKind::Mass;
    diagonal += i.kind == SymbolKind::Diagonal;
    couplings += i.kind == SymbolKind::Coupling;
  }
  EXPECT_EQ(masses, 3);  // m4 = ∞ has no symbol
  EXPECT_EQ(diagonal, 6);
  EXPECT_EQ(couplings, 1);
  EXPECT_TRUE(s.entry(Pair{1, 2}, Pair{1, 3}).is_zero());  // α₁ absent: exactly 0
  EXPECT_TRUE(s.mass(1).info(GiNaC::info_flags::positive));
  EXPECT_FALSE(s.by_name("alpha2").info(GiNaC::info_flags::positive));
  const Symbols f(Pattern::paper({2}), Obstacle::Finite);
  EXPECT_NO_THROW(f.mass(4));
}

TEST(ExamApi, ErrorsNameTheFunction) {
  EXPECT_TRUE(starts_with(message_of([] { Pattern::paper({8}); }), "Pattern::paper(): "));
  EXPECT_TRUE(starts_with(message_of([] { Pattern::parse_pairs("1-9", 4); }), "Pattern::parse_pairs(): "));
  EXPECT_TRUE(starts_with(message_of([] { Pattern::parse_couplings("1-2", 4); }), "Pattern::parse_couplings(): "));
  const Symbols s(Pattern::paper({2}), Obstacle::Infinite);
  EXPECT_TRUE(starts_with(message_of([&] { s.mass(4); }), "Symbols::mass(): "));
  EXPECT_TRUE(starts_with(message_of([&] { Scaling::parse("m9=1", s); }), "Scaling::parse(): "));
  EXPECT_TRUE(starts_with(message_of([&] { Scaling::parse("m1=x", s); }), "Scaling::parse(): "));
  const Deriver d(Pattern::paper({2}), Obstacle::Infinite);
  EXPECT_TRUE(starts_with(message_of([&] { d.derive(ContactSet(5)); }), "Deriver::derive(): "));
  EXPECT_TRUE(starts_with(message_of([] { Deriver(Pattern::paper({2}), Obstacle::Infinite, std::nullopt, -1); }), "Deriver::Deriver(): "));
}

// The body count is what the determinants take (issue 25: --bodies allowed 64
// and the derivation then failed with "n <= 20"): 20 bodies moving apart at
// most, 21 with the fixed obstacle, and a case of 21 bodies derives.
TEST(ExamApi, BodyCountIsWhatTheDeterminantsTake) {
  EXPECT_EQ(max_bodies(Obstacle::Infinite), max_moving_clusters + 1);
  EXPECT_EQ(max_bodies(Obstacle::Finite), max_moving_clusters);
  EXPECT_NO_THROW(check_bodies(2, Obstacle::Finite));
  EXPECT_NO_THROW(check_bodies(21, Obstacle::Infinite));
  EXPECT_NO_THROW(check_bodies(20, Obstacle::Finite));
  for (const auto& [n, obstacle] : {std::pair{1, Obstacle::Infinite}, {22, Obstacle::Infinite}, {21, Obstacle::Finite}, {64, Obstacle::Infinite}})
    EXPECT_EQ(message_of([n = n, obstacle = obstacle] { check_bodies(n, obstacle); }),
              "check_bodies(): n = " + std::to_string(n) +
                  ": the symbolic derivation takes 2 to 21 bodies with a fixed obstacle, 2 to 20 with a finite one (at most 20 bodies moving "
                  "apart: determinants of up to 20 x 20)");
  EXPECT_TRUE(starts_with(message_of([] { Deriver(Pattern::near(22, 1), Obstacle::Infinite); }), "check_bodies(): n = 22: "));
  EXPECT_TRUE(starts_with(message_of([] { Deriver(Pattern::near(21, 1), Obstacle::Finite); }), "check_bodies(): n = 21: "));
  // 21 bodies, contacts 3-4 … 20-21 closed: two bodies move apart.
  const Deriver d(Pattern::near(21, 1), Obstacle::Infinite);
  ContactSet closed(21);
  for (int c = 2; c < 20; ++c) closed.set_closed(c, true);
  EXPECT_EQ(d.derive(closed).velocities.size(), 21u);
}

// One entry under two spellings is declared twice, and the message names it
// (issue 25); a name --scaling does not know is refused without a stray prefix.
TEST(ExamApi, OneEntryDeclaredTwiceIsNamed) {
  Pattern p;
  p.bodies = 4;
  p.diagonal = Pattern::parse_pairs("1-2,01-2", 4);
  EXPECT_EQ(message_of([&] { p.check(); }), "Pattern::check(): the diagonal entry K 1-2 is declared twice");
  p.diagonal = Pattern::parse_pairs("1-2,1-4", 4);
  p.couplings = Pattern::parse_couplings("1-2/1-4,1-4/01-2", 4);
  EXPECT_EQ(message_of([&] { p.check(); }), "Pattern::check(): the coupling 1-2/1-4 is declared twice (the order of its pairs does not matter)");
  const Symbols s(Pattern::paper({2}), Obstacle::Infinite);
  EXPECT_TRUE(starts_with(message_of([&] { Scaling::parse("c_14_12=1", s); }), "Scaling::parse(): no parameter 'c_14_12' in this pattern"));
}

TEST(ExamApi, OrderOneKeepsTheNextCorrection) {
  const Deriver d(Pattern::paper({2}), Obstacle::Infinite, std::nullopt, 1);
  const Derivation r = d.derive(Vocabulary::paper().named_case("1").closed);
  GiNaC::parser reader(d.symbols().table(), true);
  EXPECT_TRUE(same_condition(r.conditions.front().asymptotic.numerator, reader("-alpha2-2*m1-K12-K13"), d.symbols()));
  EXPECT_EQ(r.conditions.front().orders_kept, 2);
}

TEST(ExamApi, CustomScaling) {
  const Symbols s(Pattern::paper({2}), Obstacle::Infinite);
  const Scaling sc = Scaling::parse("m1=1,K14=-1,alpha2=-1", s);
  const Deriver d(Pattern::paper({2}), Obstacle::Infinite, sc);
  const Derivation r = d.derive(Vocabulary::paper().named_case("1").closed);
  // With α₂ ~ K₁₄ ~ 1/ε the superball condition −α₂ − 2m₁ − K₁₂ − K₁₃ > 0 reduces to −α₂ > 0 at order ε^-1.
  EXPECT_EQ(r.conditions.front().leading_order, -1);
  EXPECT_TRUE(same_condition(r.conditions.front().asymptotic.numerator, GiNaC::parser(d.symbols().table(), true)("-alpha2"), d.symbols()));
}

TEST(ExamApi, EveryCaseOfSeveralPatternsPassesItsCheck) {
  std::vector<std::pair<Pattern, Obstacle>> patterns = {
      {Pattern::paper({}), Obstacle::Infinite},          {Pattern::paper({1, 2, 3, 4, 5, 6, 7}), Obstacle::Infinite},
      {Pattern::paper({4}), Obstacle::Finite},           {Pattern::all_pairs(2), Obstacle::Infinite},
      {Pattern::all_pairs(3), Obstacle::Finite},         {Pattern::near(5, 1), Obstacle::Infinite},
      {Pattern::nearest_and_next_nearest(5), Obstacle::Infinite},
  };
  for (const auto& [p, o] : patterns) {
    SCOPED_TRACE(p.describe());
    const Deriver d(p, o);
    const auto all = d.derive_all();
    EXPECT_EQ(all.size(), std::size_t{1} << (p.bodies - 1));
    for (const Derivation& r : all) {
      EXPECT_FALSE(r.check.empty());
      EXPECT_FALSE(r.determinant.is_zero());
      for (const Condition& c : r.conditions) EXPECT_TRUE(c.exact.sign_proved()) << r.case_name << " " << c.about << ": " << c.proof;
    }
  }
}

}  // namespace
}  // namespace superball::symbolic
