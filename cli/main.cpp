// superball: conditions for the superball phenomenon in Frémond's theory of
// collisions.  See README.md and `superball --help`.
#include <cerrno>
#include <cstring>
#include <iostream>
#include <new>

#include <string>
#include <vector>

#include "commands.hpp"
#include "distribute.hpp"
#include "superball/cases/error.hpp"
#include "superball/cases/scene_file.hpp"

namespace {

/// The command itself; main() starts and ends MPI around it.
int run(int argc, char** argv) {
  using namespace superball::cli;
  using superball::printable;
  CLI::App app{
      "superball: derive and check the conditions under which a stack of aligned balls dropped on a massive\n"
      "obstacle sends the top ball up faster than it fell (Fremond's theory of collisions).\n\n"
      "Typical use:\n"
      "  superball solve cases/scenes/paper-4.4-alpha2.toml            velocities after the collision\n"
      "  superball solve SCENE --precision exact --json                exact fractions, for programs\n"
      "  superball sweep SCENE --vary K.3-4=0:20:401 --switch-points   where the evolution case changes\n"
      "  superball map SCENE --x K.3-4=0:20:81 --y alpha.2=-110:0:111 --plot m\n"
      "                                                                cases and superball over a plane\n"
      "  superball derive --case 1 --alphas 2                          conditions of a case, symbolically\n"
      "  superball audit                                               the paper's printed conditions, checked\n"
      "  superball verify --case 1 --alphas 2                          a case's conditions against exact solutions\n"
      "  superball explore --alphas 3 --case 1                         is the superball reachable? witness or proof\n",
      "superball"};
  app.footer(
      "Exit codes (every command):\n"
      "  0  success\n"
      "  1  a numerical outcome you asked to be told about: a solve or sweep value whose status is not success,\n"
      "     derived conditions that disagree with exact solutions (verify)\n"
      "  2  bad input or usage: a scene file, an option, a command line (one line on stderr says what and where),\n"
      "     an output naming a file the command reads, a size this machine has no memory for\n"
      "  3  an output that cannot be written: a full disk, a closed pipe, no permission (one line: the path and why)\n"
      "  4  internal error: a bug of the tool, to be reported\n"
      "Output (-o, --out, --plot, standard output): a file is replaced whole, atomically, only at the end (its\n"
      "permissions kept; through a symbolic link, the link's target); a device, FIFO or standard output is written\n"
      "directly (a FIFO with no reader: the command waits for one, as cat and tee do).  An output that names a file the\n"
      "command reads (its scene, through any name or link) is refused before anything is written.");
  app.require_subcommand(1);
  guard_standard_descriptors();
  app.set_version_flag("--version", "superball " SUPERBALL_VERSION);
  Action action;
  add_solve(app, action);
  add_sweep(app, action);
  add_map(app, action);
  add_reproduce(app, action);
  add_derive(app, action);
  add_audit(app, action);
  add_verify(app, action);
  add_explore(app, action);
  add_drop(app, action);
  add_merge(app);
  // `superball merge PART…`: the run the parts belong to, its results taken from them.
  std::vector<std::string> words(argv + 1, argv + argc), merged;
  try {
    merged = merge_arguments(words);
  } catch (const std::exception& e) {
    std::cerr << "superball: " << printable(e.what()) << '\n';
    return bad_input;
  }
  std::vector<char*> merged_argv = {argv[0]};
  if (merged != words) {
    for (std::string& w : merged) merged_argv.push_back(w.data());
    merged_argv.push_back(nullptr);
    argc = static_cast<int>(merged_argv.size()) - 1;
    argv = merged_argv.data();
  }
  if (argc > 1 && argv[1][0] != '-') {
    std::string names;
    bool known = false;
    for (const CLI::App* sub : app.get_subcommands({})) {
      known = known || sub->get_name() == argv[1];
      names += (names.empty() ? "" : ", ") + sub->get_name();
    }
    if (!known) {
      std::cerr << "superball: unknown command '" << printable(argv[1]) << "' (commands: " << names << ")\n";
      return bad_input;
    }
  }
  // Under MPI every rank runs the command; the same error on every rank is said once, by rank 0.
  std::ostream& err = mpi_rank() == 0 ? std::cerr : *[] {
    static std::ostream none(nullptr);
    return &none;
  }();
  // The line in one write: under mpirun, standard error is relayed in the
  // pieces it was written in, and MPI_Abort's banner may fall between them.
  auto say = [&err](const std::string& line) { err << ("superball: " + line + "\n") << std::flush; };
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) {  // --help, --version
      app.exit(e);
      std::cout.flush();
      if (!std::cout) {
        std::cerr << "superball: standard output: " << std::strerror(errno) << '\n';
        return output_error;
      }
      return ok;
    }
    say(printable(e.what()) + " (see superball --help)");
    return bad_input;
  }
  // Under MPI only the commands whose work is a task list (superball/distribute/distribute.hpp) spread over the ranks;
  // any other would run whole on every rank, each writing its output.
  if (mpi_size() > 1) {
    const std::string name = app.get_subcommands().empty() ? "" : app.get_subcommands().front()->get_name();
    if (name != "derive" && name != "sweep" && name != "verify" && name != "explore" && name != "map") {
      say(name + " does not spread over MPI ranks (derive, sweep, verify, explore and map do); run it in one process, with its --threads");
      return bad_input;
    }
  }
  try {
    check_outputs(*app.get_subcommands().front());
    return action();
  } catch (...) {
    superball::distribute::abandon_ranks();  // under MPI, ranks waiting for rank 0 are not left hanging
    try {
      throw;
    } catch (const superball::InputError& e) {
      say(printable(e.what()));
      return bad_input;
    } catch (const OutputError& e) {
      say(printable(e.what()));
      return output_error;
    } catch (const std::invalid_argument& e) {
      say(printable(superball::without_function_prefix(e.what())));
      return bad_input;
    } catch (const std::bad_alloc&) {
      say("out of memory: the command needs more than this machine allows (MemAvailable, ulimit -v); ask for less "
          "(a coarser grid, fewer samples)");
      return bad_input;
    } catch (const std::exception& e) {
      say("internal error: " + printable(e.what()));
      return internal_error;
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  // Started by mpirun or srun as one of several ranks, a superball without MPI
  // would run the whole command on every rank, each writing its output.
  const std::string ranks = superball::distribute::launched_on_ranks();
  if (!superball::distribute::built_with_mpi() && !ranks.empty()) {
    if (superball::distribute::first_launched_rank())
      std::cerr << "superball: started on several ranks by an MPI launcher (" << superball::printable(ranks)
                << "), but this superball is built without MPI: every rank would run the whole command; run one process, or build with "
                   "-DSUPERBALL_WITH_MPI=ON\n";
    return superball::cli::bad_input;
  }
  superball::distribute::start_mpi(&argc, &argv);
  const int code = run(argc, argv);
  superball::distribute::stop_mpi(code);
  return code;
}
