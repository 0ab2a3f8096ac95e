#include <iostream>
#include <memory>
#include <optional>

#include "commands.hpp"
#include "present.hpp"
#include "superball/numeric/certify.hpp"
#include "superball/cases/scene_file.hpp"

namespace superball::cli {

void add_solve(CLI::App& app, Action& action) {
  struct Options {
    std::string scene, precision = "auto", plot;
    double rtol = numeric::default_rtol;
    bool json = false;
  };
  auto o = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand("solve", "Velocities after the collision of one scene, exactly, in a chosen arithmetic");
  cmd->footer(
      "The scene is a TOML file (see cases/scenes/ and docs/SCENES.md).  The solver finds the unique\n"
      "solution of the equations of motion and the constitutive laws with impenetrability (paper §2-§3),\n"
      "the evolution case (which contacts stay closed) and checks the result against the equations.\n"
      "An explicit double, long-double or digits:N answer whose case the certificate of auto does not prove\n"
      "comes with one line 'superball: warning: ...' on standard error (and in the JSON's \"warnings\").\n\n"
      "Examples:\n"
      "  superball solve cases/scenes/paper-4.4-alpha2.toml\n"
      "  superball solve cases/scenes/paper-4.4-alpha2.toml --precision exact --json\n"
      "  superball solve SCENE --precision digits:50\n"
      "  superball solve cases/scenes/paper-4.4-flight.toml --plot out   # apex heights, out/trajectories.png");
  cmd->add_option("scene", o->scene, "Scene file (TOML)")->required();
  cmd->add_option("--precision,-p", o->precision,
                  "Arithmetic: auto (default: the cheapest of double, long-double, exact whose result is certified to --rtol), "
                  "double, long-double, digits:N (MPFR floats, at least N decimal digits), exact (CLN rationals)")
      ->capture_default_str();
  CLI::Option* rtol = cmd->add_option("--rtol", o->rtol, "With --precision auto: largest certified relative error of the velocities, 0 to 1")
      ->capture_default_str();
  cmd->add_flag("--json", o->json, "Print JSON for programs instead of text");
  cmd->add_option("--plot", o->plot, "Folder for the trajectory plot (scenes with a [flight] table)")->check(non_empty());
  cmd->callback([o, rtol, &action] {
    action = [o, rtol] {
      const auto precision = numeric::SolvePrecision::parse(o->precision, rtol->count() > 0 ? std::optional<double>(o->rtol) : std::nullopt);
      const Scene scene = load_scene(o->scene);
      if (!o->plot.empty() && !scene.flight.requested)
        throw std::invalid_argument("--plot: " + o->scene + " has no [flight] table, so there is no flight to draw");
      const Presented p = precision.automatic ? solve_scene_auto(scene, precision.tolerance()) : solve_scene(scene, precision.fixed);
      if (!o->plot.empty()) draw_flight(p, o->plot);
      write_output("", o->json ? to_json(p).dump(2) + "\n" : to_text(p));
      for (const std::string& w : p.warnings) std::cerr << "superball: warning: " << w << '\n';
      return p.status == "success" ? ok : numerical_failure;
    };
  });
}

}  // namespace superball::cli
