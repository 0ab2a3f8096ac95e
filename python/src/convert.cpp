#include "convert.hpp"

#include <cln/integer_io.h>

#include <algorithm>
#include <memory>
#include <sstream>
#include <utility>
#include <vector>

namespace superball::python {
namespace {

/// The Python int of the CLN integer \p n, through its hexadecimal digits: Python
/// refuses decimal text of more than 4300 digits (sys.get_int_max_str_digits()),
/// not a power-of-two base, and an exact result may be longer.
py::object integer(const cln::cl_I& n) {
  std::ostringstream hex;
  cln::print_integer(hex, 16, n);
  const std::string text = hex.str();
  PyObject* p = PyLong_FromString(text.c_str(), nullptr, 16);
  if (!p) throw py::error_already_set();
  return py::reinterpret_steal<py::object>(p);
}

}  // namespace

py::object fraction(const cln::cl_RA& x) {
  static const py::handle type = py::object(py::module_::import("fractions").attr("Fraction")).release();
  return type(integer(cln::numerator(x)), integer(cln::denominator(x)));
}

namespace {

template <class Json>
py::object json_to_python(const Json& j) {
  using T = typename Json::value_t;
  switch (j.type()) {
    case T::null:
    case T::discarded: return py::none();
    case T::boolean: return py::bool_(j.template get<bool>());
    case T::number_integer: return py::int_(j.template get<std::int64_t>());
    case T::number_unsigned: return py::int_(j.template get<std::uint64_t>());
    case T::number_float: return py::float_(j.template get<double>());
    case T::string: return py::str(j.template get_ref<const std::string&>());
    case T::array: {
      py::list out(j.size());
      std::size_t k = 0;
      for (const auto& v : j) out[k++] = json_to_python(v);
      return std::move(out);
    }
    case T::object: {
      py::dict out;
      for (const auto& [k, v] : j.items()) out[py::str(k)] = json_to_python(v);
      return std::move(out);
    }
    case T::binary: break;
  }
  throw std::logic_error("to_python(): a binary JSON value");
}

}  // namespace

py::object to_python(const nlohmann::ordered_json& j) { return json_to_python(j); }
py::object to_python(const nlohmann::json& j) { return json_to_python(j); }

void between_tasks(const py::object& progress, const std::string& phase, std::size_t done, std::size_t total) {
  py::gil_scoped_acquire gil;
  if (PyErr_CheckSignals() != 0) throw py::error_already_set();
  if (!progress.is_none()) progress(phase, done, total);
}

numeric::TaskRunner interruptible_runner(py::object progress, std::vector<std::string> phases) {
  // The runner is copied into the library's settings: its state is shared.
  struct State {
    py::object progress;
    std::vector<std::string> phases;
    std::size_t call = 0;
  };
  auto state = std::shared_ptr<State>(new State{std::move(progress), std::move(phases), 0}, [](State* s) {
    py::gil_scoped_acquire gil;  // the callable's reference is dropped with the GIL held
    delete s;
  });
  return [state](std::size_t count, const std::function<std::string(std::size_t)>& task) {
    const std::string phase = state->phases.empty() ? std::string("tasks")
                                                    : state->phases[std::min(state->call, state->phases.size() - 1)];
    ++state->call;
    auto between = [&](std::size_t done) { between_tasks(state->progress, phase, done, count); };
    std::vector<std::string> texts;
    texts.reserve(count);
    between(0);
    for (std::size_t t = 0; t < count; ++t) {
      texts.push_back(task(t));
      between(t + 1);
    }
    return texts;
  };
}

}  // namespace superball::python
