#include <algorithm>
#include <memory>
#include <optional>
#include <sstream>

#include "commands.hpp"
#include "distribute.hpp"
#include "superball/cases/scene_file.hpp"
#include "superball/cases/vocabulary.hpp"
#include "superball/numeric/parallel.hpp"
#include "superball/numeric/range.hpp"
#include "superball/numeric/sweep.hpp"

namespace superball::cli {
namespace {

using numeric::Range;

std::string decimal(const cln::cl_RA& x, int digits = 17) { return numeric::to_decimal(x, digits); }

/// Values solved between two writes: a sweep's memory does not grow with STEPS.
constexpr int kChunk = 4096;

/// A CSV field, quoted (RFC 4180) when it holds a comma or a quote: the case
/// of a scene of other than 4 bodies is its closed contacts, "{1-2,2-3}".
std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"") == std::string::npos) return text;
  std::string q = "\"";
  for (char c : text) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

/// The header of the table (or CSV) of the velocities after the collision.
std::string rows_header(const Scene& scene, const Range& r, bool csv) {
  const std::string sep = csv ? "," : "  ";
  std::ostringstream os;
  os << r.parameter.key();
  for (int i = 1; i <= scene.size(); ++i) os << sep << "U" << i;
  os << sep << "case" << (csv ? ",status\n" : "\n");
  return os.str();
}

/// The number of tasks of a sweep: blocks of \p kChunk values (rows), or of
/// kChunk + 1 values overlapping by one (switch points).
std::size_t sweep_tasks(const Range& r, bool switches) {
  const int span = switches ? r.steps - 1 : r.steps;
  return span <= 0 ? 0 : static_cast<std::size_t>((span + kChunk - 1) / kChunk);
}

/// Task \p k of the rows: the number of rows whose status is not success,
/// a newline, then the rows of values k * kChunk onwards, in the sweep's order.
std::string rows_block(std::size_t k, const Scene& scene, const Range& r, const numeric::Precision& precision, bool csv, int threads) {
  const Vocabulary& v = Vocabulary::paper();
  const std::string sep = csv ? "," : "  ";
  const int first = static_cast<int>(k) * kChunk;
  std::ostringstream os;
  int failures = 0;
  const auto values = numeric::linspace(r.from, r.to, r.steps, first, std::min(kChunk, r.steps - first));
  for (const auto& p : numeric::sweep(scene, r.parameter, values, precision, threads)) {
    os << decimal(p.value, 10);
    for (double w : p.velocities_after) os << sep << numeric::to_string(w, csv ? 17 : 8);
    os << sep << (csv ? csv_field(v.case_name(p.closed)) : v.case_name(p.closed));
    failures += p.status != numeric::Status::Success;
    // CSV: every row has the header's fields; the table names only a status that is not success.
    if (csv || p.status != numeric::Status::Success) os << sep << numeric::to_string(p.status);
    os << '\n';
  }
  return std::to_string(failures) + "\n" + os.str();
}

