// The task list of a long command and its runners (distribute.hpp): here,
// a shard with its part file, a checkpoint folder, and the MPI ranks
// (distribute_mpi.cpp, built with SUPERBALL_WITH_MPI).
#include "distribute.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>

#include "distribute_detail.hpp"

namespace superball::cli {

const MergedRun* merged_run = nullptr;

namespace detail {
namespace {

/// FNV-1a, 64 bits: a name for a run, not a defence against forgery.
struct Hash {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  void add(std::string_view s) {
    for (unsigned char c : s) h = (h ^ c) * 0x100000001b3ULL;
    // The length too, so that ("ab", "c") and ("a", "bc") differ.
    const std::uint64_t n = s.size();
    for (int i = 0; i < 8; ++i) h = (h ^ ((n >> (8 * i)) & 0xff)) * 0x100000001b3ULL;
  }
  std::string hex() const {
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
    return buf;
  }
};

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

/// Writes \p text to \p path atomically: a temporary beside it, fsync, rename.
void write_atomically(const std::string& path, const std::string& text) {
  std::string tmp = path + ".tmpXXXXXX";
  const int fd = ::mkstemp(tmp.data());
  if (fd < 0) throw OutputError(path + ": " + std::strerror(errno));
  const char* p = text.data();
  std::size_t left = text.size();
  while (left) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int e = errno;
      ::close(fd);
      ::unlink(tmp.c_str());
      throw OutputError(path + ": " + std::strerror(e));
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0 || ::close(fd) != 0 || ::rename(tmp.c_str(), path.c_str()) != 0) {
    const int e = errno;
    ::unlink(tmp.c_str());
    throw OutputError(path + ": " + std::strerror(e));
  }
}

}  // namespace

std::string header(const std::string& kind, const std::string& run, const std::vector<std::string>& arguments, std::size_t tasks) {
  std::string h = kind + "\nrun " + run + "\nsuperball " + SUPERBALL_VERSION + "\n";
  for (const std::string& a : arguments) h += "argument " + std::to_string(a.size()) + " " + a + "\n";
  h += "tasks " + std::to_string(tasks) + "\n";
  return h;
}

/// Reads what header() wrote from \p in; \p where names the file in errors.
Header read_header(std::istream& in, const std::string& kind, const std::string& where) {
  Header h;
  std::string line;
  auto bad = [&](const std::string& what) { return std::invalid_argument(where + ": " + what); };
  if (!std::getline(in, line) || line != kind) throw bad(std::string("not a ") + (kind == "superball part 1" ? "part file" : "checkpoint folder's run file") + " of superball (its first line is not '" + kind + "')");
  if (!std::getline(in, line) || line.rfind("run ", 0) != 0) throw bad("no 'run' line");
  h.run = line.substr(4);
  if (!std::getline(in, line) || line.rfind("superball ", 0) != 0) throw bad("no 'superball' line");
  h.version = line.substr(10);
  for (;;) {
    if (!std::getline(in, line)) throw bad("cut short in its header");
    if (line.rfind("tasks ", 0) == 0) {
      h.tasks = std::stoull(line.substr(6));
      return h;
    }
    std::size_t size = 0, used = 0;
    if (line.rfind("argument ", 0) != 0) throw bad("unexpected line '" + line.substr(0, 40) + "'");
    size = std::stoull(line.substr(9), &used);
    std::string value = line.substr(9 + used + 1);
    while (value.size() < size) {  // an argument holding a newline
      std::string more;
      if (!std::getline(in, more)) throw bad("cut short in its arguments");
      value += "\n" + more;
    }
    if (value.size() != size) throw bad("an argument of the wrong length");
    h.arguments.push_back(value);
  }
}

Distribution::Task with_test_hook(const Distribution::Task& task) {
  // A TEST HOOK, not a feature: the tests of a task that fails on a rank
  // (tests/cli/distribute_test.cpp) set SUPERBALL_TEST_FAIL_TASK=K to make
  // task K (numbered from 1, as the messages number them) throw wherever it
  // runs, since no task of these commands fails on valid input.  Unset (as
  // always outside those tests), the task is returned as it is.
  const char* hook = std::getenv("SUPERBALL_TEST_FAIL_TASK");
  if (!hook || !*hook) return task;
  const unsigned long long failing = std::strtoull(hook, nullptr, 10);
  return [task, failing](std::size_t k) -> std::string {
    if (k + 1 == failing) throw std::runtime_error("SUPERBALL_TEST_FAIL_TASK=" + std::to_string(failing) + ": this task made to fail (a test hook)");
    return task(k);
  };
}

std::string task_file(const std::string& dir, std::size_t k) {
  char name[32];
  std::snprintf(name, sizeof name, "task-%08zu", k);
  return (std::filesystem::path(dir) / name).string();
}

}  // namespace detail

