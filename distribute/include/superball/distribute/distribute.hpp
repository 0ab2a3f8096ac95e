#pragma once
/// \file distribute.hpp
/// The one way a long computation's work leaves this process: a list of
/// deterministic tasks 0 … T−1, each giving plain text, delivered in task
/// order.  Where the tasks run is the runner's business:
///  - here (the caller's local runner: threads, derive's worker processes,
///    or one after the other);
///  - over the ranks of an MPI job (`mpirun -n P superball …`, `srun
///    superball …`; built with -DSUPERBALL_WITH_MPI=ON): rank 0 hands the
///    tasks out one at a time to whichever rank is free (itself included),
///    gathers the results and alone writes the output; only text crosses
///    ranks;
///  - one shard of N (`--shard I/N`): the tasks k with k mod N = I − 1,
///    written as a part file that names the run; `superball merge PART…`
///    gives the output of the whole run;
///  - with a checkpoint folder (`--checkpoint DIR`, Python's checkpoint=):
///    each finished task is written to DIR atomically; the same run started
///    again computes only the tasks not there.
/// The output is the same bytes whatever the runner, the number of ranks,
/// threads or shards: it is written from the results in task order.
///
/// A run is named by its identity (RunIdentity): the command and the
/// arguments that define its output, as data; the fronts (the `superball`
/// command, the Python module) build it from what they were given.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace superball::distribute {

/// A file of the run (a task file, the checkpoint's run file, a part file)
/// that cannot be written: "PATH: the system's reason".
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// What defines a run's output, as data: the part files and the checkpoint
/// folder store it, and its name (run_name()) tells one run from another.
struct RunIdentity {
  std::string command;                 ///< "sweep", "derive", …
  std::vector<std::string> arguments;  ///< every argument that changes the output, as text ("--NAME=VALUE", positionals first)
  /// The content of the file argument i names (a scene), by i: hashed into
  /// the run's name, not stored (a file changed between two shards makes
  /// another run).
  std::map<std::size_t, std::string> contents;
};

/// The identity of a run given by typed values (the Python module's): the
/// \p command, then each of \p options as "--NAME=VALUE" in the order of
/// the names, then each of \p inputs as "--NAME", whose content (a scene's
/// canonical text, the exact values of a sweep) is hashed into the run's
/// name and not stored.  Two calls with the same values are one run.
RunIdentity typed_identity(const std::string& command, const std::map<std::string, std::string>& options,
                           const std::map<std::string, std::string>& inputs);

/// The name of the run \p id: 16 hex digits of a hash of the superball
/// version, the command, the arguments and the contents of the files they name.
std::string run_name(const RunIdentity& id);

/// How a run is spread and kept, and where its messages go.
struct Options {
  std::string shard;       ///< "I/N", empty: the whole run
  std::string part;        ///< the part file of a shard; empty: superball-RUN-I-of-N.part
  std::string checkpoint;  ///< a folder; empty: none
  /// Writes a part file whole (default: atomically, beside it, then renamed).
  std::function<void(const std::string& path, const std::string& text)> write_part;
  /// Told of a task file that failed its checks (removed, its task computed
  /// again), one line without the "superball: " prefix; default: nothing.
  std::function<void(const std::string& line)> warn;
  /// Told how many tasks the checkpoint held already; default: nothing.
  std::function<void(const std::string& line)> note;
};

/// The results of a whole run read from its part files (read_parts()): the
/// command, run again from the parts' arguments, takes its results from here
/// instead of computing them.
struct MergedRun {
  std::string run;                        ///< the run's name (a hash of its identity)
  std::vector<std::string> arguments;     ///< the run's arguments as the parts hold them (the command first)
  std::size_t tasks = 0;                  ///< T
  std::map<std::size_t, std::string> results;
  std::map<std::size_t, std::string> files;  ///< the part file of each task (for messages)
};

/// The most bytes a task's result may have (Distribution's max_task_bytes
/// is at most this): a part file's or checkpoint's record claiming more is
/// refused before anything is read or allocated for it.
inline constexpr std::uint64_t kMaxTaskBytes = std::uint64_t{1} << 30;

/// Set by `superball merge` before it runs the command again; null otherwise.
extern const MergedRun* merged_run;

/// Reads the part files \p paths as data (every record's checksum checked,
/// nothing after `end`), checking that they are every part of one run, each
/// once; \p check(arguments, where) sees each part's stored arguments first
/// and throws std::invalid_argument("WHERE: …") when a front will not run
/// them.  Errors: std::invalid_argument, one line naming the part.
MergedRun read_parts(const std::vector<std::string>& paths,
                     const std::function<void(const std::vector<std::string>& arguments, const std::string& where)>& check);

/// A task list and how this process takes part in running it.
class Distribution {
 public:
  /// Task k's result, as text.
  using Task = std::function<std::string(std::size_t)>;
  /// Takes task k's result.
  using Deliver = std::function<void(std::size_t, std::string&&)>;
  /// Runs the tasks of \p todo (task indices, increasing) here and calls
  /// deliver(j, result) for todo[j] in that order.
  using Local = std::function<void(const std::vector<std::size_t>& todo, const Task& task, const Deliver& deliver)>;

