// Parts and checkpoints are data, never commands (issue 25): a part file
// never says where `merge` writes or which shard it runs; every task record
// carries a checksum of its run, its task and its result; a record or task
// file that is cut short, damaged, too large, a link, a FIFO or a folder is
// refused before it is read (merge) or computed again (--checkpoint); a
// result forged with a right checksum is still checked against the run.
// Every refusal is one line, never a C++ exception's text.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "support/run.hpp"

namespace {

namespace fs = std::filesystem;
using superball::test::kAddressSanitizer;
using superball::test::describe;
using superball::test::run;
using superball::test::RunResult;
using superball::test::slurp;

const std::string kPaper = std::string(SUPERBALL_CASES_DIR) + "/scenes/paper-4.4-alpha2.toml";

/// A fresh folder for one test.
std::string folder(const std::string& name) { return superball::test::fresh_folder("data", name); }

void write(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

std::vector<std::string> with(std::vector<std::string> args, const std::vector<std::string>& more) {
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

/// A refusal: exit \p code, nothing on standard output, one line on standard
/// error holding each of \p says and no C++ exception's text.
void expect_refused(const RunResult& r, const std::vector<std::string>& says, int code = 2) {
  EXPECT_EQ(r.exit_code, code) << describe(r);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err_lines().size(), 1u) << r.err;
  EXPECT_EQ(r.err.rfind("superball: ", 0), 0u) << r.err;
  for (const char* raw : {"basic_string", "std::", "bad_alloc", "_M_create", "substr", "stoull", "stoi", "json.exception", "internal error"})
    EXPECT_EQ(r.err.find(raw), std::string::npos) << raw << " in: " << r.err;
  for (const std::string& s : says) EXPECT_NE(r.err.find(s), std::string::npos) << "'" << s << "' not in: " << r.err;
}

/// The checksum of a record (distribute/src/distribute.cpp): FNV-1a over the run, the
/// task and the text, each followed by its length; what a forger computes.
std::string checksum(const std::string& run, std::size_t k, const std::string& text) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (const std::string& s : {std::string("superball task"), run, std::to_string(k), text}) {
    for (unsigned char c : s) h = (h ^ c) * 0x100000001b3ULL;
    const std::uint64_t n = s.size();
    for (int i = 0; i < 8; ++i) h = (h ^ ((n >> (8 * i)) & 0xff)) * 0x100000001b3ULL;
  }
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

/// \p file (a part, or a checkpoint's task file of run \p run) with task
/// \p k's result edited by \p edit; its checksum made right again when \p forge.
std::string edited(const std::string& file, const std::string& run, std::size_t k, const std::function<std::string(std::string)>& edit, bool forge) {
  const std::string head = "task " + std::to_string(k) + " ";
  std::size_t at = file.rfind(head, 0) == 0 ? 0 : file.find("\n" + head);
  EXPECT_NE(at, std::string::npos) << "no record of task " << k;
  if (at == std::string::npos) return file;
  at += file[at] == '\n';
  const std::size_t eol = file.find('\n', at);
  std::size_t size = 0;
  char sum[17] = {};
  EXPECT_EQ(std::sscanf(file.c_str() + at + head.size(), "%zu %16s", &size, sum), 2);
  const std::string text = edit(file.substr(eol + 1, size));
  EXPECT_NE(text, file.substr(eol + 1, size)) << "the edit changed nothing";
  return file.substr(0, at) + head + std::to_string(text.size()) + " " + (forge ? checksum(run, k, text) : std::string(sum)) + "\n" + text +
         file.substr(eol + 1 + size);
}

/// The run named by a part file or a checkpoint's run file (its second line).
std::string run_of(const std::string& file) { return file.substr(file.find("run ") + 4, 16); }

/// \p text with its first \p from replaced by \p to.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "'" << from << "' not found";
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

/// The shard runs of \p args into \p dir (part I written as pI); their paths.
std::vector<std::string> shards(const std::vector<std::string>& args, const std::string& dir, int n) {
  std::vector<std::string> parts;
  for (int i = 1; i <= n; ++i) {
    parts.push_back(dir + "/p" + std::to_string(i));
    const RunResult r = run(with(args, {"--shard", std::to_string(i) + "/" + std::to_string(n), "--part", parts.back()}));
    EXPECT_EQ(r.exit_code, 0) << describe(r);
  }
  return parts;
}

const std::vector<std::string> kExplore = {"explore", "--all", "--alphas", "2", "--starts", "2", "--evaluations", "60"};
const std::vector<std::string> kSwitches = {"sweep", kPaper, "--vary", "K.3-4=0:20:8193", "--switch-points"};

TEST(DistributeData, APartNeverSaysWhereMergeWritesOrWhichShardItRuns) {
  const std::string dir = folder("inject");
  const auto parts = shards(kExplore, dir, 2);
  const std::string victim = dir + "/victim";
  // The reproducers: the same argument added to both parts.
  for (const std::string& injected : std::vector<std::string>{"--output=" + victim, "--shard=1/2 --part=" + victim, "--out=" + dir + "/w", "--help", "-o"}) {
    std::vector<std::string> args = {"merge"};
    for (const std::string& p : parts) {
      std::string text = slurp(p), lines;
      std::size_t from = 0;
      for (std::size_t space; from <= injected.size(); from = space + 1) {
        space = injected.find(' ', from);
        if (space == std::string::npos) space = injected.size();
        const std::string a = injected.substr(from, space - from);
        lines += "argument " + std::to_string(a.size()) + " " + a + "\n";
      }
      write(p + ".bad", replaced(text, "tasks ", lines + "tasks "));
      args.push_back(p + ".bad");
    }
    write(victim, "kept\n");
    expect_refused(run(args), {"merge: " + parts[0] + ".bad: a stored argument '" + injected.substr(0, injected.find(' ')) + "'"});
    EXPECT_EQ(slurp(victim), "kept\n") << injected;
    EXPECT_FALSE(fs::exists(dir + "/w"));
  }
  // An argument of the run edited in both parts (the run's name kept): another run.
  std::vector<std::string> args = {"merge"};
  for (const std::string& p : parts) {
    write(p + ".starts", replaced(slurp(p), "argument 10 --starts=2", "argument 10 --starts=3"));
    args.push_back(p + ".starts");
  }
  expect_refused(run(args), {"merge: the parts are of run"});
  // merge's own command line says where: -o for the report, --out for the witnesses.
  const RunResult whole = run(with(kExplore, {"--out", dir + "/one"}));
  ASSERT_EQ(whole.exit_code, 0) << describe(whole);
  const RunResult merged = run({"merge", parts[1], parts[0], "-o", dir + "/report.txt", "--out", dir + "/two"});
  ASSERT_EQ(merged.exit_code, 0) << describe(merged);
  EXPECT_EQ(merged.out, "");
  EXPECT_EQ(slurp(dir + "/report.txt"), whole.out);
  std::vector<std::string> one, two;
  for (const auto& e : fs::directory_iterator(dir + "/one")) one.push_back(e.path().filename().string() + slurp(e.path().string()));
  for (const auto& e : fs::directory_iterator(dir + "/two")) two.push_back(e.path().filename().string() + slurp(e.path().string()));
  std::sort(one.begin(), one.end()), std::sort(two.begin(), two.end());
  EXPECT_FALSE(one.empty()) << "the witnesses of case yes";
  EXPECT_EQ(one, two);
  // The part of a command without those options: refused, nothing written.
  const auto sweep = shards(kSwitches, dir, 1);
  expect_refused(run({"merge", sweep[0], "--out", dir + "/three"}), {"merge: --out: sweep writes no scene files"});
  EXPECT_FALSE(fs::exists(dir + "/three"));
}

TEST(DistributeData, APartCutShortAnywhereIsRefusedWithOneLine) {
  const std::string dir = folder("cut");
  const auto parts = shards({"sweep", kPaper, "--vary", "K.3-4=0:20:101", "--switch-points"}, dir, 1);
  const std::string text = slurp(parts[0]);
  ASSERT_EQ(run({"merge", parts[0]}).exit_code, 0);
  // Every cut, on 4 threads (each run is mostly the start of a process).  Under AddressSanitizer a
  // process starts about 20 times slower: there the cuts are those within a byte of a line's end,
  // where the reader changes what it reads, and every 8th byte between them.
  std::vector<std::size_t> cuts;
  for (std::size_t cut = 0; cut < text.size(); ++cut) {
    const bool near_line_end = text[cut] == '\n' || (cut > 0 && text[cut - 1] == '\n') || (cut + 1 < text.size() && text[cut + 1] == '\n');
    if (!kAddressSanitizer || near_line_end || cut % 8 == 0) cuts.push_back(cut);
  }
  std::vector<RunResult> results(cuts.size());
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < 4; ++t)
    threads.emplace_back([&, t] {
      for (std::size_t c = t; c < cuts.size(); c += 4) {
        const std::string file = dir + "/cut" + std::to_string(t);
        write(file, text.substr(0, cuts[c]));
        results[c] = run({"merge", file});
      }
    });
  for (std::thread& t : threads) t.join();
  for (std::size_t c = 0; c < cuts.size(); ++c) {
    SCOPED_TRACE("cut at byte " + std::to_string(cuts[c]) + " of " + std::to_string(text.size()));
    expect_refused(results[c], {"merge: " + dir + "/cut" + std::to_string(c % 4) + ": "});
  }
  // Bytes after 'end': a few, or a sparse tail of 20 GB (not read: refused at once).
  write(dir + "/tail", text + "x");
  expect_refused(run({"merge", dir + "/tail"}), {"1 bytes after its 'end' line"});
  write(dir + "/huge", text);
  ASSERT_EQ(::truncate((dir + "/huge").c_str(), 20LL << 30), 0);
  const auto start = std::chrono::steady_clock::now();
  expect_refused(run({"merge", dir + "/huge"}), {"bytes after its 'end' line", "not read"});
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
  fs::remove(dir + "/huge");
  // Not a regular file: a FIFO (not waited for), a folder.
  ASSERT_EQ(::mkfifo((dir + "/fifo").c_str(), 0600), 0);
  expect_refused(run({"merge", dir + "/fifo"}), {"merge: " + dir + "/fifo: a FIFO, not a regular file: not read"});
  expect_refused(run({"merge", dir}), {"merge: " + dir + ": a folder, not a file: not read"});
  // A part of the format before this one.
  write(dir + "/old", replaced(text, "superball part 2", "superball part 1"));
  expect_refused(run({"merge", dir + "/old"}), {"a part file of another format ('superball part 1'", "make it again with this superball"});
}

TEST(DistributeData, ARecordThatFailsItsChecksumOrClaimsTooMuchIsRefusedBeforeItIsRead) {
  const std::string dir = folder("records");
  const auto parts = shards(kSwitches, dir, 1);
  const std::string text = slurp(parts[0]), run_id = run_of(text);
  // A switch point edited: its checksum no longer holds.
  write(dir + "/edited", edited(text, run_id, 0, [](std::string t) { return replaced(t, "6.4287436235676171", "99.410000000000000"); }, false));
  expect_refused(run({"merge", dir + "/edited"}), {"merge: " + dir + "/edited: task 0: fails its checksum"});
  // Lengths no task has: refused before anything is allocated.
  for (const char* length : {"10000000000", "-5", "6000000000", "99999999999999999999999", "1e9"}) {
    const std::size_t at = text.find("\ntask 0 ") + 8;
    write(dir + "/long", text.substr(0, at) + length + text.substr(text.find(' ', at)));
    expect_refused(run({"merge", dir + "/long"}), {"merge: " + dir + "/long: task 0: "});
  }
  // A record of another run (its checksum covers the run).
  write(dir + "/other", edited(text, "0123456789abcdef", 0, [](std::string t) { return t + "\n"; }, true));
  expect_refused(run({"merge", dir + "/other"}), {"merge: " + dir + "/other: task 0: fails its checksum"});
}

TEST(DistributeData, AResultForgedWithItsChecksumIsStillCheckedAgainstTheRun) {
  const std::string dir = folder("forged");
  // sweep: a switch point outside the swept range, a case this scene does not have.
  const auto parts = shards(kSwitches, dir, 1);
  const std::string text = slurp(parts[0]), run_id = run_of(text);
  write(dir + "/outside", edited(text, run_id, 0, [](std::string t) { return replaced(t, "6.4287436235676171", "99.410000000000000"); }, true));
  expect_refused(run({"merge", dir + "/outside"}), {"merge: " + dir + "/outside: task 0: a damaged result", "outside the values of its block"});
  write(dir + "/case", edited(text, run_id, 0, [](std::string t) { return replaced(t, "case 2.2 {3-4}", "case 9.9 {3-4}"); }, true));
  expect_refused(run({"merge", dir + "/case"}), {"merge: " + dir + "/case: task 0: a damaged result", "'9.9' is not a case of this scene"});
  // explore: "no (proved)" made "yes" without a witness.
  const auto explore = shards(kExplore, dir, 1);
  const std::string e = slurp(explore[0]);
  write(dir + "/yes", edited(e, run_of(e), 1,
                             [](std::string t) {
                               t = replaced(t, "\"reach\":\"no (proved)\"", "\"reach\":\"yes\"");
                               t = replaced(t, "\"cell\":\"no (proved)\"", "\"cell\":\"yes U₁⁺/a = 2\"");
                               return replaced(t, "verdict: no (proved):", "verdict: yes:");
                             },
                             true));
  expect_refused(run({"merge", dir + "/yes"}), {"merge: " + dir + "/yes: task 1: a damaged result", "the verdict yes without a witness"});
  // explore: a witness file name that leaves the --out folder.
  write(dir + "/escape", edited(e, run_of(e), 2, [](std::string t) { return replaced(t, "[\"explore_", "[\"../../explore_"); }, true));
  expect_refused(run({"merge", dir + "/escape", "--out", dir + "/w"}), {"task 2: a damaged result", "is not the file name of a witness"});
  EXPECT_FALSE(fs::exists(dir + "/w"));
  // Not JSON at all.
  write(dir + "/json", edited(e, run_of(e), 0, [](std::string t) { return "{" + t; }, true));
  expect_refused(run({"merge", dir + "/json"}), {"task 0: a damaged result (not the JSON of an explored case)"});
  // verify: a disagreement's scene file named outside --out.
  const std::vector<std::string> verify = {"verify", "--all", "--alphas", "5", "--samples", "20", "--epsilons", "1e-2", "--boundary-pairs", "2"};
  const auto vparts = shards(verify, dir, 1);
  const std::string v = slurp(vparts[0]);
  const std::size_t scene = v.find(".toml\n");
  ASSERT_NE(scene, std::string::npos) << "the asymptotic forms disagree at some points near the boundaries";
  const std::size_t k = std::stoul(v.substr(v.rfind("\ntask ", scene) + 6));
  write(dir + "/vescape", edited(v, run_of(v), k, [](std::string t) { return replaced(t, " case-", " ../case-"); }, true));
  expect_refused(run({"merge", dir + "/vescape", "--out", dir + "/s"}), {"a damaged result", "is not the file name of a disagreement of this case"});
}

/// The names of the task files of the checkpoint folder \p ck.
std::vector<std::string> task_files(const std::string& ck) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(ck))
    if (e.path().filename().string().rfind("task-", 0) == 0) names.push_back(e.path().string());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(DistributeData, ABadTaskFileIsComputedAgainWithOneLineAndTheSameBytes) {
  const std::string dir = folder("resume"), ck = dir + "/ck";
  const std::vector<std::string> args = {"sweep", kPaper, "--vary", "K.3-4=0:20:20001", "--csv", "--threads", "1"};
  const RunResult whole = run(args);
  ASSERT_EQ(whole.exit_code, 0) << describe(whole);
  ASSERT_EQ(run(with(args, {"--checkpoint", ck})).out, whole.out);
  const std::vector<std::string> files = task_files(ck);
  ASSERT_EQ(files.size(), 5u);
  const std::string run_id = run_of(slurp(ck + "/run"));
  const std::string task0 = slurp(files[0]);
  // Task 0 edited (checksum fails), 1 a symbolic link, 2 a FIFO, 3 a sparse 20 GB file, 4 the record of another task.
  write(files[0], edited(task0, run_id, 0, [](std::string t) { return replaced(t, "success", "SUCCESS"); }, false));
  fs::remove(files[1]);
  fs::create_symlink(kPaper, files[1]);
  fs::remove(files[2]);
  ASSERT_EQ(::mkfifo(files[2].c_str(), 0600), 0);
  ASSERT_EQ(::truncate(files[3].c_str(), 20LL << 30), 0);
  write(files[4], task0);
  const RunResult resumed = run(with(args, {"--checkpoint", ck}));
  EXPECT_EQ(resumed.exit_code, 0) << describe(resumed);
  EXPECT_EQ(resumed.out, whole.out);
  const auto lines = resumed.err_lines();
  ASSERT_EQ(lines.size(), 5u) << resumed.err;
  const std::string at = "superball: --checkpoint " + ck + ": ";
  EXPECT_EQ(lines[0], at + "task-00000000: task 0: fails its checksum (changed or damaged since it was written); task 0 computed again");
  EXPECT_EQ(lines[1], at + "task-00000001: a symbolic link, not read; task 1 computed again");
  EXPECT_EQ(lines[2], at + "task-00000002: a FIFO, not a regular file: not read; task 2 computed again");
  EXPECT_NE(lines[3].find(at + "task-00000003: of 21474836480 bytes, more than it can hold"), std::string::npos) << lines[3];
  EXPECT_EQ(lines[4], at + "task-00000004: holds the record of task 0; task 4 computed again");
  // Each was replaced by its task's record: the next run computes nothing.
  const RunResult again = run(with(args, {"--checkpoint", ck}));
  EXPECT_EQ(again.out, whole.out);
  EXPECT_EQ(again.err, at.substr(0, at.size() - 2) + ": 5 of 5 tasks done already, 0 to compute\n");
  EXPECT_TRUE(fs::exists(kPaper)) << "the link's target untouched";
}