using namespace detail;

void add_distribute_options(CLI::App* cmd, DistributeOptions& o, const std::string& noun, bool shards) {
  cmd->add_option("--checkpoint", o.checkpoint,
                  "Folder where each finished " + noun + " is written at once; the same command run again computes only those missing")
      ->check(non_empty());
  if (!shards) {  // not offered (hidden from --help); the command refuses them, saying why
    cmd->add_option("--shard", o.shard)->group("");
    cmd->add_option("--part", o.part)->group("");
    return;
  }
  cmd->add_option("--shard", o.shard,
                  "I/N: compute only the " + noun + "s k with k mod N = I-1 and write them as a part file (see --part); "
                  "`superball merge` joins the N parts into this run's output")
      ->check(non_empty());
  cmd->add_option("--part", o.part, "The part file of --shard (default: superball-RUN-I-of-N.part here, RUN naming the run)")->check(non_empty());
}

std::vector<std::string> run_arguments(const CLI::App& cmd) {
  static const char* const runner[] = {"shard", "part", "checkpoint", "output", "threads", "jobs", "quiet", "progress", "help"};
  std::vector<std::string> positional, named;
  // The options of the command and of its option groups (nameless subcommands), in order.
  std::vector<const CLI::Option*> options;
  std::function<void(const CLI::App&)> collect = [&](const CLI::App& app) {
    for (const CLI::Option* opt : app.get_options()) options.push_back(opt);
    for (const CLI::App* group : app.get_subcommands([](const CLI::App* sub) { return sub->get_name().empty(); })) collect(*group);
  };
  collect(cmd);
  for (const CLI::Option* opt : options) {
    if (opt->count() == 0) continue;
    bool skip = false;
    for (const char* r : runner) skip = skip || opt->check_lname(r);
    if (skip) continue;
    if (!opt->nonpositional()) {
      for (const std::string& v : opt->results()) positional.push_back(v);
    } else if (opt->get_expected_max() == 0) {  // a flag
      for (std::size_t i = 0; i < opt->count(); ++i) named.push_back("--" + opt->get_lnames().at(0));
    } else {
      for (const std::string& v : opt->results()) named.push_back("--" + opt->get_lnames().at(0) + "=" + v);
    }
  }
  std::vector<std::string> args = {cmd.get_name()};
  args.insert(args.end(), positional.begin(), positional.end());
  args.insert(args.end(), named.begin(), named.end());
  return args;
}

std::string run_name(const std::vector<std::string>& arguments) {
  Hash h;
  h.add(SUPERBALL_VERSION);
  for (const std::string& a : arguments) {
    h.add(a);
    // "--scene=FILE" or a positional FILE: the file's content is part of the run.
    const std::size_t eq = a.rfind("--", 0) == 0 ? a.find('=') : std::string::npos;
    const std::string value = eq == std::string::npos ? a : a.substr(eq + 1);
    std::error_code error;
    if (!value.empty() && std::filesystem::is_regular_file(value, error)) h.add(slurp(value));
  }
  return h.hex();
}

