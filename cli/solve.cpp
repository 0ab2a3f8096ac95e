#include <iostream>
#include <memory>

#include "commands.hpp"
#include "present.hpp"
#include "superball/cases/scene_file.hpp"

namespace superball::cli {

void add_solve(CLI::App& app, Action& action) {
  struct Options {
    std::string scene, precision = "double";
    bool json = false;
  };
  auto o = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand("solve", "Velocities after the collision of one scene, exactly, in a chosen arithmetic");
  cmd->footer(
      "The scene is a TOML file (see cases/scenes/ and docs/SCENES.md).  The solver finds the unique\n"
      "solution of the equations of motion and the constitutive laws with impenetrability (paper §2-§3),\n"
      "the evolution case (which contacts stay closed) and checks the result against the equations.\n\n"
      "Examples:\n"
      "  superball solve cases/scenes/paper-4.4-alpha2.toml\n"
      "  superball solve cases/scenes/paper-4.4-alpha2.toml --precision exact --json\n"
      "  superball solve SCENE --precision digits:50");
  cmd->add_option("scene", o->scene, "Scene file (TOML)")->required();
  cmd->add_option("--precision,-p", o->precision,
                  "Arithmetic: double (default), long-double, digits:N (CLN floats, N decimal digits), exact (CLN rationals)")
      ->capture_default_str();
  cmd->add_flag("--json", o->json, "Print JSON for programs instead of text");
  cmd->callback([o, &action] {
    action = [o] {
      const auto precision = numeric::Precision::parse(o->precision);
      const Presented p = solve_scene(load_scene(o->scene), precision);
      if (o->json)
        std::cout << to_json(p).dump(2) << '\n';
      else
        std::cout << to_text(p);
      return p.status == "success" ? ok : numerical_failure;
    };
  });
}

}  // namespace superball::cli
