// superball: conditions for the superball phenomenon in Frémond's theory of
// collisions.  See README.md and `superball --help`.
#include <iostream>

#include "commands.hpp"
#include "superball/cases/scene_file.hpp"

int main(int argc, char** argv) {
  using namespace superball::cli;
  CLI::App app{
      "superball: derive and check the conditions under which a stack of aligned balls dropped on a massive\n"
      "obstacle sends the top ball up faster than it fell (Fremond's theory of collisions).\n\n"
      "Typical use:\n"
      "  superball solve cases/scenes/paper-4.4-alpha2.toml            velocities after the collision\n"
      "  superball solve SCENE --precision exact --json                exact fractions, for programs\n"
      "  superball sweep SCENE --vary K.3-4=0:20:401 --switch-points   where the evolution case changes\n"
      "  superball derive --case 1 --alphas 2                          conditions of a case, symbolically\n"
      "  superball audit                                               the paper's printed conditions, checked\n"
      "  superball verify --case 1 --alphas 2                          a case's conditions against exact solutions\n"
      "  superball explore --alphas 3 --case 1                         is the superball reachable? witness or proof\n",
      "superball"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "superball 0.1.0");
  Action action;
  add_solve(app, action);
  add_sweep(app, action);
  add_reproduce(app, action);
  add_derive(app, action);
  add_audit(app, action);
  add_verify(app, action);
  add_explore(app, action);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    std::cerr << "superball: " << e.what() << " (see superball --help)\n";
    return bad_input;
  }
  try {
    return action();
  } catch (const superball::InputError& e) {
    std::cerr << "superball: " << e.what() << '\n';
    return bad_input;
  } catch (const OutputError& e) {
    std::cerr << "superball: " << e.what() << '\n';
    return output_error;
  } catch (const std::invalid_argument& e) {
    std::cerr << "superball: " << superball::without_function_prefix(e.what()) << '\n';
    return bad_input;
  } catch (const std::exception& e) {
    std::cerr << "superball: internal error: " << e.what() << '\n';
    return internal_error;
  }
}
