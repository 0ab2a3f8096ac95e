#pragma once
/// \file parallel.hpp
/// Independent tasks on several threads, with per-thread state and results
/// in task order: the one mechanism by which sweeps (and anything else that
/// solves many scenes) use several cores.
///
/// CLN (and GiNaC) objects are not thread-safe: their reference counts are
/// not atomic, so two threads must never hold the same object, not even
/// through a copy.  parallel_map() gives each thread its own state, built on
/// that thread; a task must read only plain data shared with other tasks
/// (a Scene, strings, numbers), never a CLN object another thread can reach.

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <iterator>
#include <optional>
#include <stdexcept>
#include <string>
#include <system_error>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>
#include "superball/numeric/export.hpp"
SUPERBALL_NUMERIC_API_BEGIN

namespace superball::numeric {

/// Where a long computation's tasks run, to spread it over several processes
/// (`mpirun -n P superball …`): called with a number of tasks T and a
/// function computing task t as plain text, it returns the T texts in task
/// order, in every process that calls it.  Empty: the caller runs the tasks
/// itself, on its threads.  Only text crosses processes, so a task's result
/// must read back exactly (MapSettings::runner, verify's VerifyOptions::runner).
using TaskRunner =
    std::function<std::vector<std::string>(std::size_t, const std::function<std::string(std::size_t)>&)>;

/// The results of \p count items computed by compute(first, size), which
/// returns the results of items first … first + size − 1 (a std::vector<R>):
/// with no \p runner, in one call here; else in ⌈count / per⌉ tasks of \p per
/// consecutive items run by \p runner, each task's results sent as text
/// (write(results) → std::string) and read back (read(text) →
/// std::vector<R>), then joined in task order.  \p function names the caller
/// in the std::logic_error thrown when the runner returns another number of
/// texts than of tasks.
template <class R, class Compute, class Write, class Read>
std::vector<R> in_tasks(const TaskRunner& runner, std::size_t count, std::size_t per, const char* function, const Compute& compute,
                        const Write& write, const Read& read) {
  if (!runner || count == 0) return compute(std::size_t{0}, count);
  per = std::max<std::size_t>(per, 1);
  const std::size_t tasks = (count + per - 1) / per;
  const std::vector<std::string> texts = runner(tasks, [&](std::size_t t) { return write(compute(t * per, std::min(per, count - t * per))); });
  if (texts.size() != tasks)
    throw std::logic_error(std::string(function) + ": the runner returned " + std::to_string(texts.size()) + " results of " + std::to_string(tasks) + " tasks");
  std::vector<R> all;
  for (const std::string& text : texts) {
    std::vector<R> some = read(text);
    all.insert(all.end(), std::make_move_iterator(some.begin()), std::make_move_iterator(some.end()));
  }
  return all;
}

/// The most worker threads a caller may ask for.
inline constexpr int max_threads = 1024;

/// The rule of every `threads` setting (`--threads`, Python's threads=),
/// and of derive's worker processes (`--jobs`, jobs=, \p name "jobs"):
/// throws std::invalid_argument("check_threads(): NAME must be a whole
/// number from 0 (all cores) to 1024, got T") unless 0 <= \p threads <= max_threads
/// (a long long: a front's integer wider than int is refused, not cut).
inline void check_threads(long long threads, const char* name = "threads") {
  if (threads < 0 || threads > max_threads)
    throw std::invalid_argument(std::string("check_threads(): ") + name + " must be a whole number from 0 (all cores) to " +
                                std::to_string(max_threads) + ", got " + std::to_string(threads));
}

/// The number of threads for a request: \p requested when it is positive,
/// else std::thread::hardware_concurrency() (all cores; 1 when unknown).
inline int thread_count(int requested) {
  if (requested > 0) return requested;
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

/// r[i] = task(state, i) for every i in [0, count), on thread_count(threads)
/// threads (never more than count; with one, on the calling thread).
///
/// - Each thread calls make_state() once, on that thread, before its first
///   task, and destroys the state before it ends; task gets it as `State&`.
/// - Tasks are handed out in increasing i; the results come back in task
///   order, whatever the number of threads, so a task whose result depends
///   only on i gives the same results on any number of threads.
/// - When tasks throw, the exception of the smallest such i is rethrown here
///   once every thread has stopped (tasks above it may not run), as in a
///   loop on one thread.  The results are handed over only after every
///   thread has ended, so they may share CLN objects with the states.
template <class MakeState, class Task>
auto parallel_map(std::size_t count, int threads, MakeState make_state, Task task) {
  using State = std::decay_t<decltype(make_state())>;
  using Result = std::decay_t<decltype(task(std::declval<State&>(), std::size_t{}))>;
  std::vector<std::optional<Result>> slots(count);
  std::atomic<std::size_t> next{0};
  std::atomic<std::size_t> failed_at{count};  // smallest index whose task threw
  std::exception_ptr error;
  std::mutex error_mutex;
  auto work = [&] {
    std::optional<State> state;
    for (std::size_t i; (i = next.fetch_add(1)) < failed_at.load();) {
      try {
        if (!state) state.emplace(make_state());
        slots[i].emplace(task(*state, i));
      } catch (...) {
        const std::lock_guard<std::mutex> lock(error_mutex);
        if (i < failed_at.load()) failed_at = i, error = std::current_exception();
      }
    }
  };
  const auto n = std::min(count, static_cast<std::size_t>(thread_count(threads)));
  if (n <= 1) {
    work();
  } else {
    std::vector<std::thread> pool;
    pool.reserve(n - 1);
    try {
      for (std::size_t t = 1; t < n; ++t) pool.emplace_back(work);
    } catch (const std::system_error&) {  // no more threads: run with those started
    }
    work();
    for (auto& t : pool) t.join();
  }
  if (error) std::rethrow_exception(error);
  std::vector<Result> results;
  results.reserve(count);
  for (auto& r : slots) results.push_back(std::move(*r));
  return results;
}

/// task(i) for i = 0 … count − 1 on \p threads threads (0: all cores), and
/// deliver(i, result) for each in increasing i, on the calling thread, as
/// soon as the results before it are delivered: for tasks whose results are
/// written out in order (a sweep's blocks of rows).  At most 2 × threads
/// results wait to be delivered, so the memory held does not grow with
/// \p count.  A task runs on a thread of its own: it must follow this file's
/// rule on CLN objects.  A task or a delivery that throws ends the run: the
/// results before the first task that threw are delivered, none after it,
/// every thread is joined, and the exception is thrown again here.
template <class Task, class Deliver>
void in_order(std::size_t count, int threads, const Task& task, const Deliver& deliver) {
  using Result = std::decay_t<decltype(task(std::size_t{}))>;
  const auto n = std::min(count, static_cast<std::size_t>(thread_count(threads)));
  const std::size_t window = 2 * n;
  std::mutex m;
  std::condition_variable changed;
  std::vector<std::optional<Result>> slots(window);  // result i in slot i mod window
  std::size_t next = 0, delivered = 0, failed_at = count;
  std::exception_ptr error;
  auto work = [&] {
    std::unique_lock<std::mutex> lock(m);
    for (;;) {
      changed.wait(lock, [&] { return next >= failed_at || next < delivered + window; });
      if (next >= failed_at) return;
      const std::size_t i = next++;
      lock.unlock();
      std::optional<Result> r;
      std::exception_ptr e;
      try {
        r.emplace(task(i));
      } catch (...) {
        e = std::current_exception();
      }
      lock.lock();
      if (e) {
        if (i < failed_at) failed_at = i, error = e;
      } else {
        slots[i % window] = std::move(r);
      }
      changed.notify_all();
    }
  };
  std::vector<std::thread> pool;
  if (n > 1) {
    pool.reserve(n);
    try {
      for (std::size_t t = 0; t < n; ++t) pool.emplace_back(work);
    } catch (const std::system_error&) {  // no more threads: run with those started
    }
  }
  auto stop = [&](std::exception_ptr e) {
    {
      const std::lock_guard<std::mutex> hold(m);
      failed_at = std::min(failed_at, delivered);
      if (e) error = e;
    }
    changed.notify_all();
    for (auto& t : pool) t.join();
    if (error) std::rethrow_exception(error);
  };
  if (pool.empty()) {  // one thread, or none to be had: here, one after the other
    for (std::size_t i = 0; i < count; ++i) deliver(i, task(i));
    return;
  }
  try {
    for (std::size_t i = 0; i < count; ++i) {
      std::optional<Result> r;
      {
        std::unique_lock<std::mutex> lock(m);
        changed.wait(lock, [&] { return slots[i % window].has_value() || i >= failed_at; });
        if (i >= failed_at) break;
        r = std::move(slots[i % window]);
        slots[i % window].reset();
      }
      deliver(i, std::move(*r));
      {
        const std::lock_guard<std::mutex> hold(m);
        delivered = i + 1;
      }
      changed.notify_all();
    }
  } catch (...) {
    stop(std::current_exception());
    return;
  }
  stop(nullptr);
}

}  // namespace superball::numeric

SUPERBALL_NUMERIC_API_END
