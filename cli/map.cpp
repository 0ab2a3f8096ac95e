#include "map.hpp"

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "distribute.hpp"
#include "gnuplot.hpp"
#include "superball/cases/scene_file.hpp"
#include "superball/distribute/identities.hpp"
#include "superball/numeric/parallel.hpp"
#include "superball/numeric/range.hpp"
#include "superball/present/overlay.hpp"
#include "superball/verify/overlay.hpp"

namespace superball::cli {

void draw_map(const std::string& prefix, const numeric::Map& m, const std::string& title, const std::vector<present::MapMark>& marks,
              const std::vector<std::pair<double, double>>& derived) {
  const std::string stem = prefix.substr(prefix.find_last_of('/') + 1);
  const bool with_derived = !derived.empty();
  write_output(prefix + ".dat", present::map_figure_data(m, marks, derived));
  const std::string png = "pngcairo size 1500,760 font 'DejaVu Sans,11'", svg = "svg size 1500,760 dynamic font 'DejaVu Sans,11'";
  // The script beside the figures redraws both by hand (`cd DIR && gnuplot STEM.gp`).
  write_output(prefix + ".gp", present::map_figure_script(m, marks, with_derived, title, stem + ".dat", png, "'" + stem + ".png'") +
                                   present::map_figure_script(m, marks, with_derived, title, stem + ".dat", svg, "'" + stem + ".svg'"));
  render(present::map_figure_script(m, marks, with_derived, title, prefix + ".dat", png, ""), prefix + ".png");
  render(present::map_figure_script(m, marks, with_derived, title, prefix + ".dat", svg, ""), prefix + ".svg");
}

namespace {

/// The grid points computed and written at a time when a map's CSV is streamed.
constexpr std::size_t stream_block = std::size_t{1} << 14;

/// The hidden --stage-times: each stage's wall time and the process's CPU
/// time in it (all threads), one line each on standard error, to see which
/// stages of a map run on one thread.
class StageTimes {
 public:
  explicit StageTimes(bool on) : on_(on) {
    if (on_) wall_ = wall(), cpu_ = cpu();
  }
  /// The stage that ends now, since the last one ended (or the start).
  void end(const char* stage) {
    if (!on_) return;
    const double w = wall(), c = cpu();
    std::fprintf(stderr, "map: stage %-11s wall %8.4f s  cpu %8.4f s\n", stage, w - wall_, c - cpu_);
    wall_ = w, cpu_ = c;
  }

 private:
  static double wall() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }
  static double cpu() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
  }
  bool on_;
  double wall_ = 0, cpu_ = 0;
};

/// The zeros of the derived conditions next to a point of their case (those
/// that can bound its region), as points of the plane.
std::vector<std::pair<double, double>> derived_points(const verify::Overlay& o, const numeric::Map& m) {
  std::vector<std::pair<double, double>> points;
  for (const verify::DerivedZero& z : o.zeros) {
    if (!z.at_case) continue;
    numeric::MapBoundary b;
    b.along_x = z.along_x;
    b.i = z.i;
    b.j = z.j;
    b.low = z.low;
    b.high = z.high;
    points.push_back(numeric::position(m, b));
  }
  return points;
}

/// The map of a drop scene (a [drop] table): the label and the top apex
/// ratio of every grid point (numeric::drop_map()), as a summary, CSV or
/// JSON, and with \p plot its figure.  Exit 1 when a run ended on
/// max_events or on an unsolved collision.
Exit drop_map(const Scene& scene, const numeric::Axis& x, const numeric::Axis& y, const numeric::MapSettings& settings, bool csv, bool json,
             const std::string& plot) {
  const numeric::DropMap m = numeric::drop_map(scene, x, y, settings);
  const std::string precision = settings.precision.name();
  const std::string text = json ? present::drop_map_json(m, scene, precision).dump(1) + "\n"
                           : csv ? present::drop_map_csv(m)
                                 : present::drop_map_summary(m, scene, precision);
  if (!plot.empty()) {
    const std::string stem = plot.substr(plot.find_last_of('/') + 1), title = scene.title.empty() ? scene.origin : scene.title;
    const std::string png = "pngcairo size 1500,760 font 'DejaVu Sans,11'", svg = "svg size 1500,760 dynamic font 'DejaVu Sans,11'";
    write_output(plot + ".dat", present::drop_map_figure_data(m));
    write_output(plot + ".gp", present::drop_map_figure_script(m, title, stem + ".dat", png, "'" + stem + ".png'") +
                                   present::drop_map_figure_script(m, title, stem + ".dat", svg, "'" + stem + ".svg'"));
    render(present::drop_map_figure_script(m, title, plot + ".dat", png, ""), plot + ".png");
    render(present::drop_map_figure_script(m, title, plot + ".dat", svg, ""), plot + ".svg");
  }
  write_output("", text);
  const bool unfinished = std::any_of(m.points.begin(), m.points.end(), [](const numeric::DropPoint& p) { return !numeric::drop_finished(p.end); });
  return unfinished ? numerical_failure : ok;
}

}  // namespace

