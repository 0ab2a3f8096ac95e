#pragma once
/// \file distribute_detail.hpp
/// What distribute.cpp and distribute_mpi.cpp share: the header of part
/// files and checkpoint folders, and the MPI runner.
#include <cstddef>
#include <functional>
#include <istream>
#include <map>
#include <string>
#include <vector>

#include "distribute.hpp"

namespace superball::cli::detail {

/// The header of a part file or a checkpoint folder's `run` file.
struct Header {
  std::string run, version;
  std::vector<std::string> arguments;
  std::size_t tasks = 0;
};

/// "KIND\nrun RUN\nsuperball VERSION\nargument LENGTH TEXT\n…tasks T\n".
std::string header(const std::string& kind, const std::string& run, const std::vector<std::string>& arguments, std::size_t tasks);

/// Reads a header of \p kind; std::invalid_argument("WHERE: what is wrong") otherwise.
Header read_header(std::istream& in, const std::string& kind, const std::string& where);

/// The file of task \p k in the checkpoint folder \p dir.
std::string task_file(const std::string& dir, std::size_t k);

/// The MPI runner: every rank calls it.  Rank 0 hands out the tasks of
/// \p todo one at a time to the ranks as they become free, itself included
/// (it computes on its own thread while another thread serves the ranks),
/// calls save(k, text) for each result as it arrives, and deliver(k, text)
/// for every k in 0 … count−1 in order, taking those not in \p todo from
/// \p done.  The other ranks compute what they are given and return when
/// told to stop.  A task that throws: see Distribution::run().
void run_on_ranks(std::size_t count, const std::vector<std::size_t>& todo, std::map<std::size_t, std::string>& done,
                  const Distribution::Task& task, const std::function<void(std::size_t, const std::string&)>& save,
                  const Distribution::Deliver& deliver);

/// After run_on_ranks() on every rank: rank 0 sends \p results (every
/// task's, in order) to the other ranks, or, when \p failed (its
/// run_on_ranks() threw), tells them to stop; they then throw (their
/// message is not printed: rank 0 says why).  Returns at once when rank 0
/// left ranks waiting for tasks (stop_mpi() then aborts the job).
void share(std::vector<std::string>& results, bool failed);

/// The test hook of Distribution: \p task, made to throw for the task named
/// by the environment variable SUPERBALL_TEST_FAIL_TASK (see distribute.cpp).
Distribution::Task with_test_hook(const Distribution::Task& task);

}  // namespace superball::cli::detail
