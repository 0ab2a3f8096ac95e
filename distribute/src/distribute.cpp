// A task list and its runners (superball/distribute/distribute.hpp): here,
// a shard with its part file, a checkpoint folder, and the MPI ranks
// (mpi.cpp, built with SUPERBALL_WITH_MPI).
#include "superball/distribute/distribute.hpp"

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
#include <limits>
#include <optional>
#include <set>
#include <string_view>
#include <sstream>
#include <stdexcept>

#include "detail.hpp"

namespace superball::distribute {

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

/// A count written in a file: decimal digits only (no sign, no leading zero),
/// at most \p max; nullopt otherwise.
std::optional<std::uint64_t> count_of(std::string_view s, std::uint64_t max) {
  if (s.empty() || s.size() > 20 || (s.size() > 1 && s[0] == '0')) return std::nullopt;
  std::uint64_t v = 0;
  for (char c : s) {
    if (c < '0' || c > '9') return std::nullopt;
    const auto d = static_cast<std::uint64_t>(c - '0');
    if (v > max / 10 || d > max - v * 10) return std::nullopt;
    v = v * 10 + d;
  }
  return v;
}

/// The words of \p line separated by single spaces.
std::vector<std::string_view> words(std::string_view line) {
  std::vector<std::string_view> w;
  for (std::size_t at = 0;;) {
    const std::size_t space = line.find(' ', at);
    w.push_back(line.substr(at, space == std::string_view::npos ? std::string_view::npos : space - at));
    if (space == std::string_view::npos) return w;
    at = space + 1;
  }
}

/// The checksum of task \p k's \p text in run \p run.
std::string checksum(const std::string& run, std::size_t k, const std::string& text) {
  Hash h;
  h.add("superball task");
  h.add(run);
  h.add(std::to_string(k));
  h.add(text);
  return h.hex();
}

/// The longest line of a header (an argument may be longer: its length comes first).
constexpr std::size_t kMaxLine = 256;
/// The longest argument and the most arguments a header may hold.
constexpr std::uint64_t kMaxArgument = std::uint64_t{1} << 20;
constexpr std::size_t kMaxArguments = 4096;
/// The most tasks of a run.
constexpr std::uint64_t kMaxTasks = std::uint64_t{1} << 40;

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

DataFile::DataFile(const std::string& path, const std::string& where, bool follow, std::uint64_t max_size) : where_(where) {
  fd_ = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | (follow ? 0 : O_NOFOLLOW));
  if (fd_ < 0) {
    const int e = errno;
    if (e == ELOOP && !follow) throw bad("a symbolic link, not read");
    throw bad(std::string("cannot be read: ") + std::strerror(e));
  }
  struct stat st {};
  std::string wrong;
  if (::fstat(fd_, &st) != 0)
    wrong = std::string("cannot be read: ") + std::strerror(errno);
  else if (S_ISDIR(st.st_mode))
    wrong = "a folder, not a file: not read";
  else if (S_ISFIFO(st.st_mode))
    wrong = "a FIFO, not a regular file: not read";
  else if (!S_ISREG(st.st_mode))
    wrong = "not a regular file: not read";
  else if (static_cast<std::uint64_t>(st.st_size) > max_size)
    wrong = "of " + std::to_string(st.st_size) + " bytes, more than it can hold (at most " + std::to_string(max_size) + "): not read";
  if (!wrong.empty()) {
    ::close(fd_);
    throw bad(wrong);
  }
  size_ = static_cast<std::uint64_t>(st.st_size);
}

DataFile::~DataFile() { ::close(fd_); }

std::invalid_argument DataFile::bad(const std::string& what) const { return std::invalid_argument(where_ + ": " + what); }