TEST(DistributeData, AForgedCheckpointIsRefusedAndAnotherRunsFolderNamedForWhatItIs) {
  const std::string dir = folder("forged-checkpoint"), ck = dir + "/ck";
  ASSERT_EQ(run(with(kSwitches, {"--checkpoint", ck})).exit_code, 0);
  const std::string run_id = run_of(slurp(ck + "/run"));
  const std::string file = ck + "/task-00000000";
  const std::string kept = slurp(file);
  write(file, edited(kept, run_id, 0, [](std::string t) { return replaced(t, "6.4287436235676171", "99.410000000000000"); }, true));
  // Its checksum holds: read, then refused when the sweep reads it back (after the line that says what the folder holds).
  const RunResult forged = run(with(kSwitches, {"--checkpoint", ck}));
  EXPECT_EQ(forged.exit_code, 2) << describe(forged);
  EXPECT_EQ(forged.out, "");
  EXPECT_EQ(forged.err, "superball: --checkpoint " + ck + ": 2 of 2 tasks done already, 0 to compute\n" + "superball: --checkpoint " + ck +
                            ": task-00000000: a damaged result (a switch point at 99.410000000000000, outside the values of its block (0 to 10))\n");
  write(file, kept);
  // Another run's folder: which run it holds, and which run this command is.
  const RunResult other = run({"sweep", kPaper, "--vary", "K.3-4=0:20:8194", "--switch-points", "--checkpoint", ck});
  expect_refused(other, {"--checkpoint " + ck + ": holds run " + run_id + " (superball sweep", "and this command is run "});
  EXPECT_EQ(other.err.find("this command is run " + run_id), std::string::npos) << other.err;
  // A folder of the format before this one.
  const std::string run_file = slurp(ck + "/run");
  write(ck + "/run", replaced(run_file, "superball checkpoint 2", "superball checkpoint 1"));
  expect_refused(run(with(kSwitches, {"--checkpoint", ck})), {"--checkpoint " + ck + ": its run file: a checkpoint folder's run file of another format ('superball checkpoint 1'"});
  write(ck + "/run", run_file);
  // Its run file edited (the run's name kept): said so.
  write(ck + "/run", replaced(slurp(ck + "/run"), "tasks 2", "tasks 3"));
  expect_refused(run(with(kSwitches, {"--checkpoint", ck})), {"its run file names this run (" + run_id + ") but does not hold its arguments and task count"});
}

