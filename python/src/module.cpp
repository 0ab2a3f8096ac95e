// _superball: the C++ side of the Python module `superball` (python/superball
// wraps it in Python's idioms).  A thin front over the libraries, as the
// `superball` command is: every computation is a library call, and what the
// two fronts share (a solution flattened for output, a derivation's JSON, the
// choice of a pattern by name) lives in present/.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cln/dfloat.h>
#include <cln/rational.h>
#include <cln/real.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "checkpoint.hpp"
#include "convert.hpp"
#include "superball/cases/error.hpp"
#include "superball/cases/parameter.hpp"
#include "superball/cases/printed_conditions.hpp"
#include "superball/cases/scene_file.hpp"
#include "superball/cases/vocabulary.hpp"
#include "superball/symbolic/derivation.hpp"
#include "superball/numeric/certify.hpp"
#include "superball/numeric/parallel.hpp"
#include "superball/numeric/sweep.hpp"
#include "superball/present/audit.hpp"
#include "superball/present/derivation.hpp"
#include "superball/present/explore.hpp"
#include "superball/present/selection.hpp"
#include "superball/present/solution.hpp"
#include "superball/present/verification.hpp"
#include "superball/symbolic/format.hpp"
#include "superball/verify/audit.hpp"
#include "superball/verify/explore.hpp"
#include "superball/verify/verification.hpp"
#include "module.hpp"

namespace py = pybind11;

namespace superball::python {
namespace {

/// Exact parameter values of a sweep, made once (from decimal or fraction
/// text, from doubles, or as the command line's linspace) and handed to the
/// library as they are.  CLN objects are not thread-safe (their reference
/// counts are not atomic) and the calls that read them run without the GIL,
/// so two Python threads using the same values take turns on \p lock.
struct Values {
  std::vector<cln::cl_RA> exact;
  std::shared_ptr<std::mutex> lock = std::make_shared<std::mutex>();
};

/// The exact rational value of the finite double \p x.
cln::cl_RA exact_double(double x) {
  if (!std::isfinite(x)) throw std::invalid_argument("values: " + numeric::to_string(x) + " is not a finite number");
  return cln::rational(cln::cl_DF(x));
}

/// The exact value of a number spelled as in a scene file ("0.001", "1/3", "5e6").
cln::cl_RA parse_exact(const std::string& text) { return numeric::parse_rational(Number::parse(text).fraction()); }

/// Values read as a scene file reads numbers ("0.001", "1/3", "5e6").
Values values_from_text(const std::vector<std::string>& texts) {
  Values v;
  v.exact.reserve(texts.size());
  for (const auto& t : texts) {
    try {
      v.exact.push_back(parse_exact(t));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("values: '" + printable(t) + "': " + without_function_prefix(e.what()));
    }
  }
  return v;
}

/// Values that are the doubles of a one-dimensional array, each taken exactly.
Values values_from_doubles(const py::array_t<double, py::array::c_style | py::array::forcecast>& a) {
  if (a.ndim() != 1) throw std::invalid_argument("values: expected a one-dimensional array, got " + std::to_string(a.ndim()) + " dimensions");
  Values v;
  v.exact.reserve(static_cast<std::size_t>(a.size()));
  const double* x = a.data();
  for (py::ssize_t k = 0; k < a.size(); ++k) v.exact.push_back(exact_double(x[k]));
  return v;
}

/// The command line's KEY=FROM:TO:STEPS: numeric::linspace() of exact ends.
Values values_linspace(const std::string& from, const std::string& to, int steps) {
  return Values{numeric::linspace(parse_exact(from), parse_exact(to), steps)};
}

/// The values rounded to double into \p y (size: the values'); call with v.lock held.
void fill_doubles(const Values& v, double* y) {
  for (std::size_t k = 0; k < v.exact.size(); ++k) y[k] = cln::double_approx(v.exact[k]);
}

/// The values rounded to double, as a NumPy array.
py::array_t<double> values_as_doubles(const Values& v) {
  py::array_t<double> out(static_cast<py::ssize_t>(v.exact.size()));
  double* y = out.mutable_data();
  py::gil_scoped_release release;
  const std::lock_guard<std::mutex> hold(*v.lock);
  fill_doubles(v, y);
  return out;
}

/// The values exactly, as "p/q" text.
std::vector<std::string> values_as_text(const Values& v) {
  std::vector<std::string> out;
  out.reserve(v.exact.size());
  py::gil_scoped_release release;
  const std::lock_guard<std::mutex> hold(*v.lock);
  for (const auto& x : v.exact) out.push_back(numeric::to_string(x));
  return out;
}

/// The distinct cases met along a sweep, numbered in the order they are met.
struct CaseTable {
  std::vector<ContactSet> cases;
  /// The number of \p s, added when new; consecutive values mostly share a case, so the last one is tried first.
  std::int32_t code(const ContactSet& s) {
    if (!cases.empty() && cases[static_cast<std::size_t>(last)] == s) return last;
    for (std::size_t k = 0; k < cases.size(); ++k)
      if (cases[k] == s) return last = static_cast<std::int32_t>(k);
    cases.push_back(s);
    return last = static_cast<std::int32_t>(cases.size() - 1);
  }
  /// The paper's names (n = 4) or "{2-3,3-4}", and the closed contacts, by number.
  py::tuple names() const {
    std::vector<std::string> name;
    std::vector<std::vector<std::string>> closed;
    for (const ContactSet& s : cases) {
      name.push_back(Vocabulary::paper().case_name(s));
      closed.push_back(s.closed_names());
    }
    return py::make_tuple(name, closed);
  }

