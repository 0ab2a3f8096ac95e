// The red-team suite (issue 12): hostile scenes and command lines, generated
// from a seed class by class, run through the built `superball` as a user
// runs it, and checked against invariants that hold for every input, not
// against stored outputs:
//
//   - the command ends by itself within kRunSeconds, with exit 0, 1, 2 or 3
//     (never 4 = internal error, never a signal);
//   - exit 2 or 3: standard error is one line "superball: ...", without raw
//     control bytes;
//   - `solve --json` that exits 0: every velocity is a finite number; status
//     success: momentum conserved, kinetic energy not increased (computed
//     here in long double from the scene as generated, not from the tool's
//     own sums);
//   - `sweep` that exits 0: no NaN or infinity printed, no negative bracket
//     width, consecutive switch points chain;
//   - `-o FILE` on a command that fails: FILE (and a symlink's target)
//     unchanged, nothing left beside it; on a command that succeeds into a
//     symlink or a FIFO: the link or FIFO kept, the text as on standard output;
//   - equivalent command lines (--threads 1 and 2, a byte-order mark or not,
//     `inf` or `+inf`, one parameter spelt two ways) give the same exit code
//     and the same output;
//   - what a class must give (refused with exit 2, success, exit 3);
//   - no raw C++ exception text in a message;
//   - issue 25: tampered job-array parts are refused by merge, which writes
//     nowhere else; a tampered checkpoint gives the untampered bytes or one
//     line; digits:N agrees with exact unless it warns; outputs never replace
//     inputs; a map under `ulimit -v` ends in time without bad_alloc; a build
//     without MPI under a launcher refuses.
//
// Each class is one test (RedTeam/Hostile.Holds/<class>).  A class runs its
// enumerated cases, then random ones until its share of the time budget is
// spent.  Environment:
//   SUPERBALL_REDTEAM_SECONDS  total time budget (default 20), shared by the classes
//   SUPERBALL_REDTEAM_SEED     seed of the random cases (default 1)
//   SUPERBALL_REDTEAM_OUT      folder where a violating case's files stay
//                              (default: the test's temporary folder)
// A violating case is kept in its own folder (the scene, the other files and
// `command`, the command lines), and reported with its class, index and seed.
// Classes listed in known-failures.txt (next to this file) report their
// violations and skip instead of failing; a listed class that holds every
// invariant says so, so that the line can be removed.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "support/run.hpp"

namespace {

namespace fs = std::filesystem;
using superball::test::slurp;

/// Longest a single run may take (no command of the suite needs a second).
constexpr double kRunSeconds = 10;
/// Default total time budget of the suite, shared by the classes (seconds).
constexpr double kDefaultBudgetSeconds = 20;
/// Momentum and energy of a successful answer, relative to the scale of the terms.
constexpr long double kMomentumRtol = 1e-6L;
constexpr long double kEnergyRtol = 1e-6L;
/// digits:N (N >= 10) against exact, relative to the largest velocity, where no warning is given.
constexpr long double kDigitsRtol = 1e-6L;
/// Bytes of an input quoted in a report.
constexpr std::size_t kQuoteBytes = 400;

double env_number(const char* name, double fallback) {
  const char* v = std::getenv(name);
  if (!v || !*v) return fallback;
  char* end = nullptr;
  const double x = std::strtod(v, &end);
  return (end && *end == 0 && std::isfinite(x) && x >= 0) ? x : fallback;
}

// ---------------------------------------------------------------------------
// Running the command

/// One command line and how it is run.
struct Command {
  std::vector<std::string> args;
  std::string stdin_text;     ///< fed on standard input (empty: /dev/null)
  bool close_stdout = false;  ///< standard output closed: every write fails
  std::string stdout_path;    ///< standard output into this file (a full device), not captured
  std::map<std::string, std::string> env;  ///< set in the command's environment, over the test's own
  std::uint64_t address_space = 0;         ///< the command's RLIMIT_AS in bytes (`ulimit -v`; 0: the test's own)
  bool setup = false;  ///< prepares the case (a run made to fail, a shard): only its end in time is checked
  /// A rank other than 0 of a launch refused: exit 2 saying nothing (rank 0
  /// says why, so that a launch of N ranks prints one line, not N).
  bool silent = false;
  Command(std::vector<std::string> a, std::string in = "") : args(std::move(a)), stdin_text(std::move(in)) {}
};

struct Outcome {
  int exit_code = -1;  ///< 128 + signal when killed
  bool timed_out = false;
  std::string out, err;
};

/// Run `superball COMMAND` in \p dir, killed (with its process group)
/// after kRunSeconds.
Outcome execute(const Command& r, const std::string& dir) {
  const std::string exe = SUPERBALL_EXE, out = dir + "/.stdout", err = dir + "/.stderr", in = dir + "/.stdin";
  if (!r.stdin_text.empty()) std::ofstream(in, std::ios::binary) << r.stdin_text;
  // Everything the child needs is made before fork(): between fork() and
  // exec() it calls only async-signal-safe functions.
  std::vector<std::string> argv_s = {exe}, env_s;
  argv_s.insert(argv_s.end(), r.args.begin(), r.args.end());
  for (char** e = environ; *e; ++e) {
    const std::string entry = *e;
    if (!r.env.count(entry.substr(0, entry.find('=')))) env_s.push_back(entry);
  }
  for (const auto& [name, value] : r.env) env_s.push_back(name + "=" + value);
  std::vector<char*> argv, envp;
  for (auto& a : argv_s) argv.push_back(a.data());
  for (auto& e : env_s) envp.push_back(e.data());
  argv.push_back(nullptr);
  envp.push_back(nullptr);
  const int in_fd = ::open(r.stdin_text.empty() ? "/dev/null" : in.c_str(), O_RDONLY | O_CLOEXEC);
  const int out_fd = r.close_stdout ? -1
                     : !r.stdout_path.empty() ? ::open(r.stdout_path.c_str(), O_WRONLY | O_CLOEXEC)
                                              : ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  const int err_fd = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  const rlimit limit{static_cast<rlim_t>(r.address_space), static_cast<rlim_t>(r.address_space)};
  Outcome o;
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::setpgid(0, 0);
    ::signal(SIGPIPE, SIG_DFL);  // the test ignores it (FifoWriter), the command must not inherit that
    if (r.address_space && ::setrlimit(RLIMIT_AS, &limit) != 0) ::_exit(126);
    ::dup2(in_fd, 0);
    if (out_fd < 0)
      ::close(1);
    else
      ::dup2(out_fd, 1);
    ::dup2(err_fd, 2);
    ::execve(exe.c_str(), argv.data(), envp.data());
    ::_exit(127);
  }
  for (const int fd : {in_fd, out_fd, err_fd})
    if (fd >= 0) ::close(fd);
  if (pid > 0) {
    ::setpgid(pid, pid);  // also here: the kill below must find the group
    const auto start = std::chrono::steady_clock::now();
    int status = 0;
    while (waitpid(pid, &status, WNOHANG) == 0) {
      if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > kRunSeconds) {
        kill(-pid, SIGKILL);
        waitpid(pid, &status, 0);
        o.timed_out = true;
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    o.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  }
  o.out = slurp(out);
  o.err = slurp(err);
  for (const auto& f : {out, err, in}) std::remove(f.c_str());
  return o;
}

/// Reads a FIFO while a command writes into it (opened without blocking, so
/// that a command that never opens it does not hang the test).
class FifoReader {
 public:
  explicit FifoReader(const std::string& path) : fd_(::open(path.c_str(), O_RDONLY | O_NONBLOCK)) {
    thread_ = std::thread([this] {
      for (bool last = false; fd_ >= 0;) {
        pollfd p{fd_, POLLIN, 0};
        ::poll(&p, 1, 20);
        char buf[65536];
        ssize_t got = 0;
        while ((got = ::read(fd_, buf, sizeof buf)) > 0) data_.append(buf, static_cast<std::size_t>(got));
        if (last) break;
        last = stop_.load();
      }
    });
  }
  /// Everything read, once the writer has exited.
  std::string finish() {
    stop_ = true;
    thread_.join();
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
    return data_;
  }
  ~FifoReader() {
    if (thread_.joinable()) finish();
  }

 private:
  int fd_;
  std::atomic<bool> stop_{false};
  std::string data_;
  std::thread thread_;
};

/// Writes a text into a FIFO once a command opens it for reading (opened
/// without blocking and retried, so that a command that never opens it does
/// not hang the test: the writer gives up after kFifoWriterPatience).
class FifoWriter {
 public:
  static constexpr std::chrono::seconds kFifoWriterPatience{15};
  FifoWriter(const std::string& path, std::string text)
      : thread_([this, path, text = std::move(text)] {
          // A reader that closes the FIFO before reading it all (a command
          // that looks at it and refuses) must not kill the test with SIGPIPE.
          ::signal(SIGPIPE, SIG_IGN);
          const auto deadline = std::chrono::steady_clock::now() + kFifoWriterPatience;
          while (!stop_.load() && std::chrono::steady_clock::now() < deadline) {
            const int fd = ::open(path.c_str(), O_WRONLY | O_NONBLOCK);
            if (fd < 0) {  // ENXIO: no reader yet
              std::this_thread::sleep_for(std::chrono::milliseconds(10));
              continue;
            }
            ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
            for (std::size_t at = 0; at < text.size();) {
              const ssize_t put = ::write(fd, text.data() + at, text.size() - at);
              if (put <= 0) break;
              at += static_cast<std::size_t>(put);
            }
            ::close(fd);
            return;
          }
        }) {}
  ~FifoWriter() {
    stop_ = true;
    thread_.join();
  }

