#include <memory>

#include "commands.hpp"
#include "superball/cases/scene_file.hpp"
#include "superball/present/drop.hpp"

namespace superball::cli {

void add_drop(CLI::App& app, Action& action) {
  struct Options {
    std::string scene, precision = "double";
    bool json = false;
  };
  auto o = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand("drop", "The whole drop of a scene with a [drop] table: every collision and flight, in time order");
  cmd->footer(
      "The bodies are released at their heights (drop_height, each body's gap; docs/SCENES.md) and fall under g;\n"
      "each collision is solved by Fremond's law of the touching cluster, the flights in closed form.  The\n"
      "output lists the collisions (time, contacts, case, velocities after, kinetic energy), the bodies that\n"
      "come to rest on a fixed obstacle (a bounce sequence accumulating at its closed-form time), each body's\n"
      "apex after its last collision and the top body's apex over its release height (docs/DROP.md).\n\n"
      "Examples:\n"
      "  superball drop cases/scenes/drop-two-balls.toml\n"
      "  superball drop cases/scenes/drop-one-ball.toml --json");
  cmd->add_option("scene", o->scene, "Scene file (TOML) with a [drop] table")->required();
  cmd->add_option("--precision,-p", o->precision, "Arithmetic: double (default), long-double, or auto (double, run again in long double when an order of events is not certified)")->capture_default_str();
  cmd->add_flag("--json", o->json, "Print JSON for programs instead of text");
  cmd->callback([o, &action] {
    action = [o] {
      const present::PresentedDrop d = present::drop_scene(load_scene(o->scene), o->precision);
      write_output("", o->json ? present::to_json(d).dump(2) + "\n" : present::to_text(d));
      return d.result.end == "max-events" || d.result.end == "numerical-issue" ? numerical_failure : ok;
    };
  });
}

}  // namespace superball::cli
