#include <cmath>
#include <memory>

#include "commands.hpp"
#include "gnuplot.hpp"
#include "present.hpp"
#include "superball/cases/scene_file.hpp"
#include "superball/present/drop.hpp"
#include "superball/present/drop_limit.hpp"

namespace superball::cli {
namespace {

/// The files --plot DIR writes (check_outputs() checks DIR itself).
const char* const kFigureFiles[] = {"trajectories.dat", "trajectories.gp", "trajectories.png", "trajectories.svg"};

/// Every body's height against time (present::drop_trace()), the collisions and rests marked, as DIR/trajectories.*.
void draw_drop(const present::PresentedDrop& d, const std::string& dir) {
  const present::DropTrace trace = present::drop_trace(d.result);
  Plot plot{"Height against time from the release (" + d.origin + ")", "time since the release (s)",
            "height above the obstacle's release height (m)", false, false, "outside right top box opaque spacing 1.4", {}, {}};
  const std::size_t n = trace.time.size();
  for (std::size_t i = 0; i < n; ++i) {
    const bool obstacle = d.result.fixed_bottom && i + 1 == n;
    plot.series.push_back({obstacle ? "obstacle" : "body " + std::to_string(i + 1), trace.time[i], trace.height[i], false});
  }
  plot.series.push_back({"collisions", trace.collision_time, trace.collision_height, true});
  if (!trace.rest_time.empty()) plot.series.push_back({"at rest", trace.rest_time, trace.rest_height, true});
  draw(dir, "trajectories", plot);
}

/// The files --gaps-to-zero --plot DIR writes.
const char* const kLimitFiles[] = {"gaps-to-zero.dat", "gaps-to-zero.gp", "gaps-to-zero.png", "gaps-to-zero.svg"};

}  // namespace

Plot gap_limit_plot(const numeric::GapLimit& limit, const Scene& scene, const std::string& title) {
  const double a = limit.landing_speed > 0 ? limit.landing_speed : 1;
  double gap = 0;  // the top gap of the scene, the x of each step
  for (const Body& b : scene.bodies)
    if (b.gap && !b.gap->is_zero()) {
      gap = b.gap->approx();
      break;
    }
  Plot plot{title, "gap between the top balls (m)", "velocity after the first cascade / a", true, false,
            "inside center right box opaque spacing 1.4", {}, {}};
  const std::vector<double>& masses = limit.simultaneous.drop.masses;
  for (std::size_t i = 0; i < masses.size(); ++i) {
    if (std::isinf(masses[i])) continue;
    Series s{"U_" + std::to_string(i + 1) + "^+/a (gapped)", {}, {}, true};
    for (const auto& step : limit.steps)
      if (step.cascade.complete) {
        s.x.push_back(gap * step.scale);
        s.y.push_back(step.cascade.velocities[i] / a);
      }
    plot.series.push_back(s);
    if (limit.simultaneous.cascade.complete)
      plot.markers.push_back({limit.simultaneous.cascade.velocities[i] / a, "U_" + std::to_string(i + 1) + "^+/a simultaneous", false, true, 0.97, false});
  }
  return plot;
}

void add_drop(CLI::App& app, Action& action) {
  struct Options {
    std::string scene, precision = "double", plot;
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
      "apex after its last collision and the top body's apex over its release height (docs/DROP.md).\n"
      "--plot DIR also draws every body's height against time, the collisions and the rests marked, into\n"
      "DIR/trajectories.png and .svg with gnuplot (DIR/trajectories.dat and .gp beside them redraw it); a bounce\n"
      "sequence that accumulates is drawn at rest from its rest time.  DIR must exist.\n\n"
      "--gaps-to-zero drops the scene again with its gaps times 1, 1e-1, ... 1e-DECADES and with every gap 0 (the\n"
      "simultaneous collision: the whole stack lands at once), and compares each drop's first cascade (its\n"
      "collisions until every body moves up at least as fast as the one below it) with the simultaneous one;\n"
      "with --plot DIR it draws the velocities after the cascades against the gap (DIR/gaps-to-zero.*).\n\n"
      "Examples:\n"
      "  superball drop cases/scenes/drop-two-balls.toml\n"
      "  superball drop cases/scenes/drop-one-ball.toml --json\n"
      "  superball drop cases/scenes/drop-three-balls.toml --plot out   # out/trajectories.png\n"
      "  superball drop cases/scenes/drop-paper-4.4.toml --gaps-to-zero");
  cmd->add_option("scene", o->scene, "Scene file (TOML) with a [drop] table")->required();
  cmd->add_option("--precision,-p", o->precision, "Arithmetic: double (default), long-double, digits:N, exact (as far as every event's time is rational: ends \"inexact\" at the first that is not), or auto (double, then long double, then exact, while an order of events is not certified)")->capture_default_str();
  cmd->add_flag("--json", o->json, "Print JSON for programs instead of text");
  cmd->add_option("--plot", o->plot, "Folder for the trajectory plot (DIR/trajectories.png, .svg, .dat, .gp; with --gaps-to-zero DIR/gaps-to-zero.*)")
      ->check(non_empty());
  CLI::Option* limit = cmd->add_flag("--gaps-to-zero", o->gaps_to_zero, "Compare the drops with the gaps shrunk by decades against the simultaneous collision");
  cmd->add_option("--decades", o->decades, "With --gaps-to-zero: the gaps go down to 1e-DECADES times the scene's (1 to 12)")
      ->capture_default_str()
      ->needs(limit);
  cmd->callback([o, &action] {
    action = [o] {
      if (!o->plot.empty())
        for (const char* file : o->gaps_to_zero ? kLimitFiles : kFigureFiles) check_not_input("--plot " + o->plot + " (" + file + ")", o->plot + "/" + file);
      if (o->gaps_to_zero) {
        const Scene scene = load_scene(o->scene);
        const present::PresentedGapLimit g = present::gap_limit_scene(scene, o->precision, o->decades);
        if (!o->plot.empty()) draw(o->plot, "gaps-to-zero", gap_limit_plot(g.result, scene, "Gaps to zero against the simultaneous collision (" + g.origin + ")"));
        write_output("", o->json ? present::to_json(g).dump(2) + "\n" : present::to_text(g));
        return ok;
      }
      const present::PresentedDrop d = present::drop_scene(load_scene(o->scene), o->precision);
      if (!o->plot.empty()) draw_drop(d, o->plot);
      write_output("", o->json ? present::to_json(d).dump(2) + "\n" : present::to_text(d));
      return numeric::drop_finished(d.result.end) ? ok : numerical_failure;
    };
  });
}

}  // namespace superball::cli
