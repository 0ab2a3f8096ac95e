#pragma once
/// \file workers.hpp
/// Work spread over forked processes, for symbolic work: GiNaC is not
/// thread-safe, so where numeric work uses threads (numeric/parallel.hpp),
/// symbolic work uses worker processes, each a copy of this one made after
/// the shared set-up (the Deriver).  Only text crosses processes.  Shared by
/// the command (`superball derive`) and the Python module (derive_all()).
#include <cstddef>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "superball/symbolic/derivation.hpp"

#include "superball/symbolic/export.hpp"
SUPERBALL_SYMBOLIC_API_BEGIN

namespace superball::symbolic {

/// A run stopped by its `interrupted` hook (Ctrl-C): the workers are
/// stopped and nothing more is delivered.
class Interrupted : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A task's failure that the caller names by a code of its own (the
/// command's "output cannot be written"), carried across processes with its
/// message and thrown again as a TaskError of the same code.
class TaskError : public std::runtime_error {
 public:
  /// A failure of code \p code (the caller's) with \p message.
  TaskError(int code, const std::string& message) : std::runtime_error(message), code_(code) {}
  /// The caller's code given to the constructor.
  int code() const { return code_; }

 private:
  int code_;
};

/// Runs task(0) … task(count − 1) in \p jobs worker processes, handing the
/// tasks out one at a time as workers become free (a long task does not hold
/// up the others), and calls deliver(k, result) here in task order, so the
/// output is the same whatever \p jobs is.  \p jobs <= 0: everything runs in
/// this process, in order, in run(); jobs >= 1: min(jobs, count) workers,
/// even for one task (so that an interrupt stops it at once).
///
/// The workers are forked by the constructor, before anything else starts
/// a thread (make the pool before a progress line's timer).  They ignore
/// SIGINT: Ctrl-C reaches this process, whose `interrupted` hook stops them;
/// on Linux they die with this process however it ends (PR_SET_PDEATHSIG).
/// A task that throws ends the run: no later task is handed out, the tasks
/// before it are finished and delivered, the other workers are stopped, and
/// run() throws the exception again with its message (std::invalid_argument,
/// std::logic_error, TaskError with its code, or std::runtime_error, by what
/// it was).  A worker that dies (a signal) makes run() throw
/// std::runtime_error("worker for task K died: …").  When several tasks
/// fail, the first of them in task order is the one reported, as with
/// \p jobs <= 0, whatever the timing.  deliver() runs in this process only;
/// it may throw (the workers are then stopped before the exception leaves).
class Workers {
 public:
  /// Task k: its result as text (only text crosses processes).
  using Task = std::function<std::string(std::size_t)>;
  /// Takes task k's result, here, in task order.
  using Deliver = std::function<void(std::size_t, std::string&&)>;
  /// Polled between results and at least every kPollInterval; true stops
  /// the run: the workers are killed and run() throws Interrupted.  In this
  /// process (\p jobs <= 0) it is polled between tasks only.
  using Interrupt = std::function<bool()>;
  /// Forks min(\p jobs, \p count) workers for the tasks 0 … \p count − 1 of \p task (none when \p jobs <= 0).
  Workers(std::size_t count, int jobs, Task task);
  Workers(const Workers&) = delete;
  Workers& operator=(const Workers&) = delete;
  /// Stops every worker still running.
  ~Workers();
  /// Runs the tasks (once) and delivers their results in order.
  void run(const Deliver& deliver, const Interrupt& interrupted = {});
  /// After run(): the CPU seconds each task took in the process that ran it
  /// (0 for a task not run), to see how evenly the work is split.
  const std::vector<double>& task_cpu_seconds() const { return cpu_; }
  /// One forked process and its two pipes (workers.cpp).
  struct Worker;

