#pragma once
// Python's checkpoint=: the tasks of a long call kept in a folder by the
// library of the command's --checkpoint (superball/distribute), with the
// same file format, the same checks and the same messages.
#include <pybind11/pybind11.h>

#include <nlohmann/json.hpp>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "superball/distribute/distribute.hpp"
#include "superball/numeric/parallel.hpp"
#include "superball/numeric/sweep.hpp"

namespace superball::python {

/// Takes task k's result and where it came from (Distribution::origin(),
/// to name it in a message when it does not read back).
using KeptDeliver = std::function<void(std::size_t k, std::string&& text, const std::string& origin)>;

/// The options of a checkpoint \p folder kept from Python: a damaged task
/// file is said through warnings.warn (a UserWarning at the caller's line,
/// with the command's text), the GIL taken for it.
distribute::Options kept_options(const std::string& folder);

/// The values of a run on a selection of cases (verify(), explore(),
/// derive_all() with a checkpoint): each keyword of the selection \p options
/// given (not None) as "selection.KEY", and the content of its scene file
/// (write_scene(), so its spelling does not count) as the input "scene".
/// The caller adds its own options to `named`, then typed_identity().
struct SelectionRun {
  std::map<std::string, std::string> named, inputs;
};
SelectionRun selection_run(const pybind11::dict& options);

/// Runs tasks 0 … count−1 of the run \p id kept in the folder \p folder (a
/// folder of another run refused, a damaged task file said through
/// warnings.warn, removed and computed again; each result written as soon
/// as it is computed) and calls deliver(k, text, origin) for every k in
/// order, those found in the folder without computing them.  Before the
/// first task computed and after each, progress(phase, done, items) and
/// Ctrl-C as between_tasks(), done counting \p per items a task (at most
/// \p items).  Call with the GIL released.
void run_kept(const std::string& folder, const distribute::RunIdentity& id, std::size_t count, std::uint64_t max_task_bytes,
              const pybind11::object& progress, const std::string& phase, std::size_t per, std::size_t items,
              const distribute::Distribution::Task& task, const KeptDeliver& deliver);

/// interruptible_runner() whose tasks are kept by run_kept(): call p of the
/// runner (phase \p phases[p], the last one past the end) in the folder
/// FOLDER/PHASE when there are several phases, FOLDER itself otherwise (as
/// the command's map keeps FOLDER/points and FOLDER/boundaries).
/// Progress counts \p per items a task, \p items in all (0: the tasks themselves).
numeric::TaskRunner kept_runner(pybind11::object progress, std::vector<std::string> phases, std::string folder, distribute::RunIdentity id,
                                std::size_t per = 1, std::size_t items = 0);

/// The text of a task of verify(): "A" or "D" (the exact conditions agree
/// or disagree), the length of the JSON (present::to_json()), the JSON,
/// then the report, each after a newline.
std::string verification_text(const nlohmann::ordered_json& json, const std::string& report, bool agrees);

/// Reads back verification_text(): (the JSON as Python objects, the report,
/// whether the exact conditions agree), as verify() gives them;
/// std::invalid_argument("WHERE: a damaged result (…)") when it is not that.
/// Call with the GIL held.
pybind11::tuple read_verification(const std::string& text, const std::string& where);

/// Translates distribute::OutputError (a checkpoint file that cannot be
/// written) into OSError with its message.
void register_checkpoint(pybind11::module_& m);

}  // namespace superball::python
