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
//     `inf` or `+inf`) give the same exit code and the same output;
//   - what a class must give (refused with exit 2, success, exit 3).
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
#include <spawn.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
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
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, r.stdin_text.empty() ? "/dev/null" : in.c_str(), O_RDONLY, 0);
  if (r.close_stdout)
    posix_spawn_file_actions_addclose(&actions, 1);
  else if (!r.stdout_path.empty())
    posix_spawn_file_actions_addopen(&actions, 1, r.stdout_path.c_str(), O_WRONLY, 0);
  else
    posix_spawn_file_actions_addopen(&actions, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP);
  posix_spawnattr_setpgroup(&attr, 0);
  std::vector<std::string> argv_s = {exe};
  argv_s.insert(argv_s.end(), r.args.begin(), r.args.end());
  std::vector<char*> argv;
  for (auto& a : argv_s) argv.push_back(a.data());
  argv.push_back(nullptr);
  Outcome o;
  pid_t pid = 0;
  if (posix_spawn(&pid, exe.c_str(), &actions, &attr, argv.data(), environ) == 0) {
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
  posix_spawnattr_destroy(&attr);
  posix_spawn_file_actions_destroy(&actions);
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

enum class Expect { Any, Refused, Success, OutputFailure };

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
      {"sweep", "@/scene.toml", "--vary", "K.1-2=0:20:5", "--threads", "0"},
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

struct Class {
  const char* name;
  int enumerated;  ///< cases always run (the issue's examples)
  Case (*make)(Rng&, int);
};

const std::vector<Class> kClasses = {
    {"valid", 8, make_valid},         {"exponent", 8, make_exponent},  {"bom", 4, make_bom},
    {"nesting", 4, make_nesting},     {"control", 8, make_control},    {"underscore", 8, make_underscore},
    {"special", 8, make_special},     {"path", 6, make_path},          {"sweep", 8, make_sweep},
    {"conflict", 21, make_conflict},  {"output", 14, make_output},     {"stdout", 8, make_stdout},
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
  std::string s = "superball";
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
  if (o.exit_code == 2 || o.exit_code == 3) {
    const auto nl = o.err.find('\n');
    if (o.err.rfind("superball: ", 0) != 0 || nl + 1 != o.err.size())
      v.push_back(who + "exit " + std::to_string(o.exit_code) + " without one line 'superball: ...' on stderr: " + visible(o.err, 200));
    for (std::size_t i = 0; i + 1 < o.err.size(); ++i) {
      const auto b = static_cast<unsigned char>(o.err[i]);
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

/// \p text with the case's folder written as "@/".
std::string normalized(std::string text, const std::string& dir) {
  for (std::size_t at; (at = text.find(dir + "/")) != std::string::npos;) text.replace(at, dir.size() + 1, "@/");
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
    if (la != lb) return visible(la, 160) + "\n     against\n     " + visible(lb, 160);
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
  for (std::size_t i = 0; i < c.runs.size(); ++i) {
    Command r = c.runs[i];
    r.args = in_folder(r.args, dir);
    if (!r.stdout_path.empty()) r.stdout_path = in_folder({r.stdout_path}, dir)[0];
    if (c.target == Target::Fifo && i + 1 == c.runs.size()) reader.emplace(target);
    outcomes.push_back(execute(r, dir));
    check_run(r, outcomes.back(), v);
    const Outcome& o = outcomes.back();
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
  if (!c.target_reference)
    for (std::size_t i = 1; i < c.runs.size(); ++i)
      if (outcomes[i].exit_code != o0.exit_code || normalized(outcomes[i].out, dir) != normalized(o0.out, dir))
        v.push_back(command_line(c.runs[i]) + ": differs from " + command_line(first) + " (exit " + std::to_string(outcomes[i].exit_code) +
                    " against " + std::to_string(o0.exit_code) + "), first different line:\n     " +
                    first_difference(normalized(outcomes[i].out + outcomes[i].err, dir), normalized(o0.out + o0.err, dir)));

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

/// Write what a case needs to be run again by hand.
void keep(const Case& c, const std::string& dir, const std::string& header) {
  std::ofstream cmd(dir + "/command");
  cmd << header << '\n';
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
    keep(c, dir, header);
    if (failing <= 10) {
      report << "-- " << header << (known ? "" : " (files in " + dir + ")") << '\n';
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

INSTANTIATE_TEST_SUITE_P(RedTeam, Hostile, ::testing::ValuesIn(kClasses),
                         [](const ::testing::TestParamInfo<Class>& info) { return std::string(info.param.name); });

}  // namespace