struct Distribution::Impl {
  std::vector<std::string> arguments;
  std::string run, checkpoint, part;
  std::size_t count = 0, shard = 0, shards = 1;
  std::map<std::size_t, std::string> done;  ///< results found (checkpoint, merge)
  std::vector<std::size_t> todo;            ///< computed by this process (or, under MPI, by the ranks)
  bool mpi = false;

  void save(std::size_t k, const std::string& text) const {
    if (!checkpoint.empty()) write_atomically(task_file(checkpoint, k), text);
  }
};

Distribution::Distribution(const CLI::App& cmd, const DistributeOptions& options, std::size_t count) : impl_(std::make_unique<Impl>()) {
  Impl& d = *impl_;
  d.arguments = run_arguments(cmd);
  d.run = run_name(d.arguments);
  d.count = count;
  d.checkpoint = options.checkpoint;
  d.mpi = mpi_size() > 1;
  const std::string name = cmd.get_name();
  if (!options.shard.empty()) {
    unsigned long long i = 0, n = 0;
    char extra = 0;
    if (std::sscanf(options.shard.c_str(), "%llu/%llu%c", &i, &n, &extra) != 2 || n < 1 || i < 1 || i > n || n > 1000000)
      throw std::invalid_argument(name + ": --shard: '" + options.shard + "' is not I/N with 1 <= I <= N (e.g. --shard 2/8)");
    if (d.mpi) throw std::invalid_argument(name + ": --shard runs one part in one process; under MPI run the whole task list (drop --shard)");
    d.shard = static_cast<std::size_t>(i - 1);
    d.shards = static_cast<std::size_t>(n);
    d.part = options.part.empty() ? "superball-" + d.run + "-" + std::to_string(i) + "-of-" + std::to_string(n) + ".part" : options.part;
  } else if (!options.part.empty()) {
    throw std::invalid_argument(name + ": --part names the part file of --shard I/N; give --shard too");
  }
  if (merged_run) {
    if (merged_run->run != d.run || merged_run->tasks != count)
      throw std::invalid_argument("merge: the parts are of run " + merged_run->run + " but its command now makes run " + d.run +
                                  " (a file it reads or the superball version changed)");
    d.done = merged_run->results;
    return;
  }
  if (!d.checkpoint.empty() && mpi_rank() == 0) {
    namespace fs = std::filesystem;
    std::error_code error;
    fs::create_directories(d.checkpoint, error);
    if (error || !fs::is_directory(d.checkpoint)) throw OutputError("--checkpoint " + d.checkpoint + ": cannot make the folder" + (error ? ": " + error.message() : ""));
    const std::string file = (fs::path(d.checkpoint) / "run").string();
    const std::string mine = header("superball checkpoint 1", d.run, d.arguments, count);
    if (fs::exists(file)) {
      const std::string theirs = slurp(file);
      if (theirs != mine) {
        std::istringstream in(theirs);
        std::string what = "another run";
        try {
          const Header h = read_header(in, "superball checkpoint 1", file);
          what = "run " + h.run + " (superball";
          for (std::size_t a = 0; a < h.arguments.size(); ++a) what += " " + h.arguments[a];
          what += ")";
        } catch (const std::exception&) {
        }
        throw std::invalid_argument("--checkpoint " + d.checkpoint + ": holds " + what + ", not this one (run " + d.run + "); give another folder");
      }
    } else {
      write_atomically(file, mine);
    }
    for (const auto& entry : fs::directory_iterator(d.checkpoint)) {
      const std::string leaf = entry.path().filename().string();
      if (leaf.find(".tmp") != std::string::npos) {  // a write cut short by a kill
        fs::remove(entry.path(), error);
        continue;
      }
      unsigned long long k = 0;
      char extra = 0;
      if (entry.is_regular_file() && std::sscanf(leaf.c_str(), "task-%llu%c", &k, &extra) == 1 && k < count) d.done.emplace(static_cast<std::size_t>(k), slurp(entry.path().string()));
    }
  }
  for (std::size_t k = d.shard; k < count; k += d.shards)
    if (!d.done.count(k)) d.todo.push_back(k);
  if (d.mpi) {  // only rank 0 read the checkpoint: every rank learns what is left (verify --case computes it on all)
    std::vector<std::string> left(1);
    for (std::size_t k : d.todo) left[0] += std::to_string(k) + " ";
    share(left, false);
    d.todo.clear();
    std::istringstream in(left.at(0));
    for (std::size_t k = 0; in >> k;) d.todo.push_back(k);
  }
  if (!d.done.empty() && mpi_rank() == 0)
    std::cerr << "superball: --checkpoint " << d.checkpoint << ": " << d.done.size() << " of " << count << " tasks done already, "
              << d.todo.size() << " to compute\n";
}