 private:
  std::size_t count_;
  Task task_;
  std::vector<Worker> workers_;
  std::vector<double> cpu_;
};

/// One line on how evenly \p seconds (Workers::task_cpu_seconds()) split
/// the work: "64 tasks, 14.6 s of CPU; the largest: 4.89 s (33.4 %), {}",
/// naming the largest task by \p name.
std::string task_cpu_summary(const std::vector<double>& seconds, const std::function<std::string(std::size_t)>& name);

/// How often a run with an `interrupted` hook polls it while workers compute.
inline constexpr int kPollIntervalMs = 100;

/// How derive_cases() runs.
struct DeriveRun {
  int jobs = 1;  ///< worker processes (Workers); 0: every case in this process, in order
  /// Called here after each case is delivered, with the cases delivered so far and their number.
  std::function<void(std::size_t done, std::size_t total)> progress;
  Workers::Interrupt interrupted;  ///< see Workers::Interrupt
};

/// Whether derive_cases() splits case \p closed in two tasks (its
/// Deriver::prepare() ahead, then the rest) when several workers run: the
/// cases of the most free clusters (at most one contact closed), four or
/// more, which take most of a run's time (at 7 bodies near2 with couplings,
/// `{}` alone is a third of it).
bool split_case(const Deriver& deriver, const ContactSet& closed);

/// The parts of the first stage of a case split_case() takes: its
/// Deriver::prepare(closed, k, parts), k = 0 … parts − 1, one task each.
/// One, but free clusters − 2 for the cases of five or more (the checks of
/// their solution and the coprimality proofs are most of that stage: at 7
/// bodies near2 with couplings, `{}`'s in one task would be a tenth of the
/// run's CPU, in four parts about 4 % each).
int prepare_parts(const Deriver& deriver, const ContactSet& closed);

/// A task of the first stage: one part of one case's Deriver::prepare().
struct PrepareTask {
  std::size_t case_index = 0;  ///< the case: its index in the run's cases
  int part = 0;                ///< the part, 0 … parts − 1
  int parts = 1;               ///< the case's prepare_parts()
};
/// The first stage's tasks for the cases \p which (indices into \p cases,
/// as prepare_todo() returns them), in its order: each case's
/// prepare_parts() parts in turn.
std::vector<PrepareTask> prepare_tasks(const Deriver& deriver, const std::vector<ContactSet>& cases, const std::vector<std::size_t>& which);

/// The first stage of a run over \p jobs worker processes (none below 2),
/// shared by the command and the Python module: of the cases \p todo
/// (indices into \p cases, those a run still has to derive), those that
/// split_case() takes get their Deriver::prepare() done, each in its own
/// worker process (forked here and ended before this returns), and its text
/// put at prepared[k], k the case's index in \p cases (\p prepared is
/// resized to cases.size(); the other entries are left as they are, empty
/// for a new vector).  The worker processes of the second stage, forked
/// after this returns, inherit \p prepared: their task for case k is
/// Deriver::derive(cases[k], prepared[k]).  Returns the indices prepared, in
/// increasing order (empty with fewer than 2 jobs).  \p progress (when
/// given) is called here with (0, number prepared) once this stage's
/// workers are forked, and again after each case prepared (never when none
/// is): a progress line may start its thread at the first call, and must
/// stop it when this returns, before the next fork.  \p cpu (when given)
/// receives the CPU seconds of each prepare task: the prepare_parts() of
/// each case, in the order returned.
/// Errors and interrupts as Workers::run().
std::vector<std::size_t> prepare_todo(const Deriver& deriver, const std::vector<ContactSet>& cases, const std::vector<std::size_t>& todo, int jobs,
                                      std::vector<std::string>& prepared, const Workers::Interrupt& interrupted = {},
                                      const std::function<void(std::size_t done, std::size_t total)>& progress = {},
                                      std::vector<double>* cpu = nullptr);

/// Derives \p cases of \p deriver over run.jobs worker processes and calls
/// deliver(k, write(k, derivation of case k)) here in case order (the same
/// whatever the number of workers; the largest cases in two stages,
/// prepare_todo()).  \p write runs in the worker: it turns a
/// Derivation into the text that crosses back (a report, JSON).  Errors and
/// interrupts as Workers::run().
void derive_cases(const Deriver& deriver, const std::vector<ContactSet>& cases,
                  const std::function<std::string(std::size_t, const Derivation&)>& write, const Workers::Deliver& deliver, const DeriveRun& run);

}  // namespace superball::symbolic

SUPERBALL_SYMBOLIC_API_END
