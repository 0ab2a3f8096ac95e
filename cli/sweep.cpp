#include <algorithm>
#include <memory>
#include <optional>
#include <set>
#include <string_view>
#include <tuple>

#include "commands.hpp"
#include "distribute.hpp"
#include "superball/cases/scene_file.hpp"
#include "superball/cases/vocabulary.hpp"
#include "superball/numeric/parallel.hpp"
#include "superball/numeric/range.hpp"
#include "superball/numeric/sweep.hpp"
#include "superball/present/sweep.hpp"

namespace superball::cli {
namespace {

using numeric::Range;

std::string decimal(const cln::cl_RA& x, int digits = 17) { return numeric::to_decimal(x, digits); }

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

/// Task \p k of the switch points, in increasing value of the parameter
/// whatever the direction of the range (the values are the same): values
/// k * kChunk … (k + 1) * kChunk, each block starting at the last value of
/// the one before, so that a change between two blocks is found.
std::string switch_block(std::size_t k, const Scene& scene, const Range& r, bool csv, int threads) {
  const cln::cl_RA& low = r.from < r.to ? r.from : r.to;
  const cln::cl_RA& high = r.from < r.to ? r.to : r.from;
  const int first = static_cast<int>(k) * kChunk;
  const auto values = numeric::linspace(low, high, r.steps, first, std::min(kChunk + 1, r.steps - first));
  return present::switch_rows(r.parameter.key(), numeric::switch_points(scene, r.parameter, values, 64, threads), csv);
}

/// Whether \p name is the name of a case of a scene of \p n bodies
/// (Vocabulary::case_name() of one of its contact sets); the set in \p set.
bool case_of_scene(const std::string& name, int n, ContactSet& set) {
  const Vocabulary& v = Vocabulary::paper();
  if (name.size() >= 2 && name.front() == '{' && name.back() == '}') {
    try {
      set = ContactSet::parse(name.substr(1, name.size() - 2), n);
    } catch (const std::exception&) {
      return false;
    }
    return v.case_name(set) == name;
  }
  for (const NamedCase& c : v.cases())
    if (c.name == name && c.closed.bodies() == n) return set = c.closed, true;
  return false;
}

/// The fields of \p line split at each \p sep ("," or two spaces), into
/// \p out (reused: no allocation per row); a CSV field in quotes
/// ("{1-2,2-3}", no quote inside) kept whole, without its quotes.
void fields(std::string_view line, std::string_view sep, std::vector<std::string_view>& out) {
  out.clear();
  std::size_t start = 0;
  bool quoted = false;
  for (std::size_t k = 0; k <= line.size(); ++k) {
    if (k < line.size() && sep == "," && line[k] == '"') {
      quoted = !quoted;
    } else if (k == line.size() || (!quoted && line.compare(k, sep.size(), sep) == 0)) {
      std::string_view f = line.substr(start, k - start);
      if (f.size() >= 2 && f.front() == '"' && f.back() == '"') f = f.substr(1, f.size() - 2);
      out.push_back(f);
      start = k + sep.size();
      k += sep.size() - 1;
    }
  }
}

/// A number printed by the sweep: the whole of \p text; nullopt otherwise.
std::optional<double> number(const std::string& text) {
  char* end = nullptr;
  const double v = text.empty() ? 0 : std::strtod(text.c_str(), &end);
  if (text.empty() || *end) return std::nullopt;
  return v;
}

/// Reads back task \p k's text of the rows (rows_block()) or the switch
/// points (switch_block()) as data and checks it against the run: the rows
/// of the block (their count, fields, cases of this scene, statuses, the
/// count of failures), the switch points inside the block's range with cases
/// of this scene that differ.  Returns the number of failures (rows) and
/// leaves the text to write; std::invalid_argument naming the task (\p run
/// says where it came from) otherwise.
int check_block(std::size_t k, std::string& text, const Scene& scene, const Range& r, bool csv, bool switches, const Distribution& run) {
  auto damaged = [&](const std::string& what) { return std::invalid_argument(run.origin(k) + ": a damaged result (" + what + ")"); };
  const int n = scene.size();
  const std::string sep = csv ? "," : "  ";
  const int first = static_cast<int>(k) * kChunk;
  std::set<std::string, std::less<>> cases;  // the names already found to be cases of this scene
  ContactSet set;
  auto check_case = [&](std::string_view name) {
    if (cases.count(name)) return;
    if (!case_of_scene(std::string(name), n, set)) throw damaged("'" + std::string(name.substr(0, 40)) + "' is not a case of this scene");
    cases.emplace(name);
  };
  std::vector<std::string_view> f;
  std::size_t at = 0;
  int failures = 0, expected = 0;
  if (!switches) {
    const std::size_t eol = text.find('\n');
    const std::optional<double> count = eol == std::string::npos ? std::nullopt : number(text.substr(0, eol));
    if (!count || !(*count >= 0 && *count <= kChunk) || *count != static_cast<int>(*count)) throw damaged("no count of failures");
    expected = static_cast<int>(*count);
    at = eol + 1;
  }
  const cln::cl_RA& low = r.from < r.to ? r.from : r.to;
  const cln::cl_RA& high = r.from < r.to ? r.to : r.from;
  const int size = switches ? std::min(kChunk + 1, r.steps - first) : std::min(kChunk, r.steps - first);
  const auto ends = numeric::linspace(low, high, r.steps, first, 1), last = numeric::linspace(low, high, r.steps, first + size - 1, 1);
  const double lo = cln::double_approx(ends.at(0)), hi = cln::double_approx(last.at(0)), slack = 1e-12 * std::max({std::abs(lo), std::abs(hi), hi - lo});
  int rows = 0;
  const std::set<std::string, std::less<>> statuses = {numeric::to_string(numeric::Status::Success), numeric::to_string(numeric::Status::NumericalIssue),
                                                       numeric::to_string(numeric::Status::NoConvergence)};
  while (at < text.size()) {
    const std::size_t eol = text.find('\n', at);
    if (eol == std::string::npos) throw damaged("its last line is cut");
    const std::string_view line = std::string_view(text).substr(at, eol - at);
    at = eol + 1;
    ++rows;
    if (!switches) {  // VALUE U1 … Un CASE [STATUS]: the case and the status checked
      fields(line, sep, f);
      const auto fn = static_cast<std::size_t>(n);
      if (f.size() != fn + 3 && (csv || f.size() != fn + 2)) throw damaged("a row of the wrong fields");
      check_case(f[fn + 1]);
      if (f.size() == fn + 3) {
        if (!statuses.count(f.back()) || (!csv && f.back() == "success")) throw damaged("'" + std::string(f.back().substr(0, 40)) + "' is not a status");
        failures += f.back() != "success";
      }
      continue;
    }
    // AT  (bracket width W): case B {..} -> case A {..}, or AT,W,B,A.
    std::string below, above, where, width;
    if (csv) {
      fields(line, ",", f);
      if (f.size() != 4) throw damaged("a switch point of the wrong fields");
      where = std::string(f[0]), width = std::string(f[1]), below = std::string(f[2]), above = std::string(f[3]);
    } else {
      const std::string key = r.parameter.key() + " = ", mid = "  (bracket width ", cases_at = "): case ", arrow = " -> case ";
      const std::size_t m = line.find(mid), c = line.find(cases_at), a = line.find(arrow);
      if (line.rfind(key, 0) != 0 || m == std::string::npos || c == std::string::npos || a == std::string::npos || !(key.size() <= m && m < c && c < a))
        throw damaged("a switch point of the wrong form");
      where = std::string(line.substr(key.size(), m - key.size()));
      width = std::string(line.substr(m + mid.size(), c - m - mid.size()));
      for (auto [from, to, name] : {std::make_tuple(c + cases_at.size(), a, &below), std::make_tuple(a + arrow.size(), line.size(), &above)}) {
        const std::string both(line.substr(from, to - from));
        const std::size_t space = both.find(' ');
        *name = both.substr(0, space);
        check_case(*name);
        case_of_scene(*name, n, set);
        if (space == std::string::npos || both.substr(space + 1) != set.to_string()) throw damaged("'" + both.substr(0, 40) + "' is not a case and its contacts");
      }
    }
    check_case(below);
    check_case(above);
    if (below == above) throw damaged("a switch point between a case and itself");
    const std::optional<double> x = number(where), w = number(width);
    if (!x || !(*x >= lo - slack && *x <= hi + slack))
      throw damaged("a switch point at " + where.substr(0, 40) + ", outside the values of its block (" + decimal(ends.at(0)) + " to " + decimal(last.at(0)) + ")");
    if (!w || !(*w > 0 && *w <= hi - lo + slack)) throw damaged("a bracket width of " + width.substr(0, 40));
  }
  if (!switches && (rows != size || failures != expected)) throw damaged("not the rows of its block");
  return failures;
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