TEST(DistributeData, ASweepsRowsForgedInItsCheckpointAreRefusedWhereTheyAreReadBack) {
  // The rows a run computes are written as they are; those read from a task file are checked first.
  const std::string dir = folder("forged-rows"), ck = dir + "/ck";
  const std::vector<std::string> rows = {"sweep", kPaper, "--vary", "K.3-4=0:20:8193", "--csv"};
  const RunResult whole = run(with(rows, {"--checkpoint", ck}));
  ASSERT_EQ(whole.exit_code, 0) << describe(whole);
  const std::string run_id = run_of(slurp(ck + "/run"));
  const std::string file = ck + "/task-00000001";
  const std::string kept = slurp(file);
  ASSERT_NE(kept.find(",3.3,success\n"), std::string::npos);
  const std::string at = "superball: --checkpoint " + ck + ": task-00000001: a damaged result (";
  // A case this scene does not have, then a failure counted that no row has: each with its checksum made again.
  write(file, edited(kept, run_id, 1, [](std::string t) { return replaced(t, ",3.3,success\n", ",9.9,success\n"); }, true));
  RunResult forged = run(with(rows, {"--checkpoint", ck}));
  EXPECT_EQ(forged.exit_code, 2) << describe(forged);
  EXPECT_NE(forged.err.find(at + "'9.9' is not a case of this scene)"), std::string::npos) << forged.err;
  write(file, edited(kept, run_id, 1, [](std::string t) { return "1" + t.substr(1); }, true));
  forged = run(with(rows, {"--checkpoint", ck}));
  EXPECT_EQ(forged.exit_code, 2) << describe(forged);
  EXPECT_NE(forged.err.find(at + "not the rows of its block)"), std::string::npos) << forged.err;
  // As it was written: the same bytes as the run that computed it.
  write(file, kept);
  EXPECT_EQ(run(with(rows, {"--checkpoint", ck})).out, whole.out);
}

