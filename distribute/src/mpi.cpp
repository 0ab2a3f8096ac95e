// The MPI runner of the task lists (superball/distribute/distribute.hpp), built with
// SUPERBALL_WITH_MPI.  Rank 0 serves the other ranks on a thread of its own
// (the only thread of the process that calls MPI after MPI_Init_thread,
// MPI_THREAD_SERIALIZED) while its main thread computes tasks too and writes
// the output; only text crosses ranks.
#include <mpi.h>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "detail.hpp"
#include "superball/cases/error.hpp"

namespace superball::distribute {
namespace {

bool started = false;
int rank_ = 0, size_ = 1;
/// Rank 0 left a run while other ranks still waited for it (its serving
/// thread failed): they cannot be told to stop, so stop_mpi() aborts the job.
bool abandoned = false;
/// A copy of MPI_COMM_WORLD for the end of the job alone (stop_mpi()), so
/// that its message cannot be taken for one of a run's.
MPI_Comm ending = MPI_COMM_NULL;

constexpr int kTagTask = 1, kTagResult = 2;
constexpr std::uint64_t kStop = ~std::uint64_t{0};

/// What a rank sends back for one task: the kind, then the text.
enum class Kind : std::uint8_t { Result = 0, InvalidArgument = 1, LogicError = 2, RuntimeError = 3 };

/// The line a worker rank writes when a signal kills it, made before each
/// task so that the handler only writes it (async-signal-safe).
char death_line[256];
std::size_t death_length = 0;

extern "C" void report_death(int signal) {
  if (death_length) {
    ssize_t unused = ::write(STDERR_FILENO, death_line, death_length);
    (void)unused;
  }
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}

/// Waits for the request \p r without spinning: MPI libraries poll a core
/// while they wait, which on a shared node takes it from the ranks that
/// compute (rank 0's own tasks, other jobs); a task lasts far longer than
/// the millisecond this adds.
void wait_gently(MPI_Request& r) {
  int done = 0;
  for (int pause = 50;; pause = std::min(pause * 2, 2000)) {
    MPI_Test(&r, &done, MPI_STATUS_IGNORE);
    if (done) return;
    std::this_thread::sleep_for(std::chrono::microseconds(pause));
  }
}

/// MPI_Probe without spinning (see wait_gently()).
void probe_gently(int tag, MPI_Status& status) {
  int found = 0;
  for (int pause = 50;; pause = std::min(pause * 2, 2000)) {
    MPI_Iprobe(MPI_ANY_SOURCE, tag, MPI_COMM_WORLD, &found, &status);
    if (found) return;
    std::this_thread::sleep_for(std::chrono::microseconds(pause));
  }
}

}  // namespace

bool built_with_mpi() { return true; }

void start_mpi(int* argc, char*** argv) {
  // Only under a launcher: a plain run does not start MPI (a singleton MPI_Init may start daemons).
  const bool launched = std::getenv("OMPI_COMM_WORLD_SIZE") || std::getenv("PMI_SIZE") || std::getenv("PMIX_RANK") || std::getenv("PMI_RANK");
  if (!launched) return;
  int provided = 0;
  if (MPI_Init_thread(argc, argv, MPI_THREAD_SERIALIZED, &provided) != MPI_SUCCESS) return;
  started = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  if (size_ > 1) MPI_Comm_dup(MPI_COMM_WORLD, &ending);
  if (size_ > 1 && provided < MPI_THREAD_SERIALIZED) {
    if (rank_ == 0) std::fputs("superball: this MPI library gives no thread support (MPI_THREAD_SERIALIZED): rank 0 will not compute tasks\n", stderr);
  }
}

void stop_mpi(int code) {
  if (!started) return;
  if (abandoned) MPI_Abort(MPI_COMM_WORLD, code ? code : 1);
  // The other ranks wait here, in MPI, until rank 0 has ended its command:
  // when rank 0 must abort the job they are then alive and waiting (Open MPI
  // 4.1's mpirun can hang for good when it aborts ranks that are already in
  // MPI_Finalize), and otherwise everyone finalizes together.
  if (ending != MPI_COMM_NULL) {
    std::uint64_t verdict = static_cast<std::uint64_t>(code);
    MPI_Request r;
    MPI_Ibcast(&verdict, 1, MPI_UINT64_T, 0, ending, &r);
    wait_gently(r);
    MPI_Comm_free(&ending);
  }
  MPI_Finalize();
  started = false;
}

void abandon_ranks() {
  if (started && rank_ == 0 && size_ > 1) abandoned = true;
}

int mpi_rank() { return rank_; }
int mpi_size() { return size_; }

namespace detail {
namespace {

std::string name_task(std::size_t k, std::size_t count) { return "task " + std::to_string(k + 1) + " of " + std::to_string(count); }

/// Runs task \p k into \p text: its result (Kind::Result), or what it threw
/// (the kind of exception, its message in \p text) to be sent or thrown again.
Kind attempt(const Distribution::Task& task, std::size_t k, std::string& text) {
  try {
    text = task(k);
    return Kind::Result;
  } catch (const std::invalid_argument& e) {
    text = without_function_prefix(e.what());
    return Kind::InvalidArgument;
  } catch (const InputError& e) {
    text = e.what();
    return Kind::InvalidArgument;
  } catch (const std::logic_error& e) {
    text = e.what();
    return Kind::LogicError;
  } catch (const std::exception& e) {
    text = e.what();
    return Kind::RuntimeError;
  }
}

/// A rank other than 0: compute what rank 0 hands out until told to stop.
void serve(std::size_t count, const Distribution::Task& task) {
  for (int s : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT, SIGTERM}) std::signal(s, report_death);
  std::string reply;
  reply.push_back(static_cast<char>(Kind::Result));  // "ready": an empty result for no task
  std::uint64_t k = kStop;
  for (;;) {
    std::string message(sizeof k, '\0');
    std::memcpy(message.data(), &k, sizeof k);
    message += reply;
    MPI_Request sent, received;
    MPI_Isend(message.data(), static_cast<int>(message.size()), MPI_BYTE, 0, kTagResult, MPI_COMM_WORLD, &sent);
    wait_gently(sent);
    MPI_Irecv(&k, 1, MPI_UINT64_T, 0, kTagTask, MPI_COMM_WORLD, &received);
    wait_gently(received);
    if (k == kStop) break;
    death_length = static_cast<std::size_t>(std::snprintf(death_line, sizeof death_line, "superball: rank %d died in %s (a signal)\n", rank_,
                                                          name_task(static_cast<std::size_t>(k), count).c_str()));
    std::string text;
    const Kind kind = attempt(task, static_cast<std::size_t>(k), text);
    death_length = 0;
    reply.assign(1, static_cast<char>(kind));
    reply += text;
  }
  for (int s : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT, SIGTERM}) std::signal(s, SIG_DFL);
}

}  // namespace

