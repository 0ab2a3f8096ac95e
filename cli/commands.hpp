#pragma once
/// \file commands.hpp
/// The CLI is a thin layer: each subcommand lives in its own file and
/// registers itself on the CLI11 app here.  Commands report bad input as one
/// line on stderr ("superball: FILE:LINE:COL: field: what is wrong") and a
/// non-zero exit; they write output files through write_file_atomically().

#include <CLI/CLI.hpp>

#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>

namespace superball::cli {

/// Exit codes shared by all commands.
enum Exit : int { ok = 0, numerical_failure = 1, bad_input = 2, output_error = 3, internal_error = 4 };

/// A command's action, run after parsing; returns the exit code.
using Action = std::function<int()>;

void add_solve(CLI::App& app, Action& action);
void add_sweep(CLI::App& app, Action& action);
void add_reproduce(CLI::App& app, Action& action);
void add_derive(CLI::App& app, Action& action);
void add_audit(CLI::App& app, Action& action);
void add_verify(CLI::App& app, Action& action);
void add_explore(CLI::App& app, Action& action);

/// An output that cannot be written (full disk, closed pipe, no permission):
/// the command ends with one line naming the path and the system's reason,
/// exit code 3.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Where a command's result goes, written piece by piece: standard output
/// when the path is empty or "-", else the file \p path, replaced as a whole
/// only by commit() (a run that fails or is interrupted leaves the old file).
/// Every write is checked; failures throw OutputError("PATH: reason").
class Output {
 public:
  explicit Output(std::string path);
  Output(const Output&) = delete;
  Output& operator=(const Output&) = delete;
  /// Drops what was written unless commit() ran.
  ~Output();
  /// Append \p text.
  void write(std::string_view text);
  /// Flush and put the result in place.
  void commit();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// A command's whole result at once: Output(path), write(text), commit().
void write_output(const std::string& path, const std::string& text);

/// write_output() into a file (\p path not empty).
void write_file_atomically(const std::string& path, const std::string& text);

}  // namespace superball::cli
