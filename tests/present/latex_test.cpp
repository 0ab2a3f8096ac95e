// The LaTeX output compiles with pdflatex (Debian's texlive-latex-base) into
// a clean document: no line wider than the text (pdflatex's "Overfull \hbox"),
// no glyph missing from a font ("Missing character"), no error, and no
// relation typeset in text mode (a text-mode > prints as ¿ in OT1 fonts, and
// the log does not say so).  The documents are the ones whose formulas once
// ran off the page: case 2.2 with α₃, case 3.3 with α₇ and a finite obstacle,
// every case with the seven α's, and case {2-3} of five bodies with the
// nearest and next-nearest pairs coupled.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "superball/cases/vocabulary.hpp"
#include "superball/present/derivation.hpp"

namespace superball::present {
namespace {

using namespace superball::symbolic;

/// An overfull box at most this much wider than the text is accepted: below
/// what a reader sees in the margin, above TeX's own \hfuzz (0.1 pt).
constexpr double kOverfullTolerancePt = 3.0;

bool have(const char* program) { return std::system((std::string("command -v ") + program + " >/dev/null 2>&1").c_str()) == 0; }

/// What pdflatex made of a document.
struct Compiled {
  int status = -1;  ///< pdflatex's exit status
  std::string log;  ///< its .log file
  /// The end of the log, for failure messages.
  std::string tail() const { return log.substr(log.size() > 3000 ? log.size() - 3000 : 0); }
};

/// Run pdflatex on \p document in a fresh folder, removed afterwards.
Compiled compile(const std::string& document, const std::string& name) {
  Compiled c;
  char tmpl[] = "/tmp/superball-latex-XXXXXX";
  const char* dir = ::mkdtemp(tmpl);
  if (!dir) return c;
  const std::string folder = dir;
  std::ofstream(folder + "/" + name + ".tex") << document;
  const std::string cmd = "cd '" + folder + "' && pdflatex -interaction=nonstopmode -halt-on-error " + name + ".tex >/dev/null 2>&1";
  c.status = std::system(cmd.c_str());
  std::ifstream in(folder + "/" + name + ".log");
  c.log.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  std::system(("rm -rf '" + folder + "'").c_str());
  return c;
}

/// What the log says is wrong with the page.
struct LogFindings {
  double widest_overfull = 0;         ///< pt, over every "Overfull \hbox (Xpt too wide)"
  int overfull = 0;                   ///< how many of them exceed kOverfullTolerancePt
  std::vector<std::string> missing;   ///< "Missing character: There is no ... in font ...!"
  std::vector<std::string> errors;    ///< lines starting with "! "
};

LogFindings read_log(const std::string& log) {
  LogFindings f;
  static const std::regex overfull(R"(Overfull \\hbox \(([0-9.]+)pt too wide\))");
  for (std::sregex_iterator it(log.begin(), log.end(), overfull), end; it != end; ++it) {
    const double w = std::stod((*it)[1].str());
    f.widest_overfull = std::max(f.widest_overfull, w);
    if (w > kOverfullTolerancePt) ++f.overfull;
  }
  std::istringstream in(log);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("Missing character", 0) == 0) f.missing.push_back(line);
    if (line.rfind("! ", 0) == 0) f.errors.push_back(line);
  }
  return f;
}

/// The places of \p document where <, > or | stand outside math ($…$, \[…\],
/// align*), with some context.
std::vector<std::string> text_mode_relations(const std::string& document) {
  std::vector<std::string> found;
  bool inline_math = false;
  int display = 0;
  for (std::size_t k = 0; k < document.size(); ++k) {
    const char c = document[k];
    if (c == '\\') {
      for (const char* open : {"\\begin{align*}", "\\["})
        if (document.compare(k, std::string(open).size(), open) == 0) ++display;
      for (const char* close : {"\\end{align*}", "\\]"})
        if (document.compare(k, std::string(close).size(), close) == 0) --display;
      ++k;  // an escaped character (\$, \{) is text
      continue;
    }
    if (c == '$') inline_math = !inline_math;
    if (!inline_math && display == 0 && (c == '<' || c == '>' || c == '|'))
      found.push_back(document.substr(k > 40 ? k - 40 : 0, 80));
  }
  return found;
}

/// Compiles \p document and expects it clean (see the file's comment).
void expect_clean(const std::string& document, const std::string& name) {
  const std::vector<std::string> relations = text_mode_relations(document);
  EXPECT_TRUE(relations.empty()) << name << ": " << relations.size() << " relations in text mode, the first: ..." << relations.front() << "...";
  const Compiled c = compile(document, name);
  ASSERT_EQ(c.status, 0) << c.tail();
  const LogFindings f = read_log(c.log);
  EXPECT_EQ(f.overfull, 0) << name << ": overfull boxes, the widest " << f.widest_overfull << " pt over the text width (tolerance "
                           << kOverfullTolerancePt << " pt)";
  EXPECT_TRUE(f.missing.empty()) << name << ": " << f.missing.front();
  EXPECT_TRUE(f.errors.empty()) << name << ": " << f.errors.front();
}

#define SKIP_WITHOUT_PDFLATEX() \
  if (!have("pdflatex")) GTEST_SKIP() << "no pdflatex binary (install texlive-latex-base)"

