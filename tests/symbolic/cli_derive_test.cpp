// `superball derive` and `superball audit` as a user runs them (the built
// binary): the JSON schema of the issue with expressions any CAS parses, the
// paper's case-1 formulas in the text output, the same output from run to
// run, bad input reported on one line.
#include <gtest/gtest.h>

#include <ginac/ginac.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "support/run.hpp"
#include "support/scale.hpp"

namespace {

using superball::test::run;
using superball::test::run_on_terminal;
using superball::test::RunResult;

/// A GiNaC reader knowing the symbols the JSON lists (plain symbols: any CAS reads the text).
GiNaC::parser reader_for(const nlohmann::json& j) {
  GiNaC::symtab table;
  for (const auto& s : j.at("symbols")) table[s.at("name").get<std::string>()] = GiNaC::symbol(s.at("name").get<std::string>());
  return GiNaC::parser(table, true);
}

TEST(CliDerive, JsonSchemaCase1Alpha2) {
  const RunResult r = run({"derive", "--case", "1", "--alphas", "2", "--format", "json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("case"), "1");
  EXPECT_EQ(j.at("closed_contacts"), nlohmann::json::array({"2-3", "3-4"}));
  for (const char* key : {"symbols", "velocities_after", "reactions", "conditions"}) EXPECT_TRUE(j.contains(key)) << key;
  GiNaC::parser reader = reader_for(j);
  const GiNaC::ex u1 = reader(j.at("velocities_after").at("U1").get<std::string>());
  EXPECT_TRUE(GiNaC::normal(u1 - reader("a*(K14+alpha2-m1)/(m1+K12+K13+K14+2*alpha2)")).is_zero());
  EXPECT_TRUE(j.at("reactions").contains("2-3"));
  EXPECT_TRUE(j.at("reactions").contains("3-4"));
  const auto& superball = j.at("conditions").at(0);
  EXPECT_EQ(superball.at("kind"), "superball");
  EXPECT_EQ(superball.at("about"), "U1 > a");
  EXPECT_EQ(superball.at("text"), "−α₂ > 2m₁ + K₁₂ + K₁₃");
  EXPECT_EQ(superball.at("latex"), "-\\alpha_{2} > 2m_{1} + K_{12} + K_{13}");
  const std::string exact = superball.at("exact");
  ASSERT_GT(exact.size(), 4u);
  EXPECT_EQ(exact.substr(exact.size() - 4), " > 0");
  EXPECT_TRUE(GiNaC::normal(reader(exact.substr(0, exact.size() - 4)) - reader("-alpha2-2*m1-K12-K13")).is_zero());
  // The canonical term order of every style: masses, K's, couplings.
  EXPECT_EQ(exact, "-2*m1 - K12 - K13 - alpha2 > 0");
  for (const auto& c : j.at("conditions")) {
    const std::string kind = c.at("kind");
    EXPECT_TRUE(kind == "superball" || kind == "evolution" || kind == "contact" || kind == "psd") << kind;
    for (const char* key : {"about", "exact", "asymptotic", "text", "latex"}) EXPECT_TRUE(c.contains(key)) << key;
    for (const char* key : {"exact", "asymptotic"}) {
      const std::string e = c.at(key);
      const auto rel = e.rfind(e.find(">=") != std::string::npos ? " >= 0" : " > 0");
      ASSERT_NE(rel, std::string::npos) << e;
      EXPECT_NO_THROW(reader(e.substr(0, rel))) << e;
    }
  }
}

TEST(CliDerive, TextHasThePaperFormulas) {
  const RunResult r = run({"derive", "--case", "1", "--alphas", "2"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* s : {"U₁⁺ = a(K₁₄ + α₂ − m₁)/(m₁ + K₁₂ + K₁₃ + K₁₄ + 2α₂)", "−α₂ > 2m₁ + K₁₂ + K₁₃", "m₁ < K₁₄ + α₂",
                        "m₂ + m₃ ≥ K₁₂ + K₁₃ + K₂₄ + K₃₄"})
    EXPECT_NE(r.out.find(s), std::string::npos) << s;
}

TEST(CliDerive, ConditionsOnMOnceForSeveralCasesAndNamedParts) {
  // Several cases: the conditions on M (the same in every case) come once, before the cases.
  const RunResult all = run({"derive", "--all", "--alphas", "3"});
  ASSERT_EQ(all.exit_code, 0) << all.err;
  const auto first_psd = all.out.find("M positive semi-definite, minor on 1-3,1-4");
  ASSERT_NE(first_psd, std::string::npos);
  EXPECT_EQ(all.out.find("M positive semi-definite, minor on 1-3,1-4", first_psd + 1), std::string::npos);
  EXPECT_LT(first_psd, all.out.find("case 0"));
  // One case keeps them, and names the positive part its readable conditions divide by.
  const RunResult one = run({"derive", "--case", "2.2", "--alphas", "3"});
  ASSERT_EQ(one.exit_code, 0) << one.err;
  for (const char* s : {"M positive semi-definite, minor on 1-3,1-4", "where S₁ = m₂ + K₁₂ + K₂₃ + K₂₄ > 0",
                        "−α₃ > 2m₁ + K₁₃ + K₁₂(2m₂ + K₂₃)/S₁"})
    EXPECT_NE(one.out.find(s), std::string::npos) << s << " not in:\n" << one.out;
  // JSON keeps the expanded form beside the readable one.
  const RunResult json = run({"derive", "--case", "2.2", "--alphas", "3", "-f", "json"});
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const nlohmann::json j = nlohmann::json::parse(json.out);
  EXPECT_EQ(j.at("named").at(0).at("name"), "S1");
  EXPECT_EQ(j.at("actual"), "depends");
  const auto& superball = j.at("conditions").at(0);
  EXPECT_EQ(superball.at("readable").at("exact").at("text"), "−α₃ > 2m₁ + K₁₃ + K₁₂(2m₂ + K₂₃)/S₁");
  EXPECT_NE(superball.at("exact").get<std::string>().find("alpha3"), std::string::npos);
}

TEST(CliDerive, GeneralCouplingNamesAndAllCases) {
  const RunResult r = run({"derive", "--bodies", "5", "--pairs", "near2", "--coupling", "near2", "--closed", "2-3", "-f", "json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  std::vector<std::string> names;
  for (const auto& s : j.at("symbols")) names.push_back(s.at("name"));
  EXPECT_NE(std::find(names.begin(), names.end(), "c_12_13"), names.end());
  EXPECT_EQ(std::find(names.begin(), names.end(), "m5"), names.end());  // fixed obstacle
  const RunResult all = run({"derive", "--all", "--alphas", "1,6", "-f", "json", "--obstacle", "finite"});
  ASSERT_EQ(all.exit_code, 0) << all.err;
  const nlohmann::json cases = nlohmann::json::parse(all.out);
  ASSERT_TRUE(cases.is_array());
  EXPECT_EQ(cases.size(), 8u);
  // The finite-obstacle form: expanded, or (compact JSON) through the elimination when long.
  const nlohmann::json& first = cases.at(0).at("conditions").at(0);
  EXPECT_TRUE(first.contains("finite") || first.at("eliminated").contains("finite")) << first.dump();
}

/// GiNaC's term order depends on the process (symbol serials, hashes); the
/// printed JSON must not: two runs in separate processes give the same bytes.
TEST(CliDerive, JsonIsTheSameFromRunToRun) {
  const std::vector<std::string> args{"derive", "--all", "--alphas", "2", "--format", "json"};
  const RunResult first = run(args), second = run(args);
  ASSERT_EQ(first.exit_code, 0) << first.err;
  ASSERT_EQ(second.exit_code, 0) << second.err;
  EXPECT_GT(first.out.size(), 1000u);
  EXPECT_EQ(first.out, second.out);
  const RunResult finite = run({"derive", "--all", "--alphas", "1,6", "--obstacle", "finite", "-f", "json"});
  ASSERT_EQ(finite.exit_code, 0) << finite.err;
  EXPECT_EQ(finite.out, run({"derive", "--all", "--alphas", "1,6", "--obstacle", "finite", "-f", "json"}).out);
}

TEST(CliDerive, BadInputIsOneLine) {
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"derive", "--case", "1", "--alphas", "9"}, {"derive", "--case", "7.7"}, {"derive", "--closed", "1-3"},
        {"derive", "--case", "1", "--scaling", "m9=1"}, {"derive", "--case", "1", "--closed", "2-3"}, {"derive", "--bodies", "5", "--case", "1"}}) {
    const RunResult r = run(args);
    EXPECT_EQ(r.exit_code, 2) << args.back();
    EXPECT_TRUE(r.out.empty()) << r.out;
    EXPECT_EQ(r.err.rfind("superball: ", 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
}

// Issue 25: --bodies 64 was taken and failed inside with "n <= 20".
TEST(CliDerive, TheBodyCountIsTheEnginesInOneLine) {
  for (const std::string n : {"64", "22"}) {
    const RunResult r = run({"derive", "--bodies", n, "--pairs", "near", "--closed", "none"});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(r.out.empty()) << r.out;
    EXPECT_EQ(r.err, "superball: n = " + n +
                         ": the symbolic derivation takes 2 to 21 bodies with a fixed obstacle, 2 to 20 with a finite one (at most 20 bodies moving "
                         "apart: determinants of up to 20 x 20)\n");
  }
  const RunResult finite = run({"derive", "--bodies", "21", "--pairs", "near", "--closed", "none", "--obstacle", "finite"});
  EXPECT_EQ(finite.exit_code, 2);
  EXPECT_EQ(finite.err.rfind("superball: n = 21: the symbolic derivation takes", 0), 0u) << finite.err;
}

// Progress on standard error: the case derive is at ("derive: case k of N (...)").

// Issue 26: compact JSON by default, every expanded form with --expanded.
// The compact JSON is the expanded one without the expanded forms that the
// case writes through its elimination: every other field equal, each such
// condition kept by its `eliminated` forms, each such velocity, reaction and
// determinant written over the names of elimination.definitions.
TEST(CliDerive, JsonIsCompactUnlessExpanded) {
  const std::vector<std::string> args = {"derive", "--bodies", "5", "--pairs", "near2", "--coupling", "near2", "--closed", "none", "--format", "json"};
  std::vector<std::string> with = args;
  with.push_back("--expanded");
  const RunResult compact = run(args), expanded = run(with);
  ASSERT_EQ(compact.exit_code, 0) << compact.err;
  ASSERT_EQ(expanded.exit_code, 0) << expanded.err;
  EXPECT_LT(compact.out.size() * 5, expanded.out.size());
  const nlohmann::json c = nlohmann::json::parse(compact.out), e = nlohmann::json::parse(expanded.out);
  ASSERT_TRUE(c.contains("elimination"));
  EXPECT_EQ(c.at("elimination"), e.at("elimination"));
  EXPECT_EQ(c.at("velocities_after").at("U1"), "V1");
  EXPECT_EQ(c.at("determinant"), "p1*p2*p3*p4");
  EXPECT_GT(e.at("determinant").get<std::string>().size(), 1000u);
  ASSERT_EQ(c.at("conditions").size(), e.at("conditions").size());
  int dropped = 0;
  for (std::size_t k = 0; k < c.at("conditions").size(); ++k) {
    const nlohmann::json& cc = c.at("conditions").at(k);
    nlohmann::json ee = e.at("conditions").at(k);
    for (const char* form : {"exact", "asymptotic"}) {
      const bool through = cc.contains("eliminated") && cc.at("eliminated").contains(form);
      EXPECT_EQ(cc.contains(form), !through) << cc.at("about") << " " << form;
      if (through) {
        ++dropped;
        const std::string f = form;
        for (const std::string& key : {f, f == "exact" ? std::string("text") : f + "_text", f == "exact" ? std::string("latex") : f + "_latex"}) ee.erase(key);
      }
    }
    EXPECT_EQ(cc, ee) << cc.at("about");
  }
  EXPECT_GE(dropped, 5);
  // The paper's cases with one alpha have no long form: the same JSON whichever the flag, but for the
  // conditions on M, which the compact list of cases has in its first case only.
  const RunResult paper = run({"derive", "--all", "--alphas", "2", "--format", "json"});
  const RunResult paper_expanded = run({"derive", "--all", "--alphas", "2", "--format", "json", "--expanded"});
  ASSERT_EQ(paper.exit_code, 0) << paper.err;
  const nlohmann::json p = nlohmann::json::parse(paper.out);
  nlohmann::json pe = nlohmann::json::parse(paper_expanded.out);
  ASSERT_EQ(p.size(), 8u);
  EXPECT_EQ(p.at(0), pe.at(0));
  for (std::size_t k = 1; k < pe.size(); ++k) {
    nlohmann::json kept = nlohmann::json::array();
    int psd = 0;
    for (const auto& c : pe.at(k).at("conditions")) {
      if (c.at("kind") == "psd") ++psd;
      else kept.push_back(c);
    }
    EXPECT_GT(psd, 0);
    pe.at(k).at("conditions") = kept;
    EXPECT_EQ(p.at(k), pe.at(k)) << k;
  }
}

TEST(CliDerive, TheOutputDoesNotDependOnTheNumberOfWorkers) {
  // Cases are derived in worker processes (GiNaC is not thread-safe) and written in order.
  for (const char* format : {"json", "text"}) {
    const RunResult one = run({"derive", "--bodies", "5", "--pairs", "near2", "--coupling", "near2", "--all", "--format", format, "-j", "1"});
    ASSERT_EQ(one.exit_code, 0) << superball::test::describe(one);
    for (const char* jobs : {"2", "3", "0"}) {
      // At a small scale (scripts/test.sh under the sanitizers) one count of several workers.
      if (superball::test::small_scale() && std::string(jobs) != "2") continue;
      const RunResult many = run({"derive", "--bodies", "5", "--pairs", "near2", "--coupling", "near2", "--all", "--format", format, "-j", jobs});
      ASSERT_EQ(many.exit_code, 0) << superball::test::describe(many);
      EXPECT_EQ(many.out, one.out) << format << ", -j " << jobs;
    }
  }
  // A finite obstacle: five of the sixteen cases are derived in two stages with several workers (split_case()).
  const RunResult one = run({"derive", "--bodies", "5", "--pairs", "near2", "--coupling", "near2", "--obstacle", "finite", "--all", "--format", "json", "-j", "1"});
  const RunResult two = run({"derive", "--bodies", "5", "--pairs", "near2", "--coupling", "near2", "--obstacle", "finite", "--all", "--format", "json", "-j", "2"});
  ASSERT_EQ(one.exit_code, 0) << superball::test::describe(one);
  EXPECT_EQ(two.out, one.out);
  const RunResult bad = run({"derive", "--all", "--alphas", "2", "-j", "-1"});
  EXPECT_EQ(bad.exit_code, 2);
}

TEST(CliDerive, ProgressIsOneLinePerCaseWhenAskedForALog) {
  const RunResult plain = run({"derive", "--all", "--alphas", "2"});
  const RunResult r = run({"derive", "--all", "--alphas", "2", "--progress"});
  ASSERT_EQ(r.exit_code, 0) << superball::test::describe(r);
  EXPECT_TRUE(plain.err.empty()) << plain.err;  // not a terminal: nothing by default
  EXPECT_EQ(r.out, plain.out);
  const std::vector<std::string> lines = r.err_lines();
  ASSERT_EQ(lines.size(), 8u) << r.err;  // each case is written as it is derived: no "writing" step
  EXPECT_EQ(lines[0], "derive: case 1 of 8 (3.3 {})");
  EXPECT_EQ(lines[4], "derive: case 5 of 8 (2.2 {3-4})");
  EXPECT_EQ(lines[7], "derive: case 8 of 8 (0 {1-2,2-3,3-4})");
  const RunResult general = run({"derive", "--bodies", "5", "--pairs", "near", "--closed", "2-3,4-5", "--progress"});
  EXPECT_EQ(general.err, "derive: case 1 of 1 ({2-3,4-5})\n");
  const RunResult tex = run({"derive", "--case", "1", "--alphas", "2", "--progress", "--format", "latex"});
  EXPECT_EQ(tex.err, "derive: case 1 of 1 (1 {2-3,3-4})\nderive: writing 1 case as latex\n");
}

TEST(CliDerive, ProgressSaysTheFirstStageInItsOwnWords) {
  // A finite obstacle at 5 bodies: with several workers {} and the four cases of one closed contact are prepared first
  // (their own workers, then the cases' workers); the line says so, then counts the cases as with one worker.
  const std::vector<std::string> args = {"derive", "--bodies", "5", "--pairs", "near2", "--coupling", "near2", "--obstacle", "finite", "--all", "--progress"};
  auto with = [&](const char* jobs) {
    std::vector<std::string> a = args;
    a.insert(a.end(), {"-j", jobs});
    return a;
  };
  const RunResult one = run(with("1")), two = run(with("2"));
  ASSERT_EQ(one.exit_code, 0) << superball::test::describe(one);
  ASSERT_EQ(two.exit_code, 0) << superball::test::describe(two);
  EXPECT_EQ(two.out, one.out);
  const std::vector<std::string> lines = two.err_lines(), cases = one.err_lines();
  ASSERT_EQ(cases.size(), 16u) << one.err;  // one worker: one stage, no first-stage line
  EXPECT_EQ(cases[0], "derive: case 1 of 16 ({})");
  ASSERT_EQ(lines.size(), 6u + 16u) << two.err;
  for (std::size_t k = 0; k <= 5; ++k) EXPECT_EQ(lines[k], "derive: preparing the 5 largest cases: " + std::to_string(k) + " of 5 done");
  EXPECT_EQ(std::vector<std::string>(lines.begin() + 6, lines.end()), cases);
  // One case prepared (an infinite obstacle: {} only), in the singular.
  const RunResult single = run({"derive", "--bodies", "5", "--pairs", "near2", "--all", "--progress", "-j", "2"});
  ASSERT_EQ(single.exit_code, 0) << superball::test::describe(single);
  EXPECT_EQ(single.err.rfind("derive: preparing the largest case: 0 of 1 done\nderive: preparing the largest case: 1 of 1 done\nderive: case 1 of 16 ({})\n", 0), 0u)
      << single.err;
  // On a terminal: the same line redrawn in place, then the cases', erased before the output.
  if (!superball::test::pseudo_terminals_available()) GTEST_SKIP() << "no pseudo-terminal on this machine";
  const RunResult t = run_on_terminal(with("2"));
  ASSERT_EQ(t.exit_code, 0) << superball::test::describe(t);
  const auto stage = t.err.find("\rderive: preparing the 5 largest cases: 5 of 5 done\033[K");
  EXPECT_NE(stage, std::string::npos) << t.err;
  EXPECT_LT(stage, t.err.find("\rderive: case 1 of 16 ({})\033[K")) << t.err;
  EXPECT_EQ(t.err.find('\n'), std::string::npos) << t.err;
  ASSERT_GE(t.err.size(), 4u);
  EXPECT_EQ(t.err.substr(t.err.size() - 4), "\r\033[K");
}

TEST(CliDerive, QuietPrintsNothingOnStandardError) {
  const RunResult r = run({"derive", "--all", "--alphas", "2", "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << superball::test::describe(r);
  EXPECT_TRUE(r.err.empty()) << r.err;
  EXPECT_EQ(r.out, run({"derive", "--all", "--alphas", "2"}).out);
  superball::test::expect_bad_input(run({"derive", "--all", "--alphas", "2", "--quiet", "--progress"}), {"--quiet", "--progress"});
  const RunResult help = run({"derive", "--help"});
  for (const char* piece : {"--quiet", "--progress", "derive: case 3 of 16 ({2-3,4-5})"})
    EXPECT_NE(help.out.find(piece), std::string::npos) << piece;
  // On a terminal too, where --progress draws its line.
  if (!superball::test::pseudo_terminals_available()) GTEST_SKIP() << "no pseudo-terminal on this machine";
  const RunResult t = run_on_terminal({"derive", "--all", "--alphas", "2", "-q"});
  EXPECT_EQ(t.exit_code, 0) << superball::test::describe(t);
  EXPECT_TRUE(t.err.empty()) << t.err;
}

TEST(CliDerive, ProgressOnATerminalIsOneLineRedrawnThenErased) {
  if (!superball::test::pseudo_terminals_available()) GTEST_SKIP() << "no pseudo-terminal on this machine";
  const RunResult t = run_on_terminal({"derive", "--all", "--alphas", "2", "--progress"});
  ASSERT_EQ(t.exit_code, 0) << superball::test::describe(t);
  EXPECT_NE(t.err.find("\rderive: case 1 of 8 (3.3 {})\033[K"), std::string::npos) << t.err;
  EXPECT_NE(t.err.find("\rderive: case 8 of 8 (0 {1-2,2-3,3-4})\033[K"), std::string::npos) << t.err;
  // Text and JSON are written case by case: no "writing" step; LaTeX has one.
  EXPECT_EQ(t.err.find("writing"), std::string::npos) << t.err;
  const RunResult tex = run_on_terminal({"derive", "--all", "--alphas", "2", "--progress", "--format", "latex", "-o", "/dev/null"});
  EXPECT_NE(tex.err.find("\rderive: writing 8 cases as latex\033[K"), std::string::npos) << tex.err;
  EXPECT_EQ(t.err.find('\n'), std::string::npos) << t.err;  // redrawn in place, never a new line
  ASSERT_GE(t.err.size(), 4u);
  EXPECT_EQ(t.err.substr(t.err.size() - 4), "\r\033[K");  // erased before the output
  // By default a derivation this short ends before the progress would appear.
  const RunResult quick = run_on_terminal({"derive", "--case", "1", "--alphas", "2"});
  EXPECT_EQ(quick.exit_code, 0);
  EXPECT_TRUE(quick.err.empty()) << quick.err;
}

TEST(CliAudit, JsonHasEveryPrintedCondition) {
  const RunResult r = run({"audit", "--samples", "300", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("conditions").size(), 14u);
  EXPECT_EQ(j.at("claims").size(), 3u);
  // Every formula also in LaTeX: ASCII markup (no Unicode of the text notation), indexed names (K_{14}).
  auto latex = [](const nlohmann::json& entry, const char* key) {
    ASSERT_TRUE(entry.contains(key)) << key << " in " << entry;
    const std::string tex = entry.at(key);
    EXPECT_FALSE(tex.empty()) << key;
    EXPECT_TRUE(std::all_of(tex.begin(), tex.end(), [](char ch) { return static_cast<unsigned char>(ch) < 0x80; })) << key << ": " << tex;
    EXPECT_NE(tex.find("_{"), std::string::npos) << key << ": " << tex;
  };
  for (const auto& c : j.at("conditions")) {
    const std::string v = c.at("verdict");
    EXPECT_TRUE(v == "identical to the exact condition" || v == "identical at the asymptotic order" || v == "different") << v;
    for (const char* key : {"printed_latex", "derived_exact_latex", "derived_asymptotic_latex"}) latex(c, key);
  }
  for (const auto& c : j.at("claims")) latex(c, "derived_superball_latex");
}

}  // namespace