 private:
  std::int32_t last = 0;
};

/// The scene's copy with \p key set to \p value through Parameter::set() (the loader's checks).
Scene with_value(const Scene& scene, const std::string& key, const std::string& value) {
  const Parameter p = Parameter::parse(key, scene);
  Number n;
  try {
    n = Number::parse(value);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(key + " = '" + printable(value) + "': " + without_function_prefix(e.what()));
  }
  Scene copy = scene;
  p.set(copy, n);
  return copy;
}

/// solve(): the flattened solution of `superball solve`; the GIL is released while it solves.
present::Presented solve(const Scene& scene, const std::string& precision, std::optional<double> rtol) {
  const auto p = numeric::SolvePrecision::parse(precision, rtol);
  py::gil_scoped_release release;
  return p.automatic ? present::solve_scene_auto(scene, p.tolerance()) : present::solve_scene(scene, p.fixed);
}

/// sweep(): values, U (one row per value), case numbers into the table of
/// distinct cases (names, closed contacts), status codes, and M PSD per value:
/// numeric::sweep_marking_psd(), which marks the values where M is not PSD
/// (here NaN velocities, case and status −1); the GIL is released while it solves.
/// With a \p checkpoint folder, each chunk is a task kept there (kept_runner()).
py::tuple sweep(const Scene& scene, const std::string& key, const Values& values, const std::string& precision, int threads,
                py::object progress, const std::string& checkpoint) {
  const Parameter parameter = Parameter::parse(key, scene);
  const auto p = numeric::Precision::parse(precision);
  const auto n = static_cast<py::ssize_t>(scene.size());
  const auto count = static_cast<py::ssize_t>(values.exact.size());
  py::array_t<double> x(count);
  py::array_t<double> u({count, n});
  py::array_t<std::int32_t> codes(count);
  py::array_t<std::int8_t> status(count);
  py::array_t<bool> psd(count);
  CaseTable table;
  {
    double* xd = x.mutable_data();
    double* ud = u.mutable_data();
    std::int32_t* cd = codes.mutable_data();
    std::int8_t* sd = status.mutable_data();
    bool* pd = psd.mutable_data();
    std::fill(ud, ud + count * n, std::numeric_limits<double>::quiet_NaN());
    std::fill(cd, cd + count, -1);
    std::fill(sd, sd + count, -1);
    py::gil_scoped_release release;
    const std::lock_guard<std::mutex> hold(*values.lock);
    numeric::TaskRunner runner;
    if (!checkpoint.empty()) {  // the run: the scene, the key, the values exactly, the precision
      std::string exact;
      for (const auto& v : values.exact) exact += numeric::to_string(v) + "\n";
      const auto id = distribute::typed_identity("sweep", {{"key", parameter.key()}, {"precision", p.name()}},
                                                 {{"scene", write_scene(scene)}, {"values", exact}});
      const py::gil_scoped_acquire gil;
      runner = kept_runner(progress, {"values"}, checkpoint, id, numeric::sweep_chunk_values, values.exact.size());
    }
    const std::vector<bool> marked = numeric::sweep_marking_psd(
        scene, parameter, values.exact, p, threads,
        [&](std::size_t k, const numeric::SweepPoint& pt) {
          const auto row = static_cast<py::ssize_t>(k);
          for (py::ssize_t i = 0; i < n; ++i) ud[row * n + i] = pt.velocities_after[static_cast<std::size_t>(i)];
          cd[row] = table.code(pt.closed);
          sd[row] = static_cast<std::int8_t>(pt.status);
        },
        [&](std::size_t done, std::size_t total) { between_tasks(progress, "values", done, total); }, runner);
    std::copy(marked.begin(), marked.end(), pd);
    fill_doubles(values, xd);
  }
  return py::make_tuple(x, u, codes, table.names(), status, psd);
}

/// sweep() of a drop scene (a [drop] table): values, top apex ratios,
/// labels, numbers of collisions and ends, numeric::drop_sweep() a block of
/// numeric::sweep_chunk_values at a time (\p progress told and Ctrl-C
/// checked between blocks), the GIL released while it runs.  A \p checkpoint
/// is refused (numeric::refuse_distributed_drop()).
py::tuple drop_sweep(const Scene& scene, const std::string& key, const Values& values, const std::string& precision, int threads,
                     py::object progress, const std::string& checkpoint) {
  const Parameter parameter = Parameter::parse(key, scene);
  const auto p = numeric::Precision::parse(precision);
  if (!checkpoint.empty()) numeric::refuse_distributed_drop(scene, "sweep");
  const auto count = static_cast<py::ssize_t>(values.exact.size());
  py::array_t<double> x(count), ratio(count);
  py::array_t<std::int32_t> events(count);
  std::vector<std::string> labels, ends;
  double* rd = ratio.mutable_data();
  std::int32_t* ed = events.mutable_data();
  {
    py::gil_scoped_release release;
    const std::lock_guard<std::mutex> hold(*values.lock);
    if (values.exact.empty()) throw std::invalid_argument("drop_sweep(): no value to run");
    // Every check of the range first, as the command's (the smallest and largest value).
    const auto [low, high] = std::minmax_element(values.exact.begin(), values.exact.end());
    (void)numeric::drop_sweep(scene, parameter, {*low, *high}, p, 1);
    const std::size_t total = values.exact.size();
    for (std::size_t first = 0; first < total; first += numeric::sweep_chunk_values) {
      between_tasks(progress, "values", first, total);
      const std::size_t size = std::min(total, first + numeric::sweep_chunk_values) - first;
      const std::vector<cln::cl_RA> chunk(values.exact.begin() + static_cast<std::ptrdiff_t>(first),
                                          values.exact.begin() + static_cast<std::ptrdiff_t>(first + size));
      const auto points = numeric::drop_sweep(scene, parameter, chunk, p, threads);
      for (std::size_t k = 0; k < size; ++k) {
        rd[first + k] = points[k].ratio;
        ed[first + k] = points[k].events;
        labels.push_back(points[k].label);
        ends.push_back(points[k].end);
      }
    }
    between_tasks(progress, "values", total, total);
    fill_doubles(values, x.mutable_data());
  }
  return py::make_tuple(x, ratio, labels, events, ends);
}

/// switch_points(): one tuple per change of case, in increasing value:
/// (low, high, middle as decimal text, bracket width as decimal text, case below and its closed contacts, the same above).
std::vector<py::tuple> switch_points(const Scene& scene, const std::string& key, const Values& values, int bits, int threads) {
  const Parameter parameter = Parameter::parse(key, scene);
  std::vector<numeric::SwitchPoint> found;
  {
    py::gil_scoped_release release;
    const std::lock_guard<std::mutex> hold(*values.lock);
    found = numeric::switch_points(scene, parameter, values.exact, bits, threads);
  }
  std::vector<py::tuple> out;
  for (const auto& s : found)
    out.push_back(py::make_tuple(numeric::to_string(s.low), numeric::to_string(s.high), numeric::to_decimal((s.low + s.high) / 2, 17),
                                 numeric::to_decimal(s.high - s.low, 3), Vocabulary::paper().case_name(s.below), s.below.closed_names(),
                                 Vocabulary::paper().case_name(s.above), s.above.closed_names()));
  return out;
}

}  // namespace

/// The library's selection options from derive()'s keywords (None: not
/// given); alphas and obstacle read by the library's parsers, as the command reads its options.
present::SelectionOptions selection(const py::dict& o) {
  present::SelectionOptions s;
  for (const auto& [k, v] : o) {
    const auto key = k.cast<std::string>();
    if (v.is_none()) continue;
    if (key == "bodies") s.bodies = v.cast<int>();
    else if (key == "order") s.order = v.cast<int>();
    else if (key == "case") s.case_name = v.cast<std::string>();
    else if (key == "closed") s.closed = v.cast<std::string>();
    else if (key == "alphas") s.alphas = present::parse_alphas(v.cast<std::string>());
    else if (key == "coupling") s.coupling = v.cast<std::string>();
    else if (key == "pairs") s.pairs = v.cast<std::string>();
    else if (key == "scene") s.scene = v.cast<std::string>();
    else if (key == "obstacle") s.obstacle = present::parse_obstacle(v.cast<std::string>());
    else if (key == "scaling") s.scaling = v.cast<std::string>();
    else if (key == "all") s.all = v.cast<bool>();
    else throw std::invalid_argument("unknown selection option '" + printable(key) + "'");
  }
  return s;
}

namespace {

/// verify(): per case, to_json(Verification) as Python objects, its report, and whether the exact conditions agree.
/// With a \p checkpoint folder, each case is a task kept there (run_kept()).
std::vector<py::tuple> verify_cases(const py::dict& options, const std::vector<std::string>& epsilons, int samples, int boundary_pairs,
                                    std::uint64_t seed, int threads, const py::object& progress, const std::string& checkpoint) {
  verify::VerifyOptions o;
  if (!epsilons.empty()) {
    o.epsilons.clear();
    for (const auto& e : epsilons) o.epsilons.push_back(verify::parse_epsilon("epsilons", e));
  }
  o.samples = samples;
  o.boundary_pairs = boundary_pairs;
  o.seed = seed;
  o.threads = threads;
  o.check();
  const present::SelectionOptions chosen = selection(options);
  present::require_case(chosen);
  const present::Selection sel = present::resolve(chosen);
  auto verify_at = [&](std::size_t k) {
    o.runner = interruptible_runner(progress, {"drawn points", "boundaries"});  // progress and Ctrl-C between tasks
    return verify::verify_case(*sel.deriver, sel.cases[k], o);
  };
  std::vector<py::tuple> out;
  for (std::size_t k = 0; checkpoint.empty() && k < sel.cases.size(); ++k) {
    const verify::Verification v = verify_at(k);
    out.push_back(py::make_tuple(to_python(present::to_json(v)), present::to_text(v), v.exact_agrees()));
  }
  if (!checkpoint.empty()) {  // the run: the selection as given, the scene's content, the options of the verification
    auto [named, inputs] = selection_run(options);
    for (const cln::cl_RA& e : o.epsilons) named["epsilons"] += (named["epsilons"].empty() ? "" : ",") + verify::epsilon_name(e);
    named["samples"] = std::to_string(samples), named["boundary-pairs"] = std::to_string(boundary_pairs), named["seed"] = std::to_string(seed);
    run_kept(checkpoint, distribute::typed_identity("verify", named, inputs), sel.cases.size(), distribute::kMaxTaskBytes, progress, "cases", 1,
             sel.cases.size(),
             [&](std::size_t k) {
               const verify::Verification v = verify_at(k);
               return verification_text(present::to_json(v), present::to_text(v), v.exact_agrees());
             },
             [&](std::size_t, std::string&& text, const std::string& origin) { out.push_back(read_verification(text, origin)); });
  }
  return out;
}

/// audit(): the JSON of `superball audit --json` as Python objects, and its report.
py::tuple audit(const std::string& epsilon, int samples, std::uint64_t seed) {
  verify::AuditOptions o;
  o.epsilon = verify::parse_epsilon("epsilon", epsilon);
  o.samples = samples;
  o.seed = seed;
  o.check();
  const verify::Audit a = verify::audit_paper(PrintedConditions::paper(), o);
  return py::make_tuple(to_python(present::audit_json(a)), present::to_text(a));
}

/// The text of one task of explore() kept in a checkpoint: the JSON
/// {"json", "text", "scene"} of a case explored (the witness scene as TOML,
/// absent without one), or {"pattern", "cell", "json"} of a cell of the table.
std::string explore_task_text(const verify::ExploreResult& r, bool cell) {
  nlohmann::ordered_json j;
  if (cell) {
    const present::RenderedCell c = present::render(r);
    j["pattern"] = c.pattern;
    j["cell"] = c.text;
    j["json"] = c.json;
  } else {
    j["json"] = present::to_json(r);
    j["text"] = present::to_text(r);
    if (r.scene) j["scene"] = write_scene(*r.scene);
  }
  return j.dump();
}

/// Reads back explore_task_text() of a case (or of a cell) as data;
/// std::invalid_argument("WHERE: a damaged result (…)") when it is not that.
nlohmann::ordered_json read_explore_task(const std::string& text, bool cell, const std::string& where) {
  auto damaged = [&](const std::string& what) { return std::invalid_argument(where + ": a damaged result (" + what + ")"); };
  nlohmann::ordered_json j = nlohmann::ordered_json::parse(text, nullptr, false);
  auto is_string = [&](const char* key) { return j.contains(key) && j[key].is_string(); };
  if (j.is_discarded() || !j.is_object() || !j.contains("json") || !j["json"].is_object() ||
      (cell ? !is_string("pattern") || !is_string("cell") : !is_string("text") || (j.contains("scene") && !is_string("scene"))))
    throw damaged(cell ? "not the JSON of an explored cell" : "not the JSON of an explored case");
  if (!j["json"].contains("reach") || !j["json"]["reach"].is_string()) throw damaged("no verdict");
  return j;
}

/// explore(): per case (or per cell of the table), to_json as Python objects, the report and the witness scene.
/// progress(phase, done, total) ("case NAME", or "cells" for the table) and Ctrl-C as the search goes
/// (ExploreOptions::progress; the GIL is held: GiNaC is not thread-safe).
/// With a \p checkpoint folder, each case (each cell of the table) is a task
/// kept there (run_kept()), told as phase "cases" ("cells") between tasks.
std::vector<py::tuple> explore(const py::dict& options, bool all_patterns, std::uint64_t seed, int starts, int evaluations, double box_low,
                               double box_high, const py::object& progress, const std::string& checkpoint) {
  verify::ExploreOptions o;
  o.seed = seed;
  o.starts = starts;
  o.evaluations = evaluations;
  o.box_low = box_low;
  o.box_high = box_high;
  o.check();
  auto told = [&progress](const std::string& phase) {
    return [&progress, phase](long long done, long long planned) {
      between_tasks(progress, phase, static_cast<std::size_t>(done), static_cast<std::size_t>(planned));
    };
  };
  const present::SelectionOptions chosen = selection(options);
  std::vector<py::tuple> out;
  if (all_patterns) present::check_all_patterns(chosen);
  if (all_patterns && checkpoint.empty()) {
    o.progress = told("cells");
    const verify::PatternTable t = verify::explore_all_patterns(o);
    out.push_back(py::make_tuple(to_python(present::to_json(t)), present::to_text(t)));
    return out;
  }
  std::optional<present::Selection> sel;
  std::vector<ContactSet> cases;
  verify::PatternTable table;
  if (all_patterns) {  // the cells of the table, pattern by pattern, case by case (as the command's tasks)
    table.options = o;
    table.patterns = verify::table_patterns();
    for (const NamedCase& c : Vocabulary::paper().cases()) {
      table.cases.push_back(c.name);
      cases.push_back(c.closed);
    }
  } else {
    present::require_case(chosen, true);
    sel = present::resolve(chosen);
    cases = sel->cases;
  }
  if (checkpoint.empty()) {
    for (const ContactSet& c : cases) {
      o.progress = told("case " + Vocabulary::paper().case_name(c));
      const verify::ExploreResult r = verify::explore_case(*sel->deriver, c, o);
      out.push_back(py::make_tuple(to_python(present::to_json(r)), present::to_text(r), r.scene ? py::cast(*r.scene) : py::none()));
    }
    return out;
  }
  // The run: the selection as given, the scene's content, the options of the search.
  auto [named, inputs] = selection_run(options);
  named["all-patterns"] = all_patterns ? "true" : "false";
  named["seed"] = std::to_string(seed), named["starts"] = std::to_string(starts), named["evaluations"] = std::to_string(evaluations);
  named["box"] = numeric::to_string(box_low) + ":" + numeric::to_string(box_high);
  const std::size_t columns = cases.size(), count = all_patterns ? table.patterns.size() * columns : columns;
  std::map<std::size_t, std::unique_ptr<symbolic::Deriver>> derivers;  // the table's, one per pattern, made when first needed
  auto deriver = [&](std::size_t row) -> const symbolic::Deriver& {
    if (!all_patterns) return *sel->deriver;
    auto& d = derivers[row];
    if (!d) d = std::make_unique<symbolic::Deriver>(symbolic::Pattern::paper(table.patterns[row]), symbolic::Obstacle::Infinite);
    return *d;
  };
  std::vector<std::vector<present::RenderedCell>> cells;
  run_kept(checkpoint, distribute::typed_identity("explore", named, inputs), count, distribute::kMaxTaskBytes, progress,
           all_patterns ? "cells" : "cases", 1, count,
           [&](std::size_t k) {
             verify::ExploreOptions each = o;
             each.progress = told("case " + Vocabulary::paper().case_name(cases[k % columns]));
             return explore_task_text(verify::explore_case(deriver(k / columns), cases[k % columns], each), all_patterns);
           },
           [&](std::size_t k, std::string&& text, const std::string& origin) {
             nlohmann::ordered_json j = read_explore_task(text, all_patterns, origin);
             if (all_patterns) {
               if (k % columns == 0) cells.emplace_back();
               cells.back().push_back({j["pattern"].get<std::string>(), j["cell"].get<std::string>(), j["json"]});
               return;
             }
             py::object scene = py::none();
             if (j.contains("scene")) {
               Scene s = parse_scene(j["scene"].get<std::string>(), origin);
               s.origin = s.title;  // as the search names its witness
               scene = py::cast(std::move(s));
             }
             out.push_back(py::make_tuple(to_python(j["json"]), j["text"].get<std::string>(), scene));
           });
  if (all_patterns) out.push_back(py::make_tuple(to_python(present::to_json(table, cells)), present::to_text(table, cells)));
  return out;
}

/// Translate the library's exceptions: bad input is a ValueError with the
/// command line's one-line message, anything else superball.Error.
void register_errors(py::module_& m) {
  static py::exception<std::runtime_error> error(m, "Error", PyExc_Exception);
  static py::handle input_error = [&] {
    py::object type = py::reinterpret_steal<py::object>(
        PyErr_NewException("_superball.InputError", py::make_tuple(error, py::handle(PyExc_ValueError)).ptr(), nullptr));
    m.attr("InputError") = type;
    return type.release();
  }();
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const py::error_already_set&) {
      throw;  // a Python exception: pybind11 restores it
    } catch (const py::builtin_exception&) {
      throw;  // pybind11's own (a cast that failed: TypeError, …)
    } catch (const InputError& e) {
      PyErr_SetString(input_error.ptr(), printable(e.what()).c_str());
    } catch (const std::invalid_argument& e) {
      PyErr_SetString(input_error.ptr(), printable(without_function_prefix(e.what())).c_str());
    } catch (const std::bad_alloc&) {
      PyErr_SetString(PyExc_MemoryError, "out of memory");
    } catch (const std::exception& e) {
      PyErr_SetString(error.ptr(), ("internal error: " + printable(e.what())).c_str());
    }
  });
}

}  // namespace
}  // namespace superball::python

