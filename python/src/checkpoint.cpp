// Python's checkpoint= (checkpoint.hpp): the command's checkpoint folders,
// kept by the same library (superball/distribute).
#include "checkpoint.hpp"

#include <algorithm>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <utility>

#include "convert.hpp"
#include "module.hpp"
#include "superball/cases/error.hpp"
#include "superball/cases/scene_file.hpp"

namespace superball::python {

namespace py = pybind11;

distribute::Options kept_options(const std::string& folder) {
  distribute::Options options;
  options.checkpoint = folder;
  options.warn = [](const std::string& line) {  // what the command says on standard error
    py::gil_scoped_acquire gil;
    // Stack level 2: the caller of the module's function (sweep(), map(), verify() call the extension).
    if (PyErr_WarnEx(PyExc_UserWarning, printable(line).c_str(), 2) != 0) throw py::error_already_set();
  };
  return options;
}

SelectionRun selection_run(const py::dict& options) {
  SelectionRun run;
  for (const auto& [key, value] : options)
    if (!value.is_none()) run.named["selection." + key.cast<std::string>()] = py::str(value).cast<std::string>();
  if (const std::string scene = selection(options).scene; !scene.empty()) run.inputs["scene"] = write_scene(load_scene(scene));
  return run;
}

void run_kept(const std::string& folder, const distribute::RunIdentity& id, std::size_t count, std::uint64_t max_task_bytes,
              const py::object& progress, const std::string& phase, std::size_t per, std::size_t items,
              const distribute::Distribution::Task& task, const KeptDeliver& deliver) {
  distribute::Distribution run(id, kept_options(folder), count, max_task_bytes);
  std::size_t done = count - run.todo().size();
  auto between = [&] { between_tasks(progress, phase, done == count ? items : std::min(done * per, items), items); };
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

numeric::TaskRunner kept_runner(py::object progress, std::vector<std::string> phases, std::string folder, distribute::RunIdentity id, std::size_t per,
                                std::size_t items) {
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
  return [state, per, items](std::size_t count, const std::function<std::string(std::size_t)>& task) {
    const std::string phase = state->phases.empty() ? std::string("tasks") : state->phases[std::min(state->call, state->phases.size() - 1)];
    ++state->call;
    const std::string folder = state->phases.size() > 1 ? (std::filesystem::path(state->folder) / phase).string() : state->folder;
    std::vector<std::string> texts(count);
    run_kept(folder, state->id, count, distribute::kMaxTaskBytes, state->progress, phase, per, items ? items : count, task,
             [&](std::size_t k, std::string&& text, const std::string&) { texts[k] = std::move(text); });
    return texts;
  };
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
