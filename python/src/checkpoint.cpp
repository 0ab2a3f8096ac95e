// Python's checkpoint= (checkpoint.hpp): the command's checkpoint folders,
// kept by the same library (superball/distribute).
#include "checkpoint.hpp"

#include <cstdio>
#include <cstdlib>
#include <algorithm>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <utility>

#include "convert.hpp"
#include "superball/cases/error.hpp"

namespace superball::python {

namespace py = pybind11;

void run_kept(const std::string& folder, const distribute::RunIdentity& id, std::size_t count, std::uint64_t max_task_bytes,
              const py::object& progress, const std::string& phase, std::size_t per, std::size_t items,
              const distribute::Distribution::Task& task, const KeptDeliver& deliver) {
  distribute::Options options;
  options.checkpoint = folder;
  options.warn = [](const std::string& line) {  // what the command says on standard error
    py::gil_scoped_acquire gil;
    // Stack level 2: the caller of the module's function (sweep(), map(), verify() call the extension).
    if (PyErr_WarnEx(PyExc_UserWarning, printable(line).c_str(), 2) != 0) throw py::error_already_set();
  };
  distribute::Distribution run(id, options, count, max_task_bytes);
  std::size_t done = count - run.todo().size();
  auto between = [&] { between_tasks(progress, phase, std::min(done * per, items), items); };
  between();
  run.run(
      task, [&](std::size_t k, std::string&& text) { deliver(k, std::move(text), run.origin(k)); },
      [&](const std::vector<std::size_t>& todo, const distribute::Distribution::Task& keeping, const distribute::Distribution::Deliver& give) {
        for (std::size_t j = 0; j < todo.size(); ++j) {
          give(j, keeping(todo[j]));
          ++done;
          between();
        }
      });
}

numeric::TaskRunner kept_runner(py::object progress, std::vector<std::string> phases, std::string folder, distribute::RunIdentity id) {
  // The runner is copied into the library's settings: its state is shared.
  struct State {
    py::object progress;
    std::vector<std::string> phases;
    std::string folder;
    distribute::RunIdentity id;
    std::size_t call = 0;
  };
  auto state = std::shared_ptr<State>(new State{std::move(progress), std::move(phases), std::move(folder), std::move(id), 0}, [](State* s) {
    py::gil_scoped_acquire gil;  // the callable's reference is dropped with the GIL held
    delete s;
  });
  return [state](std::size_t count, const std::function<std::string(std::size_t)>& task) {
    const std::string phase = state->phases.empty() ? std::string("tasks") : state->phases[std::min(state->call, state->phases.size() - 1)];
    ++state->call;
    const std::string folder = state->phases.size() > 1 ? (std::filesystem::path(state->folder) / phase).string() : state->folder;
    std::vector<std::string> texts(count);
    run_kept(folder, state->id, count, distribute::kMaxTaskBytes, state->progress, phase, 1, count, task,
             [&](std::size_t k, std::string&& text, const std::string&) { texts[k] = std::move(text); });
    return texts;
  };
}

std::string sweep_rows(const std::vector<numeric::SweepPoint>& points) {
  std::string text;
  char number[40];
  for (const numeric::SweepPoint& p : points) {
    for (double w : p.velocities_after) {
      std::snprintf(number, sizeof number, "%.17g ", w);
      text += number;
    }
    const std::vector<std::string> closed = p.closed.closed_names();
    std::string names;
    for (const std::string& c : closed) names += (names.empty() ? "" : ",") + c;
    text += (names.empty() ? "none" : names) + " " + numeric::to_string(p.status) + "\n";
  }
  return text;
}

std::vector<SweptRow> read_sweep_rows(const std::string& text, std::size_t rows, int bodies, const std::string& where) {
  auto damaged = [&](const std::string& what) { return std::invalid_argument(where + ": a damaged result (" + what + ")"); };
  static const numeric::Status statuses[] = {numeric::Status::Success, numeric::Status::NumericalIssue, numeric::Status::NoConvergence};
  std::vector<SweptRow> out;
  out.reserve(rows);
  std::size_t at = 0;
  while (at < text.size()) {
    const std::size_t eol = text.find('\n', at);
    if (eol == std::string::npos) throw damaged("its last line is cut");
    if (out.size() == rows) throw damaged("more rows than its values");
    std::vector<std::string> f;
    for (std::size_t from = at;;) {
      const std::size_t space = text.find(' ', from);
      const std::size_t end = space == std::string::npos || space > eol ? eol : space;
      f.push_back(text.substr(from, end - from));
      if (end == eol) break;
      from = end + 1;
    }
    at = eol + 1;
    if (f.size() != static_cast<std::size_t>(bodies) + 2) throw damaged("a row of the wrong fields");
    SweptRow row;
    for (int i = 0; i < bodies; ++i) {
      const std::string& w = f[static_cast<std::size_t>(i)];
      char* end = nullptr;
      const double v = w.empty() ? 0 : std::strtod(w.c_str(), &end);
      if (w.empty() || *end) throw damaged("'" + printable(w.substr(0, 40)) + "' is not a number");
      row.velocities.push_back(v);
    }
    try {
      const std::string& c = f[static_cast<std::size_t>(bodies)];
      if (c.empty()) throw std::invalid_argument("empty");
      row.closed = ContactSet::parse(c, bodies);
    } catch (const std::invalid_argument&) {
      throw damaged("'" + printable(f[static_cast<std::size_t>(bodies)].substr(0, 40)) + "' is not a case of this scene");
    }
    const std::string& s = f.back();
    bool known = false;
    for (numeric::Status st : statuses)
      if (s == numeric::to_string(st)) row.status = st, known = true;
    if (!known) throw damaged("'" + printable(s.substr(0, 40)) + "' is not a status");
    out.push_back(std::move(row));
  }
  if (out.size() != rows) throw damaged("not the rows of its values");
  return out;
}

std::string verification_text(const nlohmann::ordered_json& json, const std::string& report, bool agrees) {
  const std::string j = json.dump();
  return std::string(agrees ? "A" : "D") + "\n" + std::to_string(j.size()) + "\n" + j + "\n" + report;
}

py::tuple read_verification(const std::string& text, const std::string& where) {
  auto damaged = [&](const std::string& what) { return std::invalid_argument(where + ": a damaged result (" + what + ")"); };
  if (text.size() < 2 || (text[0] != 'A' && text[0] != 'D') || text[1] != '\n') throw damaged("no verdict of the exact conditions");
  const std::size_t eol = text.find('\n', 2);
  if (eol == std::string::npos || eol == 2 || eol - 2 > 12 || text.find_first_not_of("0123456789", 2) != eol) throw damaged("no length of its JSON");
  const std::size_t size = std::stoull(text.substr(2, eol - 2));
  if (size > text.size() - eol - 1 || text.size() == eol + 1 + size || text[eol + 1 + size] != '\n') throw damaged("its JSON cut short");
  nlohmann::ordered_json json;
  try {
    json = nlohmann::ordered_json::parse(text.substr(eol + 1, size));
  } catch (const nlohmann::json::exception&) {
    throw damaged("its JSON does not read");
  }
  if (!json.is_object()) throw damaged("its JSON is not an object");
  return py::make_tuple(to_python(json), text.substr(eol + 2 + size), text[0] == 'A');
}

void register_checkpoint(py::module_&) {
  // Registered after the module's own translator, so tried before it.
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const distribute::OutputError& e) {
      PyErr_SetString(PyExc_OSError, printable(e.what()).c_str());
    }
  });
}

}  // namespace superball::python
