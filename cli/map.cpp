#include <memory>

#include "commands.hpp"
#include "gnuplot.hpp"
#include "range.hpp"
#include "superball/cases/scene_file.hpp"
#include "superball/numeric/map.hpp"
#include "superball/numeric/parallel.hpp"
#include "superball/present/map.hpp"

namespace superball::cli {

void add_map(CLI::App& app, Action& action) {
  struct Options {
    std::string scene, x, y, precision = "double", plot;
    bool csv = false, json = false, boundary_points = false;
    int threads = numeric::thread_count(0);
  };
  auto o = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand("map", "Evolution cases and the superball over a grid of two parameters, with exact boundaries");
  cmd->footer(
      "--x and --y take KEY=FROM:TO:N as sweep --vary does (KEY: K.i-j, alpha.k (n = 4), coupling.i-j/k-l, mass.i,\n"
      "velocity.i, drop_height, fall_speed, g; FROM, TO exact numbers or fractions; N from 2 to 10000 values per\n"
      "axis, ends included).  Each grid point is solved in --precision: its evolution case, U1+/a (the top ball's\n"
      "speed after over its speed before) and the superball verdict U1+ > a.  Where M is not positive\n"
      "semi-definite (decided exactly) the collision law does not apply: the point is marked, not solved.\n"
      "Between two neighbouring solved points (along x or along y) of different case or verdict, the boundary is\n"
      "located by bisection on the exact solution (CLN rationals) to 2^-64 of the grid step, as sweep\n"
      "--switch-points does; the boundary points are chained into curves, one per pair of regions.\n"
      "Output: a summary (cases present with their share of the grid, the superball's share, the curves);\n"
      "--csv: one row per grid point (KEYX, KEYY, psd, case, closed, U1_over_a, superball, status);\n"
      "--boundary-points: the boundary points instead (with --csv as CSV: along, KEYX, KEYY, bracket_width, the\n"
      "case and verdict at each end of the bracket); --json: everything.  --plot PREFIX also draws PREFIX.png and\n"
      "PREFIX.svg with gnuplot (PREFIX.dat and PREFIX.gp beside them redraw it): the case regions in colour (the\n"
      "superball part full, the rest pale), the exact boundary curves, and U1+/a with its contour lines.\n"
      "A corner of the grid that a scene file could not hold (g <= 0, a mass <= 0, a contact opening before the\n"
      "collision), the same KEY on both axes, or a grid where M is nowhere positive semi-definite is refused\n"
      "before anything is written.  The output does not depend on --threads.\n\n"
      "Examples:\n"
      "  superball map cases/scenes/paper-fig5-alpha2.toml --x alpha.2=-200:100:121 --y alpha.5=-10:10:81\n"
      "  superball map cases/scenes/paper-4.4-alpha2.toml --x K.3-4=0:20:101 --y alpha.2=-150:0:101 --plot k34-alpha2\n"
      "  superball map cases/scenes/paper-4.4-alpha2.toml --x K.3-4=0:20:41 --y alpha.2=-150:0:41 --boundary-points --csv");
  cmd->add_option("scene", o->scene, "Scene file (TOML)")->required();
  cmd->add_option("--x", o->x, "KEY=FROM:TO:N, the horizontal axis")->required();
  cmd->add_option("--y", o->y, "KEY=FROM:TO:N, the vertical axis")->required();
  cmd->add_option("--precision,-p", o->precision, "Arithmetic of the grid points (see solve; boundaries are always exact)")
      ->capture_default_str();
  cmd->add_flag("--csv", o->csv, "Print CSV: one row per grid point (or per boundary point with --boundary-points)");
  cmd->add_flag("--json", o->json, "Print JSON for programs: axes, points, boundary points, curves");
  cmd->add_flag("--boundary-points", o->boundary_points, "Print the boundary points instead of the grid (CSV with --csv)");
  cmd->add_option("--plot", o->plot, "Also draw the map into PREFIX.png and PREFIX.svg (with PREFIX.dat, PREFIX.gp)")
      ->check(non_empty());
  cmd->add_option("--threads,-j", o->threads, "Worker threads (default: all cores)")->check(CLI::Range(1, 1024))->capture_default_str();
  cmd->callback([o, &action] {
    action = [o] {
      if (o->csv && o->json) throw std::invalid_argument("map: --csv and --json: choose one");
      const Scene scene = load_scene(o->scene);
      const Range rx = parse_range("--x", o->x, scene, numeric::map_max_steps);
      const Range ry = parse_range("--y", o->y, scene, numeric::map_max_steps);
      numeric::MapSettings settings;
      settings.precision = numeric::Precision::parse(o->precision);
      settings.threads = o->threads;
      const numeric::Map m = numeric::map(scene, {rx.parameter, rx.from, rx.to, rx.steps}, {ry.parameter, ry.from, ry.to, ry.steps}, settings);
      const std::string precision = settings.precision.name();
      std::string text;
      if (o->json)
        text = present::map_json(m, scene, precision).dump(1) + "\n";
      else if (o->boundary_points)
        text = o->csv ? present::boundaries_csv(m) : present::map_summary(m, scene, precision);
      else
        text = o->csv ? present::map_csv(m) : present::map_summary(m, scene, precision);
      if (o->boundary_points && !o->csv && !o->json) {
        text += "boundary points (the bracket's middle on the axis named first, the grid value on the other):\n";
        for (const auto& b : m.boundaries) {
          const auto [x, y] = numeric::position(m, b);
          text += "  along " + (b.along_x ? rx.parameter.key() : ry.parameter.key()) + ": (" + numeric::to_string(x, 12) + ", " +
                  numeric::to_string(y, 12) + ")  width " + numeric::to_string(cln::double_approx(b.high - b.low), 3) + "  case " +
                  present::case_name(b.below) + (b.below.superball ? " superball" : "") + " -> case " + present::case_name(b.above) +
                  (b.above.superball ? " superball" : "") + "\n";
        }
      }
      if (!o->plot.empty()) {
        const std::string title = scene.title.empty() ? scene.origin : scene.title;
        const std::string stem = o->plot.substr(o->plot.find_last_of('/') + 1);
        write_output(o->plot + ".dat", present::map_figure_data(m, {}));
        const std::string png = "pngcairo size 1500,760 font 'DejaVu Sans,11'", svg = "svg size 1500,760 dynamic font 'DejaVu Sans,11'";
        write_output(o->plot + ".gp", present::map_figure_script(m, {}, title, stem + ".dat", png, "'" + stem + ".png'") +
                                          present::map_figure_script(m, {}, title, stem + ".dat", svg, "'" + stem + ".svg'"));
        render(present::map_figure_script(m, {}, title, o->plot + ".dat", png, ""), o->plot + ".png");
        render(present::map_figure_script(m, {}, title, o->plot + ".dat", svg, ""), o->plot + ".svg");
      }
      write_output("", text);
      return ok;
    };
  });
}

}  // namespace superball::cli
