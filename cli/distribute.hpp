#pragma once
/// \file distribute.hpp
/// The command's side of the task lists (superball/distribute/distribute.hpp):
/// the options --shard, --part and --checkpoint, a run's identity built
/// from the parsed command, and `superball merge`.

#include <CLI/CLI.hpp>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "superball/distribute/distribute.hpp"

namespace superball::cli {

using distribute::Distribution;
using distribute::kMaxTaskBytes;
using distribute::merged_run;
using distribute::mpi_rank;
using distribute::mpi_size;
using distribute::run_everywhere;

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

/// The identity of a run of \p cmd (the subcommand as parsed): its name, then
/// every option given except those that do not change the output (--shard,
/// --part, --checkpoint, --output, --out, --plot, --threads, --jobs, --quiet,
/// --progress), as "--name=value", positionals first; and the content of
/// every argument that names a file (a scene).  `superball merge` runs the
/// command again from these, refusing parts whose arguments are not exactly
/// these (nothing in a part says where to write).
distribute::RunIdentity run_identity(const CLI::App& cmd);

/// \p o as the library takes them: the part file written through Output,
/// the checkpoint's messages on standard error ("superball: …").
distribute::Options distribute_options(const DistributeOptions& o);

/// `superball merge PART… [-o FILE]` on \p app, for its --help: main()
/// runs a merge through merge_arguments() before parsing.
void add_merge(CLI::App& app);

/// When \p args (without the program name) are `merge PART… [-o FILE] [--out DIR]`:
/// reads the parts as data (distribute::read_parts(); no stored argument that
/// says where to write or which shard to run), sets merged_run and returns
/// the arguments of that run (with --output FILE for -o, --out DIR for
/// --out, where the command has them); main() then parses and runs those.
/// Other arguments: returned as they are.  Errors: std::invalid_argument,
/// one line naming the part and what is wrong.
std::vector<std::string> merge_arguments(const std::vector<std::string>& args);

}  // namespace superball::cli