TEST(LatexLog, FindsWhatIsWrong) {
  SKIP_WITHOUT_PDFLATEX();
  // A rule 100 pt wider than the text, a glyph cmr10 does not have, a > in text mode.
  const std::string bad = "\\documentclass{article}\n\\begin{document}\n\\noindent\\rule{\\dimexpr\\textwidth+100pt}{1pt}\n\n"
                          "\\symbol{200} a > b, $a > b$\n\\end{document}\n";
  const Compiled c = compile(bad, "bad");
  ASSERT_EQ(c.status, 0) << c.tail();
  const LogFindings f = read_log(c.log);
  EXPECT_EQ(f.overfull, 1);
  EXPECT_NEAR(f.widest_overfull, 100, 1);
  EXPECT_EQ(f.missing.size(), 1u) << c.tail();
  EXPECT_EQ(text_mode_relations(bad).size(), 1u);
  EXPECT_TRUE(text_mode_relations("$\\alpha > 0$ and \\[ a < b \\] \\begin{align*} a &> b \\end{align*} \\$ and").empty());
}

TEST(Latex, Case1Alpha2) {
  SKIP_WITHOUT_PDFLATEX();
  const Deriver deriver(Pattern::paper({2}), Obstacle::Infinite);
  const std::string doc = latex_document({deriver.derive(Vocabulary::paper().named_case("1").closed)}, deriver);
  // Short formulas stay on their line, as the paper writes them.
  EXPECT_NE(doc.find("$-\\alpha_{2} > 2m_{1} + K_{12} + K_{13}$"), std::string::npos);
  EXPECT_NE(doc.find("U_{1}^{+} &= \\frac{a\\left(K_{14} + \\alpha_{2} - m_{1}\\right)}{m_{1} + K_{12} + K_{13} + K_{14} + 2\\alpha_{2}}"),
            std::string::npos);
  EXPECT_NE(doc.find("\\le"), std::string::npos);
  EXPECT_NE(doc.find("keeping the dominant balance only"), std::string::npos);
  EXPECT_NE(doc.find("$\\det(Z^{T}AZ) > 0$"), std::string::npos);  // in "(denominator cleared: ...)", in math mode
  expect_clean(doc, "case1");
}

TEST(Latex, Case22Alpha3) {
  SKIP_WITHOUT_PDFLATEX();
  const Deriver deriver(Pattern::paper({3}), Obstacle::Infinite);
  const std::string doc = latex_document({deriver.derive(Vocabulary::paper().named_case("2.2").closed)}, deriver);
  // The velocities' numerators were in \left( … \right) over 3,633 pt: now over \Delta, broken into rows.
  EXPECT_NE(doc.find("\\Delta &= \\det(Z^{T}AZ)"), std::string::npos);
  EXPECT_NE(doc.find("U_{1}^{+} &= \\frac{a}{\\Delta}\\bigl("), std::string::npos);
  EXPECT_NE(doc.find("&\\quad {}- "), std::string::npos);
  expect_clean(doc, "case22");
}

TEST(Latex, Case33Alpha7FiniteObstacle) {
  SKIP_WITHOUT_PDFLATEX();
  const Deriver deriver(Pattern::paper({7}), Obstacle::Finite);
  const std::string doc = latex_document({deriver.derive(Vocabulary::paper().named_case("3.3").closed)}, deriver);
  EXPECT_NE(doc.find("finite obstacle:"), std::string::npos);
  expect_clean(doc, "case33");
}

TEST(Latex, EveryCaseSevenAlphas) {
  SKIP_WITHOUT_PDFLATEX();
  const Deriver deriver(Pattern::paper({1, 2, 3, 4, 5, 6, 7}), Obstacle::Infinite);
  expect_clean(latex_document(deriver.derive_all(), deriver), "all");
}

TEST(Latex, FiveBodiesNear2Coupled) {
  SKIP_WITHOUT_PDFLATEX();
  const Deriver deriver(Pattern::nearest_and_next_nearest(5), Obstacle::Infinite);
  expect_clean(latex_document({deriver.derive(ContactSet::parse("2-3", 5))}, deriver), "near2");
}

TEST(Latex, LongDenominatorOtherThanTheDeterminantIsNamed) {
  SKIP_WITHOUT_PDFLATEX();
  // No derivation tested here has one; a velocity over a long polynomial that is not det(ZᵀAZ) is made by hand.
  const Deriver deriver(Pattern::paper({3}), Obstacle::Infinite);
  Derivation d = deriver.derive(Vocabulary::paper().named_case("2.2").closed);
  d.velocities[0].denominator = GiNaC::expand(d.determinant * d.determinant);
  const std::string doc = latex_document({d}, deriver);
  EXPECT_NE(doc.find("U_{1}^{+} &= \\frac{a}{D_{1}}\\bigl("), std::string::npos);
  EXPECT_NE(doc.find("\\intertext{where}\nD_{1} &= "), std::string::npos);
  expect_clean(doc, "named");
}

TEST(Latex, OrdersKeptInWords) {
  const Deriver deriver(Pattern::paper({2}), Obstacle::Infinite, std::nullopt, 1);
  const Derivation d = deriver.derive(Vocabulary::paper().named_case("1").closed);
  EXPECT_NE(report(d, deriver, Style::Text).find("keeping the dominant balance and the next order\n"), std::string::npos);
  EXPECT_NE(report(d, deriver, Style::Latex).find("keeping the dominant balance and the next order\\par"), std::string::npos);
  const Deriver two(Pattern::paper({2}), Obstacle::Infinite, std::nullopt, 2);
  EXPECT_NE(report(two.derive(Vocabulary::paper().named_case("1").closed), two, Style::Text).find("the dominant balance and the next 2 orders"),
            std::string::npos);
}

}  // namespace
}  // namespace superball::present