TEST(DistributeData, AMapCheckpointEditedIsComputedAgainAndForgedIsRefused) {
  const std::string dir = folder("map"), ck = dir + "/ck";
  const std::vector<std::string> map = {"map", kPaper, "--x", "K.3-4=0:20:9", "--y", "alpha.2=-150:0:9"};
  const RunResult whole = run(map);
  ASSERT_EQ(whole.exit_code, 0) << describe(whole);
  ASSERT_EQ(run(with(map, {"--checkpoint", ck})).out, whole.out);
  // A task of the grid points with a superball point: its U1+/a edited to 2^100.
  std::string file, kept;
  for (const std::string& f : task_files(ck + "/points"))
    if (slurp(f).find("\n1 0 1 ") != std::string::npos) file = f;
  ASSERT_FALSE(file.empty());
  kept = slurp(file);
  const std::string run_id = run_of(slurp(ck + "/points/run"));
  const std::size_t k = std::stoul(kept.substr(5));
  auto ratio = [](const std::string& verdict) {
    return [verdict](std::string t) {
      const std::size_t at = t.find("1 0 1 ");
      return t.substr(0, at) + verdict + "0x1p+100" + t.substr(t.find(' ', at + 6));
    };
  };
  write(file, edited(kept, run_id, k, ratio("1 0 1 "), false));
  const RunResult resumed = run(with(map, {"--checkpoint", ck}));
  EXPECT_EQ(resumed.out, whole.out);
  EXPECT_NE(resumed.err.find("task " + std::to_string(k) + ": fails its checksum (changed or damaged since it was written); task " + std::to_string(k) +
                             " computed again"),
            std::string::npos)
      << resumed.err;
  // Forged with its checksum, against the point's verdict (no superball, U1+/a = 2^100): refused.
  write(file, edited(kept, run_id, k, ratio("1 0 0 "), true));
  const RunResult forged = run(with(map, {"--checkpoint", ck}));
  EXPECT_EQ(forged.exit_code, 2) << describe(forged);
  EXPECT_EQ(forged.out, "");
  EXPECT_NE(forged.err.find("superball: a damaged line, U1+/|U1-| against its verdict: 1 0 0 0x1p+100"), std::string::npos) << forged.err;
}

