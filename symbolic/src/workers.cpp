// The worker processes of symbolic work (workers.hpp).
#include "superball/symbolic/workers.hpp"

#include <malloc.h>
#include <poll.h>
#include <signal.h>
#ifdef __linux__
#include <sys/prctl.h>
#endif
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <map>
#include <stdexcept>
#include <vector>

namespace superball::symbolic {
namespace {

constexpr std::uint64_t kStop = ~std::uint64_t{0};  ///< the task index that tells a worker to exit

/// A worker's heap (glibc): symbolic work makes and drops polynomials of
/// up to megabytes one after the other.  By default the larger of them are
/// mapped and unmapped each time, and the heap's top given back as soon as
/// it is free, so that their pages are faulted in again and again.  In a
/// worker, blocks under kWorkerMmapThreshold come from the heap, which grows
/// by kWorkerHeapPad beyond each request and keeps that much when it
/// shrinks (at most this much more memory a worker).  Measured on `{}`
/// near2 with couplings: 16 % less CPU at 7 bodies, 10–16 % at 8 (about
/// half the system time), the same peak memory, the same output.
#ifdef M_TOP_PAD
constexpr int kWorkerHeapPad = 64 << 20, kWorkerMmapThreshold = 32 << 20;
#endif

/// What a worker sends back for one task.
enum class Kind : std::uint8_t { Result = 0, InvalidArgument = 1, LogicError = 2, RuntimeError = 3, Coded = 4 };

bool write_all(int fd, const void* data, std::size_t size) {
  const char* p = static_cast<const char*>(data);
  while (size) {
    const ssize_t n = ::write(fd, p, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    p += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

/// Reads exactly \p size bytes; false at end of file or on an error.
bool read_all(int fd, void* data, std::size_t size) {
  char* p = static_cast<char*>(data);
  while (size) {
    const ssize_t n = ::read(fd, p, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    p += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

/// The CPU time of this process so far, in seconds.
double cpu_seconds() {
  timespec t{};
  ::clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

/// A worker's loop: read a task index, run it, send (index, kind, code, CPU seconds, length, text); exit on kStop.
[[noreturn]] void work(int tasks_fd, int results_fd, const std::function<std::string(std::size_t)>& task) {
  std::uint64_t k = 0;
  while (read_all(tasks_fd, &k, sizeof k) && k != kStop) {
    Kind kind = Kind::Result;
    std::int32_t code = 0;
    std::string text;
    const double start = cpu_seconds();
    try {
      text = task(static_cast<std::size_t>(k));
    } catch (const TaskError& e) {  // e.g. a checkpoint file the task could not write
      kind = Kind::Coded;
      code = e.code();
      text = e.what();
    } catch (const std::invalid_argument& e) {
      kind = Kind::InvalidArgument;
      text = e.what();
    } catch (const std::logic_error& e) {
      kind = Kind::LogicError;
      text = e.what();
    } catch (const std::exception& e) {
      kind = Kind::RuntimeError;
      text = e.what();
    }
    const std::uint64_t size = text.size();
    const double seconds = cpu_seconds() - start;
    if (!write_all(results_fd, &k, sizeof k) || !write_all(results_fd, &kind, sizeof kind) || !write_all(results_fd, &code, sizeof code) ||
        !write_all(results_fd, &seconds, sizeof seconds) || !write_all(results_fd, &size, sizeof size) ||
        !write_all(results_fd, text.data(), text.size()))
      ::_exit(3);
    if (kind != Kind::Result) ::_exit(1);
  }
  ::_exit(0);  // no destructors, no atexit handlers: the parent owns every file and the output
}

}  // namespace

struct Workers::Worker {
  pid_t pid = -1;
  int tasks = -1, results = -1;  ///< our ends of its two pipes
  std::uint64_t running = kStop; ///< the task it is working on
};

namespace {

/// Stops and reaps every worker still alive.
void stop_all(std::vector<Workers::Worker>& workers) {
  for (auto& w : workers) {
    if (w.tasks >= 0) ::close(w.tasks);
    if (w.results >= 0) ::close(w.results);
    w.tasks = w.results = -1;
    if (w.pid > 0) {
      ::kill(w.pid, SIGKILL);
      while (::waitpid(w.pid, nullptr, 0) < 0 && errno == EINTR) {
      }
      w.pid = -1;
    }
  }
}

}  // namespace

Workers::Workers(std::size_t count, int jobs, Task task) : count_(count), task_(std::move(task)) {
  if (jobs <= 0 || count == 0) return;
  workers_.resize(std::min<std::size_t>(static_cast<std::size_t>(jobs), count));
  const pid_t parent = ::getpid();
  try {
    for (std::size_t i = 0; i < workers_.size(); ++i) {
      int to_worker[2], from_worker[2];
      if (::pipe(to_worker) != 0) throw std::runtime_error(std::string("Workers: pipe: ") + std::strerror(errno));
      if (::pipe(from_worker) != 0) {
        ::close(to_worker[0]);
        ::close(to_worker[1]);
        throw std::runtime_error(std::string("Workers: pipe: ") + std::strerror(errno));
      }
      const pid_t pid = ::fork();
      if (pid < 0) {
        for (int fd : {to_worker[0], to_worker[1], from_worker[0], from_worker[1]}) ::close(fd);
        throw std::runtime_error(std::string("Workers: fork: ") + std::strerror(errno));
      }
      if (pid == 0) {
        ::close(to_worker[1]);
        ::close(from_worker[0]);
        for (std::size_t j = 0; j < i; ++j)  // the ends of the workers made before this one
          for (int fd : {workers_[j].tasks, workers_[j].results}) ::close(fd);
        ::signal(SIGPIPE, SIG_DFL);
        ::signal(SIGINT, SIG_IGN);  // Ctrl-C is this process's parent's to handle: it stops the workers
#ifdef M_TOP_PAD
        ::mallopt(M_MMAP_THRESHOLD, kWorkerMmapThreshold);
        ::mallopt(M_TOP_PAD, kWorkerHeapPad);
#endif
#ifdef __linux__
        // A parent killed outright (SIGKILL) takes its workers with it: no case goes on being derived.
        ::prctl(PR_SET_PDEATHSIG, SIGKILL);
        if (::getppid() != parent) ::_exit(1);
#endif
        work(to_worker[0], from_worker[1], task_);
      }
      ::close(to_worker[0]);
      ::close(from_worker[1]);
      workers_[i].pid = pid;
      workers_[i].tasks = to_worker[1];
      workers_[i].results = from_worker[0];
    }
  } catch (...) {
    stop_all(workers_);
    throw;
  }
}

Workers::~Workers() { stop_all(workers_); }

void Workers::run(const Deliver& deliver, const Interrupt& interrupted) {
  const std::size_t count = count_;
  auto check = [&] {
    if (interrupted && interrupted()) throw Interrupted("interrupted");
  };
  cpu_.assign(count, 0.0);
  if (workers_.empty()) {
    for (std::size_t k = 0; k < count; ++k) {
      check();
      const double start = cpu_seconds();
      std::string text = task_(k);
      cpu_[k] = cpu_seconds() - start;
      deliver(k, std::move(text));
    }
    return;
  }
  struct Guard {  // every worker stopped however this function is left
    std::vector<Worker>& w;
    ~Guard() { stop_all(w); }
  } guard{workers_};
  std::vector<Worker>& workers = workers_;
  // SIGPIPE from a worker that died: a failed write is seen as such below.
  struct sigaction ignore {}, previous {};
  ignore.sa_handler = SIG_IGN;
  ::sigaction(SIGPIPE, &ignore, &previous);
  struct Restore {
    struct sigaction& previous;
    ~Restore() { ::sigaction(SIGPIPE, &previous, nullptr); }
  } restore{previous};

  // A task that fails ends the run, but the failure reported is that of the
  // first failing task in task order, whatever the timing: the tasks before it
  // are finished and delivered first (as with jobs <= 0, where they ran
  // before it), no task after it is handed out.
  constexpr std::size_t none = ~std::size_t{0};
  std::size_t failed = none;
  Kind failed_kind = Kind::Result;
  std::int32_t failed_code = 0;
  std::string failed_text;
  auto fail = [&](std::size_t k, Kind kind, std::int32_t code, std::string text) {
    if (k >= failed) return;
    failed = k;
    failed_kind = kind;
    failed_code = code;
    failed_text = std::move(text);
  };
  // The worker \p w has ended (it reported a failure, or died): reap it.
  auto retire = [](Worker& w, int* status) {
    ::close(w.tasks);
    ::close(w.results);
    w.tasks = w.results = -1;
    while (::waitpid(w.pid, status, 0) < 0 && errno == EINTR) {
    }
    w.pid = -1;
    w.running = kStop;
  };

  std::size_t next = 0, delivered = 0;
  std::map<std::size_t, std::string> waiting;  // results that came before an earlier one
  auto hand_out = [&](Worker& w) {
    const std::uint64_t k = next < count && next < failed ? next++ : kStop;
    if (!write_all(w.tasks, &k, sizeof k)) throw std::runtime_error("worker for task " + std::to_string(k + 1) + " died before it started");
    w.running = k;
  };
  for (Worker& w : workers) hand_out(w);
  while (delivered < std::min(count, failed)) {
    check();
    std::vector<pollfd> fds;
    std::vector<Worker*> owners;
    for (Worker& w : workers)
      if (w.running != kStop) {
        fds.push_back({w.results, POLLIN, 0});
        owners.push_back(&w);
      }
    if (fds.empty()) throw std::logic_error("Workers::run(): no worker is running and results are missing");
    if (::poll(fds.data(), fds.size(), interrupted ? kPollIntervalMs : -1) < 0) {
      if (errno == EINTR) continue;
      throw std::runtime_error(std::string("Workers::run(): poll: ") + std::strerror(errno));
    }
    for (std::size_t i = 0; i < fds.size(); ++i) {
      if (!(fds[i].revents & (POLLIN | POLLHUP | POLLERR))) continue;
      Worker& w = *owners[i];
      std::uint64_t k = 0, size = 0;
      Kind kind = Kind::Result;
      std::int32_t code = 0;
      double seconds = 0;
      std::string text;
      bool ok = read_all(w.results, &k, sizeof k) && read_all(w.results, &kind, sizeof kind) && read_all(w.results, &code, sizeof code) &&
                read_all(w.results, &seconds, sizeof seconds) && read_all(w.results, &size, sizeof size);
      if (ok) {
        text.resize(static_cast<std::size_t>(size));
        ok = read_all(w.results, text.data(), text.size());
      }
      if (!ok || k != w.running) {
        const std::uint64_t task = w.running;
        int status = 0;
        retire(w, &status);
        const std::string how = WIFSIGNALED(status) ? std::string("signal ") + std::to_string(WTERMSIG(status)) + " (" + ::strsignal(WTERMSIG(status)) + ")"
                                                    : "exit status " + std::to_string(WEXITSTATUS(status));
        fail(static_cast<std::size_t>(task), Kind::RuntimeError, 0, "worker for task " + std::to_string(task + 1) + " died: " + how);
        continue;
      }
      if (kind != Kind::Result) {  // the worker exits after sending it
        retire(w, nullptr);
        fail(static_cast<std::size_t>(k), kind, code, std::move(text));
        continue;
      }
      cpu_[static_cast<std::size_t>(k)] = seconds;
      hand_out(w);
      waiting.emplace(static_cast<std::size_t>(k), std::move(text));
      for (auto it = waiting.find(delivered); delivered < failed && it != waiting.end(); it = waiting.find(delivered)) {
        deliver(delivered, std::move(it->second));
        waiting.erase(it);
        ++delivered;
      }
    }
  }
  switch (failed_kind) {
    case Kind::Result: break;
    case Kind::InvalidArgument: throw std::invalid_argument(failed_text);
    case Kind::LogicError: throw std::logic_error(failed_text);
    case Kind::RuntimeError: throw std::runtime_error(failed_text);
    case Kind::Coded: throw TaskError(failed_code, failed_text);
  }
  // Every worker has been told to stop (kStop) or has ended by now; reap them.
  for (Worker& w : workers) {
    if (w.pid <= 0) continue;
    ::close(w.tasks);
    ::close(w.results);
    w.tasks = w.results = -1;
    int status = 0;
    while (::waitpid(w.pid, &status, 0) < 0 && errno == EINTR) {
    }
    w.pid = -1;
  }
}

}  // namespace superball::symbolic

namespace superball::symbolic {

std::string task_cpu_summary(const std::vector<double>& seconds, const std::function<std::string(std::size_t)>& name) {
  double total = 0;
  std::size_t largest = 0;
  for (std::size_t k = 0; k < seconds.size(); ++k) {
    total += seconds[k];
    if (seconds[k] > seconds[largest]) largest = k;
  }
  char line[160];
  std::snprintf(line, sizeof line, "%zu tasks, %.3g s of CPU", seconds.size(), total);
  std::string out = line;
  if (seconds.empty()) return out;
  std::snprintf(line, sizeof line, "; the largest: %.3g s (%.1f %%), ", seconds[largest], total > 0 ? 100 * seconds[largest] / total : 0.0);
  return out + line + name(largest);
}

namespace {

/// The free clusters of case \p closed (the fixed obstacle's excluded), and its open contacts.
std::pair<int, int> free_and_open(const Deriver& deriver, const ContactSet& closed) {
  const int n = deriver.symbols().bodies(), fixed = deriver.symbols().obstacle() == Obstacle::Infinite ? 1 : 0;
  int open = 0;
  for (int c = 0; c + 1 < n; ++c) open += closed.closed(c) ? 0 : 1;
  return {open + 1 - fixed, open};
}

}  // namespace

bool split_case(const Deriver& deriver, const ContactSet& closed) {
  const auto [free, open] = free_and_open(deriver, closed);
  return open >= deriver.symbols().bodies() - 2 && free >= 4;
}

int prepare_parts(const Deriver& deriver, const ContactSet& closed) {
  const int free = free_and_open(deriver, closed).first;
  return free >= 5 ? free - 2 : 1;
}

std::vector<PrepareTask> prepare_tasks(const Deriver& deriver, const std::vector<ContactSet>& cases, const std::vector<std::size_t>& which) {
  std::vector<PrepareTask> tasks;
  for (std::size_t k : which)
    for (int p = 0, parts = prepare_parts(deriver, cases.at(k)); p < parts; ++p) tasks.push_back({k, p, parts});
  return tasks;
}

std::vector<std::size_t> prepare_todo(const Deriver& deriver, const std::vector<ContactSet>& cases, const std::vector<std::size_t>& todo, int jobs,
                                      std::vector<std::string>& prepared, const Workers::Interrupt& interrupted,
                                      const std::function<void(std::size_t, std::size_t)>& progress, std::vector<double>* cpu) {
  prepared.resize(cases.size());
  std::vector<std::size_t> which;
  if (jobs >= 2)
    for (std::size_t k : todo)
      if (split_case(deriver, cases.at(k))) which.push_back(k);
  if (cpu) cpu->clear();
  if (which.empty()) return which;
  const std::vector<PrepareTask> tasks = prepare_tasks(deriver, cases, which);
  Workers workers(tasks.size(), jobs, [&](std::size_t j) { return deriver.prepare(cases[tasks[j].case_index], tasks[j].part, tasks[j].parts); });
  if (progress) progress(0, which.size());
  std::vector<std::string> pieces;  // the parts of the case delivered last, in order (Workers delivers in task order)
  std::size_t done = 0;
  workers.run(
      [&](std::size_t j, std::string&& text) {
        pieces.push_back(std::move(text));
        if (tasks[j].part + 1 < tasks[j].parts) return;
        prepared[tasks[j].case_index] = pieces.size() == 1 ? std::move(pieces.front()) : Deriver::join_prepared(pieces);
        pieces.clear();
        if (progress) progress(++done, which.size());
      },
      interrupted);
  if (cpu) *cpu = workers.task_cpu_seconds();
  return which;
}

void derive_cases(const Deriver& deriver, const std::vector<ContactSet>& cases,
                  const std::function<std::string(std::size_t, const Derivation&)>& write, const Workers::Deliver& deliver, const DeriveRun& run) {
  std::vector<std::size_t> all(cases.size());
  for (std::size_t k = 0; k < all.size(); ++k) all[k] = k;
  std::vector<std::string> prepared;
  prepare_todo(deriver, cases, all, run.jobs, prepared, run.interrupted);
  Workers workers(cases.size(), run.jobs, [&](std::size_t k) { return write(k, deriver.derive(cases[k], prepared[k])); });
  if (run.progress) run.progress(0, cases.size());
  workers.run(
      [&](std::size_t k, std::string&& text) {
        deliver(k, std::move(text));
        if (run.progress) run.progress(k + 1, cases.size());
      },
      run.interrupted);
}

}  // namespace superball::symbolic