int DataFile::get() {
  if (at_ == buffer_.size()) {
    if (read_ == size_) return -1;
    buffer_.resize(static_cast<std::size_t>(std::min<std::uint64_t>(size_ - read_, 1 << 16)));
    ssize_t n = -1;
    do n = ::read(fd_, buffer_.data(), buffer_.size());
    while (n < 0 && errno == EINTR);
    if (n < 0) throw bad(std::string("cannot be read: ") + std::strerror(errno));
    if (n == 0) {  // shorter than fstat() said: it shrank while read
      size_ = read_;
      return -1;
    }
    buffer_.resize(static_cast<std::size_t>(n));
    at_ = 0;
  }
  ++read_;
  return static_cast<unsigned char>(buffer_[at_++]);
}

std::string DataFile::line(std::size_t max, const std::string& what) {
  std::string l;
  for (int c = get(); c != '\n'; c = get()) {
    if (c < 0) throw bad("cut short in " + what);
    if (l.size() == max) throw bad("a line longer than " + std::to_string(max) + " bytes in " + what + " (damaged)");
    l.push_back(static_cast<char>(c));
  }
  return l;
}

std::string DataFile::bytes(std::uint64_t n, const std::string& what) {
  if (n > left()) throw bad("cut short in " + what + " (" + std::to_string(n) + " bytes claimed, " + std::to_string(left()) + " left)");
  std::string text(static_cast<std::size_t>(n), '\0');
  std::size_t got = std::min(buffer_.size() - at_, text.size());
  std::memcpy(text.data(), buffer_.data() + at_, got);
  at_ += got, read_ += got;
  while (got < text.size()) {
    const ssize_t r = ::read(fd_, text.data() + got, text.size() - got);
    if (r < 0 && errno == EINTR) continue;
    if (r < 0) throw bad(std::string("cannot be read: ") + std::strerror(errno));
    if (r == 0) throw bad("cut short in " + what);
    got += static_cast<std::size_t>(r), read_ += static_cast<std::uint64_t>(r);
  }
  return text;
}

Header read_header(DataFile& in, const std::string& kind) {
  const bool part = kind == kPartKind;
  const std::string noun = part ? "part file" : "checkpoint folder's run file";
  const std::string family = part ? "superball part " : "superball checkpoint ";
  std::string first;
  try {
    first = in.line(64, "its first line");
  } catch (const std::invalid_argument&) {
    throw in.bad("not a " + noun + " of superball (its first line is not '" + kind + "')");
  }
  if (first.rfind(family, 0) == 0 && first != kind)
    throw in.bad("a " + noun + " of another format ('" + first + "'; superball " SUPERBALL_VERSION " reads '" + kind + "'): make it again with this superball");
  if (first != kind) throw in.bad("not a " + noun + " of superball (its first line is not '" + kind + "')");
  Header h;
  std::string line = in.line(kMaxLine, "its header");
  if (line.rfind("run ", 0) != 0 || line.size() != 20 || line.find_first_not_of("0123456789abcdef", 4) != std::string::npos)
    throw in.bad("no 'run' line of 16 hexadecimal digits (damaged)");
  h.run = line.substr(4);
  line = in.line(kMaxLine, "its header");
  if (line.rfind("superball ", 0) != 0) throw in.bad("no 'superball VERSION' line (damaged)");
  h.version = line.substr(10);
  if (h.version != SUPERBALL_VERSION) throw in.bad("written by superball " + h.version + ", this is superball " SUPERBALL_VERSION ": make it again with this superball");
  for (;;) {
    line = in.line(kMaxLine + kMaxArgument, "its header");
    const std::vector<std::string_view> w = words(line);
    if (w[0] == "tasks") {
      const auto t = w.size() == 2 ? count_of(w[1], kMaxTasks) : std::nullopt;
      if (!t) throw in.bad("a damaged 'tasks' line");
      h.tasks = static_cast<std::size_t>(*t);
      return h;
    }
    if (w[0] != "argument" || w.size() < 3) throw in.bad("a damaged line in its header (neither 'argument LENGTH TEXT' nor 'tasks T')");
    const auto size = count_of(w[1], kMaxArgument);
    if (!size) throw in.bad("an argument of a damaged length '" + std::string(w[1].substr(0, 24)) + "'");
    if (h.arguments.size() == kMaxArguments) throw in.bad("more than " + std::to_string(kMaxArguments) + " arguments (damaged)");
    const std::size_t at = 9 + w[1].size() + 1;  // "argument LENGTH "
    std::string value = line.substr(at);
    if (value.size() > *size) throw in.bad("an argument longer than its length (damaged)");
    if (value.size() < *size) {  // an argument holding a newline
      value += "\n" + in.bytes(*size - value.size() - 1, "its arguments");
      if (!in.line(0, "its arguments").empty()) throw in.bad("an argument longer than its length (damaged)");
    }
    h.arguments.push_back(std::move(value));
  }
}

