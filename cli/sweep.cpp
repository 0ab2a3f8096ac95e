#include <algorithm>
#include <memory>
#include <optional>
#include <string_view>

#include "commands.hpp"
#include "distribute.hpp"
#include "superball/cases/scene_file.hpp"
#include "superball/numeric/parallel.hpp"
#include "superball/numeric/range.hpp"
#include "superball/numeric/sweep.hpp"
#include "superball/present/sweep.hpp"

namespace superball::cli {
namespace {

using numeric::Range;

/// Values solved between two writes: a sweep's memory does not grow with STEPS.
constexpr int kChunk = 4096;

/// The number of tasks of a sweep: blocks of \p kChunk values (rows), or of
/// kChunk + 1 values overlapping by one (switch points).
std::size_t sweep_tasks(const Range& r, bool switches) {
  const int span = switches ? r.steps - 1 : r.steps;
  return span <= 0 ? 0 : static_cast<std::size_t>((span + kChunk - 1) / kChunk);
}

/// Task \p k of the rows: the number of rows whose status is not success,
/// a newline, then the rows of values k * kChunk onwards
/// (present::write_sweep_rows()), solved and formatted on \p threads threads.
std::string rows_block(std::size_t k, const Scene& scene, const Range& r, const numeric::Precision& precision, bool csv, int threads) {
  const int first = static_cast<int>(k) * kChunk;
  const auto values = numeric::linspace(r.from, r.to, r.steps, first, std::min(kChunk, r.steps - first));
  const auto points = numeric::sweep(scene, r.parameter, values, precision, threads);
  const auto failures = std::count_if(points.begin(), points.end(), [](const numeric::SweepPoint& p) { return p.status != numeric::Status::Success; });
  std::string text = std::to_string(failures) + "\n";
  present::write_sweep_rows(r, static_cast<std::size_t>(first), points, csv, threads, [&](std::string_view rows) { text += rows; });
  return text;
}

/// The values of task \p k of the switch points, in increasing value of the
/// parameter whatever the direction of the range (the values are the same):
/// values k * kChunk … (k + 1) * kChunk, each block starting at the last
/// value of the one before, so that a change between two blocks is found.
std::vector<cln::cl_RA> switch_values(std::size_t k, const Range& r) {
  const cln::cl_RA& low = r.from < r.to ? r.from : r.to;
  const cln::cl_RA& high = r.from < r.to ? r.to : r.from;
  const int first = static_cast<int>(k) * kChunk;
  return numeric::linspace(low, high, r.steps, first, std::min(kChunk + 1, r.steps - first));
}

/// Task \p k of the switch points: those between switch_values(k, r).
std::string switch_block(std::size_t k, const Scene& scene, const Range& r, bool csv, int threads) {
  return present::switch_rows(r.parameter.key(), numeric::switch_points(scene, r.parameter, switch_values(k, r), 64, threads), csv);
}

/// Reads back task \p k's text of the rows (rows_block()) or the switch
/// points (switch_block()), read from a file (a checkpoint, a part), and
/// checks it against the run: its count of failures and the rows of the
/// block (present::check_sweep_rows()), or the switch points inside the
/// block's range (present::check_switch_rows()).  Returns the number of
/// failures (rows); std::invalid_argument naming the task (\p run says where
/// it came from) otherwise.
int check_block(std::size_t k, const std::string& text, const Scene& scene, const Range& r, bool csv, bool switches, const Distribution& run) {
  const int first = static_cast<int>(k) * kChunk;
  try {
    if (switches) {
      const std::vector<cln::cl_RA> values = switch_values(k, r);
      present::check_switch_rows(text, r.parameter.key(), scene.size(), values.front(), values.back(), csv);
      return 0;
    }
    const std::size_t eol = text.find('\n');
    const std::string count = text.substr(0, eol == std::string::npos ? 0 : eol);
    if (count.empty() || count.size() > 4 || count.find_first_not_of("0123456789") != std::string::npos || std::stoi(count) > kChunk)
      throw std::invalid_argument("a damaged result (no count of failures)");
    const int failures = present::check_sweep_rows(std::string_view(text).substr(eol + 1), scene.size(), static_cast<std::size_t>(std::min(kChunk, r.steps - first)), csv);
    if (failures != std::stoi(count)) throw std::invalid_argument("a damaged result (not the rows of its block)");
    return failures;
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(run.origin(k) + ": " + e.what());
  }
}

/// The sweep of a drop scene (a [drop] table): per value, the top body's
/// apex ratio, the number of collisions, why the run ended and its label
/// (numeric::drop_label()), printed a block of kChunk values at a time.
/// Exit 1 when a run ended on max_events or on an unsolved collision.
Exit drop_rows(const Scene& scene, const Range& r, const numeric::Precision& precision, bool csv, int threads) {
  (void)numeric::drop_sweep(scene, r.parameter, {r.from, r.to}, precision, 1);  // every check of the range, before any output
  Output out("");
  out.write(present::drop_sweep_header(r.parameter.key(), csv));
  bool failed = false;
  for (int first = 0; first < r.steps; first += kChunk) {
    const auto values = numeric::linspace(r.from, r.to, r.steps, first, std::min(kChunk, r.steps - first));
    const auto points = numeric::drop_sweep(scene, r.parameter, values, precision, threads);
    for (const numeric::DropPoint& p : points) failed = failed || !numeric::drop_finished(p.end);
    out.write(present::drop_rows(values, points, csv));
  }
  out.commit();
  return failed ? numerical_failure : ok;
}

}  // namespace

void add_sweep(CLI::App& app, Action& action) {
  struct Options {
    std::string scene, vary, precision = "double";
    DistributeOptions distribute;
    bool csv = false, switches = false;
    int threads = numeric::thread_count(0);
  };
  auto o = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand("sweep", "Velocities after the collision along one parameter, and where the case changes");
  cmd->footer(
      "KEY names a parameter: K.i-j, alpha.k (n = 4), coupling.i-j/k-l, mass.i, velocity.i, drop_height,\n"
      "fall_speed, g; every spelling of one entry is one parameter (K.03-4 is K.3-4, coupling.1-4/1-2 is\n"
      "coupling.1-2/1-4 and, n = 4, alpha.2), printed by its canonical key.  FROM and TO are any numbers a\n"
      "scene file takes (integers of any size, decimals, fractions; exact), in either order; STEPS counts the values,\n"
      "ends included.  A range holding a value a scene file could not hold (g <= 0, a mass <= 0, M not\n"
      "positive semi-definite, a contact opening before the collision, ...) is refused before anything is\n"
      "printed, with one line.  Rows are printed as they are solved, a few thousand at a time.  `map` and\n"
      "Python's sweep() mark the values where M is not positive semi-definite instead, and solve the others.\n"
      "--switch-points bisects on the exact solution (CLN rationals) between sweep values whose evolution\n"
      "case differs, to 64 bits below the step, and prints every change in increasing KEY; with --csv, as\n"
      "CSV: KEY (the middle of the bracket), bracket_width, case_below, case_above.  The values are solved on\n"
      "--threads threads (default: all cores); the output does not depend on the number of threads.\n"
      "Clusters (docs/CLUSTER.md): the values are solved in blocks of " + std::to_string(kChunk) + " (the tasks): under MPI\n"
      "(`mpirun -n P superball sweep ...`, built with -DSUPERBALL_WITH_MPI=ON) the ranks take blocks as they\n"
      "become free, each on its --threads, and rank 0 writes; --shard I/N solves the blocks k with k mod N = I-1\n"
      "into a part file for `superball merge`; --checkpoint DIR keeps each finished block.  Same bytes every way.\n"
      "A drop scene (a [drop] table; keys also gap.i) is swept drop by drop: KEY, top_apex_ratio, events, end and\n"
      "label, the sequence of its collisions (CONTACTS:CASE each, a run of k as *k; docs/DROP.md), in double or\n"
      "long-double, on one process (no --switch-points, --checkpoint, --shard or MPI).\n\n"
      "Examples:\n"
      "  superball sweep cases/scenes/paper-4.4-alpha2.toml --vary K.3-4=0:20:401 --csv\n"
      "  superball sweep cases/scenes/paper-4.4-alpha2.toml --vary K.3-4=0:20:41 --switch-points\n"
      "  superball sweep cases/scenes/drop-three-balls.toml --vary gap.2=0:0.004:5");
  cmd->add_option("scene", o->scene, "Scene file (TOML)")->required();
  cmd->add_option("--vary", o->vary, "KEY=FROM:TO:STEPS")->required();
  cmd->add_option("--precision,-p", o->precision, "Arithmetic of the sweep values (see solve; not with --switch-points, which is exact)")->capture_default_str();
  cmd->add_flag("--csv", o->csv, "Print CSV: the parameter, U1..Un, the case, the status (or the switch points)");
  cmd->add_flag("--switch-points", o->switches, "Print only the parameter values where the evolution case changes (as CSV with --csv)");
  cmd->add_option("--threads,-j", o->threads, "Worker threads (default and 0: all cores; at most " + std::to_string(numeric::max_threads) + ")")
      ->capture_default_str();
  add_distribute_options(cmd, o->distribute, "block of " + std::to_string(kChunk) + " value");
  cmd->callback([o, cmd, &action] {
    action = [o, cmd] {
      const Scene scene = load_scene(o->scene);
      const Range r = numeric::parse_range("--vary", o->vary, scene, numeric::sweep_max_steps);
      if (o->switches && cmd->count("--precision") > 0)
        throw std::invalid_argument("sweep: --switch-points bisects on the exact solution; --precision does not apply to it");
      const auto precision = numeric::Precision::parse(o->precision);
      numeric::check_threads(o->threads);  // before any output, as the range
      if (scene.drop.requested) {
        if (o->switches) numeric::refuse_drop(scene, "switch_points()");
        if (mpi_size() > 1 || !o->distribute.shard.empty() || !o->distribute.part.empty() || !o->distribute.checkpoint.empty())
          numeric::refuse_distributed_drop(scene, "sweep");
        return drop_rows(scene, r, precision, o->csv, o->threads);
      }
      numeric::check_range(scene, r.parameter, r.from, r.to);  // every value, before any output
      const std::size_t count = sweep_tasks(r, o->switches);
      // A block's text: at most kChunk + 1 lines of a few numbers each.
      Distribution run(run_identity(*cmd), distribute_options(o->distribute), count, static_cast<std::uint64_t>(kChunk + 2) * (256 + 64 * static_cast<std::uint64_t>(scene.size())));
      std::optional<Output> out;
      if (run.writes_output()) out.emplace("");
      int failures = 0;
      bool any = false;
      if (out && !o->switches) out->write(present::sweep_header(r.parameter.key(), scene.size(), o->csv));
      if (out && o->switches && o->csv) out->write(present::switch_header(r.parameter.key()));
      // The blocks are solved and formatted on the threads, one a thread, and written in order as they
      // come; a run of fewer blocks than threads spreads each block's values over them instead.  Each
      // task reads the range's ends from their texts: CLN's numbers are not shared between threads.
      const int threads = numeric::thread_count(o->threads);
      const bool blocks_on_threads = run.local() && run.todo().size() >= static_cast<std::size_t>(threads);
      const int inner = blocks_on_threads ? 1 : threads;
      const std::string from = numeric::to_string(r.from), to = numeric::to_string(r.to);
      const Distribution::Local on_threads = [&](const std::vector<std::size_t>& todo, const Distribution::Task& task, const Distribution::Deliver& deliver) {
        numeric::in_order(todo.size(), threads, [&](std::size_t j) { return task(todo[j]); }, deliver);
      };
      run.run(
          [&](std::size_t k) {
            const Range mine{r.parameter, numeric::parse_rational(from), numeric::parse_rational(to), r.steps};
            return o->switches ? switch_block(k, scene, mine, o->csv, inner) : rows_block(k, scene, mine, precision, o->csv, inner);
          },
          [&](std::size_t k, std::string&& text) {
            // A result read from a file (a checkpoint, a part) is checked before it is believed; one computed here is not read again.
            if (run.read_back(k))
              failures += check_block(k, text, scene, r, o->csv, o->switches, run);
            else if (!o->switches)
              failures += std::stoi(text.substr(0, text.find('\n')));
            if (!o->switches) text.erase(0, text.find('\n') + 1);
            any = any || !text.empty();
            out->write(text);
          },
          blocks_on_threads ? on_threads : Distribution::Local());
      if (!out) return ok;  // a part file, or a rank other than 0
      if (o->switches && !any && !o->csv) out->write("no change of evolution case for " + r.parameter.key() + " in the range\n");
      out->commit();
      return failures ? numerical_failure : ok;
    };
  });
}

}  // namespace superball::cli
