// The LaTeX output compiles with a real LaTeX (Debian's texlive-latex-base):
// the paper's case 1 with α₂, and all eight cases with the seven α's (long
// polynomials that must break across lines).
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <string>

#include "superball/cases/vocabulary.hpp"
#include "superball/symbolic/format.hpp"

namespace superball::symbolic {
namespace {

bool have(const char* program) { return std::system((std::string("command -v ") + program + " >/dev/null 2>&1").c_str()) == 0; }

/// Run latex on \p document in a fresh folder; returns the exit status and keeps the log on failure.
int compile(const std::string& document, const std::string& name, std::string& log) {
  char tmpl[] = "/tmp/superball-latex-XXXXXX";
  const char* dir = ::mkdtemp(tmpl);
  if (!dir) return -1;
  const std::string folder = dir;
  std::ofstream(folder + "/" + name + ".tex") << document;
  const std::string cmd = "cd '" + folder + "' && latex -interaction=nonstopmode -halt-on-error " + name + ".tex >/dev/null 2>&1";
  const int status = std::system(cmd.c_str());
  std::ifstream in(folder + "/" + name + ".log");
  log.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  std::system(("rm -rf '" + folder + "'").c_str());
  return status;
}

TEST(Latex, Case1Alpha2Compiles) {
  if (!have("latex")) GTEST_SKIP() << "no latex binary (install texlive-latex-base)";
  const Deriver deriver(Pattern::paper({2}), Obstacle::Infinite);
  const std::string doc = latex_document({deriver.derive(Vocabulary::paper().named_case("1").closed)}, deriver);
  EXPECT_NE(doc.find("-\\alpha_{2} > 2m_{1} + K_{12} + K_{13}"), std::string::npos);
  EXPECT_NE(doc.find("\\le"), std::string::npos);
  std::string log;
  EXPECT_EQ(compile(doc, "case1", log), 0) << log.substr(log.size() > 3000 ? log.size() - 3000 : 0);
}

TEST(Latex, AllCasesAllAlphasFiniteObstacleCompiles) {
  if (!have("latex")) GTEST_SKIP() << "no latex binary (install texlive-latex-base)";
  const Deriver deriver(Pattern::paper({1, 2, 3, 4, 5, 6, 7}), Obstacle::Finite);
  std::string log;
  EXPECT_EQ(compile(latex_document(deriver.derive_all(), deriver), "all", log), 0) << log.substr(log.size() > 3000 ? log.size() - 3000 : 0);
}

TEST(Latex, GeneralCouplingsCompile) {
  if (!have("latex")) GTEST_SKIP() << "no latex binary (install texlive-latex-base)";
  const Deriver deriver(Pattern::nearest_and_next_nearest(5), Obstacle::Infinite);
  std::string log;
  EXPECT_EQ(compile(latex_document({deriver.derive(ContactSet::parse("2-3", 5))}, deriver), "general", log), 0)
      << log.substr(log.size() > 3000 ? log.size() - 3000 : 0);
}

}  // namespace
}  // namespace superball::symbolic
