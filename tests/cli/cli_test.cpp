// The `superball` command as a user runs it: the paper's scenes in text and
// JSON, sweeps and switch points, every scene of the bad catalogue (exit 2,
// one line on stderr, nothing on stdout) and bad command-line arguments.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cln/rational.h>
#include <cln/rational_io.h>
#include <cln/real.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "support/run.hpp"
#include "support/scale.hpp"

namespace {

const std::string kScenes = std::string(SUPERBALL_CASES_DIR) + "/scenes/";
const std::string kData = std::string(SUPERBALL_TEST_DATA_DIR) + "/";

const std::vector<std::string> kCatalogue = {
#include "bad_scene_list.inc"
};

using superball::test::describe;
using superball::test::expect_bad_input;
using superball::test::run;
using superball::test::RunResult;
using superball::test::slurp;

nlohmann::json json_of(const RunResult& r) {
  try {
    return nlohmann::json::parse(r.out);
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not JSON: " << e.what() << "\n" << describe(r);
    return {};
  }
}

double rational(const std::string& fraction) { return cln::double_approx(cln::cl_RA(fraction.c_str())); }

// ---------------------------------------------------------------------------
// solve

TEST(Solve, PaperSceneAsText) {
  const RunResult r = run({"solve", kScenes + "paper-4.4-alpha2.toml"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_TRUE(r.err.empty()) << r.err;
  EXPECT_NE(r.out.find("case 3.3"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("3.30688"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("superball: yes"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("status success"), std::string::npos) << r.out;
}

/// Eq. (16) as printed, and half a unit of the last printed digit.
const double kEq16[4] = {3.3069, 0.4478, 0.2849, -0.000017};
const double kEq16HalfUlp[4] = {0.5e-4, 0.5e-4, 0.5e-4, 0.5e-6};

class SolveJson : public ::testing::TestWithParam<std::string> {};

TEST_P(SolveJson, PaperSceneFieldsAndPhysics) {
  const std::string precision = GetParam();
  const RunResult r = run({"solve", kScenes + "paper-4.4-alpha2.toml", "--json", "--precision", precision});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_TRUE(r.err.empty()) << r.err;
  const nlohmann::json j = json_of(r);
  ASSERT_TRUE(j.is_object());
  EXPECT_EQ(j.at("precision"), precision);
  EXPECT_EQ(j.at("status"), "success");
  EXPECT_EQ(j.at("case"), "3.3");
  EXPECT_EQ(j.at("closed_contacts"), nlohmann::json::array());
  EXPECT_EQ(j.at("superball"), true);
  const auto& U = j.at("velocities_after");
  ASSERT_TRUE(U.is_array());
  ASSERT_EQ(U.size(), 4u);
  for (int i = 0; i < 4; ++i) {
    ASSERT_TRUE(U[i].is_number());
    EXPECT_NEAR(U[i].get<double>(), kEq16[i], kEq16HalfUlp[i]) << "U" << i + 1;
  }
  const auto& R = j.at("reactions");
  ASSERT_TRUE(R.is_object());
  EXPECT_EQ(R.size(), 3u);
  for (const char* c : {"1-2", "2-3", "3-4"}) {
    ASSERT_TRUE(R.contains(c)) << c;
    EXPECT_EQ(R.at(c).get<double>(), 0.0) << "case 3.3: every contact open";
  }
  // Energies: KE- = ½ (m1 + m2 + m3) a², KE- - KE+ = dissipation >= 0.
  const double a = 3.13209, ke_before = 0.5 * (0.001 + 10 + 15) * a * a;
  const double kb = j.at("kinetic_energy_before"), ka = j.at("kinetic_energy_after"), d = j.at("dissipation");
  EXPECT_NEAR(kb, ke_before, 1e-9 * ke_before);
  EXPECT_NEAR(kb - ka, d, 1e-9 * kb);
  EXPECT_GT(d, 0);
  EXPECT_LT(ka, kb);
  EXPECT_NEAR(j.at("momentum_before").get<double>(), j.at("momentum_after").get<double>(), 1e-9 * 25 * a);
  if (precision == "exact") {
    const auto& X = j.at("velocities_after_exact");
    ASSERT_EQ(X.size(), 4u);
    for (int i = 0; i < 4; ++i) {
      ASSERT_TRUE(X[i].is_string());
      const std::string f = X[i];
      EXPECT_EQ(f.find_first_not_of("-0123456789/"), std::string::npos) << "not a fraction: " << f;
      EXPECT_NEAR(rational(f), U[i].get<double>(), 1e-15 * std::fabs(U[i].get<double>())) << f;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Precisions, SolveJson, ::testing::Values("double", "long-double", "digits:30", "exact"),
                         [](const auto& info) {
                           std::string s = info.param;
                           for (char& c : s)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return s;
                         });

TEST(Solve, AsPrintedSceneGivesAnotherU1) {
  const RunResult r = run({"solve", kScenes + "paper-4.4-as-printed.toml", "--json"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const nlohmann::json j = json_of(r);
  EXPECT_NEAR(j.at("velocities_after")[0].get<double>(), 3.1467, 0.5e-4);
  EXPECT_GT(std::fabs(j.at("velocities_after")[0].get<double>() - kEq16[0]), 0.1);
}

TEST(Solve, ClosedContactsAndReactions) {
  // 2 kg at -1 m/s on 3 kg at +1 m/s, no dissipation: a plastic impact, both
  // at the centre-of-mass velocity 1/5, reaction m2 (1/5 - 1) = -12/5.
  const RunResult r = run({"solve", kData + "good/two-bodies-no-dissipation.toml", "--json", "--precision", "exact"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const nlohmann::json j = json_of(r);
  EXPECT_EQ(j.at("closed_contacts"), nlohmann::json::array({"1-2"}));
  EXPECT_EQ(j.at("case"), "{1-2}");  // not a 4-body scene: the set itself
  EXPECT_EQ(j.at("velocities_after_exact"), nlohmann::json::array({"1/5", "1/5"}));
  EXPECT_DOUBLE_EQ(j.at("reactions").at("1-2").get<double>(), -2.4);
  EXPECT_DOUBLE_EQ(j.at("kinetic_energy_before").get<double>(), 2.5);
  EXPECT_DOUBLE_EQ(j.at("kinetic_energy_after").get<double>(), 0.1);
  EXPECT_DOUBLE_EQ(j.at("dissipation").get<double>(), 2.4);
  EXPECT_EQ(j.at("superball"), false);
}

TEST(Solve, ExactWithAnIrrationalFallSpeed) {
  // h = 0.5, g = 9.81: a = sqrt(9.81) is irrational; an exact run prints
  // each velocity as a fraction times sqrt(981/100), and the numbers agree.
  const RunResult r = run({"solve", kData + "good/paper-4.4-alpha4-float-inf.toml", "--json", "--precision", "exact"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const nlohmann::json j = json_of(r);
  const auto& X = j.at("velocities_after_exact");
  ASSERT_EQ(X.size(), 4u);
  for (int i = 0; i < 3; ++i) {
    const std::string f = X[i];
    const auto star = f.find("*sqrt(981/100)");
    ASSERT_NE(star, std::string::npos) << f;
    EXPECT_NEAR(rational(f.substr(0, star)) * std::sqrt(9.81), j.at("velocities_after")[i].get<double>(), 1e-12) << f;
  }
  EXPECT_EQ(j.at("velocities_after")[3].get<double>(), 0.0);  // the fixed obstacle
  EXPECT_EQ(j.at("fixed_obstacle"), true);
  // The double run agrees.
  const nlohmann::json d = json_of(run({"solve", kData + "good/paper-4.4-alpha4-float-inf.toml", "--json"}));
  for (int i = 0; i < 4; ++i)
    EXPECT_NEAR(d.at("velocities_after")[i].get<double>(), j.at("velocities_after")[i].get<double>(), 1e-12);
}

// ---------------------------------------------------------------------------
// sweep

TEST(Sweep, SwitchPointsOfFig7) {
  const RunResult r = run({"sweep", kScenes + "paper-4.4-alpha2.toml", "--vary", "K.3-4=0:20:41", "--switch-points"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  std::istringstream in(r.out);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 2u) << r.out;
  EXPECT_EQ(lines[0].rfind("K.3-4 = 6.428", 0), 0u) << lines[0];
  EXPECT_NE(lines[0].find("case 2.2 {3-4} -> case 3.3 {}"), std::string::npos) << lines[0];
  EXPECT_EQ(lines[1].rfind("K.3-4 = 13.41", 0), 0u) << lines[1];
  EXPECT_NE(lines[1].find("case 3.3 {} -> case 3.2 {2-3}"), std::string::npos) << lines[1];
}

TEST(Sweep, CsvAlongK34) {
  const RunResult r = run({"sweep", kScenes + "paper-4.4-alpha2.toml", "--vary", "K.3-4=0:20:41", "--csv"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  std::istringstream in(r.out);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 42u) << r.out;
  EXPECT_EQ(lines[0], "K.3-4,U1,U2,U3,U4,case,status");
  int cases[3] = {0, 0, 0};
  for (std::size_t k = 1; k < lines.size(); ++k) {
    std::vector<std::string> cells;
    std::istringstream row(lines[k]);
    for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
    ASSERT_EQ(cells.size(), 7u) << lines[k];
    EXPECT_EQ(cells[6], "success") << lines[k];
    const double k34 = std::stod(cells[0]);
    EXPECT_NEAR(k34, 0.5 * static_cast<double>(k - 1), 1e-9);
    const double U[4] = {std::stod(cells[1]), std::stod(cells[2]), std::stod(cells[3]), std::stod(cells[4])};
    // Impenetrability along the whole sweep.
    for (int i = 0; i < 3; ++i) EXPECT_GE(U[i] - U[i + 1], -1e-12) << lines[k];
    const std::string& c = cells[5];
    EXPECT_EQ(c, k34 < 6.43 ? "2.2" : k34 < 13.41 ? "3.3" : "3.2") << lines[k];
    cases[c == "2.2" ? 0 : c == "3.3" ? 1 : 2] += 1;
    if (k34 == 10) {
      for (int i = 0; i < 4; ++i) EXPECT_NEAR(U[i], kEq16[i], kEq16HalfUlp[i]) << lines[k];
    }
  }
  EXPECT_EQ(cases[0], 13);  // 0 .. 6
  EXPECT_EQ(cases[1], 14);  // 6.5 .. 13
  EXPECT_EQ(cases[2], 14);  // 13.5 .. 20
}

TEST(Sweep, TheOutputDoesNotDependOnTheThreads) {
  const std::string scene = kScenes + "paper-4.4-alpha2.toml";
  const std::vector<std::vector<std::string>> sweeps = {
      {"--vary", "K.3-4=0:20:401", "--csv"},
      {"--vary", "K.3-4=0:20:41", "--precision", "exact"},
      {"--vary", "K.3-4=0:20:41", "--switch-points"},
      {"--vary", "alpha.2=-30:0:21", "--precision", "digits:30", "--csv"}};
  for (const auto& args : sweeps) {
    std::vector<std::string> base = {"sweep", scene};
    base.insert(base.end(), args.begin(), args.end());
    auto with = [&](const std::string& threads) {
      std::vector<std::string> a = base;
      a.insert(a.end(), {"--threads", threads});
      return run(a);
    };
    const RunResult one = with("1");
    ASSERT_EQ(one.exit_code, 0) << describe(one);
    EXPECT_GT(one.out.size(), 100u);
    for (const std::string threads : {"2", "3"}) {
      const RunResult many = with(threads);
      EXPECT_EQ(many.exit_code, 0) << describe(many);
      EXPECT_EQ(many.out, one.out) << args[1] << " on " << threads << " threads";
    }
    const RunResult all = run(base);  // default: all cores
    EXPECT_EQ(all.out, one.out) << args[1] << " on all cores";
  }
}

// ---------------------------------------------------------------------------
// bad input

class BadSceneCli : public ::testing::TestWithParam<std::string> {};

TEST_P(BadSceneCli, ExitTwoOneLineNothingOnStdout) {
  const std::string path = kData + "bad/" + GetParam();
  std::ifstream in(path, std::ios::binary);
  std::string first;
  std::getline(in, first);
  ASSERT_EQ(first.rfind("# expect: ", 0), 0u);
  const std::string expected = first.substr(10);
  const std::vector<std::vector<std::string>> variants = {{}, {"--json"}, {"--precision", "exact"}};
  for (const auto& extra : variants) {
    // At a small scale (scripts/test.sh under the sanitizers) the plain solve only: the other two
    // refuse the scene through the same reader and the same error line.
    if (superball::test::small_scale() && !extra.empty()) continue;
    std::vector<std::string> args = {"solve", path};
    args.insert(args.end(), extra.begin(), extra.end());
    expect_bad_input(run(args), {path, expected});
  }
  expect_bad_input(run({"sweep", path, "--vary", "g=1:2:3"}), {path});
}

INSTANTIATE_TEST_SUITE_P(Catalogue, BadSceneCli, ::testing::ValuesIn(kCatalogue), [](const auto& info) {
  std::string name = info.param.substr(0, info.param.rfind('.'));
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
});

TEST(BadInput, MissingSceneFile) {
  const std::string path = kData + "bad/no-such-file.toml";
  expect_bad_input(run({"solve", path}), {path, "cannot open"});
}

TEST(BadInput, FileOverTheSizeLimit) {
  const std::string path = ::testing::TempDir() + "superball-cli-big-" + std::to_string(::getpid()) + ".toml";
  {
    std::ofstream out(path, std::ios::binary);
    out << "fall_speed = 1\n[[body]]\nmass = 1\n[[body]]\nmass = \"inf\"\n";
    const std::string line(99, '#');
    for (int k = 0; k < 50000; ++k) out << line << '\n';  // 5 MB of comments
  }
  expect_bad_input(run({"solve", path}), {path, "bytes; a scene file has at most"});
  std::remove(path.c_str());
}

struct BadArgs {
  std::vector<std::string> args;
  std::vector<std::string> expected;
};

void PrintTo(const BadArgs& b, std::ostream* os) {
  *os << "superball";
  for (const auto& a : b.args) *os << " '" << a << "'";
}

class BadArguments : public ::testing::TestWithParam<BadArgs> {};

TEST_P(BadArguments, ExitNonZeroWithOneClearLine) {
  const BadArgs b = GetParam();
  const RunResult r = run(b.args);
  EXPECT_NE(r.exit_code, 0) << describe(r);
  EXPECT_TRUE(r.out.empty()) << describe(r);
  const auto lines = r.err_lines();
  ASSERT_EQ(lines.size(), 1u) << describe(r);
  for (const auto& e : b.expected) EXPECT_NE(lines[0].find(e), std::string::npos) << "'" << e << "' not in: " << lines[0];
}

const std::string kPaper = kScenes + "paper-4.4-alpha2.toml";

INSTANTIATE_TEST_SUITE_P(
    Cli, BadArguments,
    ::testing::Values(
        BadArgs{{"solve", kPaper, "--precision", "nonsense"}, {"nonsense", "double, long-double, digits:N or exact"}},
        BadArgs{{"solve", kPaper, "--precision", "digits:5"}, {"digits:5", "10"}},
        BadArgs{{"solve", kPaper, "--precision", "digits:abc"}, {"digits:abc"}},
        BadArgs{{"solve", kPaper, "-p", ""}, {"precision"}},
        BadArgs{{"sweep", kPaper, "--vary", "K.3-4=0:20"}, {"--vary K.3-4=0:20", "FROM:TO:STEPS"}},
        BadArgs{{"sweep", kPaper, "--vary", "K.3-4=0:20:1"}, {"STEPS"}},
        BadArgs{{"sweep", kPaper, "--vary", "K.3-4=0:20:many"}, {"STEPS"}},
        BadArgs{{"sweep", kPaper, "--vary", "K.3-4=0:20:1e3"}, {"STEPS"}},
        BadArgs{{"sweep", kPaper, "--vary", "K.3-4=0:20:-5"}, {"STEPS"}},
        BadArgs{{"sweep", kPaper, "--vary", "K.3-4=5:5:10"}, {"FROM and TO are equal"}},
        BadArgs{{"sweep", kPaper, "--vary", "K.3-4=a:b:3"}, {"--vary K.3-4=a:b:3", "'a'"}},
        BadArgs{{"sweep", kPaper, "--vary", "K.3-4=1/0:2:3"}, {"zero denominator"}},
        BadArgs{{"sweep", kPaper, "--vary", "K.3-4"}, {"no '='"}},
        BadArgs{{"sweep", kPaper, "--vary", "K.9-10=0:1:3"}, {"outside bodies 1..4"}},
        BadArgs{{"sweep", kPaper, "--vary", "colour=0:1:3"}, {"unknown parameter"}},
        BadArgs{{"sweep", kPaper, "--vary", "alpha.9=0:1:3"}, {"alpha"}},
        BadArgs{{"sweep", kPaper, "--vary", "K.3-4=-100:20:5"}, {"not positive semi-definite"}},
        BadArgs{{"sweep", kPaper, "--vary", "mass.1=-1:1:3"}, {"must be > 0"}},
        BadArgs{{"sweep", kPaper, "--vary", "K.3-4=0:20:5", "--precision", "quad"}, {"quad"}},
        BadArgs{{"sweep", kPaper}, {"--vary"}},
        BadArgs{{"sweep", kPaper, "--vary", "K.3-4=0:20:5", "--threads", "-1"}, {"threads must be a whole number from 0 (all cores) to 1024, got -1"}},
        BadArgs{{"solve", kPaper, "--rtol", "nan"}, {"rtol must be a number from 0 to 1, got nan"}},
        BadArgs{{"sweep", kPaper, "--vary", "K.3-4=0:20:5", "--threads", "many"}, {"--threads"}},
        BadArgs{{"solve"}, {"scene"}},
        BadArgs{{"solve", kPaper, "--bogus"}, {"--bogus"}},
        BadArgs{{"frobnicate"}, {"unknown command 'frobnicate'", "commands: solve"}},
        BadArgs{{}, {"subcommand"}}),
    [](const auto& info) { return "case" + std::to_string(info.index); });

// ---------------------------------------------------------------------------
// verify

TEST(Verify, TablesOverEpsilonAndExactAgreement) {
  const RunResult r = run({"verify", "--case", "1", "--alphas", "2", "--samples", "100", "--epsilons", "1e-2,1/1000000", "--threads", "2"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_TRUE(r.err.empty()) << r.err;  // no progress bar when stderr is not a terminal
  for (const std::string piece : {"case 1", "−α₂ > 2m₁ + K₁₂ + K₁₃", "exact agree", "  1e-2 ", "  1e-6 ", "holds (near)", "(0 where an exact form disagrees)"})
    EXPECT_NE(r.out.find(piece), std::string::npos) << "'" << piece << "' not in:\n" << r.out;
}

TEST(Verify, SixBodyPatternExactFormsAgreeOnBothSides) {
  // Issue 13: a verification run beyond the paper, CI-sized: 6 bodies, nearest and
  // next-nearest neighbours with their couplings, two contacts closed.
  const RunResult r = run({"verify", "--bodies", "6", "--pairs", "near2", "--coupling", "near2", "--closed", "2-3,4-5", "--samples", "100",
                           "--epsilons", "1e-2,1e-4", "--boundary-pairs", "2", "--json", "--threads", "2"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j.at("exact_agrees").get<bool>());
  int both_sides = 0;
  for (const auto& e : j.at("epsilons")) {
    EXPECT_EQ(e.at("all").at("exact").at("agree"), e.at("all").at("exact").at("total"));
    EXPECT_EQ(e.at("all").at("unsolved").get<int>(), 0);
    for (const auto& c : e.at("all").at("conditions")) {
      EXPECT_EQ(c.at("exact_agree").get<int>(), c.at("holds").get<int>() + c.at("fails").get<int>()) << c.dump();
      both_sides += c.at("holds").get<int>() > 0 && c.at("fails").get<int>() > 0;
    }
  }
  EXPECT_GE(both_sides, 2) << "the points must fall on both sides of some conditions for the check to mean something";
}

TEST(Verify, QuietDrawsNoProgressBarOnATerminal) {
  if (!superball::test::pseudo_terminals_available()) GTEST_SKIP() << "no pseudo-terminal on this machine";
  // About a second in a Release build, longer under the sanitizers: the bar would be drawn without --quiet.
  const RunResult r = superball::test::run_on_terminal(
      {"verify", "--case", "1", "--alphas", "2", "--samples", "2000", "--epsilons", "1e-2,1e-4", "--threads", "2", "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_TRUE(r.err.empty()) << r.err;
  EXPECT_NE(r.out.find("exact agree"), std::string::npos) << r.out;
}

TEST(Verify, JsonIsTheSameWithOneAndTwoThreads) {
  const std::vector<std::string> args = {"verify", "--case", "3.2", "--alphas", "5", "--samples", "80", "--epsilons", "1e-2,1e-4", "--json", "--threads"};
  std::vector<std::string> one = args, two = args;
  one.push_back("1");
  two.push_back("2");
  const RunResult a = run(one), b = run(two);
  ASSERT_EQ(a.exit_code, 0) << describe(a);
  EXPECT_EQ(a.out, b.out);
  const nlohmann::json j = json_of(a);
  EXPECT_EQ(j["case"], "3.2");
  EXPECT_TRUE(j["exact_agrees"].get<bool>());
  for (const auto& e : j["epsilons"]) {
    EXPECT_EQ(e["all"]["exact"]["agree"], e["all"]["exact"]["total"]);
    EXPECT_EQ(e["drawn"]["points"], 80);
  }
}

/// Every disagreement is a scene file that loads; solving it exactly gives the case its comment states.
TEST(Verify, DisagreementScenesRerunWithSolve) {
  const std::string dir = ::testing::TempDir() + "superball-verify-" + std::to_string(::getpid());
  const RunResult r = run({"verify", "--case", "1", "--alphas", "2", "--samples", "50", "--epsilons", "1e-2", "--out", dir});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) files.push_back(entry.path().string());
  ASSERT_FALSE(files.empty()) << r.out;
  EXPECT_NE(r.out.find(std::to_string(files.size()) + " scene files written to " + dir), std::string::npos) << r.out;
  int checked = 0;
  for (const std::string& file : files) {
    const std::string text = slurp(file);
    const std::string marker = "# the exact solution: case ";
    const auto at = text.find(marker);
    ASSERT_NE(at, std::string::npos) << text;
    const std::string actual = text.substr(at + marker.size(), text.find(',', at) - at - marker.size());
    EXPECT_NE(text.find("# rerun: superball solve " + file + " --precision exact"), std::string::npos) << text;
    if (checked++ >= 5) continue;  // solving every file would only repeat the check
    const RunResult s = run({"solve", file, "--precision", "exact"});
    ASSERT_EQ(s.exit_code, 0) << describe(s);
    EXPECT_NE(s.out.find("\ncase " + actual + " ("), std::string::npos) << "expected case " << actual << " in:\n" << s.out;
  }
  std::filesystem::remove_all(dir);
}

TEST(Verify, NothingWrittenWithoutDisagreements) {
  const std::string dir = ::testing::TempDir() + "superball-verify-none-" + std::to_string(::getpid());
  const RunResult r = run({"verify", "--case", "0", "--alphas", "2", "--samples", "30", "--epsilons", "1e-6", "--out", dir});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_NE(r.out.find("disagreements: 0 points"), std::string::npos) << r.out;
  EXPECT_FALSE(std::filesystem::exists(dir));
}

/// Bad options: exit 2, one line naming what is wrong, nothing on stdout.
TEST(Verify, BadOptionsGiveOneLineAndExitTwo) {
  const std::vector<std::string> base = {"verify", "--alphas", "2"};
  const std::vector<BadArgs> bad = {{{"--case", "1", "--epsilons", "2"}, {"epsilons must be in (0, 1), got 2"}},
                                    {{"--case", "1", "--epsilons", "1e-2,abc"}, {"epsilons: 'abc'"}},
                                    {{"--case", "1", "--epsilons", "0"}, {"epsilons must be in (0, 1), got 0"}},
                                    {{"--case", "1", "--epsilons", ""}, {"epsilons: no value"}},
                                    {{"--case", "1", "--threads", "-1"}, {"threads must be a whole number from 0 (all cores) to 1024, got -1"}},
                                    {{"--case", "1", "--samples", "0"}, {"samples must be a whole number from 1 to 100000000, got 0"}},
                                    {{"--case", "1", "--boundary-pairs", "-1"}, {"boundary_pairs must be a whole number from 0 to 1000000, got -1"}},
                                    {{"--case", "1", "--obstacle", "middle"}, {"obstacle must be infinite or finite, got 'middle'"}},
                                    {{"--case", "1", "--order", "21"}, {"order must be a whole number from 0 to 20, got 21"}},
                                    // Every drawn point is held until the boundaries are bisected: 5 x 10^8 of them do not fit.
                                    {{"--case", "1", "--samples", "100000000"},
                                     {"drawing 100000000 points at each of 5 values of epsilon holds about ", "available (", "draw fewer points (--samples)"}},
                                    {{"--case", "9"}, {"9"}},
                                    {{"--case", "1", "--closed", "2-3"}, {"case, closed and all each choose the cases: give one of them"}},
                                    {{}, {"give a case: case, closed or all"}}};
  for (const BadArgs& b : bad) {
    std::vector<std::string> args = base;
    args.insert(args.end(), b.args.begin(), b.args.end());
    expect_bad_input(run(args), b.expected);
  }
}

// ---------------------------------------------------------------------------
// explore

/// A witness of `superball explore` solves, in `superball solve --precision
/// exact`, to the case and the U1+ the explore report gives.
TEST(Explore, WitnessFileSolvesToTheReportedCase) {
  const std::string dir = ::testing::TempDir() + "superball-explore-" + std::to_string(::getpid());
  const RunResult r = run({"explore", "--alphas", "3", "--case", "1", "--starts", "4", "--json", "--out", dir});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  const nlohmann::json j = json_of(r);
  EXPECT_EQ(j.at("reach"), "yes");
  EXPECT_GT(rational(j.at("ratio").get<std::string>()), 1.0);
  const std::string file = dir + "/explore_alpha3_case1.toml";
  EXPECT_NE(slurp(file).find("# Found by `superball explore --alphas 3 --case 1"), std::string::npos);
  const RunResult s = run({"solve", file, "--json", "--precision", "exact"});
  ASSERT_EQ(s.exit_code, 0) << describe(s);
  const nlohmann::json x = json_of(s);
  EXPECT_EQ(x.at("case"), "1");
  EXPECT_EQ(x.at("superball"), true);
  EXPECT_EQ(x.at("velocities_after_exact")[0], j.at("U1"));
  std::remove(file.c_str());
  std::remove(dir.c_str());
}

TEST(Explore, ImpossibleCaseShowsTheClash) {
  const RunResult r = run({"explore", "--alphas", "1,6", "--case", "1", "--starts", "4"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_NE(r.out.find("verdict: no (proved)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("clash of the exact conditions"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("superball (U₁⁺ > a)"), std::string::npos) << r.out;
}

TEST(Explore, SameSeedSameOutput) {
  const std::vector<std::string> args = {"explore", "--alphas", "7", "--case", "3.2", "--starts", "4", "--seed", "5"};
  const RunResult a = run(args), b = run(args);
  ASSERT_EQ(a.exit_code, 0) << describe(a);
  EXPECT_EQ(a.out, b.out);
}

// Issue 25: a box to the ends of double is searched (it was refused as not
// 0 < LOW < HIGH); the witness is confirmed exactly as in any box.
TEST(Explore, TheBoxMayReachTheEndsOfDouble) {
  const RunResult r = run({"explore", "--alphas", "2", "--case", "1", "--box", "1e-300:1e300", "--starts", "4"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_NE(r.out.find("box: every mass and K in [1e-300, 1e+300]"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("verdict: yes"), std::string::npos) << r.out;
}

/// Bad options: exit 2, one line on stderr naming the option, nothing on stdout.
TEST(Explore, BadOptionsAreOneLine) {
  const std::vector<std::pair<std::vector<std::string>, std::vector<std::string>>> cases = {
      {{"explore", "--alphas", "3"}, {"give a case: case, closed or all, or all_patterns"}},
      {{"explore", "--all-patterns", "--case", "1"}, {"all_patterns chooses the patterns and cases: drop case, closed, all, alphas, coupling and scene"}},
      {{"explore", "--alphas", "3", "--case", "1", "--box", "5:1"}, {"box 5:1: needs 0 < LOW < HIGH"}},
      {{"explore", "--alphas", "3", "--case", "1", "--box", "1e-320:1"}, {"box ", ":1: needs 0 < LOW < HIGH with LOW >= 2.2250738585072014e-308"}},
      {{"explore", "--alphas", "3", "--case", "1", "--box", "1:1e400"}, {"box 1:inf: needs", "HIGH finite"}},
      {{"explore", "--alphas", "3", "--case", "1", "--box", "wide"}, {"box: 'wide' is not LOW:HIGH"}},
      {{"explore", "--alphas", "3", "--case", "1", "--starts", "0"}, {"starts must be a whole number from 1 to 100000, got 0"}},
      {{"explore", "--alphas", "3", "--case", "1", "--evaluations", "9"}, {"evaluations must be a whole number from 10 to 10000000, got 9"}},
      {{"explore", "--alphas", "3", "--case", "1", "--obstacle", "finite"}, {"fixed obstacle"}},
      {{"explore", "--alphas", "9", "--case", "1"}, {"9"}}};
  for (const auto& [args, expected] : cases) {
    SCOPED_TRACE(args.back());
    expect_bad_input(run(args), expected);
  }
}

TEST(Cli, Version) {
  const RunResult r = run({"--version"});
  EXPECT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_EQ(r.out.rfind("superball ", 0), 0u) << r.out;
}

}  // namespace