 private:
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

// ---------------------------------------------------------------------------
// Cases

using Rng = std::mt19937_64;

template <class T>
const T& pick(Rng& rng, const std::vector<T>& v) {
  return v[std::uniform_int_distribution<std::size_t>(0, v.size() - 1)(rng)];
}
std::string pick(Rng& rng, const std::vector<std::string>& v) { return pick<std::string>(rng, v); }
bool coin(Rng& rng, double p = 0.5) { return std::bernoulli_distribution(p)(rng); }
int between(Rng& rng, int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); }

/// A scene as the text of its values, each spelled as it goes into the TOML
/// (so `1e-3`, `"1/3"`, `inf`, `"1e400"`).
struct Spec {
  std::vector<std::string> mass, velocity;  ///< velocity "" = the body falls
  std::vector<std::pair<std::string, std::string>> K;
  std::string alpha2, fall_speed, drop_height, g;
  int n() const { return static_cast<int>(mass.size()); }
  std::string toml() const {
    std::ostringstream os;
    os << "title = \"red team\"\n";
    if (!fall_speed.empty()) os << "fall_speed = " << fall_speed << '\n';
    if (!drop_height.empty()) os << "drop_height = " << drop_height << '\n';
    if (!g.empty()) os << "g = " << g << '\n';
    for (int i = 0; i < n(); ++i) {
      os << "[[body]]\nmass = " << mass[static_cast<std::size_t>(i)] << '\n';
      if (!velocity[static_cast<std::size_t>(i)].empty()) os << "velocity = " << velocity[static_cast<std::size_t>(i)] << '\n';
    }
    os << "[dissipation]\nK = {";
    for (std::size_t k = 0; k < K.size(); ++k) os << (k ? ", " : " ") << '"' << K[k].first << "\" = " << K[k].second;
    os << " }\n";
    if (!alpha2.empty()) os << "alpha = { \"2\" = " << alpha2 << " }\n";
    return os.str();
  }
};

/// The value of a spelling of Spec (a TOML number or a string holding a
/// decimal or a fraction), or nothing when it is not a plain number.
std::optional<long double> value_of(std::string s) {
  if (s.size() >= 2 && s.front() == '"' && s.back() == '"') s = s.substr(1, s.size() - 2);
  std::string t;
  for (char c : s)
    if (c != '_') t += c;
  const auto slash = t.find('/');
  if (slash != std::string::npos) {
    const auto p = value_of(t.substr(0, slash)), q = value_of(t.substr(slash + 1));
    if (!p || !q || *q == 0) return std::nullopt;
    return *p / *q;
  }
  if (t.empty()) return std::nullopt;
  char* end = nullptr;
  const long double x = std::strtold(t.c_str(), &end);
  if (*end != 0 || std::isnan(x)) return std::nullopt;
  return x;
}

/// A scene of 2 to 5 bodies that the tool accepts: positive masses, the
/// bottom one at rest (fixed or not), K on adjacent pairs, falling bodies.
Spec random_spec(Rng& rng) {
  Spec s;
  const int n = between(rng, 2, 5);
  const std::vector<std::string> masses = {"1e-3", "0.5", "1", "10", "\"1/3\"", "2.5e2", "15", "7"};
  for (int i = 0; i + 1 < n; ++i) {
    s.mass.push_back(coin(rng, 0.3) ? "1e" + std::to_string(between(rng, -6, 6)) : pick(rng, masses));
    s.velocity.push_back("");
  }
  s.mass.push_back(coin(rng) ? "inf" : pick(rng, {std::string("5e6"), std::string("100"), std::string("1")}));
  s.velocity.push_back("0");
  const std::vector<std::string> ks = {"1", "7", "0.5", "1500", "\"1/10\"", "10", "13"};
  for (int i = 1; i < n; ++i) s.K.push_back({std::to_string(i) + "-" + std::to_string(i + 1), pick(rng, ks)});
  if (n >= 3 && coin(rng, 0.3)) s.K.push_back({"1-3", pick(rng, ks)});
  if (coin(rng))
    s.fall_speed = pick(rng, {std::string("3.13209"), std::string("1"), std::string("\"1/2\""), std::string("2.5")});
  else {
    s.drop_height = pick(rng, {std::string("0.5"), std::string("\"1/2\""), std::string("2")});
    if (coin(rng)) s.g = pick(rng, {std::string("9.81"), std::string("1"), std::string("\"981/100\"")});
  }
  return s;
}

/// Velocities before the collision of \p s, as the scene defines them.
std::optional<std::vector<long double>> velocities_before(const Spec& s) {
  std::optional<long double> a;
  if (!s.fall_speed.empty()) a = value_of(s.fall_speed);
  if (!s.drop_height.empty()) {
    const auto h = value_of(s.drop_height), g = value_of(s.g.empty() ? "9.81" : s.g);
    if (h && g) a = std::sqrt(2 * *g * *h);
  }
  std::vector<long double> u;
  for (const auto& v : s.velocity) {
    const auto x = v.empty() ? (a ? std::optional<long double>(-*a) : std::nullopt) : value_of(v);
    if (!x) return std::nullopt;
    u.push_back(*x);
  }
  return u;
}

/// What the last run of a case must give: anything (the invariants of every
/// run), exit 2, exit 0, exit 3, exit 0 with runs[0]'s output or exit 2,
/// exit 2 or 3.
enum class Expect { Any, Refused, Success, OutputFailure, SameOrRefused, NotWritten };

/// Which runs must give what runs[0] gives: All (exit code and output), Last
/// (the last run, when it exits 0: the runs between prepare it), None.
enum class Compare { All, Last, None };

/// The writers of the FIFOs a case makes as it goes.
using Writers = std::vector<std::unique_ptr<FifoWriter>>;

/// How a case's `-o` target is made before the run.
enum class Target { None, File, Symlink, DanglingSymlink, Fifo, Directory, MissingFolder, FullDevice };

/// Make \p path a full device (as /dev/full: every write fails with ENOSPC);
/// false where the system does not let us (then the case is skipped).
bool make_full_device(const std::string& path) { return mknod(path.c_str(), S_IFCHR | 0644, makedev(1, 7)) == 0; }

/// One hostile case: files written into its folder, the command lines
/// (runs[1..] must give what runs[0] gives), what it must give.
struct Case {
  std::map<std::string, std::string> files;  ///< name in the case's folder -> content
  std::map<std::string, std::string> fifos;  ///< FIFOs made in the case's folder -> what a writer puts in them
  std::vector<std::string> full_devices;     ///< full devices made in the case's folder
  std::vector<Command> runs;
  Expect expect = Expect::Any;
  std::optional<Spec> spec;    ///< the scene of a `solve --json`, for the physics check
  Target target = Target::None;
  std::string target_path;     ///< the -o argument (under the case's folder)
  bool target_reference = false;  ///< runs[0] wrote to standard output what runs[1] writes to -o
  Compare compare = Compare::All;
  /// Called before runs[i] (i from 0) with the case's folder: makes links,
  /// tampers with what the runs before wrote (a FIFO it makes gets its writer
  /// in the Writers).
  std::function<void(const std::string& dir, std::size_t run, Writers&)> before;
  std::vector<std::string> untouched;  ///< files of the case's folder the last run leaves as they were (content, link or not)
  bool nothing_new = false;            ///< the last run adds nothing to the case's folder
  std::vector<std::string> named;      ///< the one line of a refusal names one of these
  /// Spellings of one key: in the outputs, `first` reads as `second` before they are compared.
  std::vector<std::pair<std::string, std::string>> spellings;
  std::string what;  ///< what happens between the runs (shown in a report)
  /// The class's own invariant over the outcomes of the runs.
  std::function<void(const std::vector<Outcome>&, std::vector<std::string>&)> check;
};

const std::string kSentinel = "sentinel: this file must survive a failing command\n";

/// Arguments name the case's folder as "@/"; replaced before the run.
std::vector<std::string> in_folder(std::vector<std::string> args, const std::string& dir) {
  for (auto& a : args) {
    const auto at = a.find("@/");
    if (at != std::string::npos) a.replace(at, 2, dir + "/");
  }
  return args;
}

Command solve_json(Rng& rng, std::string precision = "") {
  if (precision.empty())
    precision = pick(rng, {std::string("auto"), std::string("double"), std::string("long-double"), std::string("exact"),
                           std::string("digits:30")});
  return Command{{"solve", "@/scene.toml", "--json", "--precision", precision}};
}

// The classes.  Each maker builds case `index`: indices below the class's
// count of enumerated cases are fixed (the issue's examples), above it random.

/// Valid random scenes: the physics check on ordinary answers.
Case make_valid(Rng& rng, int) {
  Case c;
  c.spec = random_spec(rng);
  c.files["scene.toml"] = c.spec->toml();
  c.runs = {solve_json(rng)};
  return c;
}

/// Huge and tiny exponents in every number of a scene.
Case make_exponent(Rng& rng, int index) {
  Case c;
  Spec s = random_spec(rng);
  static const std::vector<int> exps = {20, 40, 150, 200, 300, 307, 308, 309, 320, 324, 330, 400, 4000};
  std::string e = "1e" + std::string(coin(rng) ? "-" : "") + std::to_string(pick(rng, exps));
  std::string precision;
  // The issue's examples first: fall speed and drop height 1e400 (auto),
  // two bodies of 1e-200 (double), four bodies near 1e299 (double).
  static const std::vector<std::string> examples = {"1e400", "1e400", "1e-200", "1e299"};
  static const std::vector<int> example_fields = {6, 5, 7, 1};
  if (index < 4) e = examples[static_cast<std::size_t>(index)], precision = index < 2 ? "auto" : "double";
  if (index < 2 || coin(rng)) e = '"' + e + '"';
  const int field = index < 4 ? example_fields[static_cast<std::size_t>(index)] : between(rng, 0, 7);
  const auto body = static_cast<std::size_t>(between(rng, 0, s.n() - 1));
  switch (field) {
    case 0: s.mass[body] = e; break;
    case 1: s.mass = std::vector<std::string>(s.mass.size(), e), s.mass.back() = coin(rng) ? "inf" : e; break;
    case 2: s.velocity[body] = (coin(rng) ? "-" : "") + e; break;
    case 3: s.K[static_cast<std::size_t>(between(rng, 0, static_cast<int>(s.K.size()) - 1))].second = e; break;
    case 4: s.g = e, s.drop_height = "0.5", s.fall_speed = ""; break;
    case 5: s.drop_height = e, s.fall_speed = ""; break;
    case 6: s.fall_speed = e, s.drop_height = "", s.g = ""; break;
    default:  // the issue's pair of tiny bodies: products underflow
      s = Spec{{e, e}, {"-1e-150", "0"}, {{"1-2", "1"}}, "", "1", "", ""};
  }
  c.spec = s;
  c.files["scene.toml"] = s.toml();
  c.runs = {solve_json(rng, precision)};
  return c;
}

/// A byte-order mark before the scene: the same answer as without it.
Case make_bom(Rng& rng, int) {
  Case c;
  Spec s = random_spec(rng);
  if (coin(rng)) s.fall_speed = "   1.5e3", s.drop_height = "", s.g = "";
  // The first line holds a number (where the mark shifts the columns).
  std::string text = s.toml();
  const auto first = text.find('\n') + 1, second = text.find('\n', first) + 1;
  text = text.substr(first, second - first) + text.substr(0, first) + text.substr(second);
  c.files["a/scene.toml"] = "\xEF\xBB\xBF" + text;
  c.files["b/scene.toml"] = text;
  c.runs = {Command{{"solve", "@/a/scene.toml"}}, Command{{"solve", "@/b/scene.toml"}}};
  return c;
}

/// Keys, headers, inline tables and arrays nested thousands deep.
Case make_nesting(Rng& rng, int index) {
  Case c;
  static const std::vector<int> depths = {64, 1000, 10000, 35000, 50000, 100000};
  const int depth = index < 4 ? 50000 : pick(rng, depths);
  const int kind = index < 4 ? index : between(rng, 0, 3);
  std::string t;
  if (kind == 0 || kind == 1) {
    std::string key = "a";
    for (int i = 1; i < depth; ++i) key += ".a";
    t = kind == 0 ? key + " = 1\n" : "[" + key + "]\nb = 1\n";
  } else {
    t = "x = ";
    for (int i = 0; i < depth; ++i) t += kind == 2 ? "[" : "{a=";
    t += "1";
    for (int i = 0; i < depth; ++i) t += kind == 2 ? ']' : '}';
    t += '\n';
  }
  c.files["scene.toml"] = coin(rng) ? t : random_spec(rng).toml() + t;
  c.runs = {coin(rng) || index == 0 ? Command{{"solve", "@/scene.toml"}} : Command{{"derive", "--scene", "@/scene.toml", "--case", "1"}}};
  c.expect = Expect::Refused;
  return c;
}

/// Control characters (NUL, newline, ESC, DEL, ...) in keys, values and arguments.
Case make_control(Rng& rng, int) {
  Case c;
  static const std::vector<std::string> bytes = {std::string(1, '\0'), "\n", "\x1b", "\x7f", "\x01", "\r", "\x1b[31m", "\f"};
  const std::string b = pick(rng, bytes);
  std::string text = random_spec(rng).toml();
  const int where = between(rng, 0, 3);
  if (where == 0) {  // inside the first key on a line
    const auto at = text.find("mass");
    text.insert(at + 2, b);
  } else if (where == 1) {  // after a value (where a newline or CR would be a line end)
    const auto at = text.find('\n', text.find("mass"));
    text.insert(at, b == "\n" || b == "\r" ? "\x1b" : b);
  } else if (where == 2) {  // a quoted key of K
    const auto at = text.find("-2\"");
    text.insert(at + 1, b);
  } else {  // an unknown key of its own
    text += "ke" + b + "y = 1\n";
  }
  c.files["scene.toml"] = text;
  if (b.find('\0') == std::string::npos && coin(rng, 0.3)) {  // an argument holding the byte (a NUL cannot)
    c.files["scene.toml"] = random_spec(rng).toml();
    c.runs = {coin(rng) ? Command{{"sweep", "@/scene.toml", "--vary", "K.1" + b + "-2=0:1:3"}}
                        : Command{{"solve", "@/scene.toml", "--precision", "digits:3" + b}}};
  } else {
    c.runs = {Command{{"solve", "@/scene.toml"}}};
  }
  c.expect = Expect::Refused;
  return c;
}

/// A `solve` of \p s with field \p field (0 the top mass, 1 the first K,
/// 2 the fall speed, 3 the top velocity) spelled \p v, which must be refused.
Case refused_with(Spec s, int field, const std::string& v) {
  if (field == 0) s.mass[0] = v;
  if (field == 1) s.K[0].second = v;
  if (field == 2) s.fall_speed = v, s.drop_height = "", s.g = "";
  if (field == 3) s.velocity[0] = v;
  Case c;
  c.files["scene.toml"] = s.toml();
  c.runs = {Command{{"solve", "@/scene.toml"}}};
  c.expect = Expect::Refused;
  return c;
}

/// Numbers whose underscores TOML forbids, bare or in strings.
Case make_underscore(Rng& rng, int index) {
  static const std::vector<std::string> spellings = {"\"_1_\"", "\"1__0\"", "\"1_\"", "\"_1\"", "\"1_/3\"", "\"1/_3\"",
                                                     "1__0", "_1", "1_", "1_.5", "1._5", "1e_3", "\"1e_3\""};
  const std::string v = index == 0 ? "\"_1_\"" : pick(rng, spellings);
  Spec s = random_spec(rng);
  const int field = index == 0 ? 0 : between(rng, 0, 3);
  return refused_with(s, field, v);
}

/// inf / +inf / nan spellings: the bottom mass's spellings mean one thing;
/// NaN anywhere and infinity elsewhere are refused.
Case make_special(Rng& rng, int index) {
  Case c;
  static const std::vector<std::string> infs = {"inf", "+inf", "\"inf\"", "\"+inf\""};
  static const std::vector<std::string> bad = {"nan", "+nan", "-nan", "\"nan\"", "\"NaN\"", "\"-inf\"", "-inf",
                                               "\"Infinity\"", "\"INF\"", "\"+nan\""};
  Spec s = random_spec(rng);
  s.mass.back() = "inf";
  if (index < 3 || coin(rng)) {
    Spec t = s;
    s.mass.back() = index < 3 ? infs[static_cast<std::size_t>(index + 1)] : pick(rng, infs);
    c.files["a/scene.toml"] = s.toml();
    c.files["b/scene.toml"] = t.toml();
    c.runs = {Command{{"solve", "@/a/scene.toml"}}, Command{{"solve", "@/b/scene.toml"}}};
    return c;
  }
  const std::string v = coin(rng, 0.7) ? pick(rng, bad) : pick(rng, infs);
  const int field = between(rng, 0, 3);
  return refused_with(s, field, v);
}

/// Scene paths that are not regular files, and standard input.
Case make_path(Rng& rng, int index) {
  Case c;
  const Spec spec = random_spec(rng);
  const std::string good = spec.toml();
  c.files["folder/.keep"] = "";
  switch (index % 6) {
    case 0: c.runs = {Command{{"solve", "@/folder"}}}, c.expect = Expect::Refused; break;
    case 1:  // read as a stream, like standard input (`solve <(generator)`)
      c.fifos["fifo"] = good, c.spec = spec;
      c.runs = {Command{{"solve", "@/fifo", "--json"}}}, c.expect = Expect::Success;
      break;
    case 2: c.runs = {Command{{"solve", "@/no-such-file.toml"}}}, c.expect = Expect::Refused; break;
    case 3: c.files["empty.toml"] = "", c.runs = {Command{{"solve", "@/empty.toml"}}}, c.expect = Expect::Refused; break;
    case 4:
      c.files["big.toml"] = good + "# " + std::string(5u << 20, 'x') + "\n";
      c.runs = {Command{{"solve", "@/big.toml"}}}, c.expect = Expect::Refused;
      break;
    default:
      c.runs = {Command{{"solve", "-"}, good}}, c.expect = Expect::Success;
      c.files["scene.toml"] = good;
  }
  return c;
}

/// Sweeps across inadmissible values, descending, at every precision; the
/// output must not depend on --threads.
Case make_sweep(Rng& rng, int index) {
  Case c;
  Spec s = random_spec(rng);
  static const std::vector<std::string> fixed = {"g=-1:1:3", "drop_height=-1:1:3", "fall_speed=-1:1:3", "K.1-2=20:0:5"};
  std::string key = pick(rng, {std::string("g"), std::string("drop_height"), std::string("fall_speed"), std::string("K.1-2"),
                               std::string("mass.1"), std::string("velocity.1")});
  std::string from = pick(rng, {std::string("-1"), std::string("0"), std::string("-1e-300"), std::string("1/3")});
  std::string to = pick(rng, {std::string("1"), std::string("3"), std::string("1e300"), std::string("20"), std::string("1e400")});
  if (coin(rng, 0.3)) std::swap(from, to);
  std::string vary = key + "=" + from + ":" + to + ":" + std::to_string(pick(rng, std::vector<int>{2, 3, 5, 11}));
  if (index < static_cast<int>(fixed.size())) {
    vary = fixed[static_cast<std::size_t>(index)];
    if (vary[0] == 'g') s.drop_height = "0.5", s.fall_speed = "";
  }
  c.files["scene.toml"] = s.toml();
  std::vector<std::string> args = {"sweep", "@/scene.toml", "--vary", vary};
  const int mode = index < static_cast<int>(fixed.size()) ? index % 3 : between(rng, 0, 2);
  if (mode == 1) args.push_back("--csv");
  if (mode == 2) args.push_back("--switch-points");
  if (coin(rng, 0.3)) args.insert(args.end(), {std::string("--precision"), pick(rng, {std::string("exact"), std::string("long-double")})});
  auto with_threads = [&](const char* t) {
    auto a = args;
    a.insert(a.end(), {"--threads", t});
    return Command{a};
  };
  c.runs = {with_threads("1"), with_threads("2")};
  return c;
}

/// Options that contradict each other or make no sense: refused, not dropped.
Case make_conflict(Rng& rng, int index) {
  Case c;
  c.files["scene.toml"] = random_spec(rng).toml();
  static const std::vector<std::vector<std::string>> lines = {
      {"sweep", "@/scene.toml", "--vary", "K.1-2=0:20:5", "--switch-points", "--precision", "double"},  // the bisection is exact
      {"derive", "--scene", "@/scene.toml", "--bodies", "5", "--case", "1"},
      {"derive", "--closed", ""},
      {"nosuchcmd"},
      {"solve", "@/scene.toml", "--rtol", "nan"},
      {"solve", "@/scene.toml", "--rtol", "-1"},
      {"solve", "@/scene.toml", "--precision", "digits:0"},
      {"solve", "@/scene.toml", "--precision", "digits:-5"},
      {"solve", "@/scene.toml", "--precision", "digits:99999999999999999999"},
      {"solve", "@/scene.toml", "--precision", "float"},
      {"sweep", "@/scene.toml", "--vary", "K.1-2=0:20:5", "--threads", "-1"},
      {"sweep", "@/scene.toml", "--vary", "K.1-2=0:20:1"},
      {"sweep", "@/scene.toml", "--vary", "K.1-2=nan:1:3"},
      {"sweep", "@/scene.toml", "--vary", "K.1-2=0:inf:3"},
      {"sweep", "@/scene.toml", "--vary", "K.9-10=0:1:3"},
      {"sweep", "@/scene.toml", "--vary", "=0:1:3"},
      {"solve"},
      {"solve", "@/scene.toml", "@/scene.toml"},
      {"derive", "--case", "9"},
      {"derive", "--bodies", "2", "--closed", "1-3"},
      {"derive", "--bodies", "1000000", "--closed", "none"},
  };
  c.runs = {Command{lines[static_cast<std::size_t>(index) % lines.size()]}};
  c.expect = Expect::Refused;
  return c;
}

/// `-o` into a file, a symlink, a FIFO, a folder, a missing folder, by a
/// command that fails or succeeds.
Case make_output(Rng& rng, int index) {
  Case c;
  static const std::vector<Target> targets = {Target::File, Target::Symlink, Target::DanglingSymlink, Target::Fifo,
                                              Target::Directory, Target::MissingFolder, Target::FullDevice};
  c.target = targets[static_cast<std::size_t>(index) % targets.size()];
  const bool fails = index >= 2 * static_cast<int>(targets.size()) ? coin(rng) : (index / static_cast<int>(targets.size())) % 2 == 0;
  c.target_path = c.target == Target::MissingFolder ? "@/out/missing/derived.txt" : "@/out/derived.txt";
  const std::vector<std::string> good = {"derive", "--case", "1", "--alphas", "2"};
  const std::vector<std::string> bad = {"derive", "--case", "9", "--alphas", "2"};
  auto with_o = [&](std::vector<std::string> a) {
    a.insert(a.end(), {"-o", c.target_path});
    return a;
  };
  if (fails) {
    c.runs = {Command{with_o(bad)}};
    c.expect = Expect::Refused;
  } else {
    c.runs = {Command{good}, Command{with_o(good)}};
    c.target_reference = true;
    const bool writable = c.target == Target::File || c.target == Target::Symlink || c.target == Target::Fifo;
    // A folder, a missing folder, a full device: exit 3.
    c.expect = writable ? Expect::Success : c.target == Target::DanglingSymlink ? Expect::Any : Expect::OutputFailure;
  }
  return c;
}

/// Standard output closed, or a full device: the result cannot be written, exit 3.
Case make_stdout(Rng& rng, int index) {
  Case c;
  c.files["scene.toml"] = random_spec(rng).toml();
  static const std::vector<std::vector<std::string>> lines = {
      {"solve", "@/scene.toml", "--json"}, {"solve", "@/scene.toml"}, {"sweep", "@/scene.toml", "--vary", "K.1-2=0:20:5", "--csv"},
      {"derive", "--case", "1", "--alphas", "2"}};
  Command r{lines[static_cast<std::size_t>(index) % lines.size()]};
  if ((index / 4) % 2 == 0) {
    r.close_stdout = true;
  } else {
    c.full_devices = {"full"};
    r.stdout_path = "@/full";
  }
  c.runs = {r};
  c.expect = Expect::OutputFailure;
  return c;
}

// ---- Issue 25: the surfaces of a run spread over time and machines ----

/// The paper's scene of §4.4 read with alpha_2 = -100 (n = 4): the scene of
/// the job-array, checkpoint, spelling, memory and MPI classes.
const std::string kPaperScene =
    "title = \"Paper 4.4 read with alpha_2 = -100\"\nfall_speed = 3.13209\n"
    "[[body]]\nmass = 0.001\n[[body]]\nmass = 10\n[[body]]\nmass = 15\n[[body]]\nmass = 5e6\nvelocity = 0\n"
    "[dissipation]\nK = { \"1-2\" = 7, \"1-3\" = 7, \"1-4\" = 1500, \"2-3\" = 10, \"2-4\" = 13, \"3-4\" = 10 }\n"
    "alpha = { \"2\" = -100 }\n";

/// The superball under test is built with sanitizers (SUPERBALL_SANITIZE):
/// its shadow memory needs terabytes of address space, so no run has an
/// address-space limit, the memory class is skipped and no file is made huge.
constexpr bool kSanitized = SUPERBALL_REDTEAM_SANITIZED;

/// Address space given to a command reading files a test tampered with: a
/// claimed or real size of gigabytes ends in bad_alloc, not in the machine's
/// swap (none under sanitizers, where no file is made huge).
constexpr std::uint64_t kTamperedAddressSpace = kSanitized ? 0 : 2ull << 30;

/// The task lists of the job-array and checkpoint classes: small, fast
/// runs of several tasks (sweep: 2 blocks of 4096 values; map 9 x 9: 41 +
/// tasks; explore: the 8 cases of alpha_5, 0.3 s; verify --case: one task).
const std::vector<std::vector<std::string>> kTaskLists = {
    {"sweep", "@/scene.toml", "--vary", "K.3-4=0:20:8193", "--switch-points"},
    {"explore", "--all", "--alphas", "5", "--starts", "2", "--evaluations", "60"},
    {"verify", "--case", "1", "--alphas", "2", "--samples", "40", "--epsilons", "1/100", "--threads", "1"},
    {"map", "@/scene.toml", "--x", "K.3-4=0:20:9", "--y", "alpha.2=-150:0:9"},
};

/// How a part file or a checkpoint's task file is tampered with.
enum class Tamper { None, Flip, Number, Word, Argument, ArgumentShard, Truncate, Huge, Trailing, Symlink, Fifo, Folder };
const std::vector<Tamper> kTampers = {Tamper::Flip,      Tamper::Number, Tamper::Word,     Tamper::Argument, Tamper::ArgumentShard, Tamper::Truncate,
                                      Tamper::Huge,      Tamper::Trailing, Tamper::Symlink, Tamper::Fifo,     Tamper::Folder};
const char* tamper_name(Tamper t) {
  static const char* const names[] = {"none",     "a byte flipped", "a number edited", "a word edited", "an --output argument injected",
                                      "--shard/--part arguments injected", "truncated", "a huge length", "1 MB after its end",
                                      "a symlink to another file", "a FIFO", "a folder"};
  return names[static_cast<int>(t)];
}

/// A part file's results: the text before the first task, each task's line
/// number and text, what follows the last task (`end`).
struct PartText {
  std::string head, tail;
  struct Task {
    std::string line, text, checksum;  ///< "task K", its text, its checksum as written
  };
  std::vector<Task> tasks;
  static std::optional<PartText> parse(const std::string& s) {
    PartText p;
    std::size_t at = s.find("\ntask ");
    if (at == std::string::npos) return std::nullopt;
    p.head = s.substr(0, at + 1);
    at += 1;
    while (s.compare(at, 5, "task ") == 0) {
      const std::size_t nl = s.find('\n', at);
      if (nl == std::string::npos) return std::nullopt;
      // "task K SIZE CHECKSUM": the checksum is kept as it is (a forger who
      // does not recompute it), the size follows the edited text.
      std::istringstream words(s.substr(at, nl - at));
      std::string task, k, length, checksum;
      words >> task >> k >> length >> checksum;
      if (length.empty() || length.find_first_not_of("0123456789") != std::string::npos || length.size() > 12) return std::nullopt;
      const std::size_t size = std::stoull(length);
      if (nl + 1 + size > s.size()) return std::nullopt;
      p.tasks.push_back({task + " " + k, s.substr(nl + 1, size), checksum});
      at = nl + 1 + size + 1;
    }
    p.tail = s.substr(std::min(at, s.size()));
    return p;
  }
  /// The part again, each task's length as its (edited) text has it: an
  /// edit a careful forger makes.
  std::string text() const {
    std::string s = head;
    for (const Task& t : tasks) s += t.line + " " + std::to_string(t.text.size()) + (t.checksum.empty() ? "" : " " + t.checksum) + "\n" + t.text + "\n";
    return s + tail;
  }
};

/// Edits a number or a word of \p text (a task's result): a digit changed, a
/// number replaced by 99, a verdict or a case name swapped (everywhere in
/// the text).  False when \p text has none to edit.
bool edit_text(std::string& text, Rng& rng, bool word) {
  if (word) {
    static const std::vector<std::pair<std::string, std::string>> swaps = {
        {"no (proved)", "yes"}, {"not found", "yes"}, {"case impossible", "yes"}, {"case 2.2", "case 3.3"}, {"case 3.3", "case 3.2"},
        {"case 3.2", "case 9.9"}, {"{3-4}", "{1-2}"}, {"superball", "no superball"}, {"agree", "disagree"}, {"true", "false"}};
    std::vector<std::pair<std::string, std::string>> found;
    for (const auto& s : swaps)
      if (text.find(s.first) != std::string::npos) found.push_back(s);
    if (!found.empty()) {
      const auto& [from, to] = pick(rng, found);  // everywhere: a result may say it twice (its text and its JSON)
      for (std::size_t k = text.find(from); k != std::string::npos; k = text.find(from, k + to.size())) text.replace(k, from.size(), to);
      return true;
    }
  }
  std::vector<std::pair<std::size_t, std::size_t>> numbers;  // digit runs
  for (std::size_t k = 0; k < text.size();) {
    if (!std::isdigit(static_cast<unsigned char>(text[k]))) {
      ++k;
      continue;
    }
    std::size_t e = k;
    while (e < text.size() && std::isdigit(static_cast<unsigned char>(text[e]))) ++e;
    numbers.push_back({k, e - k});
    k = e;
  }
  if (numbers.empty()) return false;
  const auto [at, size] = pick(rng, numbers);
  if (coin(rng)) {
    text.replace(at, size, text.substr(at, size) == "99" ? "41" : "99");
  } else {  // one digit changed: a value still in range, still plausible
    const std::size_t d = at + static_cast<std::size_t>(between(rng, 0, static_cast<int>(size) - 1));
    text[d] = static_cast<char>('0' + (text[d] - '0' + between(rng, 1, 9)) % 10);
  }
  return true;
}

/// Replaces \p path by a FIFO whose writer gives what the file held.
void fifo_in_place(const std::string& path, Writers& writers) {
  const std::string text = slurp(path);
  fs::remove_all(path);
  mkfifo(path.c_str(), 0644);
  writers.push_back(std::make_unique<FifoWriter>(path, text));
}

/// Tampers with the file \p path (a part, a checkpoint's task or run file)
/// as \p how says; \p other is another file of the case (a symlink's
/// target), \p victim a file no command may write.
void tamper(const std::string& path, Tamper how, Rng& rng, const std::string& other, const std::string& victim, Writers& writers) {
  std::string s = slurp(path);
  const bool part = s.rfind("superball part", 0) == 0;
  auto write = [&](const std::string& text) { std::ofstream(path, std::ios::binary | std::ios::trunc) << text; };
  switch (how) {
    case Tamper::None: return;
    case Tamper::Flip:
      if (s.empty()) s = "x";
      s[static_cast<std::size_t>(between(rng, 0, static_cast<int>(s.size()) - 1))] ^= static_cast<char>(between(rng, 1, 255));
      return write(s);
    case Tamper::Number:
    case Tamper::Word: {
      auto p = part ? PartText::parse(s) : std::nullopt;
      if (p && !p->tasks.empty()) {
        auto& task = p->tasks[static_cast<std::size_t>(between(rng, 0, static_cast<int>(p->tasks.size()) - 1))].text;
        if (!edit_text(task, rng, how == Tamper::Word)) task += "0";
        return write(p->text());
      }
      if (!edit_text(s, rng, how == Tamper::Word)) s += "0";
      return write(s);
    }
    case Tamper::Argument:
    case Tamper::ArgumentShard: {  // before the `tasks` line, as the run's own arguments are
      const std::size_t at = s.find("\ntasks ");
      std::string lines;
      for (const std::string& a : how == Tamper::Argument ? std::vector<std::string>{"--output=" + victim}
                                                          : std::vector<std::string>{"--shard=1/2", "--part=" + victim})
        lines += "argument " + std::to_string(a.size()) + " " + a + "\n";
      if (at == std::string::npos)
        s = lines + s;
      else
        s.insert(at + 1, lines);
      return write(s);
    }
    case Tamper::Truncate: return write(s.substr(0, static_cast<std::size_t>(between(rng, 0, std::max(0, static_cast<int>(s.size()) - 1)))));
    case Tamper::Huge: {
      auto p = part ? PartText::parse(s) : std::nullopt;
      if (p && !p->tasks.empty()) {  // a task claiming gigabytes (or a negative or 20-digit length)
        static const std::vector<std::string> sizes = {"10000000000", "6000000000", "-1", "18446744073709551615", "99999999999999999999"};
        std::string t = p->head;
        for (std::size_t k = 0; k < p->tasks.size(); ++k)
          t += p->tasks[k].line + " " + (k == 0 ? pick(rng, sizes) : std::to_string(p->tasks[k].text.size())) +
               (p->tasks[k].checksum.empty() ? "" : " " + p->tasks[k].checksum) + "\n" + p->tasks[k].text + "\n";
        return write(t + p->tail);
      }
      // A sparse file of 6 GB: nothing on disk, gigabytes to whoever reads it whole.
      std::filesystem::resize_file(path, 6ull << 30);
      return;
    }
    case Tamper::Trailing: return write(s + std::string(1u << 20, 'x'));
    case Tamper::Symlink:
      fs::remove(path);
      fs::create_symlink(other, path);
      return;
    case Tamper::Fifo: return fifo_in_place(path, writers);
    case Tamper::Folder:
      fs::remove(path);
      fs::create_directories(path + "/inside");
      return;
  }
}

/// The task files of a checkpoint folder (in its stage folders too), in order.
std::vector<std::string> task_files(const std::string& folder) {
  std::vector<std::string> files;
  std::error_code ec;
  for (const auto& e : fs::recursive_directory_iterator(folder, ec))
    if (e.path().filename().string().rfind("task-", 0) == 0 && fs::is_regular_file(e.symlink_status())) files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  return files;
}

/// Job-array parts made by a first run, tampered with, then merged.  The
/// merge of untampered parts gives the bytes of the unsharded run; of a
/// tampered part, one line naming it (exit 2), never a write outside its
/// standard output, never a value the unsharded run does not print.
Case make_part(Rng& rng, int index) {
  Case c;
  // Enumerated: the parts as written, the issue's two injections into both
  // parts, a huge length, a tail after `end`, an edited word, a FIFO, a
  // flipped byte (the checkpoint class enumerates the other ways); then any
  // way, on any of sweep (0), explore (1) and verify (2).
  static const std::vector<std::pair<Tamper, std::size_t>> enumerated = {
      {Tamper::None, 0},     {Tamper::Argument, 1}, {Tamper::ArgumentShard, 1}, {Tamper::Huge, 0},
      {Tamper::Trailing, 2}, {Tamper::Word, 0},     {Tamper::Fifo, 1},          {Tamper::Flip, 2}};
  const bool listed = index < static_cast<int>(enumerated.size());
  Tamper how = listed ? enumerated[static_cast<std::size_t>(index)].first : pick(rng, kTampers);
  if (kSanitized && how == Tamper::Huge) how = Tamper::Trailing;
  const std::size_t list = listed ? enumerated[static_cast<std::size_t>(index)].second : static_cast<std::size_t>(between(rng, 0, 2));
  const std::vector<std::string> args = kTaskLists[list];
  c.files["scene.toml"] = kPaperScene;
  c.files["victim"] = kSentinel;
  c.runs = {Command{args}};
  for (const char* shard : {"1", "2"}) {
    Command r{args};
    r.args.insert(r.args.end(), {"--shard", std::string(shard) + "/2", "--part", "@/p" + std::string(shard) + ".part"});
    r.setup = true;
    c.runs.push_back(r);
  }
  const bool reversed = coin(rng);
  Command merge{{"merge", reversed ? "@/p2.part" : "@/p1.part", reversed ? "@/p1.part" : "@/p2.part"}};
  merge.address_space = kTamperedAddressSpace;
  c.runs.push_back(merge);
  // verify --case is one task: only part 1 holds it.
  const std::string target = list == 2 || coin(rng) ? "p1.part" : "p2.part";
  const bool both = how == Tamper::Argument || how == Tamper::ArgumentShard;
  const std::string other = pick(rng, {std::string("victim"), std::string("scene.toml"), target == "p1.part" ? std::string("p2.part") : std::string("p1.part")});
  const std::uint64_t seed = rng();
  c.before = [=](const std::string& dir, std::size_t run, Writers& writers) {
    if (run != 3) return;
    Rng r(seed);
    for (const std::string& name : both ? std::vector<std::string>{"p1.part", "p2.part"} : std::vector<std::string>{target})
      tamper(dir + "/" + name, how, r, dir + "/" + other, dir + "/victim", writers);
  };
  c.what = how == Tamper::None ? "the parts merged as they are" : std::string("before the merge: ") + tamper_name(how) + " in " + (both ? "both parts" : target);
  c.compare = Compare::Last;
  c.expect = how == Tamper::None ? Expect::Success : Expect::Refused;
  if (how != Tamper::None) c.named = both ? std::vector<std::string>{"p1.part", "p2.part"} : std::vector<std::string>{target};
  c.untouched = {"victim", "scene.toml"};
  c.nothing_new = true;
  return c;
}

/// A checkpoint folder made by a first run (whole, or cut short by a task
/// made to fail with the test hook SUPERBALL_TEST_FAIL_TASK), a task file
/// (or the run file) tampered with, then the same command again: the bytes
/// of a run without checkpoint (the bad task computed again), or one line
/// (exit 2); never a tampered value with exit 0.
Case make_checkpoint(Rng& rng, int index) {
  Case c;
  // Enumerated: a run cut short resumed as it is, then the ways of tampering
  // the part class does not enumerate; then any way, on any of sweep (0),
  // explore (1) and map (3) (not verify: one task, nothing to resume).
  static const std::vector<std::pair<Tamper, std::size_t>> enumerated = {
      {Tamper::None, 3},    {Tamper::Number, 0},   {Tamper::Truncate, 1}, {Tamper::Symlink, 0},
      {Tamper::Folder, 3},  {Tamper::Huge, 0},     {Tamper::Trailing, 3}, {Tamper::Word, 1}};
  const bool listed = index < static_cast<int>(enumerated.size());
  Tamper how = listed ? enumerated[static_cast<std::size_t>(index)].first : pick(rng, kTampers);
  if (kSanitized && how == Tamper::Huge) how = Tamper::Trailing;
  const std::size_t list = listed ? enumerated[static_cast<std::size_t>(index)].second : pick(rng, std::vector<std::size_t>{0, 1, 3});
  const std::vector<std::string> args = kTaskLists[list];  // not verify: one task, nothing left to resume
  c.files["scene.toml"] = kPaperScene;
  c.files["victim"] = kSentinel;
  Command first{args}, again{args};
  for (Command* r : {&first, &again}) r->args.insert(r->args.end(), {"--checkpoint", "@/ck"});
  first.setup = true;
  if (index == 0 || coin(rng, 0.4)) first.env["SUPERBALL_TEST_FAIL_TASK"] = std::to_string(between(rng, 2, 6));
  again.address_space = kTamperedAddressSpace;
  c.runs = {Command{args}, first, again};
  const std::uint64_t seed = rng();
  c.before = [=](const std::string& dir, std::size_t run, Writers& writers) {
    if (run != 2) return;
    Rng r(seed);
    const auto tasks = task_files(dir + "/ck");
    if (tasks.empty()) return;
    // The run file takes the injected arguments; a task file the rest.
    const bool run_file = how == Tamper::Argument || how == Tamper::ArgumentShard;
    const std::string file = run_file ? fs::path(pick(r, tasks)).parent_path().string() + "/run" : pick(r, tasks);
    std::string other = pick(r, tasks);
    if (other == file) other = dir + "/scene.toml";
    tamper(file, how, r, other, dir + "/victim", writers);
    std::ofstream(dir + "/tampered") << tamper_name(how) << ": " << file << "\n";
  };
  c.what = std::string(first.env.empty() ? "" : "the first run made to fail at task " + first.env["SUPERBALL_TEST_FAIL_TASK"] + "; ") +
           "before the second: " + tamper_name(how) + " in a task file (the file is named in `tampered`)";
  c.compare = Compare::Last;
  c.expect = how == Tamper::None ? Expect::Success : Expect::SameOrRefused;
  c.untouched = {"victim", "scene.toml"};
  return c;
}

/// `solve --json -p digits:N` against `-p exact` on one scene, both exited:
/// where both succeed and the first gives no warning, the same velocities
/// (kDigitsRtol of the largest) and the same case but for ties.
void check_digits(const std::string& digits, const Outcome& digits_run, const Outcome& exact_run, std::vector<std::string>& v) {
  if (digits_run.exit_code != 0 || exact_run.exit_code != 0) return;
  nlohmann::json d, e;
  try {
    d = nlohmann::json::parse(digits_run.out), e = nlohmann::json::parse(exact_run.out);
  } catch (const std::exception&) {
    return;  // check_solution has said it
  }
  if (d.value("status", "") != "success" || e.value("status", "") != "success") return;
  if (d.contains("warnings") && !d["warnings"].empty()) return;  // it says it cannot be trusted
  const std::string who = "solve -p " + digits + " against -p exact: ";
  const auto& dt = d["velocities_after_text"];
  const auto& et = e["velocities_after_exact"];
  if (!dt.is_array() || !et.is_array() || dt.size() != et.size()) return;
  std::vector<long double> dv, ev;
  long double scale = 0;
  for (std::size_t i = 0; i < dt.size(); ++i) {
    const auto x = dt[i].is_string() ? value_of(dt[i].get<std::string>()) : std::nullopt;
    const auto y = et[i].is_string() ? value_of(et[i].get<std::string>()) : std::nullopt;
    if (!x || !y || !std::isfinite(*x) || !std::isfinite(*y)) return;  // symbolic, or beyond long double: no verdict
    dv.push_back(*x), ev.push_back(*y), scale = std::max(scale, std::fabs(*y));
  }
  // The cases differ only by a tie: a contact closed in one, open in the
  // other, with its two bodies at the same velocity (both solve the law).
  std::set<std::string> closed_d, closed_e, either;
  for (const auto& x : d.value("closed_contacts", nlohmann::json::array())) closed_d.insert(x.get<std::string>());
  for (const auto& x : e.value("closed_contacts", nlohmann::json::array())) closed_e.insert(x.get<std::string>());
  std::set_symmetric_difference(closed_d.begin(), closed_d.end(), closed_e.begin(), closed_e.end(), std::inserter(either, either.end()));
  for (const auto& pair : either) {
    unsigned i = 0, j = 0;
    if (std::sscanf(pair.c_str(), "%u-%u", &i, &j) == 2 && i >= 1 && j >= 1 && i <= ev.size() && j <= ev.size() && ev[i - 1] == ev[j - 1]) continue;
    v.push_back(who + "case " + d.value("case", "?") + " against " + e.value("case", "?") + " (contact " + pair + "), with no warning");
    break;
  }
  for (std::size_t i = 0; i < dv.size(); ++i)
    if (std::fabs(dv[i] - ev[i]) > kDigitsRtol * scale) {
      std::ostringstream os;
      os.precision(12);
      os << who << "U" << i + 1 << " = " << dv[i] << " against " << ev[i] << ", with no warning";
      v.push_back(os.str());
      return;
    }
}

/// `solve --json -p digits:N` for every N accepted, on scenes with tiny and
/// huge exponents: an answer with the physics or one line; compared with
/// exact where both succeed and the answer carries no warning.
Case make_digits(Rng& rng, int index) {
  Case c;
  static const std::vector<int> enumerated = {10, 10000, 15, 16, 17, 11, 12, 13, 14};
  // The issue's scenes: a fall speed of 1e-200 on bodies 1, 1, 2; a mass of 1e-320.
  const Spec tiny_speed{{"1", "1", "2"}, {"", "", "0"}, {{"1-2", "1"}, {"2-3", "1"}}, "", "\"1e-200\"", "", ""};
  Spec s;
  int n = 0;
  if (index < static_cast<int>(enumerated.size())) {
    n = enumerated[static_cast<std::size_t>(index)], s = tiny_speed;
  } else if (index < static_cast<int>(enumerated.size()) + 3) {
    n = pick(rng, std::vector<int>{10, 15, 17}), s = random_spec(rng), s.mass[0] = "\"1e-320\"";
  } else {
    n = coin(rng, 0.9) ? between(rng, 10, 120) : between(rng, 121, 2000);
    s = coin(rng, 0.3) ? tiny_speed : random_spec(rng);
    static const std::vector<std::string> extremes = {"\"1e-200\"", "\"1e-320\"", "\"1e200\"", "1e-150", "\"1e300\"", "\"1e-4000\""};
    const int field = between(rng, 0, 3);
    if (field == 0) s.mass[static_cast<std::size_t>(between(rng, 0, s.n() - 2))] = pick(rng, extremes);
    if (field == 1) s.fall_speed = pick(rng, extremes), s.drop_height = "", s.g = "";
    if (field == 2) s.K[0].second = pick(rng, extremes);
  }
  c.spec = s;
  c.files["scene.toml"] = s.toml();
  const std::string digits = "digits:" + std::to_string(n);
  c.runs = {Command{{"solve", "@/scene.toml", "--json", "-p", digits}}, Command{{"solve", "@/scene.toml", "--json", "-p", "exact"}}};
  c.compare = Compare::None;
  c.check = [digits](const std::vector<Outcome>& o, std::vector<std::string>& v) { check_digits(digits, o[0], o[1], v); };
  return c;
}

/// Spellings of one parameter (n = 4): the first is the canonical one.
const std::vector<std::vector<std::string>> kSpellings = {
    {"K.3-4", "K.03-4", "K.3-04", "K.03-04"},
    {"alpha.2", "coupling.1-2/1-4", "coupling.1-4/1-2"},
    {"mass.1", "mass.01"},
    {"K.1-4", "K.01-4"},
};
const std::vector<std::string> kSpellingRanges = {"0:20:3", "-150:0:3", "1/10000:1/100:3", "1000:2000:3"};

/// One parameter under two spellings: two axes of a map naming it are
/// refused with one line; one axis (or --vary) under either spelling gives
/// the same output, the spelling aside.
Case make_spelling(Rng& rng, int index) {
  Case c;
  c.files["scene.toml"] = kPaperScene;
  // The issue's examples first: K.3-4 / K.03-4, alpha.2 / coupling.1-2/1-4,
  // coupling.1-4/1-2 / coupling.1-2/1-4, mass.1 / mass.01.
  static const std::vector<std::array<std::size_t, 3>> refused = {{0, 0, 1}, {1, 0, 1}, {1, 2, 1}, {2, 0, 1}};
  std::size_t p = 0, a = 0, b = 0;
  bool two_axes = index < 4 || coin(rng);
  if (index < 4) {
    p = refused[static_cast<std::size_t>(index)][0], a = refused[static_cast<std::size_t>(index)][1], b = refused[static_cast<std::size_t>(index)][2];
  } else {
    p = static_cast<std::size_t>(between(rng, 0, static_cast<int>(kSpellings.size()) - 1));
    const auto& names = kSpellings[p];
    a = static_cast<std::size_t>(between(rng, 0, static_cast<int>(names.size()) - 1));
    b = (a + static_cast<std::size_t>(between(rng, 1, static_cast<int>(names.size()) - 1))) % names.size();
  }
  const std::string x = kSpellings[p][a], y = kSpellings[p][b], range = kSpellingRanges[p];
  if (two_axes) {
    c.runs = {Command{{"map", "@/scene.toml", "--x", x + "=" + range, "--y", y + "=" + range}}};
    c.expect = Expect::Refused;
    c.named = {y};
    return c;
  }
  // One axis, spelt two ways; the other axis another parameter.
  const std::size_t q = (p + 1) % kSpellings.size();
  const bool sweep = coin(rng);
  auto line = [&](const std::string& key) {
    if (sweep) return Command{{"sweep", "@/scene.toml", "--vary", key + "=" + range.substr(0, range.rfind(':')) + ":21", "--switch-points"}};
    return Command{{"map", "@/scene.toml", "--x", key + "=" + range, "--y", kSpellings[q][0] + "=" + kSpellingRanges[q]}};
  };
  c.runs = {line(x), line(y)};
  for (const std::string& s : {x, y})
    if (s != kSpellings[p][0]) c.spellings.push_back({s, kSpellings[p][0]});
  return c;
}

/// Commands under an address-space limit (`ulimit -v`): a map at the
/// documented maximum of 10^4 x 10^4 points ends within the time limit, with
/// its output or one line; never bad_alloc (exit 4).
Case make_memory(Rng& rng, int index) {
  Case c;
  c.files["scene.toml"] = kPaperScene;
  // Each mode holds the whole grid (a plain --csv grid that does not fit is streamed instead, which takes minutes
  // at this size: docs/MAPS.md), so each is refused at once.
  static const std::vector<std::vector<std::string>> modes = {{}, {"--csv", "--checkpoint", "@/ck"}, {"--json"}, {"--boundary-points", "--csv"}};
  // At most 2 GB: a command that does fit holds no more of the machine than that.
  static const std::vector<std::uint64_t> limits = {2ull << 30, 1ull << 30, 2ull << 30, 512ull << 20};
  const std::size_t mode = index < 4 ? static_cast<std::size_t>(index) : static_cast<std::size_t>(between(rng, 0, 3));
  Command r{{"map", "@/scene.toml", "--x", "K.3-4=0:20:10000", "--y", coin(rng) ? "alpha.2=-150:0:10000" : "K.1-4=1000:2000:10000"}};
  r.args.insert(r.args.end(), modes[mode].begin(), modes[mode].end());
  r.address_space = index < 4 ? limits[static_cast<std::size_t>(index)] : pick(rng, limits);
  c.runs = {r};
  return c;
}

/// Outputs naming an input (the same name, ./name, a symlink, a hard link):
/// refused with one line, the input unchanged byte for byte.
Case make_inout(Rng& rng, int index) {
  Case c;
  const int form = index < 6 ? index % 4 : between(rng, 0, 3);  // 0 the same name, 1 ./name, 2 a symlink, 3 a hard link
  const int kind = index < 6 ? index : between(rng, 0, 7);
  // The scene's name; map --plot PREFIX writes PREFIX.dat.
  const std::string scene = kind == 0 ? "s.dat" : "t.toml", stem = kind == 0 ? "s" : "t.toml";
  const std::string alias = form == 2 ? "link" : form == 3 ? "hard" : "";
  const std::string ext = kind == 0 ? ".dat" : "";
  const std::string out = form == 0 ? "@/" + stem : form == 1 ? "@/./" + stem : "@/" + alias + (kind == 0 ? "" : ".toml");
  c.files[scene] = kPaperScene;
  const std::string in = "@/" + scene;
  switch (kind) {
    case 0: c.runs = {Command{{"map", in, "--x", "K.3-4=0:20:3", "--y", "alpha.2=-150:0:3", "--plot", out}}}; break;
    case 1: c.runs = {Command{{"explore", "--scene", in, "--case", "1", "--starts", "1", "--evaluations", "20", "-o", out}}}; break;
    case 2: c.runs = {Command{{"derive", "--scene", in, "--case", "1", "-o", out}}}; break;
    case 3: c.runs = {Command{{"sweep", in, "--vary", "K.3-4=0:20:5", "--shard", "1/1", "--part", out}}}; break;
    case 4: c.runs = {Command{{"sweep", in, "--vary", "K.3-4=0:20:5", "--checkpoint", out}}}; break;
    case 5: c.runs = {Command{{"verify", "--scene", in, "--case", "1", "--samples", "20", "--epsilons", "1/100", "--out", out}}}; break;
    case 6: c.runs = {Command{{"explore", "--scene", in, "--case", "1", "--starts", "1", "--evaluations", "20", "--out", out}}}; break;
    default: {  // merge -o over its own part
      const std::string part = "p.part", part_out = form == 0 ? "@/p.part" : form == 1 ? "@/./p.part" : "@/" + alias + ".part";
      c.runs = {Command{{"derive", "--case", "1", "--alphas", "2", "--shard", "1/1", "--part", "@/p.part"}}, Command{{"merge", "@/p.part", "-o", part_out}}};
      c.runs[0].setup = true;
      c.compare = Compare::None;
      c.before = [form, alias](const std::string& dir, std::size_t run, Writers&) {
        if (run != 1) return;
        if (form == 2) fs::create_symlink("p.part", dir + "/" + alias + ".part");
        if (form == 3) fs::create_hard_link(dir + "/p.part", dir + "/" + alias + ".part");
      };
      c.untouched = {part};
      c.expect = Expect::Refused;
      return c;
    }
  }
  c.before = [form, alias, scene, ext](const std::string& dir, std::size_t run, Writers&) {
    if (run != 0) return;
    const std::string name = alias + (ext.empty() ? ".toml" : ext);
    if (form == 2) fs::create_symlink(scene, dir + "/" + name);
    if (form == 3) fs::create_hard_link(dir + "/" + scene, dir + "/" + name);
  };
  c.untouched = {scene};
  // A folder option (--checkpoint, --out) naming a file may also say that it cannot make the folder.
  c.expect = kind == 4 || kind == 5 || kind == 6 ? Expect::NotWritten : Expect::Refused;
  return c;
}

/// mpirun around a build without MPI, simulated with the environment a
/// launcher sets (two ranks): refused with one line saying the build has no
/// MPI on rank 0, and with nothing said on rank 1 (one line for the launch).
Case make_mpi(Rng& rng, int index) {
  Case c;
  c.files["scene.toml"] = kPaperScene;
  static const std::vector<std::vector<std::string>> lines = {
      {"solve", "@/scene.toml"},
      {"sweep", "@/scene.toml", "--vary", "K.3-4=0:20:5", "--csv"},
      {"derive", "--case", "1", "--alphas", "2"},
      {"map", "@/scene.toml", "--x", "K.3-4=0:20:3", "--y", "alpha.2=-150:0:3"},
      {"explore", "--case", "1", "--alphas", "2", "--starts", "1", "--evaluations", "20"},
      {"verify", "--case", "1", "--alphas", "2", "--samples", "20", "--epsilons", "1/100"},
  };
  Command r{lines[static_cast<std::size_t>(index) % lines.size()]};
  const std::string rank = index < static_cast<int>(lines.size()) ? "0" : pick(rng, {std::string("0"), std::string("1")});
  r.env = {{"OMPI_COMM_WORLD_SIZE", "2"}, {"OMPI_COMM_WORLD_RANK", rank}, {"PMI_SIZE", "2"}, {"PMI_RANK", rank}};
  r.silent = rank != "0";
  c.runs = {r};
  c.expect = Expect::Refused;
  if (!r.silent) c.named = {"MPI"};
  return c;
}

/// A drop scene (`superball drop`, issue 27) from the text of its values
/// (as they go into the TOML; "" leaves a key out).
struct DropSpec {
  std::vector<std::string> mass, gap, velocity;  ///< top to bottom; the last mass "inf" or finite
  std::vector<std::string> K;                      ///< K of contact i-(i+1)
  std::string drop_height = "1", g, until, max_events;
  std::string toml() const {
    std::ostringstream os;
    if (!drop_height.empty()) os << "drop_height = " << drop_height << '\n';
    if (!g.empty()) os << "g = " << g << '\n';
    for (std::size_t i = 0; i < mass.size(); ++i) {
      os << "[[body]]\nmass = " << mass[i] << '\n';
      if (!gap[i].empty()) os << "gap = " << gap[i] << '\n';
      if (!velocity[i].empty()) os << "velocity = " << velocity[i] << '\n';
    }
    os << "[dissipation]\nK = {";
    for (std::size_t i = 0; i < K.size(); ++i) os << (i ? ", " : " ") << '"' << i + 1 << '-' << i + 2 << "\" = " << K[i];
    os << " }\n[drop]\n";
    if (!until.empty()) os << "until = " << until << '\n';
    if (!max_events.empty()) os << "max_events = " << max_events << '\n';
    return os.str();
  }
};

/// Two balls over a fixed floor, 1 mm apart, nearly elastic: the drop of the README.
DropSpec two_balls() { return DropSpec{{"0.001", "1", "\"inf\""}, {"0.001", "", ""}, {"", "", ""}, {"1e3", "1e3"}, "1", "", "", ""}; }

/// A random drop scene of 1 to 4 free bodies: mostly admissible values, some hostile ones.
DropSpec random_drop(Rng& rng) {
  DropSpec s;
  const int n = between(rng, 2, 5);
  const auto hostile = [&](const std::vector<std::string>& fine, const std::vector<std::string>& bad) {
    return coin(rng, 0.15) ? pick(rng, bad) : pick(rng, fine);
  };
  for (int i = 0; i < n; ++i) {
    const bool bottom = i + 1 == n;
    s.mass.push_back(bottom ? pick(rng, {std::string("\"inf\""), std::string("inf"), std::string("100"), std::string("1")})
                            : hostile({"1e-3", "0.5", "1", "10", "\"1/3\"", "1e-6", "1e3"}, {"0", "-1", "1e300", "\"1e-400\"", "nan"}));
    s.gap.push_back(bottom ? (coin(rng, 0.05) ? "0.1" : "")
                           : hostile({"", "0", "0.001", "0.01", "\"1/7\"", "1e-9", "0.5"}, {"-1", "nan", "inf", "1e308", "\"1e-400\"", "\"x\"", "true", "1e80"}));
    s.velocity.push_back(coin(rng, 0.2) ? hostile({"0", "1", "-2", "5", "\"1/3\""}, {"1e300", "nan", "\"up\""}) : "");
  }
  for (int i = 1; i < n; ++i) s.K.push_back(hostile({"9", "1e3", "1e4", "0.5", "30", "1e6"}, {"0", "-1", "1e-300", "1e300"}));
  s.drop_height = hostile({"1", "0.5", "\"1/2\"", "2"}, {"0", "-1", "", "1e300", "\"1e-400\"", "nan"});
  if (coin(rng, 0.3)) s.g = hostile({"9.81", "1", "\"981/100\""}, {"0", "-9.81", "1e-300", "1e300"});
  if (coin(rng, 0.5)) s.until = hostile({"\"apex\"", "1", "3", "0.01", "\"1/3\""}, {"0", "-1", "nan", "inf", "\"soon\"", "1e300", "\"Apex\""});
  if (coin(rng, 0.5)) s.max_events = hostile({"1", "2", "50", "1000"}, {"0", "-1", "1.5", "2147483648", "1000000000000", "\"5\""});
  return s;
}

/// A successful drop's JSON (exit 0 or 1): its own invariants.
void check_drop_json(const Outcome& o, std::vector<std::string>& v, long long max_events) {
  if (o.exit_code != 0 && o.exit_code != 1) return;
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(o.out);
  } catch (const std::exception& e) {
    return v.push_back(std::string("drop --json: not JSON: ") + e.what());
  }
  const auto finite = [&](const nlohmann::json& x, const std::string& what) {
    if (!x.is_number() || !std::isfinite(x.get<double>())) v.push_back("drop --json: " + what + " is " + x.dump());
  };
  double t = 0;
  if (static_cast<long long>(j["events"].size()) > max_events) v.push_back("drop --json: more events than max_events");
  for (const auto& e : j["events"]) {
    finite(e["time"], "a collision's time");
    if (e["time"].is_number() && e["time"].get<double>() < t) v.push_back("drop --json: collisions out of time order at " + e["time"].dump());
    if (e["time"].is_number()) t = e["time"];
    for (const auto& x : e["heights"]) finite(x, "a collision's heights");
    if (j["end"] != "numerical-issue" || &e != &j["events"].back())
      for (const auto& x : e["velocities_after"]) finite(x, "a collision's velocities_after");
    finite(e["kinetic_energy_before"], "a collision's kinetic energy before");
    if (j["end"] == "numerical-issue" && &e == &j["events"].back()) continue;  // the failed solve: no answer after
    finite(e["kinetic_energy_after"], "a collision's kinetic energy after");
    if (!e["kinetic_energy_before"].is_number() || !e["kinetic_energy_after"].is_number()) continue;
    const double before = e["kinetic_energy_before"], after = e["kinetic_energy_after"];
    if (after > before * (1 + 1e-9) + 1e-300) v.push_back("drop --json: kinetic energy increased at t = " + e["time"].dump());
  }
  // Over a fixed obstacle no body goes below it (a finite bottom body falls, and the others with it), but for
  // the rounding of an impact's position (1e-9 of the release height: a body last seen at -1e-23 m).
  double scale = 0;
  for (const auto& h : j["release_heights"])
    if (h.is_number()) scale = std::max(scale, std::fabs(h.get<double>()));
  for (const auto& a : j["apexes"]) {
    finite(a["height"], "an apex");
    if (j["fixed_obstacle"] == true && a["height"].is_number() && a["height"].get<double>() < -1e-9 * scale)
      v.push_back("drop --json: an apex below the fixed obstacle: " + a.dump());
  }
  finite(j["end_time"], "end_time");
}