void run_on_ranks(std::size_t count, const std::vector<std::size_t>& todo, std::map<std::size_t, std::string>& done,
                  const Distribution::Task& task, const std::function<void(std::size_t, const std::string&)>& save,
                  const Distribution::Deliver& deliver) {
  if (rank_ != 0) {
    serve(count, task);
    return;
  }
  // Shared by the serving thread and this one, under `lock`.
  std::mutex lock;
  std::condition_variable changed;
  std::size_t next = 0;             // the next position in todo to hand out
  std::size_t failed = count;       // the smallest task that failed
  Kind failed_kind = Kind::Result;
  std::string failed_text;
  bool stopping = false;            // this thread failed (an output error): hand out nothing more
  std::exception_ptr server_error;
  int serving = size_ - 1;          // ranks not yet told to stop
  auto fail = [&](std::size_t k, Kind kind, std::string text) {  // under lock
    if (k >= failed) return;
    failed = k, failed_kind = kind, failed_text = std::move(text);
  };
  auto take = [&]() -> std::uint64_t {  // under lock: the next task to hand out, or kStop
    if (stopping || next >= todo.size() || todo[next] >= failed) return kStop;
    return todo[next++];
  };
  std::thread server([&] {
    try {
      while (serving > 0) {
        MPI_Status status;
        probe_gently(kTagResult, status);
        int size = 0;
        MPI_Get_count(&status, MPI_BYTE, &size);
        std::string message(static_cast<std::size_t>(size), '\0');
        MPI_Recv(message.data(), size, MPI_BYTE, status.MPI_SOURCE, kTagResult, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        std::uint64_t k = kStop;
        std::memcpy(&k, message.data(), sizeof k);
        const Kind kind = static_cast<Kind>(message[sizeof k]);
        std::string text = message.substr(sizeof k + 1);
        std::uint64_t give = kStop;
        {
          std::unique_lock<std::mutex> guard(lock);
          if (k != kStop) {
            if (kind == Kind::Result) {
              guard.unlock();
              save(static_cast<std::size_t>(k), text);  // the checkpoint, as soon as the result is here
              guard.lock();
              done.emplace(static_cast<std::size_t>(k), std::move(text));
            } else {
              fail(static_cast<std::size_t>(k), kind, "rank " + std::to_string(status.MPI_SOURCE) + ", " + name_task(k, count) + ": " + text);
            }
          }
          give = take();
          if (give == kStop) --serving;
        }
        changed.notify_all();
        MPI_Send(&give, 1, MPI_UINT64_T, status.MPI_SOURCE, kTagTask, MPI_COMM_WORLD);
      }
    } catch (...) {
      const std::lock_guard<std::mutex> guard(lock);
      server_error = std::current_exception();
      abandoned = serving > 0;
      serving = 0;
    }
    changed.notify_all();
  });
  // This thread: compute tasks too, and deliver in order as results come.
  std::size_t delivered = 0;
  try {
    for (;;) {
      std::unique_lock<std::mutex> guard(lock);
      // Deliver what is ready, in order (outside the lock).
      for (auto it = done.find(delivered); delivered < failed && it != done.end(); it = done.find(delivered)) {
        std::string text = std::move(it->second);
        done.erase(it);
        const std::size_t k = delivered++;
        guard.unlock();
        deliver(k, std::move(text));
        guard.lock();
      }
      if (delivered >= std::min(count, failed) || server_error) break;
      const std::uint64_t k = take();
      if (k != kStop) {
        guard.unlock();
        std::string text;
        const Kind kind = attempt(task, static_cast<std::size_t>(k), text);
        if (kind == Kind::Result) save(static_cast<std::size_t>(k), text);
        guard.lock();
        if (kind == Kind::Result)
          done.emplace(static_cast<std::size_t>(k), std::move(text));
        else
          fail(static_cast<std::size_t>(k), kind, "rank 0, " + name_task(k, count) + ": " + text);
        continue;
      }
      changed.wait(guard);
    }
  } catch (...) {
    {
      const std::lock_guard<std::mutex> guard(lock);
      stopping = true;
    }
    server.join();
    throw;
  }
  {
    const std::lock_guard<std::mutex> guard(lock);
    stopping = true;  // hand out nothing more; the ranks still computing finish and are told to stop
  }
  server.join();
  if (server_error) std::rethrow_exception(server_error);
  switch (failed_kind) {
    case Kind::Result: break;
    case Kind::InvalidArgument: throw std::invalid_argument(failed_text);
    case Kind::LogicError: throw std::logic_error(failed_text);
    case Kind::RuntimeError: throw std::runtime_error(failed_text);
  }
}

void share(std::vector<std::string>& results, bool failed) {
  if (abandoned) return;  // the ranks still wait for tasks: stop_mpi() aborts the job
  // Rank 0: a flag (1: failed), the number of results, each result's length, then their bytes.
  std::vector<std::uint64_t> sizes;
  if (rank_ == 0) {
    sizes.push_back(failed ? 1 : 0);
    sizes.push_back(results.size());
    for (const std::string& r : results) sizes.push_back(r.size());
  }
  std::uint64_t n = sizes.size();
  // The first message waits without spinning (see wait_gently()) while rank 0
  // finishes its last task; the rest follows at once, blocking (polled in
  // pauses, a long message would crawl: a piece per poll).
  MPI_Request first;
  MPI_Ibcast(&n, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD, &first);
  wait_gently(first);
  sizes.resize(static_cast<std::size_t>(n));
  MPI_Bcast(sizes.data(), static_cast<int>(n), MPI_UINT64_T, 0, MPI_COMM_WORLD);
  if (sizes.at(0) != 0) {
    if (rank_ == 0) return;
    throw std::runtime_error("share(): rank 0 ended the run");  // said by rank 0
  }
  results.resize(static_cast<std::size_t>(sizes.at(1)));
  for (std::size_t k = 0; k < results.size(); ++k) {
    std::string& r = results[k];
    r.resize(static_cast<std::size_t>(sizes.at(k + 2)));
    // In pieces of at most 1 GiB (an MPI count is an int).
    constexpr std::size_t piece = std::size_t{1} << 30;
    for (std::size_t at = 0; at < r.size(); at += piece)
      MPI_Bcast(r.data() + at, static_cast<int>(std::min(piece, r.size() - at)), MPI_BYTE, 0, MPI_COMM_WORLD);
  }
}

}  // namespace detail
}  // namespace superball::distribute
