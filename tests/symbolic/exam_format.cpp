// Printed forms: the paper's case-1 conditions as a person writes them (text,
// term order as printed by the tool), LaTeX relations written by hand, the
// ASCII names of the JSON output, and no change of any stream's state.  The
// reports that hold these forms are tested in tests/present/.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "superball/cases/vocabulary.hpp"
#include "superball/symbolic/format.hpp"

namespace superball::symbolic {
namespace {

Derivation case1(const Deriver& d) { return d.derive(Vocabulary::paper().named_case("1").closed); }

bool contains(const std::string& haystack, const std::string& needle) { return haystack.find(needle) != std::string::npos; }

TEST(ExamFormat, SidesRule) {
  const Deriver deriver(Pattern::paper({2}), Obstacle::Infinite);
  const Symbols& s = deriver.symbols();
  GiNaC::parser reader(s.table(), true);
  // No positive term: the couplings stay on the left with their sign.
  EXPECT_EQ(format_condition(reader("-alpha2-2*m1-K12-K13"), Relation::Greater, s, Style::Text), "−α₂ > 2m₁ + K₁₂ + K₁₃");
  // The shorter side first, the relation turned.
  EXPECT_EQ(format_condition(reader("K14+alpha2-m1"), Relation::Greater, s, Style::Text), "m₁ < K₁₄ + α₂");
  EXPECT_EQ(format_condition(reader("m2+m3-K12-K13-K24-K34"), Relation::GreaterEqual, s, Style::Text), "m₂ + m₃ ≥ K₁₂ + K₁₃ + K₂₄ + K₃₄");
  // Equal sides: the couplings first.
  EXPECT_EQ(format_condition(reader("K12*K14-alpha2^2"), Relation::GreaterEqual, s, Style::Text), "α₂² ≤ K₁₂K₁₄");
  // No negative term, no term at all.
  EXPECT_EQ(format_condition(reader("K12"), Relation::Greater, s, Style::Text), "K₁₂ > 0");
  EXPECT_EQ(format_condition(reader("-m1"), Relation::Greater, s, Style::Text), "0 > m₁");
  // Rational coefficients.
  EXPECT_EQ(format_condition(reader("m1/2-K12"), Relation::Greater, s, Style::Text), "(1/2)m₁ > K₁₂");
}

TEST(ExamFormat, Latex) {
  const Deriver deriver(Pattern::paper({2}), Obstacle::Infinite);
  const Symbols& s = deriver.symbols();
  GiNaC::parser reader(s.table(), true);
  EXPECT_EQ(format_condition(reader("-alpha2-2*m1-K12-K13"), Relation::Greater, s, Style::Latex), "-\\alpha_{2} > 2m_{1} + K_{12} + K_{13}");
  EXPECT_EQ(format_condition(reader("m2+m3-K12-K13-K24-K34"), Relation::GreaterEqual, s, Style::Latex),
            "m_{2} + m_{3} \\ge K_{12} + K_{13} + K_{24} + K_{34}");
  EXPECT_EQ(format_condition(reader("K12*K14-alpha2^2"), Relation::GreaterEqual, s, Style::Latex), "\\alpha_{2}^{2} \\le K_{12} K_{14}");
  const Derivation d = case1(deriver);
  EXPECT_EQ(format_fraction(d.velocities[0], s, Style::Latex),
            "\\frac{a\\left(K_{14} + \\alpha_{2} - m_{1}\\right)}{m_{1} + K_{12} + K_{13} + K_{14} + 2\\alpha_{2}}");
}

TEST(ExamFormat, AsciiNamesAndLocalStreams) {
  const Deriver deriver(Pattern::paper({2}), Obstacle::Infinite);
  const Symbols& s = deriver.symbols();
  const Derivation d = case1(deriver);
  const std::string ascii = format_fraction(d.velocities[0], s, Style::Ascii);
  for (const char* name : {"a", "K14", "alpha2", "m1", "K12", "K13"}) EXPECT_TRUE(contains(ascii, name)) << ascii;
  EXPECT_FALSE(contains(ascii, "\\")) << ascii;
  // Printing LaTeX must not leave std::cout (or any stream) in LaTeX mode.
  std::string tex;
  for (const Condition& c : d.conditions) tex += format_form(c.exact, c.relation, s, Style::Latex);
  EXPECT_TRUE(contains(tex, "\\alpha_{2}"));
  std::ostringstream os;
  os << s.by_name("alpha2");
  EXPECT_EQ(os.str(), "alpha2");
  // General couplings and two-digit bodies.
  Pattern p = Pattern::all_pairs(10, {{Pair{1, 2}, Pair{1, 10}}});
  const Symbols big(p, Obstacle::Infinite);
  EXPECT_EQ(big.info(big.coupling(Pair{1, 2}, Pair{1, 10})).ascii, "c_12_1_10");
  EXPECT_EQ(big.info(big.diagonal(Pair{1, 10})).ascii, "K1_10");
  EXPECT_EQ(big.info(big.diagonal(Pair{1, 10})).latex, "K_{1,10}");
  EXPECT_EQ(big.info(big.diagonal(Pair{2, 3})).text, "K₂₃");
}

TEST(ExamFormat, NamesAndCommonFactor) {
  EXPECT_EQ(mass_name(4, Style::Text), "m₄");
  EXPECT_EQ(mass_name(12, Style::Latex), "m_{12}");
  EXPECT_EQ(mass_name(4, Style::Ascii), "m4");
  EXPECT_EQ(epsilon_power(GiNaC::numeric(-1), Style::Text), "ε^-1");
  EXPECT_EQ(epsilon_power(GiNaC::numeric(1, 2), Style::Latex), "\\varepsilon^{1/2}");
  EXPECT_EQ(epsilon_power(GiNaC::numeric(2), Style::Ascii), "eps^2");
  const Deriver deriver(Pattern::paper({2}), Obstacle::Infinite);
  const Symbols& s = deriver.symbols();
  GiNaC::parser reader(s.table(), true);
  const CommonFactor f = format_common_factor(reader("-2*m1*K12-2*m1*a"), s, Style::Text);
  EXPECT_TRUE(f.negative);
  EXPECT_EQ(f.factor, "2m₁");
  EXPECT_EQ(f.rest, "K₁₂ + a");
  EXPECT_FALSE(f.rest_is_one);
  const CommonFactor g = format_common_factor(reader("3*K12*K14"), s, Style::Latex);
  EXPECT_FALSE(g.negative);
  EXPECT_EQ(g.factor, "1");  // a single term is its own rest
  EXPECT_EQ(g.rest, "3K_{12} K_{14}");
}

}  // namespace
}  // namespace superball::symbolic
