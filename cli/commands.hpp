#pragma once
/// \file commands.hpp
/// The CLI is a thin layer: each subcommand lives in its own file and
/// registers itself on the CLI11 app here.  Commands report bad input as one
/// line on stderr ("superball: FILE:LINE:COL: field: what is wrong") and a
/// non-zero exit; they write output files through write_file_atomically().

#include <CLI/CLI.hpp>

#include <functional>
#include <string>

namespace superball::cli {

/// Exit codes shared by all commands.
enum Exit : int { ok = 0, bad_input = 2, numerical_failure = 3, internal_error = 4 };

/// A command's action, run after parsing; returns the exit code.
using Action = std::function<int()>;

void add_solve(CLI::App& app, Action& action);
void add_sweep(CLI::App& app, Action& action);
void add_reproduce(CLI::App& app, Action& action);
void add_derive(CLI::App& app, Action& action);
void add_audit(CLI::App& app, Action& action);
void add_verify(CLI::App& app, Action& action);
void add_explore(CLI::App& app, Action& action);

/// Write \p text to \p path through a temporary file in the same folder and
/// a rename, so an interrupted run never leaves a half-written file.
/// Throws std::runtime_error("write_file_atomically(): PATH: why").
void write_file_atomically(const std::string& path, const std::string& text);

/// A command's result: \p text on standard output when \p path is empty,
/// else into the file \p path (write_file_atomically()).
void write_output(const std::string& path, const std::string& text);

}  // namespace superball::cli