std::string record(const std::string& run, std::size_t k, const std::string& text) {
  return "task " + std::to_string(k) + " " + std::to_string(text.size()) + " " + checksum(run, k, text) + "\n" + text + "\n";
}

std::pair<std::size_t, std::string> read_record(DataFile& in, const std::string& line, const std::string& run, std::size_t tasks,
                                                std::uint64_t max_bytes) {
  const std::vector<std::string_view> w = words(line);
  if (w.size() != 4 || w[0] != "task") throw in.bad("a damaged line where a task's record starts ('" + line.substr(0, 40) + "')");
  const auto k = count_of(w[1], kMaxTasks);
  if (!k || *k >= tasks) throw in.bad("a record of task '" + std::string(w[1].substr(0, 24)) + "', not a task of this run (0 to " + std::to_string(tasks) + " - 1)");
  const std::string task = "task " + std::to_string(*k);
  const auto size = count_of(w[2], std::numeric_limits<std::uint64_t>::max());
  if (!size) throw in.bad(task + ": a damaged length '" + std::string(w[2].substr(0, 24)) + "'");
  if (*size > max_bytes)
    throw in.bad(task + ": a result of " + std::to_string(*size) + " bytes, more than a task of this run can produce (at most " + std::to_string(max_bytes) + "): not read");
  std::string text = in.bytes(*size, task);
  if (in.bytes(1, task) != "\n") throw in.bad(task + ": its result is not followed by a newline (damaged)");
  if (w[3] != checksum(run, static_cast<std::size_t>(*k), text)) throw in.bad(task + ": fails its checksum (changed or damaged since it was written)");
  return {static_cast<std::size_t>(*k), std::move(text)};
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

std::string run_name(const RunIdentity& id) {
  Hash h;
  h.add(SUPERBALL_VERSION);
  h.add(id.command);
  for (std::size_t i = 0; i < id.arguments.size(); ++i) {
    h.add(id.arguments[i]);
    if (const auto it = id.contents.find(i); it != id.contents.end()) h.add(it->second);
  }
  return h.hex();
}

RunIdentity typed_identity(const std::string& command, const std::map<std::string, std::string>& options,
                           const std::map<std::string, std::string>& inputs) {
  RunIdentity id{command, {}, {}};
  for (const auto& [name, value] : options) id.arguments.push_back("--" + name + "=" + value);
  for (const auto& [name, content] : inputs) {
    id.contents.emplace(id.arguments.size(), content);
    id.arguments.push_back("--" + name);
  }
  return id;
}

struct Distribution::Impl {
  std::vector<std::string> arguments;  ///< the command, then its arguments
  std::string run, checkpoint, part;
  std::size_t count = 0, shard = 0, shards = 1;
  std::uint64_t max_task_bytes = kMaxTaskBytes;
  std::map<std::size_t, std::string> done;  ///< results found (checkpoint, merge)
  std::vector<std::size_t> todo;            ///< computed by this process (or, under MPI, by the ranks)
  std::set<std::size_t> kept;               ///< the tasks read from the checkpoint folder
  bool mpi = false;
  std::function<void(const std::string&)> warn;
  std::function<void(const std::string&, const std::string&)> write_part;

  /// \p text of task \p k, checked against the bound of a task.
  void check_size(std::size_t k, const std::string& text) const {
    if (text.size() > max_task_bytes)
      throw std::logic_error("task " + std::to_string(k) + " gave " + std::to_string(text.size()) + " bytes, more than the bound of its command (" +
                             std::to_string(max_task_bytes) + ")");
  }
  void save(std::size_t k, const std::string& text) const {
    check_size(k, text);
    if (!checkpoint.empty()) write_atomically(task_file(checkpoint, k), record(run, k, text));
  }
  void read_checkpoint();
};

/// Reads the checkpoint folder: its run file (refused when of another run),
/// then every task file, checked (a regular file, not a link, of a size its
/// task can have, its record whole and its checksum right); a task file that
/// fails is told to warn in one line, removed, and its task computed again.
void Distribution::Impl::read_checkpoint() {
  namespace fs = std::filesystem;
  std::error_code error;
  fs::create_directories(checkpoint, error);
  if (error || !fs::is_directory(checkpoint, error)) throw OutputError("--checkpoint " + checkpoint + ": cannot make the folder" + (error ? ": " + error.message() : ""));
  const std::string file = (fs::path(checkpoint) / "run").string();
  const std::string mine = header(kCheckpointKind, run, arguments, count);
  const std::string where = "--checkpoint " + checkpoint;
  auto command = [](const std::vector<std::string>& a) {
    std::string c = "superball";
    for (const std::string& w : a) c += " " + w;
    return c;
  };
  if (fs::symlink_status(file, error).type() != fs::file_type::not_found) {
    std::string theirs;
    Header h;
    try {
      DataFile in(file, where + ": its run file", false, 4 * kMaxArgument);
      theirs = in.bytes(in.left(), "its run file");
      DataFile again(file, where + ": its run file", false, 4 * kMaxArgument);
      h = read_header(again, kCheckpointKind);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string(e.what()) + "; give another folder");
    }
    if (theirs != mine) {
      if (h.run != run)
        throw std::invalid_argument(where + ": holds run " + h.run + " (" + command(h.arguments) + "), and this command is run " + run + " (" +
                                    command(arguments) + "); give another folder");
      throw std::invalid_argument(where + ": its run file names this run (" + run + ") but does not hold its arguments and task count (" + command(h.arguments) +
                                  ", " + std::to_string(h.tasks) + " tasks; this command: " + command(arguments) + ", " + std::to_string(count) +
                                  " tasks): edited or damaged; give another folder");
    }
  } else {
    write_atomically(file, mine);
  }
  std::vector<fs::path> entries;  // in order, so that what is said of them is too
  for (fs::directory_iterator it(checkpoint, error), end; !error && it != end; it.increment(error)) entries.push_back(it->path());
  if (error) throw OutputError(where + ": cannot be read: " + error.message());
  std::sort(entries.begin(), entries.end());
  for (const fs::path& entry : entries) {
    const std::string leaf = entry.filename().string();
    if (leaf.find(".tmp") != std::string::npos) {  // a write cut short by a kill
      fs::remove(entry, error);
      continue;
    }
    const std::size_t digits = leaf.find_first_not_of('0', 5);  // task-00000012: 12
    const auto k = leaf.size() == 13 && leaf.rfind("task-", 0) == 0 ? digits == std::string::npos ? std::optional<std::uint64_t>(0) : count_of(leaf.substr(digits), count)
                                                                   : std::nullopt;
    if (!k || *k >= count || leaf != fs::path(task_file(checkpoint, *k)).filename().string()) continue;
    try {
      DataFile in(entry.string(), where + ": " + leaf, false, max_task_bytes + kMaxLine);
      auto [got, text] = read_record(in, in.line(kMaxLine, "its record"), run, count, max_task_bytes);
      if (got != *k) throw in.bad("holds the record of task " + std::to_string(got));
      if (in.left()) throw in.bad(std::to_string(in.left()) + " bytes after its record (damaged)");
      done.emplace(static_cast<std::size_t>(*k), std::move(text));
      kept.insert(static_cast<std::size_t>(*k));
    } catch (const std::invalid_argument& e) {
      // Removed first: what cannot be removed (a folder that is not empty) would stop the task's result being kept.
      if (!fs::remove(entry, error) || error)
        throw std::invalid_argument(std::string(e.what()) + "; it cannot be removed to compute task " + std::to_string(*k) + " again" +
                                    (error ? " (" + error.message() + ")" : "") + ": remove it, or give another folder");
      if (warn) warn(std::string(e.what()) + "; task " + std::to_string(*k) + " computed again");
    }
  }
}

