#pragma once
/// \file distribute.hpp
/// The one way a long command's work leaves this process: a list of
/// deterministic tasks 0 … T−1, each giving plain text, written by the
/// command in task order.  Where the tasks run is the runner's business:
///  - here (the command's local runner: threads, derive's worker processes,
///    or one after the other);
///  - over the ranks of an MPI job (`mpirun -n P superball …`, `srun
///    superball …`; built with -DSUPERBALL_WITH_MPI=ON): rank 0 hands the
///    tasks out one at a time to whichever rank is free (itself included),
///    gathers the results and alone writes the output; only text crosses
///    ranks;
///  - one shard of N (`--shard I/N`): the tasks k with k mod N = I − 1,
///    written as a part file that names the run; `superball merge PART…`
///    gives the output of the whole run;
///  - with `--checkpoint DIR`: each finished task is written to DIR
///    atomically; the same command started again computes only the tasks
///    not there.
/// The output is the same bytes whatever the runner, the number of ranks,
/// threads or shards: the command writes it from the results in task order.

#include <CLI/CLI.hpp>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"

namespace superball::cli {

/// The options --shard, --part and --checkpoint of a command whose work is
/// a task list.
struct DistributeOptions {
  std::string shard;       ///< "I/N", empty: the whole run
  std::string part;        ///< the part file of a shard; empty: superball-RUN-I-of-N.part
  std::string checkpoint;  ///< a folder; empty: none
};

/// Register --shard, --part and --checkpoint on \p cmd; \p noun names a task
/// in the help ("case", "block of 4096 values").  When not \p shards (a
/// command whose later tasks need all the earlier results: map), --shard and
/// --part are hidden and the command refuses them, saying why.
void add_distribute_options(CLI::App* cmd, DistributeOptions& o, const std::string& noun, bool shards = true);

/// The results of a whole run read from its part files by `superball merge`
/// (cli/merge.cpp): the command, parsed again from the parts' arguments,
/// takes its results from here instead of computing them.
struct MergedRun {
  std::string run;                        ///< the run's name (a hash of its identity)
  std::vector<std::string> arguments;     ///< the run's arguments as the parts hold them
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

/// The arguments that define a run of \p cmd (the subcommand as parsed): its
/// name, then every option given except those that do not change the output
/// (--shard, --part, --checkpoint, --output, --out, --plot, --threads,
/// --jobs, --quiet, --progress), as "--name=value", positionals first.
/// `superball merge` runs the command again from these, refusing parts whose
/// arguments are not exactly these (nothing in a part says where to write).
std::vector<std::string> run_arguments(const CLI::App& cmd);

/// The name of a run: 16 hex digits of a hash of the superball version, the
/// run's arguments and the content of every argument that names a file (a
/// scene changed between two shards makes another run).
std::string run_name(const std::vector<std::string>& arguments);

/// A command's task list and how this process takes part in running it.
class Distribution {
 public:
  using Task = std::function<std::string(std::size_t)>;
  using Deliver = std::function<void(std::size_t, std::string&&)>;
  /// Runs the tasks of \p todo (task indices, increasing) here and calls
  /// deliver(j, result) for todo[j] in that order.
  using Local = std::function<void(const std::vector<std::size_t>& todo, const Task& task, const Deliver& deliver)>;

  /// The run of \p cmd (parsed) with \p count tasks, each giving at most
  /// \p max_task_bytes bytes (at most kMaxTaskBytes).  Reads the checkpoint
  /// folder (refusing one of another run; a task file that fails its checks
  /// is said on standard error, removed and computed again), checks --shard,
  /// and under MPI learns this rank.  In a merge, checks that the parts'
  /// arguments are exactly this run's and their results within the bound.
  /// Throws std::invalid_argument on bad options.
  Distribution(const CLI::App& cmd, const DistributeOptions& options, std::size_t count, std::uint64_t max_task_bytes = kMaxTaskBytes);
  Distribution(const Distribution&) = delete;
  Distribution& operator=(const Distribution&) = delete;
  ~Distribution();

  /// Whether this process writes the command's output: false in a shard run
  /// (it writes a part file) and on MPI ranks other than 0.
  bool writes_output() const;
  /// Whether the tasks run in this process alone with the command's local
  /// runner (not MPI, not a merge).
  bool local() const;
  /// The tasks this process computes with the local runner (when local()):
  /// those of its shard not found in the checkpoint folder; under MPI, the
  /// tasks of the run not in the checkpoint (on every rank).
  const std::vector<std::size_t>& todo() const;

  /// Where task \p k's result came from, for a message about it: "merge:
  /// PART: task K", "--checkpoint DIR: task-0000000K" or "task K".  A
  /// command that reads a result back and finds it damaged names it so.
  std::string origin(std::size_t k) const;

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
  /// order, in every process: for a command that goes on from all of them
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

/// `superball merge PART… [-o FILE]` on \p app, for its --help: main()
/// runs a merge through merge_arguments() before parsing.
void add_merge(CLI::App& app);

/// When \p args (without the program name) are `merge PART… [-o FILE] [--out DIR]`:
/// reads the parts as data (every record's checksum checked, nothing after
/// `end`, no stored argument that says where to write or which shard to
/// run), checks that they are every part of one run (else
/// std::invalid_argument, one line naming the part and what is wrong), sets
/// merged_run and returns the arguments of that run (with --output FILE for
/// -o, --out DIR for --out, where the command has them); main() then parses
/// and runs those.  Other arguments: returned as they are.
std::vector<std::string> merge_arguments(const std::vector<std::string>& args);

/// Whether this superball was built with MPI (SUPERBALL_WITH_MPI).
bool built_with_mpi();
/// When an MPI launcher started this process as one of several ranks (its
/// environment: OMPI_COMM_WORLD_SIZE, PMI_SIZE, or Slurm's
/// SLURM_STEP_NUM_TASKS greater than 1): that variable as "NAME=VALUE";
/// otherwise "".  main() refuses to run on ranks when built without MPI.
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

}  // namespace superball::cli