Distribution::~Distribution() = default;

bool Distribution::writes_output() const { return impl_->part.empty() && mpi_rank() == 0; }
bool Distribution::local() const { return !impl_->mpi && !merged_run; }
const std::vector<std::size_t>& Distribution::todo() const { return impl_->todo; }

Distribution::Task Distribution::keeping(const Task& task) const {
  if (impl_->checkpoint.empty()) return task;
  // The task saves its result as soon as it has it (in a worker process, too).
  return [this, task](std::size_t k) {
    std::string text = task(k);
    impl_->save(k, text);
    return text;
  };
}

namespace {

/// run_on_ranks(), then every result sent to every rank (share()): the
/// results in task order, in every process.
std::vector<std::string> gather_everywhere(std::size_t count, const std::vector<std::size_t>& todo, std::map<std::size_t, std::string>& done,
                                           const Distribution::Task& task, const std::function<void(std::size_t, const std::string&)>& save) {
  std::vector<std::string> results(count);
  std::exception_ptr error;
  try {
    run_on_ranks(count, todo, done, task, save, [&](std::size_t k, std::string&& text) { results[k] = std::move(text); });
  } catch (...) {
    error = std::current_exception();
  }
  share(results, error != nullptr);
  if (error) std::rethrow_exception(error);
  return results;
}

}  // namespace

std::vector<std::string> run_everywhere(std::size_t count, const Distribution::Task& task) {
  const Distribution::Task t = with_test_hook(task);
  std::vector<std::string> results(count);
  if (mpi_size() <= 1) {
    for (std::size_t k = 0; k < count; ++k) results[k] = t(k);
    return results;
  }
  std::vector<std::size_t> todo(count);
  for (std::size_t k = 0; k < count; ++k) todo[k] = k;
  std::map<std::size_t, std::string> done;
  return gather_everywhere(count, todo, done, t, [](std::size_t, const std::string&) {});
}

std::vector<std::string> Distribution::run_everywhere(const Task& task) {
  Impl& d = *impl_;
  if (!d.part.empty()) throw std::logic_error("Distribution::run_everywhere(): a shard run has only its part of the results");
  if (d.mpi) return gather_everywhere(d.count, d.todo, d.done, with_test_hook(task), [&](std::size_t k, const std::string& text) { d.save(k, text); });
  std::vector<std::string> results(d.count);
  run(task, [&](std::size_t k, std::string&& text) { results[k] = std::move(text); });
  return results;
}