/// Hostile drop scenes and paths (issue 27's red-team pass): every bad value refused with one line naming
/// its field, what the drop computes with in range, a run bounded by max_events, the JSON's physics.
Case make_drop(Rng& rng, int index) {
  Case c;
  DropSpec s = two_balls();
  std::vector<std::string> args = {"drop", "@/scene.toml", "--json"};
  long long max_events = 10000;
  c.expect = Expect::Refused;
  switch (index) {
    case 0: s.gap[0] = "1e308", c.named = {"body[1].gap = 1e308 is outside"}; break;  // 2 g h overflowed: a teleport into contact
    case 1: s.gap[0] = "\"1e-400\"", c.named = {"body[1].gap = 1e-400"}; break;        // 0 in double: another drop
    case 2: s.drop_height = "1e300", c.named = {"drop_height = 1e300"}; break;
    case 3: s.mass.back() = "100", s.until = "1e300", c.named = {"drop.until = 1e300"}; break;  // fell to -inf
    case 4:  // two touching balls: they bounced as one to the last denormal (354,588 events); now a rest
      s.gap[0] = "", s.until = "1e6", s.max_events = "1000000", max_events = 3500, c.expect = Expect::Success;
      c.named = {};
      break;
    case 5: s.until = "\"soon\"", c.named = {"drop.until"}; break;
    case 6: s.max_events = "1000000000000", c.named = {"drop.max_events"}; break;
    case 7: s.max_events = "1.5", c.named = {"drop.max_events"}; break;
    case 8: s.gap.back() = "0.1", c.named = {"body[3].gap"}; break;
    case 9: c.files["cut.toml"] = s.toml().substr(0, s.toml().size() - 4), args[1] = "@/cut.toml"; break;  // "[drop" cut short
    case 10: c.fifos["fifo"] = s.toml(), args[1] = "@/fifo", c.expect = Expect::Success; break;
    case 11:  // a symbolic link reads as the file (its name aside)
      c.runs = {Command{{"drop", "@/scene.toml", "--json"}}, Command{{"drop", "@/link.toml", "--json"}}};
      c.before = [](const std::string& dir, std::size_t run, Writers&) {
        if (run == 1) fs::create_symlink("scene.toml", dir + "/link.toml");
      };
      c.spellings = {{"link.toml", "scene.toml"}};
      c.expect = Expect::Success;
      break;
    case 12: args[1] = "@/dangling.toml", c.before = [](const std::string& dir, std::size_t run, Writers&) {
      if (run == 0) fs::create_symlink("nowhere.toml", dir + "/dangling.toml");
    }; break;
    case 13: args = {"drop", "@/scene.toml", "--plot", "@/missing-folder"}, c.expect = Expect::OutputFailure; break;
    case 14: s.mass = {"1"}, s.gap = {""}, s.velocity = {""}, s.K = {}, c.named = {"body"}; break;  // one body
    case 15: args.insert(args.end(), {"--precision", "quad"}), c.named = {"unknown precision 'quad'"}; break;
    case 16: s.velocity[0] = "3", s.velocity[1] = "10", s.g = "\"1/10\"", c.expect = Expect::Success; break;  // thrown upward, weak g
    default: s = random_drop(rng), c.expect = Expect::Any;
  }
  c.files["scene.toml"] = s.toml();
  if (c.runs.empty()) c.runs = {Command{args}};
  if (!s.max_events.empty() && index != 4) {
    const auto m = value_of(s.max_events);
    if (m && *m >= 1 && *m == std::floor(*m)) max_events = static_cast<long long>(*m);
  }
  c.check = [max_events](const std::vector<Outcome>& o, std::vector<std::string>& v) {
    for (const Outcome& x : o) check_drop_json(x, v, max_events);
  };
  return c;
}