Distribution::Distribution(const RunIdentity& id, const Options& options, std::size_t count, std::uint64_t max_task_bytes)
    : impl_(std::make_unique<Impl>()) {
  Impl& d = *impl_;
  d.arguments = {id.command};
  d.arguments.insert(d.arguments.end(), id.arguments.begin(), id.arguments.end());
  d.run = run_name(id);
  d.warn = options.warn;
  d.write_part = options.write_part ? options.write_part : write_atomically;
  d.count = count;
  d.max_task_bytes = std::min(max_task_bytes, kMaxTaskBytes);
  d.checkpoint = options.checkpoint;
  d.mpi = mpi_size() > 1;
  const std::string& name = id.command;
  if (merged_run) {  // the parts describe the run; nothing in them is obeyed (merge_arguments() refused shards and outputs)
    if (merged_run->arguments != d.arguments)
      throw std::invalid_argument("merge: the parts' arguments (" + [&] {
        std::string c;
        for (const std::string& a : merged_run->arguments) c += (c.empty() ? "" : " ") + a;
        return c;
      }() + ") are not those of a run (edited?)");
    if (merged_run->run != d.run || merged_run->tasks != count)
      throw std::invalid_argument("merge: the parts are of run " + merged_run->run + " but its command now makes run " + d.run +
                                  " (a file it reads or the superball version changed)");
    for (const auto& [k, text] : merged_run->results)
      if (text.size() > d.max_task_bytes)
        throw std::invalid_argument("merge: " + merged_run->files.at(k) + ": task " + std::to_string(k) + ": a result of " + std::to_string(text.size()) +
                                    " bytes, more than a task of this run can produce (" + std::to_string(d.max_task_bytes) + ")");
    d.done = merged_run->results;
    return;
  }
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
  if (!d.checkpoint.empty() && mpi_rank() == 0) d.read_checkpoint();
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
  if (!d.done.empty() && mpi_rank() == 0 && options.note)
    options.note("--checkpoint " + d.checkpoint + ": " + std::to_string(d.done.size()) + " of " + std::to_string(count) + " tasks done already, " +
                 std::to_string(d.todo.size()) + " to compute");
}

