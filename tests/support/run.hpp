#pragma once
/// \file run.hpp
/// The `superball` command as a user runs it, for the tests of the command:
/// the built binary (its path in SUPERBALL_EXE, set by the test target) run
/// with arguments, its exit code, standard output and standard error captured.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <spawn.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#ifndef SUPERBALL_EXE
#error "SUPERBALL_EXE (the path of the superball binary) must be defined by the test target"
#endif

extern char** environ;

namespace superball::test {

/// Built with AddressSanitizer: a process starts far slower, and its shadow
/// memory does not fit under `ulimit -v`.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool kAddressSanitizer = true;
#else
inline constexpr bool kAddressSanitizer = false;
#endif
#else
inline constexpr bool kAddressSanitizer = false;
#endif

/// What a run of the binary gave.
struct RunResult {
  int exit_code = -1;  ///< 128 + signal when killed by a signal
  std::string out, err;
  /// Standard error, line by line.
  std::vector<std::string> err_lines() const {
    std::vector<std::string> lines;
    std::istringstream in(err);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
  }
};

/// The lines of \p text, without their newlines.
inline std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

/// The fields of a CSV line (RFC 4180: a quoted field may hold commas).
inline std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t k = 0; k < line.size(); ++k) {
    const char c = line[k];
    if (c == '"' && quoted && k + 1 < line.size() && line[k + 1] == '"') {
      fields.back() += '"', ++k;
    } else if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  return fields;
}