struct Class {
  const char* name;
  int enumerated;  ///< cases always run (the issue's examples)
  Case (*make)(Rng&, int);
  const char* skip = nullptr;  ///< why the class has nothing to check in this build
};

/// The superball under test was built with MPI (SUPERBALL_WITH_MPI): a
/// launcher's environment without the launcher would make it wait for ranks.
constexpr bool kWithMpi = SUPERBALL_REDTEAM_WITH_MPI;

const std::vector<Class> kClasses = {
    {"valid", 8, make_valid},         {"exponent", 8, make_exponent},  {"bom", 4, make_bom},
    {"nesting", 4, make_nesting},     {"control", 8, make_control},    {"underscore", 8, make_underscore},
    {"special", 8, make_special},     {"path", 6, make_path},          {"sweep", 8, make_sweep},
    {"conflict", 21, make_conflict},  {"output", 14, make_output},     {"stdout", 8, make_stdout},
    {"part", 8, make_part},           {"checkpoint", 8, make_checkpoint}, {"digits", 12, make_digits},
    {"spelling", 4, make_spelling},
    {"memory", 4, make_memory, kSanitized ? "superball is built with sanitizers: it cannot start under an address-space limit" : nullptr},
    {"inout", 8, make_inout},
    {"drop", 17, make_drop},
    {"mpi", 6, make_mpi, kWithMpi ? "superball is built with MPI: a launcher's environment without mpirun has nothing to check" : nullptr},
};

