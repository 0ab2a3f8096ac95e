// The reports of a derivation (present/derivation.hpp) called directly:
// known answers on the paper's case 1 and case 2.1 of α₂ (paper §4.1) in
// text, LaTeX and JSON, and their structure: every condition of the case in
// each form, the JSON's keys, the LaTeX's braces and $…$ balanced.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "superball/cases/vocabulary.hpp"
#include "superball/present/derivation.hpp"
#include "superball/symbolic/format.hpp"

namespace superball::present {
namespace {

using namespace superball::symbolic;

Derivation named(const Deriver& d, const char* name) { return d.derive(Vocabulary::paper().named_case(name).closed); }

bool contains(const std::string& haystack, const std::string& needle) { return haystack.find(needle) != std::string::npos; }

/// Whether every { has its }, outside escapes (\{ \}), never closing below zero.
bool braces_balanced(const std::string& tex) {
  int depth = 0;
  for (std::size_t k = 0; k < tex.size(); ++k) {
    if (tex[k] == '\\') {
      ++k;
      continue;
    }
    if (tex[k] == '{') ++depth;
    if (tex[k] == '}' && --depth < 0) return false;
  }
  return depth == 0;
}

/// The number of unescaped $ in \p tex.
int dollars(const std::string& tex) {
  int n = 0;
  for (std::size_t k = 0; k < tex.size(); ++k) {
    if (tex[k] == '\\') {
      ++k;
      continue;
    }
    n += tex[k] == '$';
  }
  return n;
}

/// \p tex without its math: what lies outside $…$ and align* displays.
std::string outside_math(const std::string& tex) {
  static const std::string begin = "\\begin{align*}", end = "\\end{align*}";
  std::string out;
  bool math = false, display = false;
  for (std::size_t k = 0; k < tex.size(); ++k) {
    if (!math && tex.compare(k, begin.size(), begin) == 0) display = true;
    if (display && tex.compare(k, end.size(), end) == 0) {
      display = false;
      k += end.size() - 1;
      continue;
    }
    if (tex[k] == '\\' && k + 1 < tex.size() && tex[k + 1] == '$') {
      if (!math && !display) out += "\\$";
      ++k;
      continue;
    }
    if (!display && tex[k] == '$') {
      math = !math;
      continue;
    }
    if (!math && !display) out += tex[k];
  }
  return out;
}

TEST(DerivationReport, Case1TextAsInThePaper) {
  const Deriver deriver(Pattern::paper({2}), Obstacle::Infinite);
  const std::string text = report(named(deriver, "1"), deriver, Style::Text);
  EXPECT_TRUE(contains(text, "U₁⁺ = a(K₁₄ + α₂ − m₁)/(m₁ + K₁₂ + K₁₃ + K₁₄ + 2α₂)")) << text;
  EXPECT_TRUE(contains(text, "−α₂ > 2m₁ + K₁₂ + K₁₃")) << text;
  EXPECT_TRUE(contains(text, "m₁ < K₁₄ + α₂")) << text;
  EXPECT_TRUE(contains(text, "m₂ + m₃ ≥ K₁₂ + K₁₃ + K₂₄ + K₃₄")) << text;
  EXPECT_TRUE(contains(text, "α₂² ≤ K₁₂K₁₄")) << text;
  EXPECT_TRUE(contains(text, "obstacle: fixed (m₄ = ∞, it stays at rest)")) << text;
}

TEST(DerivationReport, Case21EveryConditionInTextAndLatex) {
  const Deriver deriver(Pattern::paper({2}), Obstacle::Infinite);
  const Derivation d = named(deriver, "2.1");
  const std::string text = report(d, deriver, Style::Text), tex = report(d, deriver, Style::Latex);
  EXPECT_EQ(text.rfind("case 2.1", 0), 0u) << text;
  EXPECT_TRUE(contains(tex, "\\subsection*{case 2.1")) << tex;
  for (const Condition& c : d.conditions) {
    EXPECT_TRUE(contains(text, condition_title(c, Style::Text))) << condition_title(c, Style::Text);
    EXPECT_TRUE(contains(text, format_form(c.exact, c.relation, *d.symbols, Style::Text))) << condition_title(c, Style::Text);
    EXPECT_TRUE(contains(tex, condition_title(c, Style::Latex))) << condition_title(c, Style::Latex);
  }
  // Two closed contacts of case 2.1 ({1-2, 3-4}): one reaction each, in both styles; none on the open 2-3.
  for (const Pair& p : {Pair{1, 2}, Pair{3, 4}}) {
    EXPECT_TRUE(contains(text, reaction_name(p, Style::Text) + " = ")) << text;
    EXPECT_TRUE(contains(tex, reaction_name(p, Style::Latex))) << tex;
  }
  EXPECT_FALSE(contains(text, reaction_name(Pair{2, 3}, Style::Text) + " = "));
  // Without the conditions on M: none of the PSD titles.
  const std::string short_text = report(d, deriver, Style::Text, false);
  EXPECT_FALSE(contains(short_text, "M positive semi-definite, minor on"));
  EXPECT_TRUE(contains(text, "M positive semi-definite, minor on"));
  EXPECT_TRUE(contains(report_psd(deriver, Style::Text), "M positive semi-definite, minor on"));
}

TEST(DerivationReport, LatexBalancedAndInMathMode) {
  const Deriver deriver(Pattern::paper({2}), Obstacle::Infinite);
  const Derivation d = named(deriver, "2.1");
  const std::string tex = report(d, deriver, Style::Latex);
  EXPECT_TRUE(braces_balanced(tex));
  EXPECT_EQ(dollars(tex) % 2, 0);
  // Every symbol and relation of the formulas sits in math mode: outside it, no _ ^ \le \frac \alpha.
  const std::string outside = outside_math(tex);
  EXPECT_TRUE(contains(outside, "\\subsection*{case 2.1"));
  for (const char* math_only : {"_{", "^{", "\\le", "\\frac", "\\alpha", ">"})
    EXPECT_FALSE(contains(outside, math_only)) << math_only << " outside math:\n" << outside;
  const std::string doc = latex_document({d}, deriver);
  EXPECT_EQ(doc.rfind("\\documentclass", 0), 0u);
  EXPECT_TRUE(contains(doc, "\\end{document}\n"));
  EXPECT_TRUE(braces_balanced(doc));
  EXPECT_TRUE(contains(doc, tex));  // one case: the report with its conditions on M
}

TEST(DerivationReport, AsciiIsJson) {
  const Deriver deriver(Pattern::paper({2}), Obstacle::Infinite);
  EXPECT_THROW(report(named(deriver, "1"), deriver, Style::Ascii), std::invalid_argument);
  EXPECT_THROW(report_psd(deriver, Style::Ascii), std::invalid_argument);
}

TEST(DerivationJson, Case21KeysAndEveryCondition) {
  const Deriver deriver(Pattern::paper({2}), Obstacle::Infinite);
  const Derivation d = named(deriver, "2.1");
  std::vector<nlohmann::ordered_json> psd;
  const nlohmann::ordered_json j = derivation_json(d, deriver, psd, /*expanded=*/false);
  for (const char* key : {"case", "closed_contacts", "pattern", "obstacle", "scaling", "symbols", "velocities_after", "reactions", "determinant", "check",
                          "named", "actual", "conditions"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["case"], "2.1");
  EXPECT_EQ(j["obstacle"], "infinite");
  EXPECT_EQ(j["velocities_after"].size(), 4u);
  EXPECT_EQ(j["reactions"].size(), 2u);
  EXPECT_TRUE(j["reactions"].contains("1-2"));
  EXPECT_TRUE(j["reactions"].contains("3-4"));
  EXPECT_EQ(j["velocities_after"]["U1"], format_fraction(d.velocities[0], *d.symbols, Style::Ascii));
  // Every condition of the case (those on M from the deriver, once), with its forms in the three notations.
  EXPECT_EQ(j["conditions"].size(), d.conditions.size());
  std::set<std::string> seen;
  for (const auto& c : j["conditions"]) {
    for (const char* key : {"kind", "about", "exact", "asymptotic", "text", "latex", "order", "verdict", "asymptotic_verdict", "proof"})
      EXPECT_TRUE(c.contains(key)) << key;
    EXPECT_TRUE(braces_balanced(c["latex"].get<std::string>()));
    seen.insert(c["kind"].get<std::string>() + " " + c["about"].get<std::string>());
  }
  for (const Condition& c : d.conditions) EXPECT_EQ(seen.count(std::string(to_string(c.kind)) + " " + c.about), 1u) << c.about;
  const auto superball = std::find_if(d.conditions.begin(), d.conditions.end(), [](const Condition& c) { return c.kind == ConditionKind::Superball; });
  ASSERT_NE(superball, d.conditions.end());
  EXPECT_EQ(j["conditions"][0]["exact"], format_condition(superball->exact, superball->relation, *d.symbols, Style::Ascii));
  // The conditions on M are made once and reused by the next case.
  ASSERT_FALSE(psd.empty());
  const nlohmann::ordered_json again = derivation_json(named(deriver, "1"), deriver, psd, /*expanded=*/false);
  EXPECT_EQ(again["conditions"].back(), psd.back());
}

}  // namespace
}  // namespace superball::present

namespace superball::present {
namespace {

/// Every case of \p deriver derived with every form and with the forms a
/// compact report prints: the same compact JSON, text and LaTeX, byte for
/// byte.  Returns the velocities and reactions left unbuilt.
int same_compact_reports(const Deriver& deriver) {
  const int n = deriver.symbols().bodies();
  int unbuilt = 0;
  for (std::uint64_t mask = 0; mask < (std::uint64_t{1} << (n - 1)); ++mask) {
    const ContactSet c = ContactSet::from_mask(mask, n);
    const Derivation all = deriver.derive(c, std::string(), Forms::All), printed = deriver.derive(c, std::string(), Forms::Printed);
    std::vector<nlohmann::ordered_json> psd_all, psd_printed;
    EXPECT_EQ(derivation_json(all, deriver, psd_all, false, true).dump(2), derivation_json(printed, deriver, psd_printed, false, true).dump(2))
        << c.to_string();
    EXPECT_EQ(report(all, deriver, Style::Text), report(printed, deriver, Style::Text)) << c.to_string();
    EXPECT_EQ(report(all, deriver, Style::Latex), report(printed, deriver, Style::Latex)) << c.to_string();
    for (const std::vector<Fraction>* v : {&all.velocities, &all.reactions})
      for (const Fraction& f : *v) {
        EXPECT_EQ(f.terms, GiNaC::is_a<GiNaC::add>(f.numerator) ? f.numerator.nops() : f.numerator.is_zero() ? f.terms : 1u) << c.to_string();
        EXPECT_FALSE(f.denominator.is_zero()) << c.to_string() << ": every form is built";
      }
    for (const std::vector<Fraction>* v : {&printed.velocities, &printed.reactions})
      for (const Fraction& f : *v)
        if (f.denominator.is_zero()) {  // left unbuilt: long, and written through the case's elimination
          ++unbuilt;
          EXPECT_TRUE(printed.elimination.has_value()) << c.to_string();
          EXPECT_TRUE(through_elimination(printed, f)) << c.to_string();
        }
  }
  return unbuilt;
}

TEST(DerivationForms, PrintedGivesTheSameCompactReportsWithoutTheLongForms) {
  // 6 bodies near2 with couplings: the cases of the most free clusters have velocities of more than 100 terms.
  EXPECT_GT(same_compact_reports(Deriver(Pattern::nearest_and_next_nearest(6), Obstacle::Infinite)), 0);
  EXPECT_GT(same_compact_reports(Deriver(Pattern::nearest_and_next_nearest(5), Obstacle::Finite)), 0);
  same_compact_reports(Deriver(Pattern::paper({2}), Obstacle::Infinite));  // short forms only: nothing left out, nothing differs
}

}  // namespace
}  // namespace superball::present