void Distribution::run(const Task& unhooked, const Deliver& deliver, const Local& local) {
  Impl& d = *impl_;
  const Task task = with_test_hook(unhooked);
  if (merged_run) {
    for (auto& [k, text] : d.done) deliver(k, std::move(text));
    return;
  }
  if (d.mpi) {
    run_on_ranks(
        d.count, d.todo, d.done, task, [&](std::size_t k, const std::string& text) { d.save(k, text); }, deliver);
    return;
  }
  const Task saving = keeping(task);
  std::map<std::size_t, std::string>& done = d.done;
  std::size_t next = 0;  // the next task to deliver (whole run)
  auto flush = [&] {
    for (auto it = done.find(next); it != done.end(); it = done.find(next)) {
      deliver(next, std::move(it->second));
      done.erase(it);
      ++next;
    }
  };
  if (!d.part.empty()) {  // a shard: the part file, no output
    std::string part = header("superball part 1", d.run, d.arguments, d.count);
    part += "part " + std::to_string(d.shard + 1) + " of " + std::to_string(d.shards) + "\n";
    auto add = [&](std::size_t k, const std::string& text) { part += "task " + std::to_string(k) + " " + std::to_string(text.size()) + "\n" + text + "\n"; };
    std::map<std::size_t, std::string> mine;
    for (std::size_t k = d.shard; k < d.count; k += d.shards)
      if (d.done.count(k)) mine.emplace(k, d.done[k]);
    const Deliver keep = [&](std::size_t j, std::string&& text) { mine.emplace(d.todo[j], std::move(text)); };
    if (local)
      local(d.todo, saving, keep);
    else
      for (std::size_t j = 0; j < d.todo.size(); ++j) keep(j, saving(d.todo[j]));
    for (const auto& [k, text] : mine) add(k, text);
    part += "end\n";
    write_output(d.part, part);
    return;
  }
  flush();
  const Deliver in_order = [&](std::size_t j, std::string&& text) {
    done.emplace(d.todo[j], std::move(text));
    flush();
  };
  if (local)
    local(d.todo, saving, in_order);
  else
    for (std::size_t j = 0; j < d.todo.size(); ++j) in_order(j, saving(d.todo[j]));
}

// ---- superball merge ----

void add_merge(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("merge", "Join the part files of a run made with --shard I/N into the output of the whole run");
  cmd->footer(
      "Each part file names its run (a hash of the command, the superball version and the files it reads), its\n"
      "part I of N and holds the results of its tasks.  merge checks that the files are the N parts of one run,\n"
      "each once, none cut short, then runs the command again with the results taken from them: its output\n"
      "(standard output, or -o FILE) is byte for byte that of the run in one process.  The files the command\n"
      "reads must still be there, unchanged (same run name).\n\n"
      "Example (a Slurm job array, or any loop):\n"
      "  superball derive --bodies 6 --pairs near2 --all --format json --shard 1/3 --part p1.part\n"
      "  superball derive --bodies 6 --pairs near2 --all --format json --shard 2/3 --part p2.part\n"
      "  superball derive --bodies 6 --pairs near2 --all --format json --shard 3/3 --part p3.part\n"
      "  superball merge p1.part p2.part p3.part -o all.json");
  static std::vector<std::string> parts;
  static std::string output;
  cmd->add_option("parts", parts, "The part files (any order)")->required();
  cmd->add_option("--output,-o", output, "Write to this file instead of standard output (derive; the others: redirect standard output)");
}