// ---------------------------------------------------------------------------
// Invariants

/// \p s with control bytes shown as \xNN, cut at \p limit bytes.
std::string visible(const std::string& s, std::size_t limit = kQuoteBytes) {
  std::string v;
  for (std::size_t i = 0; i < s.size() && i < limit; ++i) {
    const auto b = static_cast<unsigned char>(s[i]);
    if ((b < 0x20 && b != '\n') || b == 0x7f) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", b);
      v += hex;
    } else {
      v += s[i];
    }
  }
  if (s.size() > limit) v += "... (" + std::to_string(s.size()) + " bytes)";
  return v;
}

std::string command_line(const Command& r) {
  std::string s;
  if (r.address_space) s += "(ulimit -v " + std::to_string(r.address_space >> 10) + ") ";
  for (const auto& [name, value] : r.env) s += name + "=" + visible(value, 40) + " ";
  s += "superball";
  for (const auto& a : r.args) s += " '" + visible(a, 80) + "'";
  if (r.close_stdout) s += " >&-";
  if (!r.stdout_path.empty()) s += " > " + r.stdout_path + " (a full device)";
  if (!r.stdin_text.empty()) s += " < (the case's stdin)";
  return s;
}

/// The invariants of one run on its own.
void check_run(const Command& r, const Outcome& o, std::vector<std::string>& v) {
  const std::string who = command_line(r) + ": ";
  if (o.timed_out) return v.push_back(who + "no answer within " + std::to_string(int(kRunSeconds)) + " s");
  if (o.exit_code >= 128) return v.push_back(who + "killed by signal " + std::to_string(o.exit_code - 128));
  if (o.exit_code < 0 || o.exit_code > 3) v.push_back(who + "exit " + std::to_string(o.exit_code) + ": " + visible(o.err, 200));
  if (r.silent) {
    if (o.exit_code != 2 || !o.err.empty() || !o.out.empty())
      v.push_back(who + "exit " + std::to_string(o.exit_code) + " (expected 2, saying nothing: rank 0 says why): " + visible(o.err + o.out, 200));
    return;
  }
  if (o.exit_code == 2 || o.exit_code == 3) {
    // A resumed run's note on what its checkpoint holds may come before the one line.
    static const std::regex note("superball: --checkpoint .*: [0-9]+ of [0-9]+ tasks done already, [0-9]+ to compute\n");
    std::string err = o.err;
    for (std::smatch m; std::regex_search(err, m, note, std::regex_constants::match_continuous) && m.suffix().length() > 0;)
      err = m.suffix().str();
    const auto nl = err.find('\n');
    if (err.rfind("superball: ", 0) != 0 || nl + 1 != err.size())
      v.push_back(who + "exit " + std::to_string(o.exit_code) + " without one line 'superball: ...' on stderr: " + visible(o.err, 200));
    // What a C++ library says, not the tool: a message must say what is wrong with the input.
    static const std::vector<std::string> raw = {"basic_string", "std::", "bad_alloc", "_M_", "stoull", "stoi", "Not a 32-bit integer", "vector::"};
    for (const auto& r : raw)
      if (o.err.find(r) != std::string::npos) {
        v.push_back(who + "a raw C++ exception text in the message: " + visible(o.err, 200));
        break;
      }
    for (std::size_t i = 0; i + 1 < err.size(); ++i) {
      const auto b = static_cast<unsigned char>(err[i]);
      if (b < 0x20 || b == 0x7f) {
        v.push_back(who + "raw control byte in the message: " + visible(o.err, 200));
        break;
      }
    }
  }
}

