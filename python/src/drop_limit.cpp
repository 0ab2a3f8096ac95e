// gaps_to_zero(): numeric::gaps_to_zero() for Python through
// present::gap_limit_scene(), its result as the command's JSON (Python
// objects, never JSON text) and text.
#include <pybind11/pybind11.h>

#include <string>

#include "convert.hpp"
#include "superball/present/drop_limit.hpp"

namespace superball::python {
namespace {

/// The drops of \p scene with its gaps shrunk by decades against the
/// simultaneous collision: the fields of `superball drop --gaps-to-zero
/// --json` and, under "text", what the command prints.
py::dict gaps_to_zero(const Scene& scene, const std::string& precision, int decades) {
  const present::PresentedGapLimit g = present::gap_limit_scene(scene, precision, decades);
  py::dict out = to_python(present::to_json(g));
  out["text"] = present::to_text(g);
  return out;
}

}  // namespace

void register_gap_limit(py::module_& m) {
  m.def("gaps_to_zero", &gaps_to_zero, py::arg("scene"), py::arg("precision"), py::arg("decades"));
}

}  // namespace superball::python
