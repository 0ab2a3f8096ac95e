// `superball reproduce` as a user runs it: a quick report (fewer audit
// points) is complete (every section, every figure it references, no
// temporary file left), its section on the printed conditions is the audit
// of `superball audit` at the same settings, and report.tex compiles with a
// real LaTeX (Debian's texlive-latex-base; skipped without pdflatex).  A bad
// --out is one line, exit 2, and leaves nothing behind.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "support/run.hpp"

namespace {

namespace fs = std::filesystem;
using superball::test::describe;
using superball::test::expect_bad_input;
using superball::test::run;
using superball::test::RunResult;
using superball::test::slurp;

/// Audit points per search in the quick report (the default, 20000, is the full report).
const std::string kSamples = "300";

bool have(const char* program) { return std::system((std::string("command -v ") + program + " >/dev/null 2>&1").c_str()) == 0; }

/// A fresh empty folder, removed with everything in it at the end of the test.
class TempFolder {
 public:
  TempFolder() {
    std::string tmpl = ::testing::TempDir() + "superball-reproduce-XXXXXX";
    if (::mkdtemp(tmpl.data())) path_ = tmpl;
  }
  ~TempFolder() {
    if (path_.empty()) return;
    std::error_code ec;
    fs::permissions(path_, fs::perms::owner_all, fs::perm_options::add, ec);
    fs::remove_all(path_, ec);
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

std::vector<std::string> files_in(const std::string& folder) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(folder)) names.push_back(e.path().filename().string());
  return names;
}

TEST(Reproduce, QuickReportIsCompleteAndCompiles) {
  const TempFolder tmp;
  ASSERT_FALSE(tmp.path().empty());
  const std::string out = tmp.path() + "/report";
  const RunResult r = run({"reproduce", "--out", out, "--samples", kSamples, "--verify-samples", "100", "--explore-starts", "2"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_TRUE(r.err.empty()) << r.err;

  // Only the report, the figures and their data and scripts: no temporary file left.
  const std::set<std::string> kinds = {".md", ".tex", ".png", ".svg", ".dat", ".gp"};
  for (const std::string& name : files_in(out)) {
    EXPECT_EQ(name.find(".tmp"), std::string::npos) << name;
    EXPECT_TRUE(kinds.count(fs::path(name).extension().string())) << name;
  }

  const std::string md = slurp(out + "/report.md"), tex = slurp(out + "/report.tex");
  EXPECT_NE(r.out.find(md), std::string::npos) << "stdout shows the report";
  for (const char* heading :
       {"\n## Eq. (16): velocities after the collision", "\n## Fig. 5: U1+ against alpha_2 and against alpha_5",
        "\n## Fig. 7: where the evolution case changes along K34", "\n## Maps: the cases and the superball in a plane of two parameters",
        "\n## The epsilon family of §4.1", "\n## The §4.4 stack dropped with gaps, against the simultaneous collision",
        "\n## The printed conditions of §4.1–§4.3 against the derivation", "\n### §4.1, case 1, coupling α₂",
        "\n### §4.2, case 2.1, coupling α₁, α₆", "\n### §4.3, case 3.2, coupling α₅", "\n### The claims in words",
        "\n## The derived conditions against exact solutions, and the alpha-patterns", "\n### Case 1, coupling alpha_2",
        "\n### Case 2.1, coupling alpha_1, alpha_6", "\n### Case 3.2, coupling alpha_5", "\n### Case 3.3, coupling alpha_4",
        "\n### Which coupling gives the superball in which case"})
    EXPECT_NE(md.find(heading), std::string::npos) << heading;

  // The verification runs: the exact conditions of each of the paper's four cases agree with the exact
  // solution at every point; the pattern table has a row per pattern of `superball explore --all-patterns`.
  std::size_t agree = 0;
  for (std::size_t at = md.find("The exact conditions agree with the exact solution at every point"); at != std::string::npos;
       at = md.find("The exact conditions agree with the exact solution at every point", at + 1))
    ++agree;
  EXPECT_EQ(agree, 4u);
  EXPECT_EQ(md.find("DISAGREE"), std::string::npos);
  for (const char* row : {"\n| α₁ |", "\n| α₂ |", "\n| α₃ |", "\n| α₄ |", "\n| α₅ |", "\n| α₆ |", "\n| α₇ |", "\n| α₁, α₆ |"})
    EXPECT_NE(md.find(row), std::string::npos) << row;

  // Every figure referenced exists, in both reports.
  int figures = 0;
  const std::regex png(R"(\\includegraphics\[[^\]]*\]\{([^}]+)\})"), svg(R"(!\[[^\]]*\]\(([^)]+)\))");
  for (std::sregex_iterator it(tex.begin(), tex.end(), png), end; it != end; ++it, ++figures)
    EXPECT_TRUE(fs::is_regular_file(out + "/" + (*it)[1].str())) << (*it)[1];
  for (std::sregex_iterator it(md.begin(), md.end(), svg), end; it != end; ++it)
    EXPECT_TRUE(fs::is_regular_file(out + "/" + (*it)[1].str())) << (*it)[1];
  EXPECT_EQ(figures, 7);
  // The drop: the gapped stack's limit is not the simultaneous collision (case 3.3).
  EXPECT_NE(md.find("but not to the simultaneous collision: at 1 nm ball 1 leaves at 1.787 a after 3 binary collisions, against 1.005 a in the paper's case 3.3"), std::string::npos);

  // The two maps: every exact boundary point lies on a zero of a derived condition.
  std::size_t overlaid = 0;
  for (std::size_t at = md.find("derived zero: yes"); at != std::string::npos; at = md.find("derived zero: yes", at + 1)) ++overlaid;
  EXPECT_EQ(overlaid, 2u);

  // The section on the printed conditions is the audit at the same settings:
  // every derived condition, verdict and disagreeing point of `superball audit`.
  const RunResult a = run({"audit", "--samples", kSamples, "--json"});
  ASSERT_EQ(a.exit_code, 0) << describe(a);
  const nlohmann::json audit = nlohmann::json::parse(a.out);
  ASSERT_EQ(audit.at("conditions").size(), 14u);
  for (const auto& c : audit.at("conditions")) {
    const std::string verdict = c.at("verdict");
    EXPECT_NE(md.find("| " + c.at("derived_exact").get<std::string>() + " |"), std::string::npos) << c.at("derived_exact");
    EXPECT_NE(tex.find("& $" + c.at("derived_exact_latex").get<std::string>() + "$ &"), std::string::npos) << c.at("derived_exact_latex");
    EXPECT_NE(md.find(verdict == "different" ? "**different**" : verdict), std::string::npos) << verdict;
    if (c.contains("witness")) {
      EXPECT_NE(md.find(c.at("witness").at("quantity").get<std::string>() + ": the condition "), std::string::npos) << c;
    }
  }
  for (const auto& c : audit.at("claims")) {
    EXPECT_NE(md.find(c.at("verdict").get<std::string>() + " (" + std::to_string(c.at("tried").get<int>()) + " points tried"), std::string::npos) << c;
    EXPECT_NE(md.find("| " + c.at("derived_superball").get<std::string>() + " |"), std::string::npos) << c;
    EXPECT_NE(tex.find("& $" + c.at("derived_superball_latex").get<std::string>() + "$ &"), std::string::npos) << c;
  }
  // The derived formulas are typeset as LaTeX math, not as Unicode text.
  EXPECT_NE(tex.find("$-\\alpha_{2} > 2m_{1} + K_{12} + K_{13}$"), std::string::npos);
  EXPECT_EQ(tex.find("α"), std::string::npos);
  EXPECT_EQ(tex.find("₁"), std::string::npos);

  if (!have("pdflatex")) GTEST_SKIP() << "no pdflatex (install texlive-latex-base)";
  const std::string latex = "cd '" + out + "' && pdflatex -interaction=nonstopmode -halt-on-error report.tex >/dev/null 2>&1";
  const int status = std::system((latex + " && " + latex.substr(latex.find("pdflatex"))).c_str());  // twice: longtable widths
  const std::string log = slurp(out + "/report.log");
  ASSERT_EQ(status, 0) << log.substr(log.size() > 3000 ? log.size() - 3000 : 0);
  const std::string pdf = slurp(out + "/report.pdf");
  EXPECT_EQ(pdf.rfind("%PDF", 0), 0u);
  EXPECT_EQ(log.find("Overfull \\hbox"), std::string::npos) << "a line or table wider than the page";
}

TEST(Reproduce, OutThatCannotBeCreatedIsOneLineExitThreeAndNothingWritten) {
  const TempFolder tmp;
  ASSERT_FALSE(tmp.path().empty());
  const std::string file = tmp.path() + "/a-file";
  std::ofstream(file) << "not a folder\n";
  expect_output_error(run({"reproduce", "--out", file, "--samples", kSamples}), {"--out " + file, "not a folder"});
  expect_output_error(run({"reproduce", "--out", file + "/report", "--samples", kSamples}), {"--out " + file + "/report", "cannot create"});
  expect_output_error(run({"reproduce", "--out", tmp.path() + "/missing/report", "--samples", kSamples}), {"cannot create"});
  EXPECT_EQ(slurp(file), "not a folder\n");
  EXPECT_EQ(files_in(tmp.path()), std::vector<std::string>{"a-file"});
}

TEST(Reproduce, ReadOnlyOutIsOneLineExitThreeAndNothingWritten) {
  if (::geteuid() == 0) GTEST_SKIP() << "running as root: a read-only folder is still writable";
  const TempFolder tmp;
  ASSERT_FALSE(tmp.path().empty());
  const std::string locked = tmp.path() + "/locked";
  ASSERT_EQ(::mkdir(locked.c_str(), 0555), 0);
  expect_output_error(run({"reproduce", "--out", locked, "--samples", kSamples}), {"--out " + locked, "cannot write"});
  expect_output_error(run({"reproduce", "--out", locked + "/report", "--samples", kSamples}), {"cannot create"});
  EXPECT_TRUE(files_in(locked).empty());
}

TEST(Reproduce, BadCountsAreRefusedByTheLibraryBeforeAnythingIsWritten) {
  // ReproduceOptions::check() (verify/reproduce.hpp) says what a bad count is; the command adds no rule.
  const TempFolder tmp;
  ASSERT_FALSE(tmp.path().empty());
  const std::string out = tmp.path() + "/report";
  expect_bad_input(run({"reproduce", "--out", out, "--samples", "0"}), {"samples must be a whole number from 1 to 10000000, got 0"});
  expect_bad_input(run({"reproduce", "--out", out, "--verify-samples", "100000001"}),
                   {"verify_samples must be a whole number from 1 to 100000000, got 100000001"});
  expect_bad_input(run({"reproduce", "--out", out, "--explore-starts", "-1"}), {"explore_starts must be a whole number from 1 to 100000, got -1"});
  expect_bad_input(run({"reproduce", "--out", out, "--threads", "2000"}), {"threads must be a whole number from 0 (all cores) to 1024, got 2000"});
  EXPECT_TRUE(files_in(tmp.path()).empty());
}

}  // namespace
