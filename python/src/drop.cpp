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
/// --json`, under "text" what `superball drop` prints, and under "trace" the
/// samples `superball drop --plot` draws (present::DropTrace).
py::dict drop(const Scene& scene, const std::string& precision) {
  const present::PresentedDrop d = present::drop_scene(scene, precision);
  py::dict out = to_python(present::to_json(d));
  out["text"] = present::to_text(d);
  const present::DropTrace t = present::drop_trace(d.result);
  py::dict trace;
  trace["time"] = t.time;
  trace["height"] = t.height;
  trace["collisions"] = py::make_tuple(t.collision_time, t.collision_height);
  trace["rest"] = py::make_tuple(t.rest_time, t.rest_height);
  out["trace"] = trace;
  return out;
}

}  // namespace

void register_drop(py::module_& m) {
  m.def("drop", &drop, py::arg("scene"), py::arg("precision"));
  m.def("drop_finished", &numeric::drop_finished, py::arg("end"));
}

}  // namespace superball::python
