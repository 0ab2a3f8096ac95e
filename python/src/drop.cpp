// drop(): numeric::drop() for Python through present::drop_scene(), its
// result as the command's JSON (Python objects, never JSON text), its text
// and its trajectories (present::drop_trace(), for DropResult.plot()).
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>

#include "convert.hpp"
#include "superball/present/drop.hpp"

namespace superball::python {
namespace {

/// The whole drop of \p scene in \p precision: the fields of `superball drop
/// --json` and, under "text", what `superball drop` prints.
py::dict drop(const Scene& scene, const std::string& precision) {
  const present::PresentedDrop d = present::drop_scene(scene, precision);
  py::dict out = to_python(present::to_json(d));
  out["text"] = present::to_text(d);
  return out;
}

}  // namespace

void register_drop(py::module_& m) { m.def("drop", &drop, py::arg("scene"), py::arg("precision")); }

}  // namespace superball::python