/// A solve --json that exited 0: finite velocities; success: physics.
void check_solution(const Command& r, const Outcome& o, const Spec* spec, std::vector<std::string>& v) {
  const std::string who = command_line(r) + ": ";
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(o.out);
  } catch (const std::exception& e) {
    return v.push_back(who + "stdout is not JSON: " + e.what());
  }
  std::vector<long double> after;
  // Beyond double (long double, digits:N, exact) the answer is the *_text or
  // *_exact fields; the float fields are its rounding to double, null where
  // it is beyond double's range (a fall speed of 1e400).
  const bool exact = j.value("precision", "double") != "double" &&
                     (j.contains("velocities_after_exact") || j.contains("velocities_after_text"));
  for (const char* key : {"velocities_before", "velocities_after"})
    for (const auto& x : j.value(key, nlohmann::json::array()))
      if (!(exact && x.is_null()) && (!x.is_number() || !std::isfinite(x.get<double>())))
        return v.push_back(who + key + " holds " + x.dump() + " (status " + j.value("status", "?") + ")");
  if (j.value("status", "") != "success" || !spec) return;
  const auto& texts = j.contains("velocities_after_exact") ? j["velocities_after_exact"] : j["velocities_after_text"];
  const auto& doubles = j["velocities_after"];
  for (std::size_t i = 0; i < doubles.size(); ++i) {
    // The text (a decimal or fraction) keeps what a double cannot (1e-400);
    // a symbolic text (sqrt) cannot be read here: no verdict.
    const auto t = i < texts.size() && texts[i].is_string() ? value_of(texts[i].get<std::string>()) : std::nullopt;
    if (!t || !std::isfinite(*t)) return;
    after.push_back(*t);
  }
  const auto before = velocities_before(*spec);
  if (!before || before->size() != after.size()) return;
  const bool fixed = j.value("fixed_obstacle", false);
  long double p0 = 0, p1 = 0, scale = 0, e0 = 0, e1 = 0;
  for (std::size_t i = 0; i < after.size(); ++i) {
    const auto m = value_of(spec->mass[i]);
    if (!m) return;
    if (std::isinf(*m)) continue;
    p0 += *m * (*before)[i], p1 += *m * after[i];
    scale += std::fabs(*m * (*before)[i]) + std::fabs(*m * after[i]);
    e0 += *m * (*before)[i] * (*before)[i] / 2, e1 += *m * after[i] * after[i] / 2;
  }
  if (!std::isfinite(scale) || !std::isfinite(e0) || !std::isfinite(e1)) return;  // beyond long double: no verdict
  std::ostringstream os;
  os.precision(6);
  if (!fixed && std::fabs(p1 - p0) > kMomentumRtol * scale) {
    os << "momentum " << p0 << " before, " << p1 << " after, with status success";
    v.push_back(who + os.str());
  }
  const bool obstacle_at_rest = (*before).back() == 0;
  if ((!fixed || obstacle_at_rest) && e1 > e0 * (1 + kEnergyRtol)) {
    os.str("");
    os << "kinetic energy " << e0 << " before, " << e1 << " after, with status success";
    v.push_back(who + os.str());
  }
}

