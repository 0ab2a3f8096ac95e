#pragma once
// Work spread over forked processes, for the symbolic commands: GiNaC is not
// thread-safe, so where numeric work uses threads (numeric/parallel.hpp),
// symbolic work uses worker processes, each a copy of this one made after
// the shared set-up (the Deriver).  Only text crosses processes.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace superball::cli {

/// Runs task(0) … task(count − 1) in \p jobs worker processes, handing the
/// tasks out one at a time as workers become free (a long task does not hold
/// up the others), and calls deliver(k, result) here in task order, so the
/// output is the same whatever \p jobs is.  \p jobs <= 1 or a single task:
/// everything runs in this process, in order, in run().
///
/// The workers are forked by the constructor, before anything else starts
/// a thread (make the pool before a StepProgress).  A task that throws ends
/// the run: no later task is handed out, the tasks before it are finished
/// and delivered, the other workers are stopped, and run() throws the
/// exception again with its message (std::invalid_argument,
/// std::logic_error, OutputError or std::runtime_error, by what it was).  A worker that
/// dies (a signal) makes run() throw std::runtime_error("worker for task K
/// died: …").  When several tasks fail, the first of them in task order is
/// the one reported, as with \p jobs <= 1, whatever the timing.
/// deliver() runs in this process only; it may throw (the workers are then
/// stopped before the exception leaves).
class Workers {
 public:
  using Task = std::function<std::string(std::size_t)>;
  using Deliver = std::function<void(std::size_t, std::string&&)>;
  Workers(std::size_t count, int jobs, Task task);
  Workers(const Workers&) = delete;
  Workers& operator=(const Workers&) = delete;
  /// Stops every worker still running.
  ~Workers();
  /// Runs the tasks (once) and delivers their results in order.
  void run(const Deliver& deliver);
  /// One forked process and its two pipes (workers.cpp).
  struct Worker;

 private:
  std::size_t count_;
  Task task_;
  std::vector<Worker> workers_;
};

}  // namespace superball::cli
