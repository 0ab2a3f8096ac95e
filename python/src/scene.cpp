// Scenes for Python: built from a structured value in C++ (cases'
// scene_from_value(), the loader's own checks, no TOML text), and what a
// scene holds as Python objects (its K, couplings, α and the keys a sweep
// or a map can vary).
#include <pybind11/stl.h>

#include <string>
#include <vector>

#include "convert.hpp"
#include "superball/cases/error.hpp"
#include "superball/cases/parameter.hpp"
#include "superball/cases/scene_file.hpp"
#include "superball/numeric/problem.hpp"
#include "superball/numeric/scalar.hpp"

namespace superball::python {
namespace {

/// The name of \p v's type, as Python spells it ("numpy.bool_", "complex").
std::string type_name(py::handle v) {
  const py::handle t = py::type::handle_of(v);
  const std::string module = py::str(t.attr("__module__")), name = py::str(t.attr("__qualname__"));
  return module == "builtins" ? name : module + "." + name;
}

/// str(\p v), or repr(\p v) with \p repr; an int past Python's limit of int
/// to decimal text (sys.get_int_max_str_digits()) is refused naming \p field.
std::string text(py::handle v, bool repr, const std::string& origin, const std::string& field) {
  try {
    return (repr ? py::repr(v) : py::str(v)).cast<std::string>();
  } catch (const py::error_already_set& e) {
    if (!e.matches(PyExc_ValueError)) throw;
    throw InputError(printable(origin + ": " + field + ": a number of more digits than Python writes as text (sys.get_int_max_str_digits(): " +
                               py::str(py::module_::import("sys").attr("get_int_max_str_digits")()).cast<std::string>() + ")"));
  }
}

/// \p v (dicts, lists and tuples, strings, booleans, ints) as a SceneValue;
/// \p field names it in the message of a value of another type.  A list
/// longer than max_scene_bodies (no array of a scene file can hold more) is
/// refused before one item is read: a scene never costs more than that.
SceneValue scene_value(py::handle v, const std::string& origin, const std::string& field, int depth) {
  SceneValue out;
  if (depth > max_scene_nesting)
    throw InputError(printable(origin + ": " + field + ": tables and arrays nest deeper than " + std::to_string(max_scene_nesting) +
                               " levels (a scene needs a few)"));
  if (py::isinstance<py::bool_>(v)) {
    out.kind = SceneValue::Kind::Boolean;
    out.flag = v.cast<bool>();
  } else if (py::isinstance<py::str>(v)) {
    out.kind = SceneValue::Kind::String;
    out.text = v.cast<std::string>();
  } else if (py::isinstance<py::int_>(v)) {
    out.kind = SceneValue::Kind::String;
    out.text = text(v, false, origin, field);
  } else if (py::isinstance<py::dict>(v)) {
    out.kind = SceneValue::Kind::Table;
    for (const auto& [key, value] : py::reinterpret_borrow<py::dict>(v)) {
      const std::string k = py::str(key).cast<std::string>();
      out.members.emplace_back(k, scene_value(value, origin, field.empty() ? k : field + "." + k, depth + 1));
    }
  } else if (py::isinstance<py::list>(v) || py::isinstance<py::tuple>(v)) {
    out.kind = SceneValue::Kind::Array;
    if (const std::size_t n = py::len(v); n > static_cast<std::size_t>(max_scene_bodies))
      throw InputError(printable(origin + ": " + field + ": at most " + std::to_string(max_scene_bodies) + (field == "body" ? " bodies" : " items") +
                                 " (got " + std::to_string(n) + ")"));
    out.items.reserve(py::len(v));
    std::size_t k = 0;
    for (py::handle item : v) {
      ++k;
      out.items.push_back(scene_value(item, origin, field + "[" + std::to_string(k) + "]", depth + 1));
    }
  } else {
    throw InputError(printable(origin + ": " + field + ": expected a number, a string, a list or a dict, got " +
                               text(v, true, origin, field) + " (" + type_name(v) + ")"));
  }
  return out;
}

/// The scene of \p value (a dict shaped as a scene file: title, body, dissipation, …).
Scene from_value(py::handle value, const std::string& origin) { return scene_from_value(scene_value(value, origin, "", 0), origin); }

py::object exact(const Number& n) { return fraction(numeric::parse_rational(n.fraction())); }

/// M's declared entries: "K" {"i-j": Fraction}, "alpha" {k: Fraction} (the
/// couplings the paper names, n = 4), "coupling" {"i-j/k-l": Fraction} (the others).
py::dict matrix(const Scene& s) {
  py::dict k, alpha, coupling;
  for (const MatrixEntry& e : s.entries) {
    if (e.diagonal()) {
      k[py::str(e.first.name())] = exact(e.value);
      continue;
    }
    const std::string key = Parameter::parse("coupling." + e.first.name() + "/" + e.second.name(), s).key();
    if (key.rfind("alpha.", 0) == 0) alpha[py::int_(std::stoi(key.substr(6)))] = exact(e.value);
    else coupling[py::str(key.substr(9))] = exact(e.value);
  }
  py::dict out;
  out["K"] = k;
  out["alpha"] = alpha;
  out["coupling"] = coupling;
  return out;
}

/// The keys of the values the scene holds, as sweep() and map() take them
/// (canonical: Parameter::key()): M's entries, the masses, the velocities
/// given, the fall (fall_speed, or drop_height and g) and, in a drop scene,
/// the gaps.
std::vector<std::string> keys(const Scene& s) {
  std::vector<std::string> out;
  for (const MatrixEntry& e : s.entries)
    out.push_back(Parameter::parse(e.diagonal() ? "K." + e.first.name() : "coupling." + e.first.name() + "/" + e.second.name(), s).key());
  for (int i = 0; i < s.size(); ++i)
    if (!s.bodies[static_cast<std::size_t>(i)].infinite) out.push_back("mass." + std::to_string(i + 1));
  for (int i = 0; i < s.size(); ++i)
    if (s.bodies[static_cast<std::size_t>(i)].velocity) out.push_back("velocity." + std::to_string(i + 1));
  if (s.fall_speed) out.emplace_back("fall_speed");
  if (s.drop_height) {
    out.emplace_back("drop_height");
    out.emplace_back("g");
  }
  // A drop's release gaps (0 when not given); body n − 1's distance to the bottom body is drop_height.
  if (s.drop.requested)
    for (int i = 1; i <= s.size() - 2; ++i) out.push_back("gap." + std::to_string(i));
  return out;
}

/// The velocities given before the collision, per body (None: the body falls at −a).
py::list velocities(const Scene& s) {
  py::list out;
  for (const Body& b : s.bodies) out.append(b.velocity ? exact(*b.velocity) : py::none());
  return out;
}

py::object optional_number(const std::optional<Number>& n) { return n ? exact(*n) : py::none(); }

/// U⁻ exactly, per body (ExactScene: −a for a falling body, its velocity
/// otherwise; a fixed obstacle's velocity as given, 0 when not); None for a
/// falling body when a = √(2 g h) is irrational.
py::list velocities_before(const Scene& s) {
  const numeric::ExactScene e = numeric::ExactScene::from(s, numeric::ExactScene::MCheck::Caller);
  cln::cl_RA a = 0;
  const bool rational_a = e.a_squared && cln::sqrtp(*e.a_squared, &a);
  py::list out;
  for (std::size_t i = 0; i < e.fall.size(); ++i) {
    if (cln::zerop(e.fall[i])) out.append(fraction(e.velocity[i]));
    else if (rational_a) out.append(fraction(e.fall[i] * a + e.velocity[i]));
    else out.append(py::none());
  }
  return out;
}

}  // namespace

void register_scene(py::module_& m) {
  auto scene = py::reinterpret_borrow<py::class_<Scene>>(m.attr("Scene"));
  m.attr("max_scene_bodies") = max_scene_bodies;
  scene.def_static("from_value", &from_value, py::arg("value"), py::arg("origin"))
      .def_property_readonly("matrix", &matrix)
      .def_property_readonly("keys", &keys)
      .def_property_readonly("velocities", &velocities)
      .def_property_readonly("velocities_before", &velocities_before)
      .def_property_readonly("fall_speed", [](const Scene& s) { return optional_number(s.fall_speed); })
      .def_property_readonly("drop_height", [](const Scene& s) { return optional_number(s.drop_height); })
      .def_property_readonly("g", [](const Scene& s) { return exact(s.g); })
      .def_property_readonly("flight", [](const Scene& s) { return s.flight.requested; })
      .def_property_readonly("drop", [](const Scene& s) { return s.drop.requested; });
}

}  // namespace superball::python