#ifndef SUPERBALL_MPIEXEC
// Built without MPI (as CI's stage 2): started by a launcher as one of
// several ranks, superball refuses rather than run the whole command on each.
TEST(DistributeData, ABuildWithoutMpiStartedOnSeveralRanksRefuses) {
  for (const auto& [size, rank] : {std::pair<const char*, const char*>{"OMPI_COMM_WORLD_SIZE", "OMPI_COMM_WORLD_RANK"}, {"PMI_SIZE", "PMI_RANK"},
                                   {"SLURM_STEP_NUM_TASKS", "SLURM_PROCID"}}) {
    ::setenv(size, "2", 1);
    ::setenv(rank, "0", 1);
    const RunResult first = run({"solve", kPaper});
    ::setenv(rank, "1", 1);
    const RunResult second = run({"solve", kPaper});
    ::unsetenv(size);
    ::unsetenv(rank);
    expect_refused(first, {"superball: started on several ranks by an MPI launcher (" + std::string(size) + "=2), but this superball is built without MPI"});
    EXPECT_EQ(second.exit_code, 2) << describe(second);
    EXPECT_EQ(second.out + second.err, "") << "only the first rank says why";
  }
  ::setenv("OMPI_COMM_WORLD_SIZE", "1", 1);  // one rank: a plain run
  const RunResult one = run({"solve", kPaper});
  ::unsetenv("OMPI_COMM_WORLD_SIZE");
  EXPECT_EQ(one.exit_code, 0) << describe(one);
}
#endif

}  // namespace