Distribution::~Distribution() = default;

bool Distribution::writes_output() const { return impl_->part.empty() && mpi_rank() == 0; }
bool Distribution::local() const { return !impl_->mpi && !merged_run; }
const std::vector<std::size_t>& Distribution::todo() const { return impl_->todo; }

std::string Distribution::origin(std::size_t k) const {
  if (merged_run && merged_run->files.count(k)) return "merge: " + merged_run->files.at(k) + ": task " + std::to_string(k);
  if (impl_->kept.count(k)) return "--checkpoint " + impl_->checkpoint + ": " + std::filesystem::path(task_file(impl_->checkpoint, k)).filename().string();
  return "task " + std::to_string(k);
}

bool Distribution::read_back(std::size_t k) const { return (merged_run && merged_run->files.count(k)) || impl_->kept.count(k); }

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
    std::string part = header(kPartKind, d.run, d.arguments, d.count);
    part += "part " + std::to_string(d.shard + 1) + " of " + std::to_string(d.shards) + "\n";
    auto add = [&](std::size_t k, const std::string& text) {
      d.check_size(k, text);
      part += record(d.run, k, text);
    };
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
    d.write_part(d.part, part);
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

// ---- the parts of a run ----

MergedRun read_parts(const std::vector<std::string>& paths,
                     const std::function<void(const std::vector<std::string>& arguments, const std::string& where)>& check) {
  MergedRun merged;
  Header first;
  std::map<std::size_t, std::string> which;  // part number -> its file
  std::size_t shards = 0;
  for (const std::string& path : paths) {
    const std::string where = "merge: " + path;
    DataFile in(path, where, true, std::numeric_limits<std::uint64_t>::max());
    const Header h = read_header(in, kPartKind);
    check(h.arguments, where);
    const std::string line = in.line(kMaxLine, "its header");
    const std::vector<std::string_view> w = words(line);
    const auto i = w.size() == 4 && w[0] == "part" && w[2] == "of" ? count_of(w[1], 1000000) : std::nullopt;
    const auto n = i ? count_of(w[3], 1000000) : std::nullopt;
    if (!n || *i < 1 || *i > *n) throw in.bad("no 'part I of N' line (damaged)");
    if (which.empty()) {
      first = h;
      shards = *n;
      merged.run = h.run;
      merged.tasks = h.tasks;
      merged.arguments = h.arguments;
    } else if (h.run != first.run || h.tasks != first.tasks || h.arguments != first.arguments) {
      std::string cmd;
      for (const std::string& a : h.arguments) cmd += " " + a;
      throw in.bad("a part of another run (" + h.run + ":" + cmd + ") than " + which.begin()->second + " (" + first.run + ")");
    } else if (*n != shards) {
      throw in.bad("part " + std::to_string(*i) + " of " + std::to_string(*n) + ", but " + which.begin()->second + " is a part of " + std::to_string(shards));
    }
    if (which.count(*i)) throw in.bad("part " + std::to_string(*i) + " of " + std::to_string(*n) + " again (also " + which[*i] + ")");
    which[*i] = path;
    std::size_t held = 0;
    for (std::string l = in.line(kMaxLine, "its tasks (no 'end' line)"); l != "end"; l = in.line(kMaxLine, "its tasks (no 'end' line)")) {
      auto [k, text] = read_record(in, l, h.run, h.tasks, kMaxTaskBytes);
      if (k % *n != *i - 1) throw in.bad("task " + std::to_string(k) + " is not a task of part " + std::to_string(*i) + " of " + std::to_string(*n) + " (damaged)");
      if (merged.results.count(k)) throw in.bad("task " + std::to_string(k) + " twice (damaged)");
      merged.results.emplace(k, std::move(text));
      merged.files.emplace(k, path);
      ++held;
    }
    if (in.left()) throw in.bad(std::to_string(in.left()) + " bytes after its 'end' line (damaged or appended to): not read");
    const std::size_t expected = h.tasks > *i - 1 ? (h.tasks - (*i - 1) + *n - 1) / *n : 0;
    if (held != expected) throw in.bad("holds " + std::to_string(held) + " of the " + std::to_string(expected) + " tasks of its part (damaged)");
  }
  for (std::size_t i = 1; i <= shards; ++i)
    if (!which.count(i)) throw std::invalid_argument("merge: part " + std::to_string(i) + " of " + std::to_string(shards) + " of run " + first.run + " is missing");
  return merged;
}

}  // namespace superball::distribute

namespace superball::distribute {

std::string launched_on_ranks() {
  // What MPI launchers set in every rank: Open MPI's mpirun, the PMI of
  // MPICH's and Intel's mpiexec (hydra), Slurm's srun (a job step's tasks).
  static const char* const sizes[] = {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "SLURM_STEP_NUM_TASKS"};
  for (const char* name : sizes) {
    const char* value = std::getenv(name);
    char* end = nullptr;
    const long long n = value && *value ? std::strtoll(value, &end, 10) : 0;
    if (value && *value && !*end && n > 1) return std::string(name) + "=" + value;
  }
  return "";
}

bool first_launched_rank() {
  for (const char* name : {"OMPI_COMM_WORLD_RANK", "PMI_RANK", "PMIX_RANK", "SLURM_PROCID"}) {
    const char* value = std::getenv(name);
    if (value && *value) return std::string(value) == "0";
  }
  return true;
}

}  // namespace superball::distribute

#ifndef SUPERBALL_WITH_MPI
namespace superball::distribute {
bool built_with_mpi() { return false; }
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
}  // namespace superball::distribute
#endif