/// A sweep that exited 0: finite numbers, positive brackets, chained switches.
void check_sweep(const Command& r, const Outcome& o, std::vector<std::string>& v) {
  const std::string who = command_line(r) + ": ";
  static const std::regex nonfinite("(^|[^A-Za-z])[-+]?(nan|inf)([^A-Za-z]|$)", std::regex::icase);
  if (std::regex_search(o.out, nonfinite)) v.push_back(who + "exit 0 with a non-finite value: " + visible(o.out, 300));
  if (o.out.find("bracket width -") != std::string::npos) v.push_back(who + "negative bracket width: " + visible(o.out, 300));
  static const std::regex line(": case (\\S+) .* -> case (\\S+) ");
  std::istringstream in(o.out);
  std::string previous;
  for (std::string l; std::getline(in, l);) {
    std::smatch m;
    if (!std::regex_search(l, m, line)) continue;
    if (!previous.empty() && m[1] != previous)
      v.push_back(who + "switch points do not chain: one ends in case " + previous + ", the next starts from case " + m[1].str());
    previous = m[2];
  }
}

/// \p text with the case's folder written as "@/" (and the spellings of a
/// key read as the case says).
std::string normalized(std::string text, const std::string& dir, const std::vector<std::pair<std::string, std::string>>& spellings = {}) {
  for (std::size_t at; (at = text.find(dir + "/")) != std::string::npos;) text.replace(at, dir.size() + 1, "@/");
  for (const auto& [spelt, read] : spellings)
    for (std::size_t at = 0; (at = text.find(spelt, at)) != std::string::npos; at += read.size()) text.replace(at, spelt.size(), read);
  for (const char* twin : {"@/a/", "@/b/"})
    for (std::size_t at; (at = text.find(twin)) != std::string::npos;) text.replace(at, 4, "@/x/");
  return text;
}

/// The first line where \p a and \p b differ, both shown.
std::string first_difference(const std::string& a, const std::string& b) {
  std::istringstream sa(a), sb(b);
  std::string la, lb;
  while (true) {
    const bool ga = static_cast<bool>(std::getline(sa, la)), gb = static_cast<bool>(std::getline(sb, lb));
    if (!ga && !gb) return "(none)";
    if (!ga) la = "(end)";
    if (!gb) lb = "(end)";
    if (la == lb) continue;
    // A long line from a little before the first byte that differs.
    std::size_t at = 0;
    while (at < la.size() && at < lb.size() && la[at] == lb[at]) ++at;
    const std::size_t from = at > 60 ? at - 60 : 0;
    const std::string cut = from ? "..." : "";
    return cut + visible(la.substr(std::min(from, la.size())), 160) + "\n     against\n     " + cut + visible(lb.substr(std::min(from, lb.size())), 160);
  }
}

std::set<std::string> listing(const std::string& dir) {
  std::set<std::string> names;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) names.insert(e.path().filename().string());
  return names;
}

/// Run case \p c in \p dir; the violated invariants.
std::vector<std::string> check_case(const Case& c, const std::string& dir) {
  std::vector<std::string> v;
  fs::create_directories(dir);
  for (const auto& [name, content] : c.files) {
    fs::create_directories(fs::path(dir + "/" + name).parent_path());
    std::ofstream(dir + "/" + name, std::ios::binary) << content;
  }
  std::vector<std::unique_ptr<FifoWriter>> writers;
  for (const auto& [name, text] : c.fifos) {
    mkfifo((dir + "/" + name).c_str(), 0644);
    writers.push_back(std::make_unique<FifoWriter>(dir + "/" + name, text));
  }
  for (const auto& f : c.full_devices)
    if (!make_full_device(dir + "/" + f)) return {};  // not permitted here: nothing to check
  // The -o target.
  const std::string target = in_folder({c.target_path}, dir)[0], out_dir = dir + "/out";
  if (c.target != Target::None) fs::create_directories(out_dir);
  std::optional<FifoReader> reader;
  switch (c.target) {
    case Target::File: std::ofstream(target) << kSentinel; break;
    case Target::Symlink:
      std::ofstream(out_dir + "/real.txt") << kSentinel;
      fs::create_symlink("real.txt", target);
      break;
    case Target::DanglingSymlink: fs::create_symlink("absent.txt", target); break;
    case Target::Fifo: mkfifo(target.c_str(), 0644); break;
    case Target::Directory: fs::create_directories(target); break;
    case Target::FullDevice:
      if (!make_full_device(target)) return {};  // not permitted here: nothing to check
      break;
    default: break;
  }
  const auto before = listing(out_dir);

  std::vector<Outcome> outcomes;
  Writers more_writers;  // of the FIFOs c.before makes
  std::map<std::string, std::pair<std::string, bool>> kept;  // c.untouched before the last run: content, symlink or not
  std::set<std::string> present;                            // the case's folder before the last run
  for (std::size_t i = 0; i < c.runs.size(); ++i) {
    Command r = c.runs[i];
    r.args = in_folder(r.args, dir);
    if (!r.stdout_path.empty()) r.stdout_path = in_folder({r.stdout_path}, dir)[0];
    if (c.before) c.before(dir, i, more_writers);
    if (i + 1 == c.runs.size()) {
      for (const auto& name : c.untouched) kept[name] = {slurp(dir + "/" + name), fs::is_symlink(dir + "/" + name)};
      present = listing(dir);
    }
    if (c.target == Target::Fifo && i + 1 == c.runs.size()) reader.emplace(target);
    outcomes.push_back(execute(r, dir));
    const Outcome& o = outcomes.back();
    if (r.setup) {  // a run that prepares the case may fail, but not hang
      if (o.timed_out) v.push_back(command_line(r) + ": no answer within " + std::to_string(int(kRunSeconds)) + " s");
      continue;
    }
    check_run(r, o, v);
    if (r.close_stdout || !r.stdout_path.empty()) continue;
    if (o.exit_code == 0 && r.args[0] == "solve" && std::find(r.args.begin(), r.args.end(), "--json") != r.args.end())
      check_solution(r, o, c.spec ? &*c.spec : nullptr, v);
    if (o.exit_code == 0 && r.args[0] == "sweep") check_sweep(r, o, v);
  }
  const Command& first = c.runs[0];
  const Outcome& o0 = outcomes[0];
  // What the class must give, on the last run (the -o run of an output case).
  const Outcome& last = outcomes.back();
  Command last_run = c.runs.back();
  last_run.args = in_folder(last_run.args, dir);
  if (!last_run.stdout_path.empty()) last_run.stdout_path = in_folder({last_run.stdout_path}, dir)[0];
  const std::string got = command_line(last_run) + ": got exit " + std::to_string(last.exit_code) + ", ";
  const std::string said = visible(last.err.empty() ? last.out : last.err, 200);
  if (c.expect == Expect::Refused && last.exit_code != 2) v.push_back(got + "expected 2 (refused): " + said);
  if (c.expect == Expect::Success && last.exit_code != 0) v.push_back(got + "expected 0: " + said);
  if (c.expect == Expect::OutputFailure && last.exit_code != 3) v.push_back(got + "expected 3 (output cannot be written): " + said);
  if (c.expect == Expect::NotWritten && last.exit_code != 2 && last.exit_code != 3)
    v.push_back(got + "expected 2 (refused) or 3 (output cannot be written): " + said);
  if (c.expect == Expect::SameOrRefused && last.exit_code != 0 && last.exit_code != 2)
    v.push_back(got + "expected 0 (the output of " + command_line(first) + ") or 2 (refused): " + said);
  if (last.exit_code == 2 && !c.named.empty() &&
      std::none_of(c.named.begin(), c.named.end(), [&](const std::string& n) { return last.err.find(n) != std::string::npos; })) {
    std::string names;
    for (const auto& n : c.named) names += (names.empty() ? "" : " or ") + n;
    v.push_back(got + "the refusal does not name " + names + ": " + visible(last.err, 200));
  }
  const auto same = [&](const Outcome& a) { return normalized(a.out, dir, c.spellings) == normalized(o0.out, dir, c.spellings); };
  if (c.compare == Compare::All && !c.target_reference)
    for (std::size_t i = 1; i < c.runs.size(); ++i)
      if (outcomes[i].exit_code != o0.exit_code || !same(outcomes[i]))
        v.push_back(command_line(c.runs[i]) + ": differs from " + command_line(first) + " (exit " + std::to_string(outcomes[i].exit_code) +
                    " against " + std::to_string(o0.exit_code) + "), first different line:\n     " +
                    first_difference(normalized(outcomes[i].out + outcomes[i].err, dir, c.spellings),
                                     normalized(o0.out + o0.err, dir, c.spellings)));
  if (c.compare == Compare::Last && last.exit_code == 0 && !same(last))
    v.push_back(got + "an output that is not that of " + command_line(first) + " (exit " + std::to_string(o0.exit_code) +
                "), first different line:\n     " + first_difference(normalized(last.out, dir), normalized(o0.out, dir)));
  for (const auto& [name, was] : kept) {
    const std::string path = dir + "/" + name;
    if (slurp(path) != was.first || fs::is_symlink(path) != was.second)
      v.push_back(got + "changed " + name + (was.second ? " (a symlink)" : "") + ", which it must leave as it was");
  }
  if (c.nothing_new) {
    std::string extra;
    for (const auto& n : listing(dir))
      if (!present.count(n)) extra += " " + n;
    if (!extra.empty()) v.push_back(got + "made files it was not told to write:" + extra);
  }
  if (c.check) c.check(outcomes, v);

  // The -o target afterwards.
  if (c.target != Target::None) {
    const std::string fifo_text = reader ? reader->finish() : "";
    const std::string w = command_line(last_run) + ": ";
    std::error_code ec;
    const auto st = fs::symlink_status(target, ec);
    auto after = listing(out_dir);
    if (last.exit_code == 0 && c.target == Target::MissingFolder) after.erase("missing");
    if (last.exit_code == 0 && c.target == Target::File) after.insert("derived.txt");
    if (last.exit_code == 0 && before.count("derived.txt") == 0) after.erase("derived.txt");
    if (last.exit_code == 0 && c.target == Target::DanglingSymlink) {  // written through the link
      after.erase("absent.txt");
      if (slurp(out_dir + "/absent.txt") != o0.out) v.push_back(w + "the dangling symlink's new target does not hold the output");
    }
    if (after != before) {
      std::string extra;
      for (const auto& n : after)
        if (!before.count(n)) extra += " " + n;
      v.push_back(w + "files left beside the target:" + extra);
    }
    const std::string expected = c.target_reference ? o0.out : kSentinel;
    if (c.target == Target::File && slurp(target) != (last.exit_code == 0 ? expected : kSentinel))
      v.push_back(w + "the target file does not hold " + std::string(last.exit_code == 0 ? "the output" : "its old content"));
    if (c.target == Target::Symlink || c.target == Target::DanglingSymlink) {
      if (!fs::is_symlink(st)) v.push_back(w + "the symlink was replaced by a " + (fs::is_regular_file(st) ? "regular file" : "other file"));
      if (c.target == Target::Symlink && slurp(out_dir + "/real.txt") != (last.exit_code == 0 ? expected : kSentinel))
        v.push_back(w + "the symlink's target does not hold " + std::string(last.exit_code == 0 ? "the output" : "its old content"));
    }
    if (c.target == Target::Fifo) {
      if (!fs::is_fifo(st)) v.push_back(w + "the FIFO was replaced");
      if (last.exit_code == 0 && fifo_text != expected) v.push_back(w + "the FIFO's reader got " + std::to_string(fifo_text.size()) + " bytes, not the output");
    }
    if (c.target == Target::Directory && !fs::is_directory(st)) v.push_back(w + "the folder was replaced");
    if (c.target == Target::FullDevice && !fs::is_character_file(st)) v.push_back(w + "the device was replaced");
  }
  return v;
}