std::vector<std::string> merge_arguments(const std::vector<std::string>& args) {
  if (args.empty() || args[0] != "merge") return args;
  std::vector<std::string> parts;
  std::string output;
  for (std::size_t a = 1; a < args.size(); ++a) {
    const std::string& s = args[a];
    if (s == "--help" || s == "-h") return args;
    if (s == "-o" || s == "--output") {
      if (a + 1 == args.size()) throw std::invalid_argument("merge: " + s + " needs a file name");
      output = args[++a];
    } else if (s.rfind("--output=", 0) == 0) {
      output = s.substr(9);
    } else if (!s.empty() && s[0] == '-') {
      throw std::invalid_argument("merge: unknown option '" + s + "' (superball merge PART... [-o FILE])");
    } else {
      parts.push_back(s);
    }
  }
  if (parts.empty()) throw std::invalid_argument("merge: no part file (superball merge PART... [-o FILE])");
  static MergedRun merged;
  Header first;
  std::map<std::size_t, std::string> which;  // part number -> its file
  std::size_t shards = 0;
  for (const std::string& path : parts) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::invalid_argument("merge: " + path + ": cannot be read: " + std::strerror(errno));
    const Header h = read_header(in, "superball part 1", "merge: " + path);
    auto bad = [&](const std::string& what) { return std::invalid_argument("merge: " + path + ": " + what); };
    std::string line;
    unsigned long long i = 0, n = 0;
    if (!std::getline(in, line) || std::sscanf(line.c_str(), "part %llu of %llu", &i, &n) != 2 || i < 1 || i > n) throw bad("no 'part I of N' line");
    if (which.empty()) {
      first = h;
      shards = n;
      merged.run = h.run;
      merged.tasks = h.tasks;
    } else if (h.run != first.run || h.tasks != first.tasks) {
      std::string cmd;
      for (const std::string& a : h.arguments) cmd += " " + a;
      throw bad("a part of another run (" + h.run + ":" + cmd + ") than " + which.begin()->second + " (" + first.run + ")");
    } else if (n != shards) {
      throw bad("part " + std::to_string(i) + " of " + std::to_string(n) + ", but " + which.begin()->second + " is a part of " + std::to_string(shards));
    }
    if (which.count(i)) throw bad("part " + std::to_string(i) + " of " + std::to_string(n) + " again (also " + which[i] + ")");
    which[i] = path;
    bool ended = false;
    while (std::getline(in, line)) {
      if (line == "end") {
        ended = true;
        break;
      }
      unsigned long long k = 0, size = 0;
      if (std::sscanf(line.c_str(), "task %llu %llu", &k, &size) != 2 || k >= h.tasks || k % n != i - 1) throw bad("a damaged task line '" + line.substr(0, 40) + "'");
      std::string text(static_cast<std::size_t>(size), '\0');
      if (!in.read(text.data(), static_cast<std::streamsize>(size)) || in.get() != '\n') throw bad("cut short in task " + std::to_string(k));
      merged.results[static_cast<std::size_t>(k)] = std::move(text);
    }
    if (!ended) throw bad("cut short (no 'end' line)");
  }
  for (std::size_t i = 1; i <= shards; ++i)
    if (!which.count(i)) throw std::invalid_argument("merge: part " + std::to_string(i) + " of " + std::to_string(shards) + " of run " + first.run + " is missing");
  if (merged.results.size() != merged.tasks)
    throw std::invalid_argument("merge: the parts hold " + std::to_string(merged.results.size()) + " of the run's " + std::to_string(merged.tasks) + " tasks");
  merged_run = &merged;
  std::vector<std::string> run = first.arguments;
  if (!output.empty()) {
    if (run.empty() || run[0] != "derive")
      throw std::invalid_argument("merge: -o: " + (run.empty() ? std::string("this command") : run[0]) +
                                  " writes to standard output; redirect it (superball merge PART... > FILE)");
    run.push_back("--output=" + output);
  }
  return run;
}

}  // namespace superball::cli

#ifndef SUPERBALL_WITH_MPI
namespace superball::cli {
void start_mpi(int*, char***) {}
void stop_mpi(int) {}
void abandon_ranks() {}
int mpi_rank() { return 0; }
int mpi_size() { return 1; }
namespace detail {
void run_on_ranks(std::size_t, const std::vector<std::size_t>&, std::map<std::size_t, std::string>&, const Distribution::Task&,
                  const std::function<void(std::size_t, const std::string&)>&, const Distribution::Deliver&) {
  throw std::logic_error("run_on_ranks(): built without MPI");
}
void share(std::vector<std::string>&, bool) { throw std::logic_error("share(): built without MPI"); }
}  // namespace detail
}  // namespace superball::cli
#endif
