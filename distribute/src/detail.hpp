#pragma once
/// \file detail.hpp
/// What distribute.cpp and mpi.cpp share: the header of part
/// files and checkpoint folders, and the MPI runner.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <utility>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "superball/distribute/distribute.hpp"

namespace superball::distribute::detail {

/// The header of a part file or a checkpoint folder's `run` file.
struct Header {
  std::string run, version;
  std::vector<std::string> arguments;
  std::size_t tasks = 0;
};

/// The first line of a part file and of a checkpoint's `run` file: the
/// format's version is in it, and a file of another version is refused.
inline constexpr const char* kPartKind = "superball part 2";
inline constexpr const char* kCheckpointKind = "superball checkpoint 2";

/// "KIND\nrun RUN\nsuperball VERSION\nargument LENGTH TEXT\n…tasks T\n".
std::string header(const std::string& kind, const std::string& run, const std::vector<std::string>& arguments, std::size_t tasks);

/// A file read as data, never trusted: opened without blocking (a FIFO does
/// not wait) and, unless \p follow, without following a symbolic link; only
/// a regular file of at most \p max_size bytes (its size known from fstat()
/// before anything is read).  Every length is checked against the bytes left
/// before anything is allocated.  Errors: std::invalid_argument("WHERE: …").
class DataFile {
 public:
  DataFile(const std::string& path, const std::string& where, bool follow, std::uint64_t max_size);
  DataFile(const DataFile&) = delete;
  DataFile& operator=(const DataFile&) = delete;
  ~DataFile();
  /// The next line without its newline, at most \p max bytes; "cut short in
  /// \p what" at the end of the file.
  std::string line(std::size_t max, const std::string& what);
  /// The next \p n bytes, \p n checked against the bytes left first.
  std::string bytes(std::uint64_t n, const std::string& what);
  /// Bytes not read yet.
  std::uint64_t left() const { return size_ - read_; }
  /// std::invalid_argument("WHERE: what").
  std::invalid_argument bad(const std::string& what) const;

 private:
  int get();
  int fd_ = -1;
  std::string where_;
  std::uint64_t size_ = 0, read_ = 0;
  std::string buffer_;
  std::size_t at_ = 0;
};

/// Reads a header of \p kind; std::invalid_argument("WHERE: what is wrong") otherwise.
Header read_header(DataFile& in, const std::string& kind);

/// A task's result as stored in a part file or a checkpoint's task file:
/// "task K SIZE CHECKSUM\nTEXT\n", the checksum covering the run, K and TEXT.
std::string record(const std::string& run, std::size_t k, const std::string& text);

/// The record whose first line, \p line, was just read from \p in (of run \p run, for at most \p tasks tasks, a
/// result of at most \p max_bytes): its task and text.  A record that fails
/// its checksum, is cut short, or claims more: std::invalid_argument.
std::pair<std::size_t, std::string> read_record(DataFile& in, const std::string& line, const std::string& run, std::size_t tasks,
                                                std::uint64_t max_bytes);

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

}  // namespace superball::distribute::detail