/// Write what a case needs to be run again by hand, and what it violated.
void keep(const Case& c, const std::string& dir, const std::string& header, const std::vector<std::string>& violations) {
  std::ofstream(dir + "/violations") << [&] {
    std::string all;
    for (const auto& x : violations) all += x + "\n";
    return all;
  }();
  std::ofstream cmd(dir + "/command");
  cmd << header << '\n';
  if (!c.what.empty()) cmd << c.what << '\n';
  for (const auto& r : c.runs) {
    Command shown = r;
    shown.args = in_folder(r.args, dir);
    cmd << command_line(shown) << '\n';
    if (!r.stdin_text.empty()) std::ofstream(dir + "/stdin") << r.stdin_text;
  }
}

std::set<std::string> known_failures() {
  std::set<std::string> known;
  std::ifstream in(SUPERBALL_REDTEAM_KNOWN);
  for (std::string line; std::getline(in, line);) {
    line = line.substr(0, line.find('#'));
    std::istringstream words(line);
    std::string name;
    if (words >> name) known.insert(name);
  }
  return known;
}

void PrintTo(const Class& c, std::ostream* os) { *os << c.name; }

class Hostile : public ::testing::TestWithParam<Class> {};

TEST_P(Hostile, Holds) {
  const Class& cls = GetParam();
  if (cls.skip) GTEST_SKIP() << cls.name << ": " << cls.skip;
  const double budget = env_number("SUPERBALL_REDTEAM_SECONDS", kDefaultBudgetSeconds) / static_cast<double>(kClasses.size());
  const auto seed = static_cast<std::uint64_t>(env_number("SUPERBALL_REDTEAM_SEED", 1));
  const char* out = std::getenv("SUPERBALL_REDTEAM_OUT");
  const std::string base = (out && *out ? std::string(out) + "/" : ::testing::TempDir()) + "superball-redteam-" +
                           std::to_string(::getpid()) + "/" + cls.name;
  const bool known = known_failures().count(cls.name) > 0;
  const auto start = std::chrono::steady_clock::now();
  int cases = 0, failing = 0;
  std::ostringstream report;
  for (int index = 0;; ++index) {
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (index >= cls.enumerated && elapsed >= budget) break;
    Rng rng(seed * 0x9E3779B97F4A7C15ull ^ std::hash<std::string>{}(cls.name) ^ (static_cast<std::uint64_t>(index) << 20));
    const Case c = cls.make(rng, index);
    const std::string dir = base + "/" + std::to_string(index);
    const auto v = check_case(c, dir);
    ++cases;
    if (v.empty()) {
      fs::remove_all(dir);
      continue;
    }
    ++failing;
    const std::string header = std::string("class ") + cls.name + ", case " + std::to_string(index) + ", seed " + std::to_string(seed);
    keep(c, dir, header, v);
    if (failing <= 10) {
      report << "-- " << header << (known ? "" : " (files in " + dir + ")") << '\n';
      if (!c.what.empty()) report << "   " << c.what << '\n';
      for (const auto& x : v) report << "   " << x << '\n';
      for (const auto& [name, content] : c.files)
        if (!content.empty()) report << "   " << name << ":\n" << visible(content) << '\n';
    }
  }
  std::error_code ec;
  if (failing == 0 || known) {  // a known class's report is enough
    fs::remove_all(base, ec);
    fs::remove(fs::path(base).parent_path(), ec);  // when the last class leaves it empty
  }
  std::cout << cls.name << ": " << cases << " cases, " << failing << " violating (seed " << seed << ")\n";
  if (known) {
    if (failing == 0)
      std::cout << cls.name << " is listed in known-failures.txt but held every invariant: remove the line\n";
    else
      GTEST_SKIP() << "known failing class " << cls.name << ": " << failing << " of " << cases << " cases\n" << report.str();
    return;
  }
  EXPECT_EQ(failing, 0) << report.str();
}

// The checks themselves, on made-up outcomes: each invariant can fail.

Outcome made_up(int exit_code, std::string out, std::string err) {
  Outcome o;
  o.exit_code = exit_code, o.out = std::move(out), o.err = std::move(err);
  return o;
}

TEST(RedTeamChecks, RunInvariants) {
  const Command r({"solve", "x.toml"});
  auto count = [&](const Outcome& o) {
    std::vector<std::string> v;
    check_run(r, o, v);
    return v.size();
  };
  EXPECT_EQ(count(made_up(2, "", "superball: x.toml:1:1: bad\n")), 0u);
  EXPECT_EQ(count(made_up(1, "status numerical-issue\n", "")), 0u);
  EXPECT_GT(count(made_up(4, "", "superball: internal error: Division by zero.\n")), 0u);
  EXPECT_GT(count(made_up(139, "", "")), 0u);
  EXPECT_GT(count(made_up(2, "", "superball: two\nlines\n")), 0u);
  EXPECT_GT(count(made_up(2, "", "superball: \x1b[31mred\n")), 0u);
  EXPECT_GT(count(made_up(3, "", "oops\n")), 0u);
  EXPECT_EQ(count(made_up(2, "", "superball: --checkpoint ck: 3 of 8 tasks done already, 5 to compute\nsuperball: ck/task-00000002: bad\n")), 0u);
  EXPECT_GT(count(made_up(2, "", "superball: --checkpoint ck: 3 of 8 tasks done already, 5 to compute\nsuperball: one\nsuperball: two\n")), 0u);
  EXPECT_GT(count(made_up(2, "", "superball: merge: basic_string::substr: __pos (which is 12) > this->size() (which is 11)\n")), 0u);
  Outcome late = made_up(137, "", "");
  late.timed_out = true;
  EXPECT_GT(count(late), 0u);
}

TEST(RedTeamChecks, SweepInvariants) {
  const Command r({"sweep"});
  auto count = [&](const std::string& out) {
    std::vector<std::string> v;
    check_sweep(r, made_up(0, out, ""), v);
    return v.size();
  };
  EXPECT_EQ(count("g  U1  U2  case\n1  -0.5  0  {1-2}\n"), 0u);
  EXPECT_GT(count("g  U1  U2  case\n-1  -nan  -nan  {1-2}\n"), 0u);
  EXPECT_GT(count("K = 2  (bracket width -1e-19): case 2.2 {1-2} -> case 3.3 {} \n"), 0u);
  EXPECT_EQ(count("K = 2  (bracket width 1e-19): case 2.2 {1-2} -> case 3.3 {} \nK = 3  (bracket width 1e-19): case 3.3 {} -> case 3.2 {2-3} \n"), 0u);
  EXPECT_GT(count("K = 2  (bracket width 1e-19): case 2.2 {1-2} -> case 3.3 {} \nK = 3  (bracket width 1e-19): case 2.2 {1-2} -> case 3.2 {2-3} \n"), 0u);
}

TEST(RedTeamChecks, SolutionInvariants) {
  // Two unit masses, the top one at -1, a free obstacle: momentum -1.
  const Spec spec{{"1", "1"}, {"-1", "0"}, {{"1-2", "1"}}, "", "1", "", ""};
  const Command r({"solve", "--json"});
  auto count = [&](const std::string& after, const std::string& status = "success") {
    const std::string json = R"({"status": ")" + status + R"(", "fixed_obstacle": false, "velocities_before": [-1.0, 0.0],
        "velocities_after": [)" + after + R"(], "velocities_after_text": ["-0.5", "-0.5"]})";
    std::vector<std::string> v;
    check_solution(r, made_up(0, json, ""), &spec, v);
    return v.size();
  };
  EXPECT_EQ(count("-0.5, -0.5"), 0u);
  EXPECT_GT(count("null, -0.5"), 0u);
  EXPECT_GT(count("null, -0.5", "numerical-issue"), 0u);
  // The text says -0.5 each: momentum and energy hold; a text of 0 would not.
  const std::string zero = R"({"status": "success", "fixed_obstacle": false, "velocities_before": [-1.0, 0.0],
      "velocities_after": [0.0, 0.0], "velocities_after_text": ["0", "0"]})";
  std::vector<std::string> v;
  check_solution(r, made_up(0, zero, ""), &spec, v);
  EXPECT_GT(v.size(), 0u);
  const std::string faster = R"({"status": "success", "fixed_obstacle": false, "velocities_before": [-1.0, 0.0],
      "velocities_after": [-2.0, 1.0], "velocities_after_text": ["-2", "1"]})";
  v.clear();
  check_solution(r, made_up(0, faster, ""), &spec, v);
  EXPECT_GT(v.size(), 0u);  // momentum -1 kept, energy 0.5 -> 2.5
}

TEST(RedTeamChecks, DigitsAgainstExact) {
  auto answer = [](const std::string& closed, const std::string& u1, const std::string& u2, const std::string& extra = "") {
    const bool exact = u1.find('/') != std::string::npos;
    return made_up(0, R"({"status": "success", "case": "{)" + closed + R"(}", "closed_contacts": [)" + (closed.empty() ? "" : "\"" + closed + "\"") +
                          R"(], ")" + (exact ? "velocities_after_exact" : "velocities_after_text") + R"(": [")" + u1 + R"(", ")" + u2 + R"("])" + extra + "}",
                   "");
  };
  auto count = [](const Outcome& d, const Outcome& e) {
    std::vector<std::string> v;
    check_digits("digits:20", d, e, v);
    return v.size();
  };
  EXPECT_EQ(count(answer("", "0.5", "-0.25"), answer("", "1/2", "-1/4")), 0u);
  EXPECT_GT(count(answer("", "0.5", "-0.26"), answer("", "1/2", "-1/4")), 0u);
  // A contact open in one and closed in the other: a tie when its bodies move together.
  EXPECT_EQ(count(answer("", "-0.5", "-0.5"), answer("1-2", "-1/2", "-1/2")), 0u);
  EXPECT_GT(count(answer("", "0.5", "-0.25"), answer("1-2", "1/2", "-1/4")), 0u);
  // An answer that warns is not held to exact.
  EXPECT_EQ(count(answer("", "0.5", "-0.26", R"(, "warnings": ["the bound is vacuous"])"), answer("", "1/2", "-1/4")), 0u);
}

// Each way of tampering changes the part (a tampered part that came out
// unchanged would make the suite expect a refusal of a good part).
TEST(RedTeamChecks, TamperingChangesThePart) {
  PartText p;
  p.head = "superball part 2\nrun 0123456789abcdef\nsuperball 0.2.0\nargument 5 sweep\nargument 23 --vary=K.3-4=0:20:10001\ntasks 3\npart 2 of 3\n";
  p.tasks = {{"task 1", "K.3-4 = 13.411993850493881  (bracket width 1.08e-22): case 3.3 {} -> case 3.2 {2-3}\n", "89abcdef01234567"}};
  p.tail = "end\n";
  const std::string good = p.text();
  ASSERT_NE(good.find("task 1 84 89abcdef01234567\n"), std::string::npos);
  const auto again = PartText::parse(good);
  ASSERT_TRUE(again.has_value());
  EXPECT_EQ(again->text(), good);
  const std::string dir = ::testing::TempDir() + "superball-redteam-tamper-" + std::to_string(::getpid());
  fs::create_directories(dir);
  std::ofstream(dir + "/other") << "other\n";
  for (const Tamper how : kTampers)
    for (std::uint64_t seed = 0; seed < 5; ++seed) {
      const std::string path = dir + "/p.part";
      fs::remove_all(path);
      std::ofstream(path, std::ios::binary) << good;
      Rng rng(seed);
      {
        Writers writers;
        tamper(path, how, rng, dir + "/other", dir + "/victim", writers);
        const auto st = fs::symlink_status(path);
        if (fs::is_regular_file(st)) {
          EXPECT_NE(slurp(path), good) << tamper_name(how) << ", seed " << seed;
        }
        if (how == Tamper::Argument || how == Tamper::ArgumentShard) {
          EXPECT_NE(slurp(path).find(dir + "/victim"), std::string::npos);
        }
        EXPECT_EQ(fs::is_symlink(st), how == Tamper::Symlink);
        EXPECT_EQ(fs::is_fifo(st), how == Tamper::Fifo);
        EXPECT_EQ(fs::is_directory(st), how == Tamper::Folder);
      }
    }
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(RedTeam, Hostile, ::testing::ValuesIn(kClasses),
                         [](const ::testing::TestParamInfo<Class>& info) { return std::string(info.param.name); });

}  // namespace
