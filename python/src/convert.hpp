#pragma once
/// \file convert.hpp
/// Library values as native Python objects (dicts, lists, fractions.Fraction,
/// NumPy arrays), built directly in C++: nothing crosses into Python as JSON
/// text.  And the pieces a long call shares: progress and Ctrl-C.

#include <pybind11/pybind11.h>

#include <cln/rational.h>
#include <nlohmann/json.hpp>

#include <cstddef>
#include <string>

#include "superball/numeric/parallel.hpp"

namespace superball::python {

namespace py = pybind11;

/// \p x as a fractions.Fraction (call with the GIL held).
py::object fraction(const cln::cl_RA& x);

/// \p j as Python objects: objects as dicts (in order), arrays as lists,
/// numbers as int or float, strings, booleans, None (call with the GIL held).
/// The library's JSON values of a result (the command's --json) cross into
/// Python so, as values: no text is written or parsed.
py::object to_python(const nlohmann::ordered_json& j);
/// to_python() of an unordered JSON value (its keys in JSON's sorted order).
py::object to_python(const nlohmann::json& j);

/// A numeric::TaskRunner for a long call made with the GIL released: it runs
/// the tasks here, one after the other (each on the call's threads), and
/// between two tasks takes the GIL to call \p progress(phase, done, total)
/// (unless it is None) and PyErr_CheckSignals(), so that Ctrl-C stops the
/// call with KeyboardInterrupt (py::error_already_set thrown through the
/// library).  \p phases names the successive calls of the runner ("points",
/// "boundaries"); a call past the last is named by the last.
numeric::TaskRunner interruptible_runner(py::object progress, std::vector<std::string> phases);

/// Between two parts of a long call made with the GIL released: takes the
/// GIL, stops the call with KeyboardInterrupt on Ctrl-C (PyErr_CheckSignals(),
/// py::error_already_set thrown) and calls \p progress(phase, done, total)
/// unless it is None.
void between_tasks(const py::object& progress, const std::string& phase, std::size_t done, std::size_t total);

/// Register the functions of map.cpp on \p m.
void register_map(py::module_& m);
/// drop(): drop.cpp.
void register_drop(py::module_& m);
/// gaps_to_zero(): a drop as its gaps go to 0 against the simultaneous collision.
void register_gap_limit(py::module_& m);
/// Register scene.cpp's construction from a structured value and the
/// properties of a scene on \p m's class Scene.
void register_scene(py::module_& m);

}  // namespace superball::python
