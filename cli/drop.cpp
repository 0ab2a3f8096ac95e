#include <memory>

#include "commands.hpp"
#include "superball/cases/scene_file.hpp"
#include "superball/present/drop.hpp"
#include "superball/present/drop_limit.hpp"

namespace superball::cli {

void add_drop(CLI::App& app, Action& action) {
  struct Options {
    std::string scene, precision = "double";
    bool json = false, gaps_to_zero = false;
    int decades = 8;
  };
  auto o = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand("drop", "The whole drop of a scene with a [drop] table: every collision and flight, in time order");
  cmd->footer(
      "The bodies are released at their heights (drop_height, each body's gap; docs/SCENES.md) and fall under g;\n"
      "each collision is solved by Fremond's law of the touching cluster, the flights in closed form.  The\n"
      "output lists the collisions (time, contacts, case, velocities after, kinetic energy), the bodies that\n"
      "come to rest on a fixed obstacle (a bounce sequence accumulating at its closed-form time), each body's\n"
      "apex after its last collision and the top body's apex over its release height (docs/DROP.md).\n\n"
      "--gaps-to-zero drops the scene again with its gaps times 1, 1e-1, ... 1e-DECADES and with every gap 0 (the\n"
      "simultaneous collision: the whole stack lands at once), and compares each drop's first cascade (its\n"
      "collisions until every body moves up at least as fast as the one below it) with the simultaneous one.\n\n"
      "Examples:\n"
      "  superball drop cases/scenes/drop-two-balls.toml\n"
      "  superball drop cases/scenes/drop-one-ball.toml --json\n"
      "  superball drop cases/scenes/drop-paper-4.4.toml --gaps-to-zero");
  cmd->add_option("scene", o->scene, "Scene file (TOML) with a [drop] table")->required();
  cmd->add_option("--precision,-p", o->precision, "Arithmetic: double (default) or long-double")->capture_default_str();
  cmd->add_flag("--json", o->json, "Print JSON for programs instead of text");
  CLI::Option* limit = cmd->add_flag("--gaps-to-zero", o->gaps_to_zero, "Compare the drops with the gaps shrunk by decades against the simultaneous collision");
  cmd->add_option("--decades", o->decades, "With --gaps-to-zero: the gaps go down to 1e-DECADES times the scene's (1 to 12)")
      ->capture_default_str()
      ->needs(limit);
  cmd->callback([o, &action] {
    action = [o] {
      if (o->gaps_to_zero) {
        const present::PresentedGapLimit g = present::gap_limit_scene(load_scene(o->scene), o->precision, o->decades);
        write_output("", o->json ? present::to_json(g).dump(2) + "\n" : present::to_text(g));
        return ok;
      }
      const present::PresentedDrop d = present::drop_scene(load_scene(o->scene), o->precision);
      write_output("", o->json ? present::to_json(d).dump(2) + "\n" : present::to_text(d));
      return d.result.end == "max-events" || d.result.end == "numerical-issue" ? numerical_failure : ok;
    };
  });
}

}  // namespace superball::cli
