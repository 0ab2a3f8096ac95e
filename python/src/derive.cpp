// _superball.derive and _superball.evaluate: the Python module's derivations
// (python/superball/_derive.py wraps them).  The cases are derived by the
// library's worker processes (symbolic/workers.hpp), as `superball derive`
// derives them; each comes back as text from its worker and is made into
// Python dicts, lists and strings here.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <ginac/ginac.h>
#include <nlohmann/json.hpp>

#include <functional>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "checkpoint.hpp"
#include "convert.hpp"
#include "module.hpp"
#include "superball/distribute/distribute.hpp"
#include "superball/cases/error.hpp"
#include "superball/numeric/memory.hpp"
#include "superball/numeric/parallel.hpp"
#include "superball/present/derivation.hpp"
#include "superball/present/selection.hpp"
#include "superball/symbolic/format.hpp"
#include "superball/symbolic/workers.hpp"

namespace py = pybind11;

namespace superball::python {
namespace {

/// One case as it crosses from its worker: the command's JSON of the case
/// (present::derivation_json) and the text and LaTeX of its velocities,
/// reactions and report.
std::string case_record(const symbolic::Derivation& d, const symbolic::Deriver& deriver, bool expanded, bool with_psd,
                        std::vector<nlohmann::ordered_json>& psd) {
  using symbolic::Style;
  const symbolic::Symbols& s = *d.symbols;
  nlohmann::ordered_json x;
  x["data"] = present::derivation_json(d, deriver, psd, expanded, with_psd);
  // Compact as the JSON is: a long value written through the elimination (V₁, a sum over the V's).
  auto through = [&](const symbolic::Fraction& f) { return !expanded && present::through_elimination(d, f); };
  std::vector<std::string> vt, vl, rt, rl;
  for (int i = 1, cluster = 1; i <= s.bodies(); ++i) {
    const symbolic::Fraction& f = d.velocities[static_cast<std::size_t>(i - 1)];
    for (const Style style : {Style::Text, Style::Latex})
      (style == Style::Text ? vt : vl).push_back(through(f) ? symbolic::cluster_velocity_name(cluster, style) : symbolic::format_fraction(f, s, style));
    if (i < s.bodies() && !d.closed.closed(i - 1)) ++cluster;  // the next body starts a cluster
  }
  for (int k = 0; k + 1 < s.bodies(); ++k) {
    const bool closed = d.closed.closed(k);
    const symbolic::Fraction& f = d.reactions[static_cast<std::size_t>(k)];
    for (const Style style : {Style::Text, Style::Latex})
      (style == Style::Text ? rt : rl)
          .push_back(!closed ? "0"
                     : through(f) ? symbolic::format_linear(d.reactions_eliminated[static_cast<std::size_t>(k)], s, style, true)
                                  : symbolic::format_fraction(f, s, style));
  }
  x["velocities_text"] = vt;
  x["velocities_latex"] = vl;
  x["reactions_text"] = rt;
  x["reactions_latex"] = rl;
  x["report"] = present::report(d, deriver, Style::Text);
  x["report_latex"] = present::report(d, deriver, Style::Latex);
  return x.dump();
}

/// derive_all() with a checkpoint \p folder: each case is a task kept there
/// (the run: the selection as given, the scene's content, \p expanded), run
/// by the worker processes, each writing its case to the folder as soon as
/// it has it (Distribution::keeping(), as the command's derive); only the
/// cases not there are derived, the largest of them in two stages: their
/// symbolic::prepare_todo() first, into \p prepared (by case), which
/// \p task reads.  deliver(k, text) for every case in order;
/// progress(done, total) once with the cases found in the folder, then after
/// each case derived.
void derive_kept(const std::string& folder, const py::dict& options, const present::Selection& sel, bool expanded, int workers,
                 std::vector<std::string>& prepared, const std::function<std::string(std::size_t)>& task,
                 const std::function<void(std::size_t, std::string&&, const std::string& origin)>& deliver,
                 const std::function<void(std::size_t, std::size_t)>& progress, const symbolic::Workers::Interrupt& interrupted) {
  SelectionRun id = selection_run(options);
  id.named["expanded"] = expanded ? "true" : "false";
  const std::size_t count = sel.cases.size();
  distribute::Distribution run(distribute::typed_identity("derive", id.named, id.inputs), kept_options(folder), count);
  std::vector<bool> computed(count, false);
  for (std::size_t k : run.todo()) computed[k] = true;
  std::size_t done = count - run.todo().size();
  progress(done, count);
  const py::gil_scoped_release release;
  symbolic::prepare_todo(*sel.deriver, sel.cases, run.todo(), workers, prepared, interrupted);
  // Forked before anything here starts a thread; a task file the worker cannot write crosses back as a TaskError.
  constexpr int kCannotWrite = 3;
  symbolic::Workers pool(run.todo().size(), workers, [&, kept = run.keeping(task)](std::size_t j) {
    try {
      return kept(run.todo()[j]);
    } catch (const distribute::OutputError& e) {
      throw symbolic::TaskError(kCannotWrite, e.what());
    }
  });
  run.run(
      task,
      [&](std::size_t k, std::string&& text) {
        deliver(k, std::move(text), run.origin(k));
        if (computed[k]) progress(++done, count);
      },
      [&](const std::vector<std::size_t>&, const distribute::Distribution::Task&, const distribute::Distribution::Deliver& give) {
        try {
          pool.run(give, interrupted);
        } catch (const symbolic::TaskError& e) {
          throw distribute::OutputError(e.what());
        }
      });
}

/// derive(): every case of the selection \p options, in case order, each a
/// dict {data, velocities_text, velocities_latex, reactions_text,
/// reactions_latex, report, report_latex}.  \p jobs worker processes at most
/// (0: all cores), fewer when their memory would not fit; \p notice(text)
/// is called once with the estimate (present::plan_derivation()) and
/// \p progress(done, total) after each case, both with the GIL held; Ctrl-C
/// (a pending KeyboardInterrupt) stops the workers at once.  With a
/// \p checkpoint folder: derive_kept().
py::list derive(const py::dict& options, bool expanded, int jobs, const py::object& progress, const py::object& notice, const std::string& checkpoint) {
  const present::Selection sel = present::resolve(selection(options));
  if (sel.cases.empty()) throw std::invalid_argument("derive: give a case (case= or closed=), or use derive_all()");
  const symbolic::Deriver& deriver = *sel.deriver;
  const present::DerivePlan plan = present::plan_derivation(sel, jobs, numeric::available_memory());
  if (!notice.is_none()) notice(plan.text, plan.estimate.seconds);
  py::list out;
  std::vector<nlohmann::ordered_json> psd;  // in each worker: the conditions on M, made once
  symbolic::DeriveRun run;
  run.jobs = plan.workers;
  run.progress = [&](std::size_t done, std::size_t total) {
    if (progress.is_none()) return;
    const py::gil_scoped_acquire gil;
    progress(done, total);
  };
  run.interrupted = [] {
    const py::gil_scoped_acquire gil;
    return PyErr_CheckSignals() != 0;  // KeyboardInterrupt (or another signal handler's exception) now pending
  };
  auto deliver = [&](std::size_t, std::string&& text) {
    const nlohmann::ordered_json j = nlohmann::ordered_json::parse(text, nullptr, false);
    text.clear();
    const py::gil_scoped_acquire gil;
    out.append(to_python(j));
  };
  try {
    if (!checkpoint.empty()) {
      // As the command's JSON: compact with several cases, the conditions on M in the first case only.
      std::vector<std::string> prepared(sel.cases.size());  // the largest cases' first stage, inherited by the workers
      auto task = [&](std::size_t k) {
        return case_record(deriver.derive(sel.cases[k], prepared[k], present::printed_forms(expanded)), deriver, expanded, expanded || sel.cases.size() == 1 || k == 0, psd);
      };
      derive_kept(checkpoint, options, sel, expanded, plan.workers, prepared, task,
                  [&](std::size_t k, std::string&& text, const std::string& origin) {
                    if (!nlohmann::ordered_json::accept(text))  // a task file edited so that its checksum holds
                      throw std::invalid_argument(origin + ": a damaged result (its JSON does not read)");
                    deliver(k, std::move(text));
                  },
                  run.progress, run.interrupted);
      return out;
    }
    const py::gil_scoped_release release;
    symbolic::derive_cases(
        deriver, sel.cases,
        [&](std::size_t k, const symbolic::Derivation& d) {
          // As the command's JSON: compact with several cases, the conditions on M in the first case only.
          return case_record(d, deriver, expanded, expanded || sel.cases.size() == 1 || k == 0, psd);
        },
        deliver, run);
  } catch (const symbolic::Interrupted&) {
    throw py::error_already_set();  // the exception the signal handler set
  }
  return out;
}

/// A relation "lhs REL rhs" of GiNaC's ASCII syntax as lhs − rhs; an expression without one as it is.
std::string difference(const std::string& text) {
  for (const char* rel : {" >= ", " <= ", " > ", " < "}) {
    const auto at = text.find(rel);
    if (at != std::string::npos) return "(" + text.substr(0, at) + ")-(" + text.substr(at + std::string(rel).size()) + ")";
  }
  return text;
}

/// evaluate(): the exact value of \p form (a condition "P > Q" taken as
/// P − Q, or an expression) at \p values (name → (numerator, denominator)
/// as decimal text), after the \p definitions (name, value) in order, each
/// evaluated at the values and the definitions before it; the names of
/// \p zero are taken as 0 (the asymptotic forms through the elimination).
/// Returns a fractions.Fraction.  Throws std::invalid_argument naming the
/// symbols without a value, or a definition that divides by zero there.
py::object evaluate(const std::string& form, const std::vector<std::pair<std::string, std::string>>& definitions,
                    const std::map<std::string, std::pair<std::string, std::string>>& values, const std::vector<std::string>& zero) {
  GiNaC::parser reader;  // not strict: every name it meets is a symbol, shared by name across the calls
  GiNaC::exmap at;
  for (const auto& [name, value] : values) {
    const GiNaC::ex v = reader(value.first + "/(" + value.second + ")");
    at[reader(name)] = v;
  }
  for (const std::string& name : zero) at[reader(name)] = 0;
  auto value_of = [&](const std::string& what, const std::string& text) {
    GiNaC::ex v;
    try {
      v = reader(text).subs(at, GiNaC::subs_options::no_pattern);
    } catch (const std::exception& e) {  // GiNaC: "power::eval(): division by zero", a parse error
      throw std::invalid_argument("evaluate: " + what + ": " + e.what());
    }
    if (!GiNaC::is_a<GiNaC::numeric>(v) || !GiNaC::ex_to<GiNaC::numeric>(v).is_rational()) {
      std::string missing;
      GiNaC::exset symbols;
      for (GiNaC::const_preorder_iterator it = v.preorder_begin(); it != v.preorder_end(); ++it)
        if (GiNaC::is_a<GiNaC::symbol>(*it)) symbols.insert(*it);
      for (const GiNaC::ex& s : symbols) {
        std::ostringstream name;
        name << s;
        missing += (missing.empty() ? "" : ", ") + name.str();
      }
      throw std::invalid_argument("evaluate: " + what + ": no value for " + (missing.empty() ? "every symbol" : missing));
    }
    return v;
  };
  for (const auto& [name, text] : definitions) at[reader(name)] = value_of(name, text);
  const GiNaC::numeric v = GiNaC::ex_to<GiNaC::numeric>(value_of("the condition", difference(form)));
  std::ostringstream num, den;
  num << v.numer();
  den << v.denom();
  const py::module_ builtins = py::module_::import("builtins");
  return py::module_::import("fractions").attr("Fraction")(builtins.attr("int")(num.str()), builtins.attr("int")(den.str()));
}

}  // namespace

void register_derive(py::module_& m) {
  m.def("derive", &derive, py::arg("options"), py::arg("expanded"), py::arg("jobs"), py::arg("progress"), py::arg("notice"), py::arg("checkpoint"));
  m.def("evaluate", &evaluate, py::arg("form"), py::arg("definitions"), py::arg("values"), py::arg("zero"));
}

}  // namespace superball::python
