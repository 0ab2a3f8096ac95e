// The task lists of the long commands (issue 17, superball/distribute/distribute.hpp): the
// output of a run split into shards and merged, resumed from a checkpoint
// after a kill, or run over MPI ranks, is byte for byte that of the run in
// one process; merges of parts that do not make one run are refused with one
// line.
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "support/run.hpp"
#include "support/scale.hpp"

namespace {

namespace fs = std::filesystem;
using superball::test::describe;
using superball::test::run;
using superball::test::run_program;
using superball::test::RunResult;
using superball::test::slurp;

const std::string kPaper = std::string(SUPERBALL_CASES_DIR) + "/scenes/paper-4.4-alpha2.toml";

/// A fresh folder for one test.
std::string folder(const std::string& name) { return superball::test::fresh_folder("distribute", name); }

std::vector<std::string> with(std::vector<std::string> args, const std::vector<std::string>& more) {
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

/// The runs compared: derive of every case of a 5-body pattern (16 cases,
/// text and JSON), sweeps of 5 blocks of values (rows) and 2 (switch
/// points, each block bisected exactly), verify of the 8 cases of a pattern,
/// verify of one case (under MPI its 5 tasks of drawn points and 8 of
/// boundary searches spread over the ranks), explore of the 64 cells of the
/// pattern table and of the 8 cases of a pattern (JSON, on a small budget),
/// each spread over 3 ranks or shards.
const std::vector<std::vector<std::string>>& runs() {
  static const std::vector<std::vector<std::string>> r = {
      {"derive", "--bodies", "5", "--pairs", "near2", "--coupling", "near2", "--all", "--format", "json"},
      {"derive", "--bodies", "5", "--pairs", "near2", "--all"},
      {"sweep", kPaper, "--vary", "K.3-4=0:20:20001", "--csv"},
      {"sweep", kPaper, "--vary", "K.3-4=20:0:8193", "--switch-points"},
      {"verify", "--all", "--alphas", "5", "--samples", "20", "--epsilons", "1e-2", "--boundary-pairs", "2", "--json"},
      {"verify", "--case", "1", "--alphas", "2", "--samples", "900", "--epsilons", "1e-2,1e-3", "--boundary-pairs", "3"},
      {"explore", "--all-patterns", "--starts", "2", "--evaluations", "60"},
      {"explore", "--alphas", "4", "--all", "--json", "--starts", "4", "--evaluations", "200"},
  };
  return r;
}


/// A map across the edge of M positive semi-definite: 81 grid points (41
/// tasks of 2 on one thread), then the bisections of its boundaries.
const std::vector<std::string> kMap = {"map", kPaper, "--x", "K.3-4=0:20:9", "--y", "alpha.2=-150:0:9"};

/// The shard runs of \p args into \p dir (part I written as pI); their paths.
std::vector<std::string> shards(const std::vector<std::string>& args, const std::string& dir, int n) {
  std::vector<std::string> parts;
  for (int i = 1; i <= n; ++i) {
    parts.push_back(dir + "/p" + std::to_string(i));
    const RunResult r = run(with(args, {"--shard", std::to_string(i) + "/" + std::to_string(n), "--part", parts.back()}));
    EXPECT_EQ(r.exit_code, 0) << describe(r);
    EXPECT_EQ(r.out, "") << "a shard writes its part file only";
  }
  return parts;
}

TEST(Distribute, ThreeShardsMergedAreTheSingleRunByteForByte) {
  const std::string dir = folder("shards");
  for (std::size_t k = 0; k < runs().size(); ++k) {
    // Under AddressSanitizer (every process starts far slower) one run of
    // each command: derive, sweep, verify and explore as JSON or CSV.
    if (superball::test::kAddressSanitizer && k % 2 == 1) continue;
    // At the small scale, the derive and the sweep are split and merged below
    // (derive -o, the sweep over 7 shards) and compared with their single run
    // there: the same code paths, run once.
    if (superball::test::small_scale() && (k == 0 || k == 2)) continue;
    const std::vector<std::string>& args = runs()[k];
    const RunResult whole = run(args);
    ASSERT_EQ(whole.exit_code, 0) << describe(whole);
    std::vector<std::string> parts = shards(args, dir, 3);
    // Any order of the parts.
    const RunResult merged = run({"merge", parts[2], parts[0], parts[1]});
    ASSERT_EQ(merged.exit_code, 0) << describe(merged);
    EXPECT_EQ(merged.out, whole.out) << args[0] << " " << args.back();
    EXPECT_EQ(merged.err, "");
  }
  // derive -o through merge -o: the same file.
  const std::vector<std::string> derive = runs()[0];
  ASSERT_EQ(run(with(derive, {"-o", dir + "/whole.json"})).exit_code, 0);
  const auto parts = shards(derive, dir, 3);
  const RunResult merged = run({"merge", parts[0], parts[1], parts[2], "-o", dir + "/merged.json"});
  ASSERT_EQ(merged.exit_code, 0) << describe(merged);
  EXPECT_EQ(slurp(dir + "/merged.json"), slurp(dir + "/whole.json"));
  // verify --out: the scene files of the disagreements, written by the merge (--out), are those of the single run.
  const std::vector<std::string> verify = {"verify", "--all", "--alphas", "5", "--samples", "20", "--epsilons", "1e-2", "--boundary-pairs", "2",
                                           "--out", dir + "/scenes"};
  const RunResult single = run(verify);
  std::map<std::string, std::string> files;
  for (const auto& e : fs::directory_iterator(dir + "/scenes")) files[e.path().string()] = slurp(e.path().string());
  ASSERT_FALSE(files.empty()) << "the asymptotic forms disagree at some points near the boundaries";
  fs::remove_all(dir + "/scenes");
  const auto vparts = shards(verify, dir, 3);
  EXPECT_FALSE(fs::exists(dir + "/scenes")) << "a shard writes its part file only";
  // The parts never say where to write: the merge's own --out does.
  const RunResult vmerged = run({"merge", vparts[0], vparts[1], vparts[2], "--out", dir + "/scenes"});
  EXPECT_EQ(vmerged.out, single.out);
  EXPECT_EQ(vmerged.exit_code, single.exit_code);
  std::map<std::string, std::string> merged_files;
  for (const auto& e : fs::directory_iterator(dir + "/scenes")) merged_files[e.path().string()] = slurp(e.path().string());
  EXPECT_EQ(merged_files, files);
  // More shards than tasks: the empty parts merge too (5 blocks, 7 shards).
  const auto many = shards(runs()[2], dir, 7);
  std::vector<std::string> args = {"merge"};
  args.insert(args.end(), many.begin(), many.end());
  EXPECT_EQ(run(args).out, run(runs()[2]).out);
}

TEST(Distribute, MergesThatAreNotOneRunAreRefusedWithOneLine) {
  const std::string dir = folder("bad-merges");
  const auto a = shards(runs()[2], dir + "/", 3);
  fs::create_directories(dir + "/b");
  const auto b = shards(with(runs()[2], {"--precision", "long-double"}), dir + "/b", 3);
  auto expect_refused = [](const std::vector<std::string>& args, const std::vector<std::string>& says) {
    const RunResult r = run(args);
    EXPECT_EQ(r.exit_code, 2) << describe(r);
    EXPECT_EQ(r.out, "");
    ASSERT_EQ(r.err_lines().size(), 1u) << r.err;
    for (const std::string& s : says) EXPECT_NE(r.err.find(s), std::string::npos) << "'" << s << "' not in: " << r.err;
  };
  expect_refused({"merge", a[0], a[2]}, {"merge: part 2 of 3 of run", "is missing"});
  expect_refused({"merge", a[0], b[1], a[2]}, {"merge: " + b[1], "a part of another run", "--precision=long-double"});
  expect_refused({"merge", a[0], a[1], a[1], a[2]}, {"merge: " + a[1], "part 2 of 3 again"});
  const auto four = shards(runs()[2], dir + "/b", 4);
  expect_refused({"merge", a[0], a[1], four[2]}, {"merge: " + four[2], "part 3 of 4, but"});
  // A part cut short (a copy that did not finish), a file that is not a part, no part at all.
  const std::string text = slurp(a[1]);
  std::ofstream(dir + "/short", std::ios::binary) << text.substr(0, text.size() / 2);
  expect_refused({"merge", a[0], dir + "/short", a[2]}, {"merge: " + dir + "/short", "cut short"});
  expect_refused({"merge", a[0], kPaper, a[2]}, {"merge: " + kPaper, "not a part file of superball"});
  expect_refused({"merge", a[0], dir + "/none", a[2]}, {"merge: " + dir + "/none", "cannot be read"});
  expect_refused({"merge"}, {"merge: no part file"});
  expect_refused({"merge", a[0], a[1], a[2], "-o", dir + "/x"}, {"merge: -o: sweep writes to standard output; redirect it"});
  EXPECT_FALSE(fs::exists(dir + "/x"));
  // The scene changed since the shards ran: the command now makes another run.
  const std::string scene = dir + "/scene.toml";
  fs::copy_file(kPaper, scene);
  const auto c = shards({"sweep", scene, "--vary", "K.3-4=0:20:101"}, dir + "/b", 2);
  std::ofstream(scene, std::ios::app) << "# edited\n";
  expect_refused({"merge", c[0], c[1]}, {"merge: the parts are of run", "a file it reads or the superball version changed"});
  // Bad --shard values.
  for (const std::string s : {"0/3", "4/3", "3", "1/0", "a/b", "1/3x"}) {
    const RunResult r = run(with(runs()[2], {"--shard", s}));
    EXPECT_EQ(r.exit_code, 2) << s << describe(r);
    EXPECT_NE(r.err.find("--shard: '" + s + "' is not I/N"), std::string::npos) << r.err;
  }
}

TEST(Distribute, ACheckpointResumesWithTheSameBytesAndRefusesAnotherRun) {
  const std::string dir = folder("checkpoint");
  const auto& args = runs()[2];
  const RunResult whole = run(args);
  const RunResult first = run(with(args, {"--checkpoint", dir + "/ck"}));
  ASSERT_EQ(first.exit_code, 0) << describe(first);
  EXPECT_EQ(first.out, whole.out);
  // Two blocks lost: the run again computes those two only, and says so.
  fs::remove(dir + "/ck/task-00000001");
  fs::remove(dir + "/ck/task-00000004");
  const RunResult again = run(with(args, {"--checkpoint", dir + "/ck", "--threads", "1"}));
  ASSERT_EQ(again.exit_code, 0) << describe(again);
  EXPECT_EQ(again.out, whole.out);
  EXPECT_EQ(again.err, "superball: --checkpoint " + dir + "/ck: 3 of 5 tasks done already, 2 to compute\n");
  // The folder of another run.
  const RunResult other = run({"sweep", kPaper, "--vary", "K.3-4=0:20:20002", "--checkpoint", dir + "/ck"});
  EXPECT_EQ(other.exit_code, 2);
  EXPECT_EQ(other.out, "");
  EXPECT_NE(other.err.find("--checkpoint " + dir + "/ck: holds run"), std::string::npos) << other.err;
  EXPECT_NE(other.err.find("--vary=K.3-4=0:20:20001"), std::string::npos) << other.err;
}

/// A checkpoint whose task 2 cannot be kept: a folder that is not empty holds its name.
std::string unwritable_checkpoint(const std::string& name) {
  const std::string dir = folder(name);
  fs::create_directories(dir + "/ck/task-00000001/x");
  return dir;
}

TEST(Distribute, ACheckpointWhoseTaskCannotBeKeptIsRefusedBeforeAnyWork) {
  // The folder cannot be removed to compute its task again (nothing of the user's is deleted):
  // refused in one line when the checkpoint is read, before any task runs, and nothing written.
  const std::string dir = unwritable_checkpoint("unwritable");
  const RunResult r = run(with(runs()[0], {"--checkpoint", dir + "/ck", "-o", dir + "/out.json"}));
  EXPECT_EQ(r.exit_code, 2) << describe(r);
  EXPECT_EQ(r.err, "superball: --checkpoint " + dir + "/ck: task-00000001: a folder, not a file: not read; it cannot be removed to compute task 1 " +
                       "again (Directory not empty): remove it, or give another folder\n");
  EXPECT_FALSE(fs::exists(dir + "/out.json"));
  EXPECT_TRUE(fs::exists(dir + "/ck/task-00000001/x"));
}

TEST(Distribute, KilledAndResumedGivesTheUninterruptedOutput) {
  // derive of a 5-body pattern: 16 cases, one worker process; killed (SIGKILL)
  // once a few cases are in the checkpoint, then run again.
  const std::string dir = folder("kill");
  const std::vector<std::string> args = {"derive", "--bodies", "5", "--pairs", "near2", "--coupling", "near2", "--all", "--format", "json", "--jobs", "1"};
  const RunResult whole = run(args);
  ASSERT_EQ(whole.exit_code, 0) << describe(whole);
  const std::string out = dir + "/out.json", ck = dir + "/ck";
  std::vector<std::string> argv_s = {SUPERBALL_EXE};
  for (const auto& a : with(args, {"--checkpoint", ck, "-o", out})) argv_s.push_back(a);
  std::vector<char*> argv;
  for (auto& a : argv_s) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  ASSERT_EQ(posix_spawn(&pid, SUPERBALL_EXE, nullptr, nullptr, argv.data(), environ), 0);
  auto done = [&] {
    std::size_t n = 0;
    std::error_code error;
    for (const auto& e : fs::directory_iterator(ck, error)) {
      const std::string name = e.path().filename().string();
      n += name.rfind("task-", 0) == 0 && name.find(".tmp") == std::string::npos;  // not one being written
    }
    return n;
  };
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (done() < 3 && std::chrono::steady_clock::now() < deadline) std::this_thread::sleep_for(std::chrono::milliseconds(2));
  ::kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  const std::size_t kept = done();
  ASSERT_GE(kept, 3u);
  // Killed before the end (else the machine was too fast: then a resume of every case):
  // the output is not there, not even in part (a SIGKILL leaves only Output's hidden temporary).
  if (WIFSIGNALED(status)) {
    EXPECT_FALSE(fs::exists(out)) << "the killed run wrote its output";
  }
  const RunResult resumed = run(with(args, {"--checkpoint", ck, "-o", out}));
  ASSERT_EQ(resumed.exit_code, 0) << describe(resumed);
  EXPECT_EQ(slurp(out), whole.out);
  EXPECT_NE(resumed.err.find(std::to_string(kept) + " of 16 tasks done already, " + std::to_string(16 - kept) + " to compute"), std::string::npos)
      << resumed.err;
}

/// The lines of \p err that superball wrote (not the launcher's notes).
std::vector<std::string> superball_lines(const RunResult& r) {
  std::vector<std::string> lines;
  for (const std::string& line : r.err_lines())
    if (line.rfind("superball:", 0) == 0) lines.push_back(line);
  return lines;
}

/// The names of the task files in the checkpoint folder \p dir.
std::vector<std::string> task_files(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  names.erase(std::remove_if(names.begin(), names.end(), [](const std::string& n) { return n.rfind("task-", 0) != 0; }), names.end());
  return names;
}

TEST(Distribute, AMapResumesFromItsCheckpointInBothStages) {
  // map's two task lists, its grid points and then its bisections, each kept
  // in a subfolder of the checkpoint.
  const std::string dir = folder("map-checkpoint"), ck = dir + "/ck";
  const std::vector<std::string> args = with(kMap, {"--json", "--threads", "1"});
  const RunResult whole = run(args);
  ASSERT_EQ(whole.exit_code, 0) << describe(whole);
  // Task 5 of the grid points fails (the test hook of distribute/src/distribute.cpp): no
  // output, the four before it kept, no bisection begun.
  ::setenv("SUPERBALL_TEST_FAIL_TASK", "5", 1);
  const RunResult failed = run(with(args, {"--checkpoint", ck}));
  ::unsetenv("SUPERBALL_TEST_FAIL_TASK");
  EXPECT_EQ(failed.exit_code, 4) << describe(failed);
  EXPECT_EQ(failed.out, "");
  EXPECT_EQ(task_files(ck + "/points"), (std::vector<std::string>{"task-00000000", "task-00000001", "task-00000002", "task-00000003"}));
  EXPECT_FALSE(fs::exists(ck + "/boundaries"));
  // Run again: the same bytes as the run without a checkpoint.
  const RunResult resumed = run(with(args, {"--checkpoint", ck}));
  ASSERT_EQ(resumed.exit_code, 0) << describe(resumed);
  EXPECT_EQ(resumed.out, whole.out);
  EXPECT_EQ(resumed.err, "superball: --checkpoint " + ck + "/points: 4 of 41 tasks done already, 37 to compute\n");
  // Two tasks of each stage lost (on two threads now): only those computed again.
  const std::size_t bisections = task_files(ck + "/boundaries").size();
  ASSERT_GE(bisections, 2u);
  fs::remove(ck + "/points/task-00000007");
  fs::remove(ck + "/points/task-00000030");
  fs::remove(ck + "/boundaries/task-00000000");
  fs::remove(ck + "/boundaries/" + task_files(ck + "/boundaries").back());
  const RunResult again = run(with(kMap, {"--json", "--threads", "2", "--checkpoint", ck}));
  ASSERT_EQ(again.exit_code, 0) << describe(again);
  EXPECT_EQ(again.out, whole.out);
  EXPECT_EQ(again.err, "superball: --checkpoint " + ck + "/points: 39 of 41 tasks done already, 2 to compute\n" + "superball: --checkpoint " + ck +
                           "/boundaries: " + std::to_string(bisections - 2) + " of " + std::to_string(bisections) + " tasks done already, 2 to compute\n");
  // The folder of another map: refused with one line, nothing written.
  const RunResult other = run({"map", kPaper, "--x", "K.3-4=0:20:9", "--y", "alpha.2=-150:0:11", "--checkpoint", ck});
  EXPECT_EQ(other.exit_code, 2) << describe(other);
  EXPECT_EQ(other.out, "");
  EXPECT_EQ(superball_lines(other).size(), 1u) << other.err;
  EXPECT_NE(other.err.find("--checkpoint " + ck + "/points: holds run"), std::string::npos) << other.err;
  // No shards of a map: its bisections need every grid point.
  const RunResult shard = run(with(kMap, {"--shard", "1/2"}));
  EXPECT_EQ(shard.exit_code, 2) << describe(shard);
  EXPECT_EQ(shard.out, "");
  EXPECT_EQ(shard.err,
            "superball: map: --shard: a map is not split into shards (its bisections need every grid point first); run it over MPI ranks, or resume it with "
            "--checkpoint\n");
}

#ifdef SUPERBALL_MPIEXEC
/// `mpirun -n P superball ARGS...` (as root in a container too, more ranks than cores).
/// \p environment: NAME=VALUE set in every rank.
RunResult mpirun(int ranks, const std::vector<std::string>& args, const std::vector<std::string>& environment = {}) {
  // No single-copy transfers (CMA): containers often forbid the ptrace they need.
  std::vector<std::string> all = {"--oversubscribe", "--allow-run-as-root", "--mca", "btl_vader_single_copy_mechanism", "none",
                                  "-n", std::to_string(ranks)};
  for (const std::string& e : environment) all.insert(all.end(), {"-x", e});
  all.push_back(SUPERBALL_EXE);
  all.insert(all.end(), args.begin(), args.end());
  return run_program(SUPERBALL_MPIEXEC, all);
}

/// The option that makes a run use one thread (or worker process) per rank.
std::vector<std::string> one_thread(const std::string& command) {
  if (command == "derive") return {"--jobs", "1"};
  if (command == "explore") return {};  // one thread always
  return {"--threads", "1"};
}

TEST(DistributeMpi, TwoAndThreeRanksGiveTheSingleProcessOutputByteForByte) {
  for (const auto& args : runs()) {
    const RunResult whole = run(args);
    ASSERT_EQ(whole.exit_code, 0) << describe(whole);
    for (int p : {2, 3}) {
      const RunResult r = mpirun(p, with(args, one_thread(args[0])));
      ASSERT_EQ(r.exit_code, 0) << p << " ranks: " << describe(r);
      EXPECT_EQ(r.out, whole.out) << p << " ranks: " << args[0] << " " << args.back();
      EXPECT_EQ(r.err, "");
    }
  }
}

TEST(DistributeMpi, RanksWithACheckpointResume) {
  const std::string dir = folder("mpi-checkpoint");
  const auto& args = runs()[0];
  const RunResult whole = run(args);
  const RunResult first = mpirun(3, with(args, {"--checkpoint", dir}));
  ASSERT_EQ(first.exit_code, 0) << describe(first);
  EXPECT_EQ(first.out, whole.out);
  for (const std::string k : {"00000000", "00000007", "00000015"}) fs::remove(dir + "/task-" + k);
  const RunResult again = mpirun(2, with(args, {"--checkpoint", dir}));
  ASSERT_EQ(again.exit_code, 0) << describe(again);
  EXPECT_EQ(again.out, whole.out);
  EXPECT_EQ(again.err, "superball: --checkpoint " + dir + ": 13 of 16 tasks done already, 3 to compute\n");
}

TEST(DistributeMpi, ACheckpointWhoseTaskCannotBeKeptIsRefusedBeforeAnyWork) {
  // Rank 0 reads the checkpoint before any task is handed out: one line, exit 2, no output.
  const std::string dir = unwritable_checkpoint("mpi-unwritable");
  const RunResult r = mpirun(3, with(runs()[0], {"--checkpoint", dir + "/ck", "-o", dir + "/out.json"}));
  EXPECT_EQ(r.exit_code, 2) << describe(r);
  EXPECT_NE(r.err.find("superball: --checkpoint " + dir + "/ck: task-00000001: a folder, not a file: not read; it cannot be removed"), std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir + "/out.json"));
}

TEST(DistributeMpi, BadInputIsOneLineFromRankZero) {
  const RunResult r = mpirun(3, {"sweep", kPaper, "--vary", "K.3-4=0:20:1"});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(r.out, "");
  std::size_t said = 0;
  for (const std::string& line : r.err_lines()) said += line.rfind("superball: --vary K.3-4=0:20:1: STEPS must be", 0) == 0;
  EXPECT_EQ(said, 1u) << r.err;
  const RunResult shard = mpirun(2, with(runs()[2], {"--shard", "1/2"}));
  EXPECT_NE(shard.exit_code, 0);
  EXPECT_NE(shard.err.find("--shard runs one part in one process"), std::string::npos) << shard.err;
  // An error of rank 0 alone (the checkpoint folder of another run) while the
  // other ranks wait for it: one line, the job ended (it was left hanging).
  const std::string dir = folder("mpi-other-run");
  ASSERT_EQ(run(with(runs()[2], {"--checkpoint", dir})).exit_code, 0);
  const RunResult other = mpirun(2, {"sweep", kPaper, "--vary", "K.3-4=0:20:20002", "--checkpoint", dir});
  EXPECT_EQ(other.exit_code, 2) << describe(other);
  EXPECT_EQ(other.out, "");
  ASSERT_EQ(superball_lines(other).size(), 1u) << other.err;
  EXPECT_EQ(superball_lines(other)[0].rfind("superball: --checkpoint " + dir + ": holds run", 0), 0u) << other.err;
  // A command that is not a task list would run whole on every rank: refused.
  const RunResult solve = mpirun(2, {"solve", kPaper});
  EXPECT_EQ(solve.out, "");
  EXPECT_NE(solve.err.find("superball: solve does not spread over MPI ranks"), std::string::npos) << solve.err;
}

TEST(DistributeMpi, OneVerifyCaseOverRanksWritesTheSameSceneFiles) {
  // The disagreements of one case come back from the ranks as text (their
  // points as fractions); rank 0 makes their scene files again from them.
  const std::string dir = folder("mpi-one-case"), out = dir + "/scenes";
  const std::vector<std::string> args = {"verify", "--case", "3.2", "--alphas", "5", "--samples", "400", "--epsilons", "1e-2,1e-3",
                                         "--boundary-pairs", "3", "--out", out};
  auto files = [&] {
    std::map<std::string, std::string> f;
    for (const auto& e : fs::directory_iterator(out)) f[e.path().filename().string()] = slurp(e.path().string());
    fs::remove_all(out);
    return f;
  };
  const RunResult single = run(args);
  ASSERT_EQ(single.exit_code, 0) << describe(single);
  const auto expected = files();
  ASSERT_GT(expected.size(), 10u) << "the asymptotic forms disagree near the boundaries";
  for (int p : {2, 3}) {
    const RunResult r = mpirun(p, with(args, {"--threads", "1"}));
    ASSERT_EQ(r.exit_code, 0) << describe(r);
    EXPECT_EQ(r.out, single.out) << p << " ranks";
    EXPECT_EQ(files(), expected) << p << " ranks";
  }
  // With a checkpoint: the case kept, the same command again computes nothing and writes the same.
  const RunResult first = mpirun(2, with(args, {"--checkpoint", dir + "/ck"}));
  ASSERT_EQ(first.exit_code, 0) << describe(first);
  EXPECT_EQ(files(), expected);
  const RunResult again = mpirun(2, with(args, {"--checkpoint", dir + "/ck"}));
  ASSERT_EQ(again.exit_code, 0) << describe(again);
  EXPECT_EQ(again.out, single.out);
  EXPECT_EQ(again.err, "superball: --checkpoint " + dir + "/ck: 1 of 1 tasks done already, 0 to compute\n");
  EXPECT_EQ(files(), expected);
}

/// A small map across the edge of M's PSD cone (K₃₄, α₂ at §4.4): 81 points
/// (41 tasks of 2), then its bisections, as tasks over the ranks.
TEST(DistributeMpi, AMapOverRanksIsTheSingleProcessMapByteForByte) {
  // Every output of map: the summary with the boundary points, the grid and
  // the boundary points as CSV, everything as JSON.
  for (const std::vector<std::string>& output : std::vector<std::vector<std::string>>{{"--boundary-points"}, {"--csv"}, {"--boundary-points", "--csv"}, {"--json"}}) {
    const RunResult whole = run(with(kMap, output));
    ASSERT_EQ(whole.exit_code, 0) << describe(whole);
    ASSERT_NE(whole.out.find(output[0] == "--json" ? "\"boundaries\"" : output.back() == "--csv" ? "," : "M not PSD"), std::string::npos) << whole.out;
    for (int p : {2, 3}) {
      const RunResult r = mpirun(p, with(with(kMap, output), {"--threads", "1"}));
      ASSERT_EQ(r.exit_code, 0) << p << " ranks: " << describe(r);
      EXPECT_EQ(r.out, whole.out) << p << " ranks: map " << output.back();
      EXPECT_EQ(r.err, "");
    }
  }
  // --plot: rank 0 draws the figure from the whole map; its data and script are the single run's bytes.
  const std::string one = folder("map-plot-one"), two = folder("map-plot-two");
  ASSERT_EQ(run(with(kMap, {"--plot", one + "/m"})).exit_code, 0);
  const RunResult plotted = mpirun(2, with(kMap, {"--plot", two + "/m", "--threads", "1"}));
  ASSERT_EQ(plotted.exit_code, 0) << describe(plotted);
  for (const std::string file : {"/m.dat", "/m.gp"}) EXPECT_EQ(slurp(two + file), slurp(one + file)) << file;
  EXPECT_GT(fs::file_size(two + "/m.png"), 0u);
  EXPECT_GT(fs::file_size(two + "/m.svg"), 0u);
  // Bad input: one line, from rank 0.
  const RunResult bad = mpirun(2, {"map", kPaper, "--x", "K.3-4=0:20:5", "--y", "alpha.2=-400:-200:5"});
  EXPECT_EQ(bad.exit_code, 2) << describe(bad);
  EXPECT_EQ(bad.out, "");
  ASSERT_EQ(superball_lines(bad).size(), 1u) << bad.err;
  EXPECT_NE(superball_lines(bad)[0].find("not positive semi-definite at any point of the map"), std::string::npos) << bad.err;
}

TEST(DistributeMpi, AMapOverRanksResumesFromItsCheckpoint) {
  const std::string dir = folder("mpi-map-checkpoint"), ck = dir + "/ck";
  const std::vector<std::string> args = with(kMap, {"--json", "--threads", "1"});
  const RunResult whole = run(args);
  ASSERT_EQ(whole.exit_code, 0) << describe(whole);
  // Task 5 of the grid points fails on some rank; rank 0 kept what it gathered.
  const RunResult failed = mpirun(3, with(args, {"--checkpoint", ck}), {"SUPERBALL_TEST_FAIL_TASK=5"});
  EXPECT_EQ(failed.exit_code, 4) << describe(failed);
  EXPECT_EQ(failed.out, "");
  EXPECT_FALSE(fs::exists(ck + "/points/task-00000004"));
  // Resumed on 2 ranks: the single run's bytes; then a run with every task kept computes nothing.
  const RunResult resumed = mpirun(2, with(args, {"--checkpoint", ck}));
  ASSERT_EQ(resumed.exit_code, 0) << describe(resumed);
  EXPECT_EQ(resumed.out, whole.out);
  EXPECT_EQ(resumed.err.rfind("superball: --checkpoint " + ck + "/points: ", 0), 0u) << resumed.err;
  const std::string bisections = std::to_string(task_files(ck + "/boundaries").size());
  const RunResult again = mpirun(3, with(args, {"--checkpoint", ck}));
  ASSERT_EQ(again.exit_code, 0) << describe(again);
  EXPECT_EQ(again.out, whole.out);
  EXPECT_EQ(again.err, "superball: --checkpoint " + ck + "/points: 41 of 41 tasks done already, 0 to compute\n" + "superball: --checkpoint " + ck +
                           "/boundaries: " + bisections + " of " + bisections + " tasks done already, 0 to compute\n");
}

TEST(DistributeMpi, ATaskThatFailsOnARankIsOneLineNamingItAndNoOutput) {
  // No task of these commands fails on valid input: the test hook
  // SUPERBALL_TEST_FAIL_TASK=K (distribute/src/distribute.cpp) makes task K throw on
  // whichever rank runs it.
  const std::string dir = folder("mpi-failing");
  const std::vector<std::string> hook = {"SUPERBALL_TEST_FAIL_TASK=5"};
  // derive -o with a checkpoint: no output file (not even in part), one line naming the rank and task 5 of 16.
  const RunResult derive = mpirun(3, with(runs()[0], {"--jobs", "1", "--checkpoint", dir + "/ck", "-o", dir + "/out.json"}), hook);
  EXPECT_EQ(derive.exit_code, 4) << describe(derive);
  EXPECT_EQ(derive.out, "");
  ASSERT_EQ(superball_lines(derive).size(), 1u) << derive.err;
  EXPECT_TRUE(std::regex_match(superball_lines(derive)[0], std::regex("superball: internal error: rank [012], task 5 of 16: SUPERBALL_TEST_FAIL_TASK=5: .*")))
      << superball_lines(derive)[0];
  EXPECT_FALSE(fs::exists(dir + "/out.json"));
  // The tasks before it were kept; the run again (without the hook) finishes with the single run's bytes.
  for (const std::string k : {"00000000", "00000001", "00000002", "00000003"}) EXPECT_TRUE(fs::exists(dir + "/ck/task-" + k)) << k;
  EXPECT_FALSE(fs::exists(dir + "/ck/task-00000004"));
  const RunResult again = mpirun(2, with(runs()[0], {"--jobs", "1", "--checkpoint", dir + "/ck", "-o", dir + "/out.json"}));
  ASSERT_EQ(again.exit_code, 0) << describe(again);
  EXPECT_EQ(slurp(dir + "/out.json"), run(runs()[0]).out);
  // verify of one case: its tasks are blocks of points (5 of drawn points here), spread over the ranks.
  const RunResult one = mpirun(2, with(runs()[5], {"--threads", "1"}), hook);
  EXPECT_EQ(one.exit_code, 4) << describe(one);
  EXPECT_EQ(one.out, "");
  ASSERT_EQ(superball_lines(one).size(), 1u) << one.err;
  EXPECT_TRUE(std::regex_match(superball_lines(one)[0], std::regex("superball: internal error: rank [01], task 5 of 5: SUPERBALL_TEST_FAIL_TASK=5: .*")))
      << superball_lines(one)[0];
  // sweep to standard output: the blocks before the failing one are written, none after it.
  const RunResult sweep = mpirun(3, with(runs()[2], {"--threads", "1"}), {"SUPERBALL_TEST_FAIL_TASK=3"});
  EXPECT_EQ(sweep.exit_code, 4) << describe(sweep);
  const std::string whole = run(runs()[2]).out;
  std::size_t rows = 0, at = 0;
  for (; rows < 1 + 2 * 4096; ++rows) at = whole.find('\n', at) + 1;  // the header and blocks 1 and 2
  EXPECT_EQ(sweep.out, whole.substr(0, at));
  ASSERT_EQ(superball_lines(sweep).size(), 1u) << sweep.err;
  EXPECT_NE(superball_lines(sweep)[0].find("task 3 of 5: SUPERBALL_TEST_FAIL_TASK=3"), std::string::npos) << superball_lines(sweep)[0];
  // map: a task of its grid points (41 of 2 points) fails; nothing written.
  const RunResult map = mpirun(3, with(kMap, {"--threads", "1"}), hook);
  EXPECT_EQ(map.exit_code, 4) << describe(map);
  EXPECT_EQ(map.out, "");
  ASSERT_EQ(superball_lines(map).size(), 1u) << map.err;
  EXPECT_TRUE(std::regex_match(superball_lines(map)[0], std::regex("superball: internal error: rank [012], task 5 of 41: SUPERBALL_TEST_FAIL_TASK=5: .*")))
      << superball_lines(map)[0];
}
#endif

}  // namespace