/// A new, empty folder for one test: TempDir()/superball-PREFIX-PID-NAME.
inline std::string fresh_folder(const std::string& prefix, const std::string& name) {
  const std::string dir = ::testing::TempDir() + "superball-" + prefix + "-" + std::to_string(::getpid()) + "-" + name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

/// The whole content of the file \p path ("" when it cannot be read).
inline std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

/// Where a run's standard output goes: captured (the default), closed, or
/// into an existing path opened for writing without creating it (a FIFO, a
/// device, a file).
struct StandardOutput {
  enum Kind { Captured, Closed, Into } kind = Captured;
  std::string path;  ///< for Into
};

/// Run `superball ARGS...`, standard error (and standard output, unless
/// \p stdout_to says otherwise) captured through temporary files, removed
/// afterwards.
inline RunResult run_program(const std::string& exe, const std::vector<std::string>& args, const StandardOutput& stdout_to = {});

inline RunResult run(const std::vector<std::string>& args, const StandardOutput& stdout_to = {}) { return run_program(SUPERBALL_EXE, args, stdout_to); }

/// Run the program \p exe (a path) with \p args, as run() runs superball
/// (e.g. mpirun with superball among its arguments).
inline RunResult run_program(const std::string& exe, const std::vector<std::string>& args, const StandardOutput& stdout_to) {
  static int counter = 0;
  const std::string base = ::testing::TempDir() + "superball-run-" + std::to_string(::getpid()) + "-" + std::to_string(++counter);
  const std::string out = base + ".out", err = base + ".err";
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (stdout_to.kind == StandardOutput::Captured)
    posix_spawn_file_actions_addopen(&actions, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  else if (stdout_to.kind == StandardOutput::Closed)
    posix_spawn_file_actions_addclose(&actions, 1);
  else
    posix_spawn_file_actions_addopen(&actions, 1, stdout_to.path.c_str(), O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  std::vector<std::string> argv_s = {exe};
  argv_s.insert(argv_s.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_s) argv.push_back(a.data());
  argv.push_back(nullptr);
  RunResult r;
  pid_t pid = 0;
  if (posix_spawn(&pid, exe.c_str(), &actions, nullptr, argv.data(), environ) == 0) {
    int status = 0;
    waitpid(pid, &status, 0);
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  }
  posix_spawn_file_actions_destroy(&actions);
  if (stdout_to.kind == StandardOutput::Captured) r.out = slurp(out);
  r.err = slurp(err);
  std::remove(out.c_str());
  std::remove(err.c_str());
  return r;
}

/// Whether this machine can make a pseudo-terminal (a container may have no
/// /dev/ptmx): tests of run_on_terminal() skip without one.
inline bool pseudo_terminals_available() {
  const int master = ::posix_openpt(O_RDWR | O_NOCTTY);
  if (master < 0) return false;
  const bool ok = ::grantpt(master) == 0 && ::unlockpt(master) == 0 && ::ptsname(master) != nullptr;
  ::close(master);
  return ok;
}

/// Run `superball ARGS...` with its standard error on a terminal (a new
/// pseudo-terminal: what it wrote there, with the terminal's \\r\\n for \\n,
/// is `err`), standard output captured.  For the output a command shows only
/// on a terminal (progress).  Fails the test when no pseudo-terminal can be
/// made (check pseudo_terminals_available() first).
inline RunResult run_on_terminal(const std::vector<std::string>& args) {
  static int counter = 0;
  RunResult r;
  const int master = ::posix_openpt(O_RDWR | O_NOCTTY);
  if (master < 0 || ::grantpt(master) != 0 || ::unlockpt(master) != 0 || !::ptsname(master)) {
    ADD_FAILURE() << "run_on_terminal(): no pseudo-terminal";
    if (master >= 0) ::close(master);
    return r;
  }
  const std::string terminal = ::ptsname(master);
  const std::string exe = SUPERBALL_EXE;
  const std::string out = ::testing::TempDir() + "superball-tty-" + std::to_string(::getpid()) + "-" + std::to_string(++counter) + ".out";
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, 2, terminal.c_str(), O_RDWR | O_NOCTTY, 0);
  posix_spawn_file_actions_addclose(&actions, master);
  std::vector<std::string> argv_s = {exe};
  argv_s.insert(argv_s.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_s) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawn(&pid, exe.c_str(), &actions, nullptr, argv.data(), environ) == 0) {
    // Read the terminal while the command runs (a full terminal would block it), then what is left.
    auto drain = [&](int timeout_ms) {
      pollfd p{master, POLLIN, 0};
      char buffer[4096];
      while (::poll(&p, 1, timeout_ms) > 0 && (p.revents & POLLIN)) {
        const ssize_t got = ::read(master, buffer, sizeof buffer);
        if (got <= 0) break;
        r.err.append(buffer, static_cast<std::size_t>(got));
      }
    };
    int status = 0;
    while (::waitpid(pid, &status, WNOHANG) == 0) drain(50);
    drain(0);
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  }
  posix_spawn_file_actions_destroy(&actions);
  ::close(master);
  r.out = slurp(out);
  std::remove(out.c_str());
  return r;
}

/// A run for failure messages: exit code, stdout and stderr.
inline std::string describe(const RunResult& r) {
  return "exit " + std::to_string(r.exit_code) + "\nstdout:\n" + r.out + "\nstderr:\n" + r.err;
}

/// A refusal: exit \p code, exactly one line on stderr ("superball: ...")
/// containing every piece of \p expected, nothing on stdout.
inline void expect_refusal(const RunResult& r, int code, const std::vector<std::string>& expected) {
  EXPECT_EQ(r.exit_code, code) << describe(r);
  EXPECT_TRUE(r.out.empty()) << describe(r);
  const auto lines = r.err_lines();
  ASSERT_EQ(lines.size(), 1u) << describe(r);
  EXPECT_EQ(lines[0].rfind("superball: ", 0), 0u) << lines[0];
  for (const auto& e : expected) EXPECT_NE(lines[0].find(e), std::string::npos) << "'" << e << "' not in: " << lines[0];
  EXPECT_EQ(r.err.back(), '\n');
}

/// Bad input or usage: exit 2, one line naming \p expected.
inline void expect_bad_input(const RunResult& r, const std::vector<std::string>& expected) { expect_refusal(r, 2, expected); }

/// An output that cannot be written: exit 3, one line naming \p expected.
inline void expect_output_error(const RunResult& r, const std::vector<std::string>& expected) { expect_refusal(r, 3, expected); }

}  // namespace superball::test