void add_map(CLI::App& app, Action& action) {
  struct Options {
    std::string scene, x, y, precision = "double", plot, out;
    bool csv = false, json = false, boundary_points = false, overlay = false, stage_times = false;
    int threads = numeric::thread_count(0);
    DistributeOptions distribute;
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
      "--switch-points does, and so is the edge of M positive semi-definite; the boundary points are chained into\n"
      "curves (one per pair of cases, the superball edge, the PSD edge).\n"
      "Output: a summary (cases present with their share of the grid, the superball's share, the curves);\n"
      "--csv: one row per grid point (KEYX, KEYY, psd, case, closed, U1_over_a, superball, status);\n"
      "--boundary-points: the boundary points instead (with --csv as CSV: along, KEYX, KEYY, bracket_width, then\n"
      "psd, case and verdict at each end of the bracket); --json: everything.  --plot PREFIX also draws\n"
      "PREFIX.png and PREFIX.svg with gnuplot (PREFIX.dat and PREFIX.gp beside them redraw it): the case regions\n"
      "in colour (the superball part full, the rest pale), the exact boundary curves, U1+/a with its contours.\n"
      "--overlay derives the conditions of every case present (superball, each contact's opening, each\n"
      "reaction's sign; symbolic, as derive --scene does), locates their zeros exactly on the grid lines and\n"
      "checks that every boundary point lies within the two brackets' widths of a zero of a condition of a case\n"
      "on its sides; it prints the largest distance, draws the zeros on the figure, and writes each\n"
      "disagreement as a scene file into --out DIR (exit 1 when there is one).  It needs the keys among K,\n"
      "alpha, coupling, mass, fall_speed and a rational fall speed.\n"
      "A corner of the grid that a scene file could not hold (g <= 0, a mass <= 0, a contact opening before the\n"
      "collision), one parameter on both axes (in any spelling: K.03-4 is K.3-4, alpha.2 is coupling.1-2/1-4), or a\n"
      "grid where M is nowhere positive semi-definite is refused\n"
      "before anything is written.  The output does not depend on --threads.\n"
      "Memory: a grid whose points and output would not fit in what this process may still allocate (MemAvailable,\n"
      "ulimit -v) is refused at once with the estimate (docs/MAPS.md), except the grid alone as --csv, which is then\n"
      "written as it is computed.\n"
      "Over MPI (`mpirun -n P superball map ...`, built with -DSUPERBALL_WITH_MPI=ON) the grid points, then the\n"
      "bisections, are handed out to the ranks as tasks (each on --threads threads); rank 0 writes the same bytes\n"
      "as one process (and draws --plot, runs --overlay).  --checkpoint DIR keeps each finished task (DIR/points,\n"
      "then DIR/boundaries; at most 64 of each): the same command run again, also under MPI, computes only those\n"
      "missing and writes the same bytes.  map has no --shard: its bisections need every grid point first.\n"
      "A drop scene (a [drop] table; keys also gap.i) is mapped drop by drop: per point the top body's apex ratio\n"
      "and its label, the sequence of its collisions (docs/DROP.md); the summary lists the labels, --csv gives\n"
      "KEYX, KEYY, top_apex_ratio, events, end, label; no boundary is bisected (no exact solution of one collision),\n"
      "and --overlay, --boundary-points, --checkpoint and MPI are refused.\n\n"
      "Examples:\n"
      "  superball map cases/scenes/paper-fig5-alpha2.toml --x alpha.2=-200:100:121 --y alpha.5=-10:10:81\n"
      "  superball map cases/scenes/paper-4.4-alpha2.toml --x K.3-4=0:20:101 --y alpha.2=-150:0:101 --plot k34-alpha2\n"
      "  superball map cases/scenes/paper-4.4-alpha2.toml --x K.3-4=0:20:41 --y alpha.2=-150:0:41 --overlay\n"
      "  superball map cases/scenes/paper-4.4-alpha2.toml --x K.3-4=0:20:41 --y alpha.2=-150:0:41 --boundary-points --csv\n"
      "  superball map cases/scenes/drop-three-balls.toml --x gap.1=0:0.004:21 --y gap.2=0:0.004:21");
  cmd->add_option("scene", o->scene, "Scene file (TOML)")->required();
  cmd->add_option("--x", o->x, "KEY=FROM:TO:N, the horizontal axis")->required();
  cmd->add_option("--y", o->y, "KEY=FROM:TO:N, the vertical axis")->required();
  cmd->add_option("--precision,-p", o->precision, "Arithmetic of the grid points (see solve; boundaries are always exact)")
      ->capture_default_str();
  cmd->add_flag("--csv", o->csv, "Print CSV: one row per grid point (or per boundary point with --boundary-points)");
  cmd->add_flag("--json", o->json, "Print JSON for programs: axes, points, boundary points, curves (and the overlay)");
  cmd->add_flag("--boundary-points", o->boundary_points, "Print the boundary points instead of the grid (CSV with --csv)");
  cmd->add_option("--plot", o->plot, "Also draw the map into PREFIX.png and PREFIX.svg (with PREFIX.dat, PREFIX.gp)")
      ->check(non_empty());
  cmd->add_flag("--overlay", o->overlay, "Derive each case's conditions and compare their zeros with the exact boundaries");
  cmd->add_option("--out", o->out, "With --overlay: write each disagreeing boundary point as a scene file in this folder")
      ->check(non_empty());
  cmd->add_option("--threads,-j", o->threads, "Worker threads (default and 0: all cores; at most " + std::to_string(numeric::max_threads) + ")")
      ->capture_default_str();
  add_distribute_options(cmd, o->distribute, "group of grid points (then of bisections)", false);
  cmd->add_flag("--stage-times", o->stage_times, "After the run, say on standard error the wall and CPU time of each stage")->group("");
  cmd->callback([o, cmd, &action] {
    action = [o, cmd] {
      StageTimes times(o->stage_times);
      if (o->csv && o->json) throw std::invalid_argument("map: --csv and --json: choose one");
      if (!o->distribute.shard.empty() || !o->distribute.part.empty())
        throw std::invalid_argument(std::string("map: ") + (o->distribute.shard.empty() ? "--part" : "--shard") +
                                    ": a map is not split into shards (its bisections need every grid point first); run it over MPI ranks, or resume it with --checkpoint");
      if (!o->out.empty() && !o->overlay) throw std::invalid_argument("map: --out writes the disagreements of --overlay; add --overlay");
      if (!o->out.empty() && std::filesystem::exists(o->out) && !std::filesystem::is_directory(o->out))
        throw OutputError("--out " + o->out + ": exists and is not a folder");
      const Scene scene = load_scene(o->scene);
      const numeric::Range rx = numeric::parse_range("--x", o->x, scene, numeric::map_max_steps);
      const numeric::Range ry = numeric::parse_range("--y", o->y, scene, numeric::map_max_steps);
      numeric::MapSettings settings;
      settings.precision = numeric::Precision::parse(o->precision);
      settings.threads = o->threads;
      settings.check();  // before any output (the grid alone as CSV is streamed)
      // Under MPI every rank takes part in the map (its grid points, then its
      // bisections, handed out as tasks) and holds the whole map after it;
      // rank 0 alone goes on (overlay, output, figures).  Each of the two
      // stages is a task list of its own, with its checkpoint subfolder.
      const numeric::Axis ax{rx.parameter, rx.from, rx.to, rx.steps}, ay{ry.parameter, ry.from, ry.to, ry.steps};
      if (scene.drop.requested) {
        if (o->overlay) numeric::refuse_drop(scene, "overlay");
        if (o->boundary_points) numeric::refuse_drop(scene, "boundary_points");
        if (mpi_size() > 1 || !o->distribute.checkpoint.empty()) numeric::refuse_distributed_drop(scene, "map");
        return drop_map(scene, ax, ay, settings, o->csv, o->json, o->plot);
      }
      int stage = 0;
      if (mpi_size() > 1 || !o->distribute.checkpoint.empty())
        settings.runner = [&](std::size_t count, const Distribution::Task& task) {
          DistributeOptions options;
          if (!o->distribute.checkpoint.empty())
            options.checkpoint = (std::filesystem::path(o->distribute.checkpoint) / (stage == 0 ? "points" : "boundaries")).string();
          ++stage;
          // The run as both fronts name it: Python's map(checkpoint=) takes this folder, and this command Python's.
          Distribution run(distribute::map_identity(scene, ax, ay, settings.precision), distribute_options(options), count);
          return run.run_everywhere(task);
        };
      // What the output holds beside the map, in the estimate of map(), which refuses a map that would not fit.
      using present::MapOutput;
      settings.output_bytes_per_point =
          present::map_output_bytes_per_point(o->json ? MapOutput::Json : o->csv && !o->boundary_points ? MapOutput::Csv : MapOutput::Summary) +
          (o->plot.empty() ? 0 : present::map_output_bytes_per_point(MapOutput::Figure));
      // The grid alone as CSV needs no boundaries: when it is too large to hold, its rows are written as they are computed.
      if (o->csv && !o->boundary_points && o->plot.empty() && !o->overlay && !settings.runner && !settings.fits(ax, ay)) {
        Output out("");
        out.write(present::map_csv_header(ax, ay));
        numeric::map_points(scene, ax, ay, settings, stream_block,
                            [&](std::size_t first, const std::vector<numeric::MapPoint>& points) {
                              present::write_csv_rows(ax, ay, first, points, settings.threads, [&](std::string_view rows) { out.write(rows); });
                            });
        out.commit();
        return ok;
      }
      times.end("setup");
      settings.stage_end = [&](const char* stage) { times.end(stage); };
      const numeric::Map m = numeric::map(scene, ax, ay, settings);
      if (mpi_rank() != 0) return ok;
      std::optional<verify::Overlay> overlay;
      if (o->overlay) overlay = verify::overlay(scene, m, settings.bits);
      const std::string precision = settings.precision.name();
      // The grid as CSV or JSON is formatted on the threads and written as it comes, after the figure and the scene files.
      const bool grid_text = o->json || (o->csv && !o->boundary_points);
      std::string text;
      if (o->csv && o->boundary_points) {
        text = present::boundaries_csv(m);
      } else if (!grid_text) {
        text = present::map_summary(m, scene, precision);
        if (overlay) text += present::to_text(*overlay, m);
        if (o->boundary_points) {
          text += "boundary points (the middle of the bracket on the axis named, the grid value on the other):\n";
          for (const auto& b : m.boundaries) {
            const auto [x, y] = numeric::position(m, b);
            auto side = [](bool psd, const numeric::Region& r) {
              return psd ? "case " + present::case_name(r) + (r.superball ? " superball" : "") : std::string("M not PSD");
            };
            text += "  along " + (b.along_x ? rx.parameter.key() : ry.parameter.key()) + ": (" + numeric::to_string(x, 12) + ", " +
                    numeric::to_string(y, 12) + ")  width " + numeric::to_string(cln::double_approx(b.high - b.low), 3) + "  " +
                    side(b.below_psd, b.below) + " -> " + side(b.above_psd, b.above) + "\n";
          }
        }
      }
      int written = 0;
      if (overlay && !o->out.empty())
        for (const verify::OverlayMatch& match : overlay->matches) {
          if (match.agrees()) continue;
          if (written == 0) {
            std::error_code error;
            std::filesystem::create_directories(o->out, error);
            if (error) throw OutputError("--out " + o->out + ": cannot create the folder: " + error.message());
          }
          const std::string n = std::to_string(++written);
          const std::string path = (std::filesystem::path(o->out) / ("map-disagreement-" + std::string(n.size() < 4 ? 4 - n.size() : 0, '0') + n + ".toml")).string();
          write_output(path, write_scene(overlay->scene_at(scene, m, match),
                                         "superball map --overlay: a boundary point of the exact solutions with no derived zero within the\n"
                                         "brackets' widths (see the summary); rerun: superball solve " + path + " --precision exact"));
        }
      if (!o->plot.empty())
        draw_map(o->plot, m, scene.title.empty() ? scene.origin : scene.title, {}, overlay ? derived_points(*overlay, m) : std::vector<std::pair<double, double>>{});
      if (written && !o->json && !o->csv) text += std::to_string(written) + " scene files written to " + o->out + "\n";
      if (grid_text) {
        Output out("");
        const present::TextSink sink = [&](std::string_view piece) { out.write(piece); };
        if (o->json) {
          nlohmann::ordered_json extra = nlohmann::ordered_json::object();
          if (overlay) extra["overlay"] = present::to_json(*overlay, m);
          present::write_map_json(m, scene, precision, extra, settings.threads, sink);
        } else {
          present::write_map_csv(m, settings.threads, sink);
        }
        out.commit();
      } else {
        write_output("", text);
      }
      times.end("output");
      if (!overlay || overlay->agrees()) return ok;
      std::cerr << "superball: the derived conditions disagree with the exact boundaries at some points (see the overlay"
                << (o->out.empty() ? "; --out DIR writes them as scene files)\n" : ")\n");
      return numerical_failure;
    };
  });
}

}  // namespace superball::cli