  /// The run \p id with \p count tasks, each giving at most \p max_task_bytes
  /// bytes (at most kMaxTaskBytes).  Reads the checkpoint folder (refusing
  /// one of another run; a task file that fails its checks is told to
  /// options.warn, removed and computed again), checks the shard, and under
  /// MPI learns this rank.  In a merge, checks that the parts' arguments are
  /// exactly this run's and their results within the bound.  Throws
  /// std::invalid_argument on bad options, OutputError when the folder
  /// cannot be made or written.
  Distribution(const RunIdentity& id, const Options& options, std::size_t count, std::uint64_t max_task_bytes = kMaxTaskBytes);
  Distribution(const Distribution&) = delete;
  Distribution& operator=(const Distribution&) = delete;
  ~Distribution();

  /// Whether this process writes the output: false in a shard run (it
  /// writes a part file) and on MPI ranks other than 0.
  bool writes_output() const;
  /// Whether the tasks run in this process alone with the local runner (not
  /// MPI, not a merge).
  bool local() const;
  /// The tasks this process computes with the local runner (when local()):
  /// those of its shard not found in the checkpoint folder; under MPI, the
  /// tasks of the run not in the checkpoint (on every rank).
  const std::vector<std::size_t>& todo() const;

  /// Where task \p k's result came from, for a message about it: "merge:
  /// PART: task K", "--checkpoint DIR: task-0000000K" or "task K".  A
  /// caller that reads a result back and finds it damaged names it so.
  std::string origin(std::size_t k) const;
  /// Whether task \p k's result was read from a file (a task file of the
  /// checkpoint folder, a part in a merge) rather than computed in this run:
  /// such a result is checked by its reader before it is believed (its
  /// record's checksum says only that the file is whole, not what wrote it).
  bool read_back(std::size_t k) const;

  /// \p task, which also writes its result to the checkpoint folder (if
  /// any) as soon as it has it: for a local runner made before run() (derive's
  /// worker processes, forked with it).  run() gives the local runner this.
  Task keeping(const Task& task) const;

  /// Runs the tasks and, where writes_output(), calls deliver(k, result) for
  /// every k in 0 … count−1 in order (in a shard run, writes the part file).
  /// \p local runs todo() here (default: one after the other).  A task that
  /// throws ends the run: the tasks before it are delivered, none after it,
  /// and the exception is thrown again here (under MPI its message names the
  /// rank and the task: "rank 2, task 7 of 16: …").
  void run(const Task& task, const Deliver& deliver, const Local& local = {});

  /// Runs the tasks as run() does (one after the other here, or over the
  /// ranks; the checkpoint kept and read) and returns every result in task
  /// order, in every process: for a caller that goes on from all of them
  /// (map bisects between the grid points the tasks solved).  Under MPI,
  /// rank 0 then sends the results to every rank, as run_everywhere() does;
  /// every rank must call it.  std::logic_error in a shard run.
  std::vector<std::string> run_everywhere(const Task& task);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Tasks 0 … count−1 whose results every process needs (the stages of one
/// verification spread over the ranks, `verify --case`): under MPI, handed
/// out to the ranks as Distribution::run() does (rank 0 computing too), then
/// every result sent from rank 0 to every rank; otherwise run here, one after
/// the other.  Returns the results in task order, in every process.  A task
/// that throws: as in Distribution::run(), on rank 0; the other ranks throw
/// a message that is not printed.  Every rank must call it, in the same order.
std::vector<std::string> run_everywhere(std::size_t count, const Distribution::Task& task);

/// Whether this superball was built with MPI (SUPERBALL_WITH_MPI).
bool built_with_mpi();
/// When an MPI launcher started this process as one of several ranks (its
/// environment: OMPI_COMM_WORLD_SIZE, PMI_SIZE, or Slurm's
/// SLURM_STEP_NUM_TASKS greater than 1): that variable as "NAME=VALUE";
/// otherwise "".  The command refuses to run on ranks when built without MPI.
std::string launched_on_ranks();
/// Whether the launcher's rank variable (OMPI_COMM_WORLD_RANK, PMI_RANK,
/// PMIX_RANK, SLURM_PROCID) is 0 or unset: the rank that says why it refuses.
bool first_launched_rank();

/// MPI (built with SUPERBALL_WITH_MPI): starts MPI when this process was
/// launched by an MPI launcher (mpirun, mpiexec, srun), from main().
void start_mpi(int* argc, char*** argv);
/// Ends MPI, if started; from main() before it returns \p code.  When rank
/// 0 had to leave ranks waiting for tasks (its serving thread failed, e.g.
/// the checkpoint could not be written), aborts the job with \p code
/// instead: they could not be told to stop.
void stop_mpi(int code);
/// Rank 0 is ending the command with an error (main(), when the command
/// throws): other ranks may still wait for it (a task, the results), and only
/// rank 0 said why, so stop_mpi() aborts the job with the exit code instead
/// of waiting for them.  No effect on other ranks or without MPI.
void abandon_ranks();
/// This process's rank (0 without MPI).
int mpi_rank();
/// The number of ranks (1 without MPI).
int mpi_size();

}  // namespace superball::distribute
