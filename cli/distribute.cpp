// The command's side of the task lists (distribute.hpp): its options, a
// run's identity from the parsed command, and `superball merge`.
#include "distribute.hpp"

#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <sstream>
#include <stdexcept>

#include "commands.hpp"
#include "superball/cases/error.hpp"

namespace superball::cli {

void add_distribute_options(CLI::App* cmd, DistributeOptions& o, const std::string& noun, bool shards) {
  cmd->add_option("--checkpoint", o.checkpoint,
                  "Folder where each finished " + noun + " is written at once; the same command run again computes only those missing")
      ->check(non_empty());
  if (!shards) {  // not offered (hidden from --help); the command refuses them, saying why
    cmd->add_option("--shard", o.shard)->group("");
    cmd->add_option("--part", o.part)->group("");
    return;
  }
  cmd->add_option("--shard", o.shard,
                  "I/N: compute only the " + noun + "s k with k mod N = I-1 and write them as a part file (see --part); "
                  "`superball merge` joins the N parts into this run's output")
      ->check(non_empty());
  cmd->add_option("--part", o.part, "The part file of --shard (default: superball-RUN-I-of-N.part here, RUN naming the run)")->check(non_empty());
}

distribute::RunIdentity run_identity(const CLI::App& cmd) {
  static const char* const runner[] = {"shard", "part", "checkpoint", "output", "out", "plot", "threads", "jobs", "quiet", "progress", "help"};
  std::vector<std::string> positional, named;
  // The options of the command and of its option groups (nameless subcommands), in order.
  std::vector<const CLI::Option*> options;
  std::function<void(const CLI::App&)> collect = [&](const CLI::App& app) {
    for (const CLI::Option* opt : app.get_options()) options.push_back(opt);
    for (const CLI::App* group : app.get_subcommands([](const CLI::App* sub) { return sub->get_name().empty(); })) collect(*group);
  };
  collect(cmd);
  for (const CLI::Option* opt : options) {
    if (opt->count() == 0) continue;
    bool skip = false;
    for (const char* r : runner) skip = skip || opt->check_lname(r);
    if (skip) continue;
    if (!opt->nonpositional()) {
      for (const std::string& v : opt->results()) positional.push_back(v);
    } else if (opt->get_expected_max() == 0) {  // a flag
      for (std::size_t i = 0; i < opt->count(); ++i) named.push_back("--" + opt->get_lnames().at(0));
    } else {
      for (const std::string& v : opt->results()) named.push_back("--" + opt->get_lnames().at(0) + "=" + v);
    }
  }
  distribute::RunIdentity id{cmd.get_name(), positional, {}};
  id.arguments.insert(id.arguments.end(), named.begin(), named.end());
  for (std::size_t i = 0; i < id.arguments.size(); ++i) {
    // "--scene=FILE" or a positional FILE: the file's content is part of the run.
    const std::string& a = id.arguments[i];
    const std::size_t eq = a.rfind("--", 0) == 0 ? a.find('=') : std::string::npos;
    const std::string value = eq == std::string::npos ? a : a.substr(eq + 1);
    std::error_code error;
    if (!value.empty() && std::filesystem::is_regular_file(value, error)) {
      std::ifstream in(value, std::ios::binary);
      std::ostringstream os;
      os << in.rdbuf();
      id.contents.emplace(i, os.str());
    }
  }
  return id;
}

distribute::Options distribute_options(const DistributeOptions& o) {
  distribute::Options d;
  d.shard = o.shard;
  d.part = o.part;
  d.checkpoint = o.checkpoint;
  d.write_part = [](const std::string& path, const std::string& text) { write_output(path, text); };
  d.warn = d.note = [](const std::string& line) { std::cerr << ("superball: " + printable(line) + "\n"); };
  return d;
}

void add_merge(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("merge", "Join the part files of a run made with --shard I/N into the output of the whole run");
  cmd->footer(
      "Each part file names its run (a hash of the command, the superball version and the files it reads), its\n"
      "part I of N and holds the results of its tasks, each with a checksum of the run, the task and its result.\n"
      "merge checks that the files are the N parts of one run, each once, whole, every checksum right, nothing\n"
      "after 'end', then runs the command again with the results taken from them: its output is byte for byte\n"
      "that of the run in one process.  A part is data: it never says where to write.  The output goes to\n"
      "standard output, or where merge's own -o FILE (derive, explore) and --out DIR (the scene files of verify\n"
      "and explore) say.  The files the command reads must still be there, unchanged (same run name).\n\n"
      "Example (a Slurm job array, or any loop):\n"
      "  superball derive --bodies 6 --pairs near2 --all --format json --shard 1/3 --part p1.part\n"
      "  superball derive --bodies 6 --pairs near2 --all --format json --shard 2/3 --part p2.part\n"
      "  superball derive --bodies 6 --pairs near2 --all --format json --shard 3/3 --part p3.part\n"
      "  superball merge p1.part p2.part p3.part -o all.json");
  static std::vector<std::string> parts;
  static std::string output, out;
  cmd->add_option("parts", parts, "The part files (any order)")->required();
  cmd->add_option("--output,-o", output, "Write to this file instead of standard output (derive, explore; the others: redirect standard output)");
  cmd->add_option("--out", out, "Write the scene files (verify's disagreements, explore's witnesses) into this folder");
}

namespace {

/// The commands that make parts, and the options of merge's own command line
/// each takes: where the merge writes is said there, never by the parts.
struct Mergeable {
  const char* command;
  bool output, out;  ///< takes --output FILE (merge -o), --out DIR (merge --out)
};
constexpr Mergeable kMergeable[] = {{"derive", true, false}, {"sweep", false, false}, {"verify", false, true}, {"explore", true, true}};

/// Options a part's arguments never hold: a part describes its run, it does
/// not say where to write, which shard to run or which folder to read.
constexpr const char* kNeverInPart[] = {"shard", "part", "checkpoint", "output", "out", "plot", "threads", "jobs", "quiet", "progress", "help", "version"};

/// Checks the arguments stored in a part before anything
/// parses them: a command that makes parts, then only positionals and
/// --NAME[=VALUE] options other than kNeverInPart; \p where names the part.
const Mergeable& check_part_arguments(const std::vector<std::string>& arguments, const std::string& where) {
  const auto bad = [&](const std::string& what) { return std::invalid_argument(where + ": " + what); };
  const Mergeable* m = nullptr;
  for (const Mergeable& c : kMergeable) m = !arguments.empty() && arguments[0] == c.command ? &c : m;
  if (!m) throw bad("its arguments do not start with a command that makes parts (derive, sweep, verify, explore)");
  for (std::size_t a = 1; a < arguments.size(); ++a) {
    const std::string& w = arguments[a];
    if (w.empty() || w[0] != '-') continue;
    const std::string name = w.rfind("--", 0) == 0 ? w.substr(2, w.find('=') == std::string::npos ? std::string::npos : w.find('=') - 2) : "";
    if (name.empty()) throw bad("a stored argument '" + w.substr(0, 40) + "' that is not --NAME or --NAME=VALUE (edited?)");
    for (const char* never : kNeverInPart)
      if (name == never)
        throw bad("a stored argument '" + w.substr(0, 60) + "': a part describes its run, it never says where to write or which shard to run (edited?)");
  }
  return *m;
}

}  // namespace

std::vector<std::string> merge_arguments(const std::vector<std::string>& args) {
  if (args.empty() || args[0] != "merge") return args;
  std::vector<std::string> parts;
  std::string output, out;
  for (std::size_t a = 1; a < args.size(); ++a) {
    const std::string& s = args[a];
    if (s == "--help" || s == "-h") return args;
    if (s == "-o" || s == "--output" || s == "--out") {
      if (a + 1 == args.size() || args[a + 1].empty()) throw std::invalid_argument("merge: " + s + " needs a " + (s == "--out" ? "folder" : "file") + " name");
      (s == "--out" ? out : output) = args[++a];
    } else if (s.rfind("--output=", 0) == 0 || s.rfind("--out=", 0) == 0) {
      const std::size_t eq = s.find('=');
      if (eq + 1 == s.size()) throw std::invalid_argument("merge: " + s.substr(0, eq) + " needs a name");
      (s[5] == '=' ? out : output) = s.substr(eq + 1);
    } else if (!s.empty() && s[0] == '-') {
      throw std::invalid_argument("merge: unknown option '" + s + "' (superball merge PART... [-o FILE] [--out DIR])");
    } else {
      parts.push_back(s);
    }
  }
  if (parts.empty()) throw std::invalid_argument("merge: no part file (superball merge PART... [-o FILE] [--out DIR])");
  for (const std::string& path : parts) note_input("part", path);  // merge's -o and --out never name a part it reads
  const Mergeable* command = nullptr;
  static distribute::MergedRun merged;
  merged = distribute::read_parts(parts, [&](const std::vector<std::string>& arguments, const std::string& where) {
    command = &check_part_arguments(arguments, where);
  });
  merged_run = &merged;
  std::vector<std::string> run = merged.arguments;
  // Where the merge writes: its own command line, nothing else.
  if (!output.empty()) {
    if (!command->output)
      throw std::invalid_argument("merge: -o: " + run[0] + " writes to standard output; redirect it (superball merge PART... > FILE)");
    run.push_back("--output=" + output);
  }
  if (!out.empty()) {
    if (!command->out) throw std::invalid_argument("merge: --out: " + run[0] + " writes no scene files");
    run.push_back("--out=" + out);
  }
  return run;
}

}  // namespace superball::cli