PYBIND11_MODULE(_superball, m) {
  using namespace superball;
  using namespace superball::python;
  m.doc() = "The C++ side of the Python module superball (use `import superball`).";
  register_errors(m);

  py::class_<Scene>(m, "Scene")
      .def_static("load", &load_scene, py::arg("path"))
      .def_static("parse", &parse_scene, py::arg("text"), py::arg("origin"))
      .def("to_toml", [](const Scene& s, const std::string& comment) { return write_scene(s, comment); }, py::arg("comment") = "")
      .def("with_value", &with_value, py::arg("key"), py::arg("value"))
      .def_property_readonly("title", [](const Scene& s) { return s.title; })
      .def_property_readonly("origin", [](const Scene& s) { return s.origin; })
      .def_property_readonly("bodies", &Scene::size)
      .def_property_readonly("masses", [](const Scene& s) {
        std::vector<std::string> out;
        for (const Body& b : s.bodies) out.push_back(b.infinite ? std::string("inf") : b.mass.fraction());
        return out;
      });

  py::class_<Values>(m, "Values")
      .def_static("from_text", &values_from_text)
      .def_static("from_doubles", &values_from_doubles)
      .def_static("linspace", &values_linspace)
      .def("__len__", [](const Values& v) { return v.exact.size(); })
      .def("as_doubles", &values_as_doubles)
      .def("as_text", &values_as_text);

  py::class_<present::Presented>(m, "Solution")
      .def_readonly("origin", &present::Presented::origin)
      .def_readonly("title", &present::Presented::title)
      .def_readonly("precision", &present::Presented::precision)
      .def_readonly("status", &present::Presented::status)
      .def_readonly("case", &present::Presented::case_name)
      .def_readonly("bodies", &present::Presented::n)
      .def_readonly("pivots", &present::Presented::pivots)
      .def_readonly("fixed_obstacle", &present::Presented::fixed_bottom)
      .def_readonly("superball", &present::Presented::superball)
      .def_readonly("exact", &present::Presented::exact)
      .def_readonly("closed_contacts", &present::Presented::closed)
      .def_readonly("after_text", &present::Presented::after_text)
      .def_readonly("reaction_text", &present::Presented::reaction_text)
      .def_readonly("kinetic_energy_before", &present::Presented::ke_before)
      .def_readonly("kinetic_energy_after", &present::Presented::ke_after)
      .def_readonly("dissipation", &present::Presented::dissipation)
      .def_readonly("momentum_before", &present::Presented::momentum_before)
      .def_readonly("momentum_after", &present::Presented::momentum_after)
      .def_readonly("residual_motion", &present::Presented::residual_motion)
      .def_readonly("residual_complementarity", &present::Presented::residual_complementarity)
      .def_readonly("requested", &present::Presented::requested)
      .def_readonly("error_bound", &present::Presented::error_bound)
      .def_readonly("escalation", &present::Presented::escalation)
      .def_readonly("warnings", &present::Presented::warnings)
      .def_property_readonly("masses", [](const present::Presented& p) { return py::array_t<double>(p.masses.size(), p.masses.data()); })
      .def_property_readonly("before", [](const present::Presented& p) { return py::array_t<double>(p.before.size(), p.before.data()); })
      .def_property_readonly("after", [](const present::Presented& p) { return py::array_t<double>(p.after.size(), p.after.data()); })
      .def_property_readonly("reactions", [](const present::Presented& p) { return py::array_t<double>(p.reactions.size(), p.reactions.data()); })
      .def("to_dict", [](const present::Presented& p) { return to_python(present::to_json(p)); })
      .def("to_text", [](const present::Presented& p) { return present::to_text(p); });

  m.def("solve", &solve, py::arg("scene"), py::arg("precision"), py::arg("rtol"));
  m.def("drop_sweep", &drop_sweep, py::arg("scene"), py::arg("key"), py::arg("values"), py::arg("precision"), py::arg("threads"),
        py::arg("progress"), py::arg("checkpoint"));
  m.def("sweep", &sweep, py::arg("scene"), py::arg("key"), py::arg("values"), py::arg("precision"), py::arg("threads"), py::arg("progress"),
        py::arg("checkpoint"));
  m.def("switch_points", &switch_points, py::arg("scene"), py::arg("key"), py::arg("values"), py::arg("bits"), py::arg("threads"));
  register_derive(m);
  m.def("verify", &verify_cases, py::arg("options"), py::arg("epsilons"), py::arg("samples"), py::arg("boundary_pairs"), py::arg("seed"),
        py::arg("threads"), py::arg("progress"), py::arg("checkpoint"));
  m.def("audit", &audit, py::arg("epsilon"), py::arg("samples"), py::arg("seed"));
  m.def("explore", &explore, py::arg("options"), py::arg("all_patterns"), py::arg("seed"), py::arg("starts"), py::arg("evaluations"),
        py::arg("box_low"), py::arg("box_high"), py::arg("progress"), py::arg("checkpoint"));
  register_map(m);
  register_drop(m);
  register_gap_limit(m);
  register_checkpoint(m);
  register_scene(m);
  m.def("thread_count", &numeric::thread_count, py::arg("requested"));
  m.attr("default_rtol") = numeric::default_rtol;
  m.attr("__version__") = SUPERBALL_VERSION;
}