/// Task \p k of the switch points, in increasing value of the parameter
/// whatever the direction of the range (the values are the same): values
/// k * kChunk … (k + 1) * kChunk, each block starting at the last value of
/// the one before, so that a change between two blocks is found.
std::string switch_block(std::size_t k, const Scene& scene, const Range& r, bool csv, int threads) {
  const Vocabulary& v = Vocabulary::paper();
  const cln::cl_RA& low = r.from < r.to ? r.from : r.to;
  const cln::cl_RA& high = r.from < r.to ? r.to : r.from;
  const int first = static_cast<int>(k) * kChunk;
  std::ostringstream os;
  const auto values = numeric::linspace(low, high, r.steps, first, std::min(kChunk + 1, r.steps - first));
  for (const auto& s : numeric::switch_points(scene, r.parameter, values, 64, threads)) {
    const std::string at = decimal((s.low + s.high) / 2), width = decimal(s.high - s.low, 3);
    if (csv)
      os << at << ',' << width << ',' << csv_field(v.case_name(s.below)) << ',' << csv_field(v.case_name(s.above)) << '\n';
    else
      os << r.parameter.key() << " = " << at << "  (bracket width " << width << "): case " << v.case_name(s.below) << " "
         << s.below.to_string() << " -> case " << v.case_name(s.above) << " " << s.above.to_string() << '\n';
  }
  return os.str();
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
      "printed.  Rows are printed as they are solved, a few thousand at a time.\n"
      "--switch-points bisects on the exact solution (CLN rationals) between sweep values whose evolution\n"
      "case differs, to 64 bits below the step, and prints every change in increasing KEY; with --csv, as\n"
      "CSV: KEY (the middle of the bracket), bracket_width, case_below, case_above.  The values are solved on\n"
      "--threads threads (default: all cores); the output does not depend on the number of threads.\n"
      "Clusters (docs/CLUSTER.md): the values are solved in blocks of " + std::to_string(kChunk) + " (the tasks): under MPI\n"
      "(`mpirun -n P superball sweep ...`, built with -DSUPERBALL_WITH_MPI=ON) the ranks take blocks as they\n"
      "become free, each on its --threads, and rank 0 writes; --shard I/N solves the blocks k with k mod N = I-1\n"
      "into a part file for `superball merge`; --checkpoint DIR keeps each finished block.  Same bytes every way.\n\n"
      "Examples:\n"
      "  superball sweep cases/scenes/paper-4.4-alpha2.toml --vary K.3-4=0:20:401 --csv\n"
      "  superball sweep cases/scenes/paper-4.4-alpha2.toml --vary K.3-4=0:20:41 --switch-points");
  cmd->add_option("scene", o->scene, "Scene file (TOML)")->required();
  cmd->add_option("--vary", o->vary, "KEY=FROM:TO:STEPS")->required();
  cmd->add_option("--precision,-p", o->precision, "Arithmetic of the sweep values (see solve; not with --switch-points, which is exact)")->capture_default_str();
  cmd->add_flag("--csv", o->csv, "Print CSV: the parameter, U1..Un, the case, the status (or the switch points)");
  cmd->add_flag("--switch-points", o->switches, "Print only the parameter values where the evolution case changes (as CSV with --csv)");
  cmd->add_option("--threads,-j", o->threads, "Worker threads (default: all cores)")
      ->check(CLI::Range(1, 1024))
      ->capture_default_str();
  add_distribute_options(cmd, o->distribute, "block of " + std::to_string(kChunk) + " value");
  cmd->callback([o, cmd, &action] {
    action = [o, cmd] {
      const Scene scene = load_scene(o->scene);
      const Range r = numeric::parse_range("--vary", o->vary, scene, numeric::sweep_max_steps);
      if (o->switches && cmd->count("--precision") > 0)
        throw std::invalid_argument("sweep: --switch-points bisects on the exact solution; --precision does not apply to it");
      const auto precision = numeric::Precision::parse(o->precision);
      numeric::check_range(scene, r.parameter, r.from, r.to);  // every value, before any output
      const std::size_t count = sweep_tasks(r, o->switches);
      Distribution run(*cmd, o->distribute, count);
      std::optional<Output> out;
      if (run.writes_output()) out.emplace("");
      int failures = 0;
      bool any = false;
      if (out && !o->switches) out->write(rows_header(scene, r, o->csv));
      if (out && o->switches && o->csv) out->write(r.parameter.key() + ",bracket_width,case_below,case_above\n");
      run.run(
          [&](std::size_t k) {
            return o->switches ? switch_block(k, scene, r, o->csv, o->threads) : rows_block(k, scene, r, precision, o->csv, o->threads);
          },
          [&](std::size_t, std::string&& text) {
            if (!o->switches) {
              const std::size_t eol = text.find('\n');
              failures += std::stoi(text.substr(0, eol));
              text.erase(0, eol + 1);
            }
            any = any || !text.empty();
            out->write(text);
          });
      if (!out) return ok;  // a part file, or a rank other than 0
      if (o->switches && !any && !o->csv) out->write("no change of evolution case for " + r.parameter.key() + " in the range\n");
      out->commit();
      return failures ? numerical_failure : ok;
    };
  });
}

}  // namespace superball::cli
