// Where the commands' results go (cli::Output): every kind of target (new
// file, existing file, symbolic link, FIFO, full device, standard output
// full or closed), the temporary never left behind, and the exit codes of
// every command held to their documented meaning.  Every node is made in a
// fresh temporary folder; no test touches a system path.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "commands.hpp"
#include "support/run.hpp"
#include "support/scale.hpp"

namespace {

namespace fs = std::filesystem;
using superball::test::describe;
using superball::test::expect_bad_input;
using superball::test::run;
using superball::test::RunResult;
using superball::test::slurp;

const std::string kScenes = std::string(SUPERBALL_CASES_DIR) + "/scenes/";
const std::string kPaper = kScenes + "paper-4.4-alpha2.toml";

/// A fresh folder for one test, removed at its end.
class Folder {
 public:
  Folder() {
    std::string t = ::testing::TempDir() + "superball-output-XXXXXX";
    path_ = ::mkdtemp(t.data()) ? t : "";
    EXPECT_FALSE(path_.empty());
  }
  ~Folder() {
    std::error_code e;
    fs::remove_all(path_, e);
  }
  std::string operator/(const std::string& name) const { return path_ + "/" + name; }
  /// The names in the folder, sorted.
  std::vector<std::string> names() const {
    std::vector<std::string> out;
    for (const auto& e : fs::directory_iterator(path_)) out.push_back(e.path().filename().string());
    std::sort(out.begin(), out.end());
    return out;
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

/// Run the binary with standard output on the file \p stdout_path opened for
/// writing (without creating it), or closed when \p stdout_path is empty;
/// standard error captured.
RunResult run_with_stdout(const std::vector<std::string>& args, const std::string& stdout_path) {
  using superball::test::StandardOutput;
  return run(args, stdout_path.empty() ? StandardOutput{StandardOutput::Closed, ""} : StandardOutput{StandardOutput::Into, stdout_path});
}

/// A character device like /dev/full (1, 7: every write fails with ENOSPC),
/// made in \p folder; "" when this process may not make device nodes.
std::string make_full_device(const Folder& folder) {
  const std::string path = folder / "full";
  if (::mknod(path.c_str(), S_IFCHR | 0666, makedev(1, 7)) != 0) return "";
  // A folder on a file system mounted nodev refuses to open it.
  const int fd = ::open(path.c_str(), O_WRONLY);
  if (fd < 0) return "";
  ::close(fd);
  return path;
}

/// Exit 3, one line "superball: NAME: No space left on device", nothing else.
void expect_full(const RunResult& r, const std::string& name) {
  EXPECT_EQ(r.exit_code, 3) << describe(r);
  EXPECT_EQ(r.err, "superball: " + name + ": No space left on device\n") << describe(r);
}

/// The derivation the output tests write: small and fast.
const std::vector<std::string> kDerive = {"derive", "--case", "1", "--alphas", "2"};

std::vector<std::string> with(std::vector<std::string> args, const std::vector<std::string>& more) {
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

mode_t current_umask() {
  const mode_t mask = ::umask(022);
  ::umask(mask);
  return mask;
}

// ---------------------------------------------------------------------------
// -o: each kind of target

TEST(Output, NewFileHasTheUmaskPermissionsAndNoTemporaryIsLeft) {
  Folder dir;
  const std::string path = dir / "derived.txt";
  const RunResult r = run(with(kDerive, {"-o", path}));
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_EQ(slurp(path), run(kDerive).out);
  struct stat st {};
  ASSERT_EQ(::stat(path.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0666 & ~current_umask());
  EXPECT_EQ(dir.names(), std::vector<std::string>{"derived.txt"});
}

TEST(Output, ExistingFileIsReplacedWholeAndKeepsItsPermissions) {
  Folder dir;
  const std::string path = dir / "derived.txt";
  { std::ofstream(path) << std::string(100000, 'x'); }  // longer than the result: nothing of it may remain
  ASSERT_EQ(::chmod(path.c_str(), 0640), 0);
  struct stat before {};
  ASSERT_EQ(::stat(path.c_str(), &before), 0);
  const RunResult r = run(with(kDerive, {"-o", path}));
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_EQ(slurp(path), run(kDerive).out);
  struct stat after {};
  ASSERT_EQ(::stat(path.c_str(), &after), 0);
  EXPECT_EQ(after.st_mode & 07777, 0640u);
  EXPECT_NE(after.st_ino, before.st_ino) << "replaced by rename, not rewritten in place";
  EXPECT_EQ(dir.names(), std::vector<std::string>{"derived.txt"});
}

TEST(Output, SymbolicLinkKeptAndItsTargetReplaced) {
  Folder dir;
  fs::create_directory(dir / "real");
  const std::string target = dir / "real/derived.txt", link = dir / "link.txt";
  { std::ofstream(target) << "old\n"; }
  ASSERT_EQ(::symlink("real/derived.txt", link.c_str()), 0);
  const RunResult r = run(with(kDerive, {"-o", link}));
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(fs::read_symlink(link), "real/derived.txt");
  EXPECT_EQ(slurp(target), run(kDerive).out);
  EXPECT_EQ(dir.names(), (std::vector<std::string>{"link.txt", "real"}));
  EXPECT_EQ(fs::directory_iterator(dir / "real")->path().filename(), "derived.txt");
}

TEST(Output, DanglingSymbolicLinkIsRefused) {
  Folder dir;
  const std::string link = dir / "link.txt";
  ASSERT_EQ(::symlink("nowhere.txt", link.c_str()), 0);
  const RunResult r = run(with(kDerive, {"-o", link}));
  EXPECT_EQ(r.exit_code, 3) << describe(r);
  EXPECT_EQ(r.err, "superball: " + link + ": a symbolic link to a file that does not exist\n");
  EXPECT_EQ(dir.names(), std::vector<std::string>{"link.txt"});
}

TEST(Output, FifoIsWrittenIntoNotReplaced) {
  Folder dir;
  const std::string fifo = dir / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::string received;
  std::thread reader([&] { received = slurp(fifo); });
  const RunResult r = run(with(kDerive, {"-o", fifo}));
  reader.join();
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_EQ(received, run(kDerive).out);
  struct stat st {};
  ASSERT_EQ(::lstat(fifo.c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode));
  EXPECT_EQ(dir.names(), std::vector<std::string>{"pipe"});
}

// ---------------------------------------------------------------------------
// An output is never an input (issue 25): every output option that names the
// command's scene, under every spelling of it, is refused with one line
// before anything is written, and the scene is left as it was.

/// The spellings of \p dir's file \p name: itself, DIR/./NAME,
/// DIR/sub/../NAME, a symbolic link and a hard link to it (made in \p dir,
/// named from \p stem and \p ext so that a prefix can name them too).
std::vector<std::pair<std::string, std::string>> spellings(const Folder& dir, const std::string& stem, const std::string& ext) {
  const std::string file = dir / (stem + ext);
  fs::create_directories(dir / "sub");
  EXPECT_EQ(::symlink((stem + ext).c_str(), (dir / ("soft-" + stem + ext)).c_str()), 0);
  EXPECT_EQ(::link(file.c_str(), (dir / ("hard-" + stem + ext)).c_str()), 0);
  // (what, the path without ext)
  return {{"the same name", dir / stem},
          {"./name", dir.path() + "/./" + stem},
          {"sub/../name", dir.path() + "/sub/../" + stem},
          {"a symbolic link", dir / ("soft-" + stem)},
          {"a hard link", dir / ("hard-" + stem)}};
}

/// Refused: exit 2, one line saying which input, the scene unchanged, nothing new in \p dir.
void expect_refused_over_input(const RunResult& r, const Folder& dir, const std::string& scene, const std::string& before) {
  expect_bad_input(r, {"which this command reads; write the output elsewhere"});
  EXPECT_EQ(slurp(scene), before);
  std::vector<std::string> names = dir.names();
  names.erase(std::remove_if(names.begin(), names.end(), [](const std::string& n) { return n.find(".toml") != std::string::npos || n.find(".dat") != std::string::npos || n == "sub"; }),
              names.end());
  EXPECT_TRUE(names.empty()) << names.front();
}

TEST(OutputOverInput, EveryOptionUnderEverySpellingIsRefused) {
  Folder dir;
  const std::string scene = dir / "s.toml", before = slurp(kPaper);
  { std::ofstream(scene) << before; }
  std::size_t spelling = 0;
  for (const auto& [what, stem] : spellings(dir, "s", ".toml")) {
    const std::string path = stem + ".toml";
    SCOPED_TRACE(what + ": " + path);
    const std::vector<std::vector<std::string>> commands = {
        {"explore", "--scene", scene, "--case", "1", "-o", path},  // the reproducer, -o
        {"explore", "--scene", scene, "--case", "1", "--output", path},
        {"derive", "--scene", scene, "--case", "1", "-o", path},
        {"verify", "--scene", scene, "--case", "1", "--out", path},
        {"explore", "--scene", scene, "--case", "1", "--out", path},
        {"sweep", scene, "--vary", "K.3-4=0:20:5", "--shard", "1/2", "--part", path},
        {"sweep", scene, "--vary", "K.3-4=0:20:5", "--checkpoint", path},
        {"map", scene, "--x", "K.3-4=0:20:5", "--y", "alpha.2=-110:0:5", "--checkpoint", path},
        {"map", scene, "--x", "K.3-4=0:20:5", "--y", "alpha.2=-110:0:5", "--overlay", "--out", path},
        {"solve", scene, "--plot", path},
        {"solve", path, "--plot", scene}};  // the input under the other spelling
    for (std::size_t c = 0; c < commands.size(); ++c) {
      // At a small scale (scripts/test.sh under the sanitizers) each command under one spelling,
      // each spelling for two or three commands.
      if (superball::test::small_scale() && c % 5 != spelling) continue;
      const auto& args = commands[c];
      SCOPED_TRACE(args[0] + " " + args[args.size() - 2]);
      expect_refused_over_input(run(args), dir, scene, before);
    }
    ++spelling;
  }
}

TEST(OutputOverInput, MapPlotPrefixNamingTheSceneIsRefused) {
  // The reproducer: `map s.dat … --plot s` replaced the scene s.dat with the figure's data.
  Folder dir;
  const std::string scene = dir / "s.dat", before = slurp(kPaper);
  { std::ofstream(scene) << before; }
  for (const auto& [what, prefix] : spellings(dir, "s", ".dat")) {
    SCOPED_TRACE(what + ": " + prefix);
    expect_refused_over_input(run({"map", scene, "--x", "K.3-4=0:20:5", "--y", "alpha.2=-110:0:5", "--plot", prefix}), dir, scene, before);
  }
}

TEST(OutputOverInput, OutputClassRefusesANotedInput) {
  // The one place every write goes through: a file noted as read is never replaced, through any name.
  Folder dir;
  const std::string input = dir / "input.toml";
  { std::ofstream(input) << "kept\n"; }
  ASSERT_EQ(::symlink("input.toml", (dir / "link.toml").c_str()), 0);
  superball::cli::note_input("--scene", input);
  // The note lasts as long as this process: the file stays open, so that its inode is not reused by a later test's file.
  ASSERT_GE(::open(input.c_str(), O_RDONLY | O_CLOEXEC), 0);
  for (const std::string& path : {input, dir.path() + "/./input.toml", dir / "link.toml"}) {
    try {
      superball::cli::Output out(path);
      ADD_FAILURE() << "not refused: " << path;
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()), path + ": is the file of --scene " + input + ", which this command reads; write the output elsewhere");
    }
  }
  EXPECT_EQ(slurp(input), "kept\n");
  // A file beside it is written as always.
  superball::cli::write_output(dir / "other.toml", "new\n");
  EXPECT_EQ(slurp(dir / "other.toml"), "new\n");
}

TEST(OutputOverInput, AnOutputBesideTheInputIsWritten) {
  // Not every output near an input is refused: a plot prefix whose files differ from the scene's name.
  Folder dir;
  const std::string scene = dir / "s.toml";
  { std::ofstream(scene) << slurp(kPaper); }
  const RunResult r = run({"derive", "--scene", scene, "--case", "1", "-o", dir / "s.txt"});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_FALSE(slurp(dir / "s.txt").empty());
}

TEST(Output, FifoWithNoReaderWaitsForOne) {
  // As cat and tee do (README, Output): the command waits at the FIFO until a reader opens it, then writes everything.
  Folder dir;
  const std::string fifo = dir / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::vector<std::string> args = with(kDerive, {"-o", fifo});
  args.insert(args.begin(), SUPERBALL_EXE);
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  ASSERT_EQ(::posix_spawn(&pid, SUPERBALL_EXE, nullptr, nullptr, argv.data(), environ), 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  int status = 0;
  EXPECT_EQ(::waitpid(pid, &status, WNOHANG), 0) << "ended without a reader, status " << status;
  const std::string received = slurp(fifo);
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << status;
  EXPECT_EQ(received, run(kDerive).out);
}

TEST(Output, FullDeviceIsWrittenIntoNotReplaced) {
  Folder dir;
  const std::string full = make_full_device(dir);
  if (full.empty()) GTEST_SKIP() << "cannot make a device node here (mknod needs root and a folder not mounted nodev)";
  expect_full(run(with(kDerive, {"-o", full})), full);
  expect_full(run({"audit", "--samples", "10", "-o", full}), full);
  struct stat st {};
  ASSERT_EQ(::lstat(full.c_str(), &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode)) << "the device node was replaced";
  EXPECT_EQ(dir.names(), std::vector<std::string>{"full"});
}

TEST(Output, UnwritablePlaceSaysWhy) {
  Folder dir;
  { std::ofstream(dir / "file") << "x\n"; }
  const RunResult r = run(with(kDerive, {"-o", dir / "file/derived.txt"}));
  EXPECT_EQ(r.exit_code, 3) << describe(r);
  EXPECT_EQ(r.err, "superball: " + (dir / "file/derived.txt") + ": Not a directory\n");
  const RunResult d = run(with(kDerive, {"-o", dir.path()}));
  EXPECT_EQ(d.exit_code, 3) << describe(d);
  EXPECT_EQ(d.err, "superball: " + dir.path() + ": Is a directory\n");
}

TEST(Output, DashIsStandardOutput) {
  const std::string expected = run(kDerive).out;
  ASSERT_FALSE(expected.empty());
  const RunResult r = run(with(kDerive, {"-o", "-"}));
  EXPECT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_EQ(r.out, expected);
}

TEST(Output, PlotFiguresGoThroughOutput) {
  // The figure gnuplot draws reaches its file through Output: a link to it is kept, a full device is an error.
  Folder dir;
  const std::string flight = kScenes + "paper-4.4-flight.toml";
  fs::create_directory(dir / "real");
  { std::ofstream(dir / "real/figure.png") << "old\n"; }
  ASSERT_EQ(::symlink("real/figure.png", (dir / "trajectories.png").c_str()), 0);
  const RunResult r = run({"solve", flight, "--plot", dir.path()});
  ASSERT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_TRUE(fs::is_symlink(dir / "trajectories.png"));
  EXPECT_EQ(slurp(dir / "real/figure.png").substr(1, 3), "PNG");
  EXPECT_NE(slurp(dir / "trajectories.svg").find("<svg"), std::string::npos);
  const std::string full = make_full_device(dir);
  if (full.empty()) GTEST_SKIP() << "cannot make a device node here (mknod needs root and a folder not mounted nodev)";
  ASSERT_EQ(::rename(full.c_str(), (dir / "trajectories.svg").c_str()), 0);
  expect_full(run({"solve", flight, "--plot", dir.path()}), dir / "trajectories.svg");
  struct stat st {};
  ASSERT_EQ(::lstat((dir / "trajectories.svg").c_str(), &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode)) << "the device node was replaced";
}

// ---------------------------------------------------------------------------
// Standard output full or closed: every command that prints its result

const std::vector<std::vector<std::string>> kPrinting = {
    {"solve", kPaper},
    {"solve", kPaper, "--json"},
    {"solve", kPaper, "--precision", "exact", "--json"},
    {"derive", "--case", "1", "--alphas", "2"},
    {"derive", "--case", "1", "--alphas", "2", "--format", "json"},
    {"verify", "--case", "1", "--alphas", "2", "--samples", "20", "--epsilons", "1e-2", "--threads", "1"},
    {"explore", "--alphas", "1,6", "--case", "1", "--starts", "2"},
    {"audit", "--samples", "10"},
};

TEST(StandardOutput, FullGivesExitThreeAndTheReason) {
  Folder dir;
  const std::string full = make_full_device(dir);
  if (full.empty()) GTEST_SKIP() << "cannot make a device node here (mknod needs root and a folder not mounted nodev)";
  for (const auto& args : kPrinting) {
    SCOPED_TRACE(args[0] + " " + args.back());
    expect_full(run_with_stdout(args, full), "standard output");
  }
  expect_full(run_with_stdout({"--help"}, full), "standard output");
}

TEST(StandardOutput, ClosedGivesExitThreeAndTheReason) {
  for (const auto& args : kPrinting) {
    SCOPED_TRACE(args[0] + " " + args.back());
    const RunResult r = run_with_stdout(args, "");
    EXPECT_EQ(r.exit_code, 3) << describe(r);
    EXPECT_EQ(r.err, "superball: standard output: Bad file descriptor\n") << describe(r);
  }
}

TEST(StandardOutput, ClosedDoesNotSendOutputIntoAFile) {
  // With descriptor 1 closed, the temporary of -o would get number 1 if nothing held it.
  Folder dir;
  const RunResult r = run_with_stdout(with(kDerive, {"-o", dir / "derived.txt"}), "");
  EXPECT_EQ(r.exit_code, 0) << describe(r);
  EXPECT_EQ(slurp(dir / "derived.txt"), run(kDerive).out);
}

// ---------------------------------------------------------------------------
// Output itself: the temporary on every exit path

TEST(OutputClass, TemporaryRemovedWhenNotCommitted) {
  Folder dir;
  {
    superball::cli::Output out(dir / "result.txt");
    out.write("partial");
    EXPECT_EQ(dir.names().size(), 1u) << "the temporary, beside the target";
  }
  EXPECT_TRUE(dir.names().empty());
}

TEST(OutputClass, OldFileIntactUntilCommit) {
  Folder dir;
  const std::string path = dir / "result.txt";
  { std::ofstream(path) << "old\n"; }
  superball::cli::Output out(path);
  out.write("new\n");
  EXPECT_EQ(slurp(path), "old\n");
  out.commit();
  EXPECT_EQ(slurp(path), "new\n");
  EXPECT_EQ(dir.names(), std::vector<std::string>{"result.txt"});
}

TEST(OutputClass, SignalsRemoveTheTemporary) {
  for (int signal : {SIGINT, SIGTERM, SIGHUP, SIGPIPE}) {
    SCOPED_TRACE(strsignal(signal));
    Folder dir;
    const std::string path = dir / "result.txt";
    { std::ofstream(path) << "old\n"; }
    const pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      superball::cli::Output out(path);
      out.write("half of it");
      ::raise(signal);
      ::_exit(0);  // not reached: the signal ends the process
    }
    int status = 0;
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == signal) << "the signal is re-raised, status " << status;
    EXPECT_EQ(dir.names(), std::vector<std::string>{"result.txt"});
    EXPECT_EQ(slurp(path), "old\n");
  }
}

TEST(OutputClass, NoSuchFolderSaysSo) {
  Folder dir;
  try {
    superball::cli::Output out(dir / "missing/result.txt");
    FAIL() << "no exception";
  } catch (const superball::cli::OutputError& e) {
    EXPECT_EQ(std::string(e.what()), dir / "missing/result.txt" + ": No such file or directory");
  }
}

// ---------------------------------------------------------------------------
// Exit codes: one meaning each (superball --help)

struct ExitCase {
  std::vector<std::string> args;
  int code;
  std::string says;  ///< a piece of the one line on stderr (codes 2 and 3)
};

class ExitCodes : public ::testing::TestWithParam<ExitCase> {};

TEST_P(ExitCodes, OneMeaningEach) {
  const ExitCase& c = GetParam();
  const RunResult r = run(c.args);
  if (c.code == 2) {
    expect_bad_input(r, {c.says});
    return;
  }
  EXPECT_EQ(r.exit_code, c.code) << describe(r);
  if (c.code == 0) {
    EXPECT_TRUE(r.err.empty()) << describe(r);
  }
  if (c.code == 3) {
    EXPECT_EQ(r.err_lines().size(), 1u) << describe(r);
  }
  if (!c.says.empty()) {
    EXPECT_NE(r.err.find(c.says), std::string::npos) << describe(r);
  }
}

const std::string kNotAFolder = std::string(SUPERBALL_CASES_DIR) + "/scenes/paper-4.4-alpha2.toml/x";

INSTANTIATE_TEST_SUITE_P(
    EveryCommand, ExitCodes,
    ::testing::Values(
        // 0: success
        ExitCase{{"solve", kPaper}, 0, ""}, ExitCase{{"sweep", kPaper, "--vary", "K.3-4=0:20:5"}, 0, ""},
        ExitCase{{"derive", "--case", "1", "--alphas", "2"}, 0, ""}, ExitCase{{"audit", "--samples", "10"}, 0, ""},
        ExitCase{{"verify", "--case", "1", "--alphas", "2", "--samples", "20", "--epsilons", "1e-2"}, 0, ""},
        ExitCase{{"explore", "--alphas", "1,6", "--case", "1", "--starts", "2"}, 0, ""}, ExitCase{{"--help"}, 0, ""},
        ExitCase{{"--version"}, 0, ""},
        // 1: a numerical outcome (double cannot resolve this scene: status numerical-issue)
        ExitCase{{"solve", std::string(SUPERBALL_TEST_DATA_DIR) + "/hard/eps-1e-9.toml", "--precision", "double"}, 1, ""},
        // 2: bad input or usage
        ExitCase{{}, 2, "subcommand"}, ExitCase{{"nosuchcmd"}, 2, "unknown command 'nosuchcmd' (commands: solve, sweep"},
        ExitCase{{"solv\x1b[31m"}, 2, "unknown command 'solv\\e[31m'"},
        ExitCase{{"solve", kPaper, "--nosuchoption"}, 2, "--nosuchoption"},
        ExitCase{{"solve", kPaper, "--precision", "double", "--rtol", "1e-3"}, 2, "rtol is the certified error of precision auto"},
        ExitCase{{"derive", "--closed", ""}, 2, "--closed"}, ExitCase{{"derive", "--case", ""}, 2, "--case"},
        ExitCase{{"derive", "--closed", "none", "--alphas", ""}, 2, "--alphas"},
        ExitCase{{"derive", "--case", "1", "--alphas", "2", "-o", ""}, 2, "--output"},
        ExitCase{{"derive", "--scene", kPaper, "--bodies", "5", "--closed", "none"}, 2, "scene gives the number of bodies and the pattern: drop bodies, alphas, coupling and pairs"},
        ExitCase{{"derive", "--scene", kPaper, "--pairs", "near", "--closed", "none"}, 2, "scene gives the number of bodies and the pattern: drop bodies, alphas, coupling and pairs"},
        ExitCase{{"derive", "--scene", kPaper, "--alphas", "2", "--closed", "none"}, 2, "scene gives the number of bodies and the pattern: drop bodies, alphas, coupling and pairs"},
        ExitCase{{"verify", "--scene", kPaper, "--coupling", "1-2/1-3", "--closed", "none"}, 2, "scene gives the number of bodies and the pattern: drop bodies, alphas, coupling and pairs"},
        ExitCase{{"explore", "--all-patterns", "--alphas", "2"}, 2, "all_patterns chooses the patterns and cases"},
        ExitCase{{"derive", "--case", "1", "--closed", "2-3"}, 2, "case"},
        ExitCase{{"derive", "--bodies", "21", "--pairs", "near", "--closed", "none"}, 2, "this machine has"},
        ExitCase{{"solve", kScenes + "nosuchscene.toml"}, 2, "nosuchscene.toml"},
        // 3: an output that cannot be written
        ExitCase{{"derive", "--case", "1", "--alphas", "2", "-o", kNotAFolder}, 3, "Not a directory"},
        ExitCase{{"audit", "--samples", "10", "-o", kNotAFolder}, 3, "Not a directory"},
        ExitCase{{"explore", "--alphas", "1,6", "--case", "1", "--starts", "2", "-o", kNotAFolder}, 3, "Not a directory"}));

}  // namespace
