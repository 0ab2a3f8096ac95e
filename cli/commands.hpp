#pragma once
/// \file commands.hpp
/// The CLI is a thin layer: each subcommand lives in its own file and
/// registers itself on the CLI11 app here.  Commands report bad input as one
/// line on stderr ("superball: FILE:LINE:COL: field: what is wrong") and a
/// non-zero exit; they write every result through Output.

#include <CLI/CLI.hpp>

#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "superball/distribute/distribute.hpp"

namespace superball::cli {

/// Exit codes shared by all commands.
enum Exit : int { ok = 0, numerical_failure = 1, bad_input = 2, output_error = 3, internal_error = 4 };

/// A command's action, run after parsing; returns the exit code.
using Action = std::function<int()>;

void add_solve(CLI::App& app, Action& action);
void add_sweep(CLI::App& app, Action& action);
void add_map(CLI::App& app, Action& action);
void add_reproduce(CLI::App& app, Action& action);
void add_derive(CLI::App& app, Action& action);
void add_audit(CLI::App& app, Action& action);
void add_verify(CLI::App& app, Action& action);
void add_explore(CLI::App& app, Action& action);
void add_drop(CLI::App& app, Action& action);

/// Refuses the empty string: "" names no file, case or list, and a command
/// must not take it for "none" or "standard output" (use "none" or "-").
inline const CLI::Validator& non_empty() {
  static const CLI::Validator v([](const std::string& s) { return s.empty() ? std::string("is empty") : std::string(); }, "", "NONEMPTY");
  return v;
}

/// An output that cannot be written (full disk, closed pipe, no permission):
/// the command ends with one line naming the path and the system's reason,
/// exit code 3.  The type the task lists' files throw too (a checkpoint, a part).
using OutputError = distribute::OutputError;

/// Where a command's result goes, written piece by piece; the one way the
/// commands write anything (model: coreutils' install/mv, moreutils' sponge).
///  - "", "-", /dev/stdout: standard output, written directly;
///  - an existing device, FIFO or socket: opened and written directly, never
///    replaced (a FIFO with no reader: open() waits for one, as cat and tee do);
///  - a file the command reads (note_input()): refused, std::invalid_argument;
///  - a regular file or a new path: a temporary (mkstemp) beside it, with the
///    existing file's permissions (and owner, when run as root) or 0666 & ~umask,
///    replaced by rename() in commit() after fsync() of the file, then fsync()
///    of the folder; the old file stays whole until then;
///  - an existing symbolic link: its target is replaced that way, the link kept.
/// Every write and close is checked: a failure throws OutputError("PATH:
/// strerror(errno)"), e.g. "out.json: No space left on device" (exit 3).
/// The temporary is removed by the destructor when commit() did not run, and
/// by SIGINT, SIGTERM, SIGHUP and SIGPIPE (the signal is then re-raised).
class Output {
 public:
  /// Open \p path as above; throws OutputError when it cannot be written.
  explicit Output(std::string path);
  Output(const Output&) = delete;
  Output& operator=(const Output&) = delete;
  /// Drops what was written unless commit() ran.
  ~Output();
  /// Append \p text (all of it, or OutputError).
  void write(std::string_view text);
  /// Put the result in place (see above); call once, after the last write().
  void commit();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Record \p path, the value of \p option ("--scene", "part", or "" for a
/// positional scene), as a regular file the running command reads (when it
/// is one): no Output may then replace it.  Called by check_outputs() for
/// the scenes, by merge for its parts.
void note_input(const std::string& option, const std::string& path);

/// Throws std::invalid_argument("WHAT: is the file of --scene t.toml, which
/// this command reads; write the output elsewhere") when \p path is a noted
/// input, whatever its spelling: the same name, ./name, a symbolic or a hard
/// link to it (the same st_dev and st_ino).  A path that does not exist yet
/// is no input.  Output's constructor calls it, so nothing is written over
/// an input.
void check_not_input(const std::string& what, const std::string& path);

/// Before a parsed command runs: its inputs noted (the positional scene,
/// --scene) and every output it names checked against them with
/// check_not_input(), before anything is written: -o/--output, --out,
/// --part, --checkpoint, --plot (and for map the files PREFIX.dat, .gp,
/// .png and .svg it makes).  Called by main() for every command.
void check_outputs(const CLI::App& command);

/// A command's whole result at once: Output(path), write(text), commit().
void write_output(const std::string& path, std::string_view text);

/// Called first by main(): a standard descriptor (0, 1, 2) that is closed is
/// opened read-only on /dev/null, so that no file opened later takes its
/// number and writes to a closed standard output still fail (EBADF).
void guard_standard_descriptors();

}  // namespace superball::cli
