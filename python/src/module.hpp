#pragma once
// What the parts of the extension _superball share (module.cpp, derive.cpp).
#include <pybind11/pybind11.h>

#include "superball/present/selection.hpp"

namespace superball::python {

/// The command line's selection options from the keywords of derive(),
/// verify() and explore() (None: the default); module.cpp.
present::SelectionOptions selection(const pybind11::dict& o);

/// derive() and the evaluation of conditions: derive.cpp.
void register_derive(pybind11::module_& m);

}  // namespace superball::python
