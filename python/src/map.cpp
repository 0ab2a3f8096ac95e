// map(): numeric::map() for Python, its result as NumPy arrays, Fractions and
// dicts (the numbers of `superball map --json`, built from the same Map), with
// the overlay of the derived conditions when asked (verify::overlay()).
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cln/real.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "checkpoint.hpp"
#include "superball/distribute/identities.hpp"
#include "convert.hpp"
#include "superball/cases/scene_file.hpp"
#include "superball/cases/vocabulary.hpp"
#include "superball/numeric/map.hpp"
#include "superball/numeric/range.hpp"
#include "superball/present/map.hpp"
#include "superball/present/overlay.hpp"
#include "superball/verify/overlay.hpp"

namespace superball::python {
namespace {

/// An axis of KEY=FROM:TO:STEPS text, read by the library's range parser (its checks and messages).
numeric::Axis axis(const std::string& name, const std::string& text, const Scene& scene) {
  const numeric::Range r = numeric::parse_range(name, text, scene, numeric::map_max_steps);
  return numeric::Axis{r.parameter, r.from, r.to, r.steps};
}

/// The axis as a dict: key, exact ends, steps, and its values rounded to double.
py::dict axis_dict(const numeric::Axis& a) {
  py::dict d;
  d["key"] = a.parameter.key();
  d["from"] = fraction(a.from);
  d["to"] = fraction(a.to);
  d["steps"] = a.steps;
  py::array_t<double> values(a.steps);
  double* v = values.mutable_data();
  const std::vector<cln::cl_RA> exact = a.values();
  for (std::size_t k = 0; k < exact.size(); ++k) v[k] = cln::double_approx(exact[k]);
  d["values"] = std::move(values);
  return d;
}

/// A region as the command's JSON has it: case, closed contacts, superball verdict (psd false and nothing else when M is not PSD).
py::dict region(bool psd, const numeric::Region& r) {
  py::dict d;
  d["psd"] = psd;
  if (!psd) return d;
  d["case"] = present::case_name(r);
  d["closed"] = r.closed.closed_names();
  d["superball"] = r.superball;
  return d;
}

/// The map as Python objects: per-point arrays (ny, nx), row j at y_j, column i at x_i.
py::dict result(const numeric::Map& m, const Scene& scene, const std::string& precision) {
  const auto nx = static_cast<py::ssize_t>(m.x.steps), ny = static_cast<py::ssize_t>(m.y.steps);
  py::array_t<double> ratio({ny, nx});
  py::array_t<bool> superball({ny, nx}), psd({ny, nx});
  py::array_t<std::int32_t> codes({ny, nx});
  py::array_t<std::int8_t> status({ny, nx});
  double* rd = ratio.mutable_data();
  bool* sd = superball.mutable_data();
  bool* pd = psd.mutable_data();
  std::int32_t* cd = codes.mutable_data();
  std::int8_t* td = status.mutable_data();
  std::vector<ContactSet> cases;  // the distinct cases, in the order met
  for (std::size_t k = 0; k < m.points.size(); ++k) {
    const numeric::MapPoint& p = m.points[k];
    pd[k] = p.admissible;
    sd[k] = p.admissible && p.region.superball;
    rd[k] = p.admissible ? p.ratio : std::numeric_limits<double>::quiet_NaN();
    td[k] = p.admissible ? static_cast<std::int8_t>(p.status) : std::int8_t{-1};
    cd[k] = -1;
    if (!p.admissible) continue;
    std::size_t c = 0;
    while (c < cases.size() && cases[c] != p.region.closed) ++c;
    if (c == cases.size()) cases.push_back(p.region.closed);
    cd[k] = static_cast<std::int32_t>(c);
  }
  py::list names, closed;
  for (const ContactSet& c : cases) {
    names.append(Vocabulary::paper().case_name(c));
    closed.append(py::tuple(py::cast(c.closed_names())));
  }
  py::list boundaries;
  for (const numeric::MapBoundary& b : m.boundaries) {
    const auto [x, y] = numeric::position(m, b);
    py::dict d;
    d["along"] = b.along_x ? m.x.parameter.key() : m.y.parameter.key();
    d["along_x"] = b.along_x;
    d["i"] = b.i;
    d["j"] = b.j;
    d["x"] = x;
    d["y"] = y;
    d["low"] = fraction(b.low);
    d["high"] = fraction(b.high);
    d["bracket_width"] = cln::double_approx(b.high - b.low);
    d["below"] = region(b.below_psd, b.below);
    d["above"] = region(b.above_psd, b.above);
    boundaries.append(std::move(d));
  }
  py::list curves;
  using Kind = numeric::MapCurve::Kind;
  for (const numeric::MapCurve& c : m.curves) {
    py::dict d;
    d["kind"] = c.kind == Kind::Superball ? "superball edge" : c.kind == Kind::Psd ? "psd edge" : "case change";
    if (c.kind == Kind::Case) d["cases"] = py::make_tuple(Vocabulary::paper().case_name(c.first), Vocabulary::paper().case_name(c.second));
    d["closed"] = c.closed;
    d["boundaries"] = c.points;
    py::array_t<double> xy({static_cast<py::ssize_t>(c.points.size()), py::ssize_t{2}});
    double* v = xy.mutable_data();
    for (std::size_t k = 0; k < c.points.size(); ++k) {
      const auto [x, y] = numeric::position(m, m.boundaries[c.points[k]]);
      v[2 * k] = x;
      v[2 * k + 1] = y;
    }
    d["points"] = std::move(xy);
    curves.append(std::move(d));
  }
  py::dict out;
  out["scene"] = scene.origin;
  out["title"] = scene.title;
  out["precision"] = precision;
  out["x"] = axis_dict(m.x);
  out["y"] = axis_dict(m.y);
  out["case_codes"] = std::move(codes);
  out["case_list"] = py::tuple(names);
  out["closed_list"] = py::tuple(closed);
  out["ratio"] = std::move(ratio);
  out["superball"] = std::move(superball);
  out["psd"] = std::move(psd);
  out["status_codes"] = std::move(status);
  out["boundary_points"] = std::move(boundaries);
  out["curves"] = std::move(curves);
  out["summary"] = present::map_summary(m, scene, precision);
  return out;
}

/// The overlay as the command's JSON has it (present::to_json()), its brackets
/// as Fractions, and its text (present::to_text()) under "text".
py::dict overlay_dict(const verify::Overlay& o, const numeric::Map& m) {
  py::dict d = to_python(present::to_json(o, m));
  for (py::handle zero : d["zeros"].cast<py::list>()) {
    py::dict z = py::reinterpret_borrow<py::dict>(zero);
    for (const char* end : {"low", "high"}) z[end] = fraction(numeric::parse_rational(z[end].cast<std::string>()));
  }
  d["text"] = present::to_text(o, m);
  return d;
}

/// map(): the grid of \p x by \p y (KEY=FROM:TO:STEPS) solved in \p precision
/// on \p threads (0: all cores; check_threads() refuses any other value
/// out of range, wider than int too), boundaries bisected exactly; the GIL is
/// released while it computes, Ctrl-C stops it between two of its tasks, and
/// \p progress (None or a callable (phase, done, total)) is told of each.
/// With a \p checkpoint folder, the tasks are kept there (kept_runner()).
/// With \p overlay, the derived conditions of the cases present are located
/// on the grid lines and compared with the boundaries (verify::overlay()).
py::dict map(const Scene& scene, const std::string& x, const std::string& y, const std::string& precision, long long threads, py::object progress,
             const std::string& checkpoint, bool overlay) {
  numeric::check_threads(threads);
  const numeric::Axis ax = axis("x", x, scene), ay = axis("y", y, scene);
  numeric::MapSettings settings;
  settings.precision = numeric::Precision::parse(precision);
  settings.threads = static_cast<int>(threads);
  settings.output_bytes_per_point = present::map_output_bytes_per_point(present::MapOutput::Arrays);
  settings.runner = checkpoint.empty() ? interruptible_runner(std::move(progress), {"points", "boundaries"})
                                       : kept_runner(std::move(progress), {"points", "boundaries"}, checkpoint,
                                                     distribute::map_identity(scene, ax, ay, settings.precision));
  std::optional<numeric::Map> m;
  std::optional<verify::Overlay> o;
  {
    py::gil_scoped_release release;
    m = numeric::map(scene, ax, ay, settings);
    if (overlay) o = verify::overlay(scene, *m, settings.bits);
  }
  settings.runner = nullptr;  // drops the progress callable with the GIL held
  py::dict out = result(*m, scene, settings.precision.name());
  if (o) out["overlay"] = overlay_dict(*o, *m);
  return out;
}

/// map() of a drop scene (a [drop] table): numeric::drop_map() of the grid
/// of \p x by \p y in \p precision on \p threads, the GIL released while it
/// runs, as arrays (ny, nx): top apex ratio, label code into "labels"
/// (present::drop_map_labels()), number of collisions, and the ends as a
/// list; "summary" is the command's.  A \p checkpoint is refused
/// (numeric::refuse_distributed_drop()), \p overlay too (numeric::refuse_drop()).
py::dict drop_map(const Scene& scene, const std::string& x, const std::string& y, const std::string& precision, long long threads,
                  const std::string& checkpoint, bool overlay) {
  numeric::check_threads(threads);
  const numeric::Axis ax = axis("x", x, scene), ay = axis("y", y, scene);
  numeric::MapSettings settings;
  settings.precision = numeric::Precision::parse(precision);
  settings.threads = static_cast<int>(threads);
  if (overlay) numeric::refuse_drop(scene, "overlay");
  if (!checkpoint.empty()) numeric::refuse_distributed_drop(scene, "map");
  settings.output_bytes_per_point = present::map_output_bytes_per_point(present::MapOutput::Arrays);
  std::optional<numeric::DropMap> m;
  {
    py::gil_scoped_release release;
    m = numeric::drop_map(scene, ax, ay, settings);
  }
  const auto nx = static_cast<py::ssize_t>(m->x.steps), ny = static_cast<py::ssize_t>(m->y.steps);
  py::array_t<double> ratio({ny, nx});
  py::array_t<std::int32_t> codes({ny, nx}), events({ny, nx});
  const std::vector<std::string> labels = present::drop_map_labels(*m);
  py::list ends;
  for (std::size_t k = 0; k < m->points.size(); ++k) {
    const numeric::DropPoint& p = m->points[k];
    ratio.mutable_data()[k] = p.ratio;
    events.mutable_data()[k] = p.events;
    codes.mutable_data()[k] = static_cast<std::int32_t>(std::find(labels.begin(), labels.end(), p.label) - labels.begin());
    ends.append(p.end);
  }
  py::dict out;
  out["scene"] = scene.origin;
  out["title"] = scene.title;
  out["precision"] = settings.precision.name();
  out["x"] = axis_dict(m->x);
  out["y"] = axis_dict(m->y);
  out["ratio"] = std::move(ratio);
  out["label_codes"] = std::move(codes);
  out["label_list"] = py::tuple(py::cast(labels));
  out["events"] = std::move(events);
  out["end"] = std::move(ends);
  out["boundaries"] = present::drop_map_no_boundaries;
  out["summary"] = present::drop_map_summary(*m, scene, settings.precision.name());
  return out;
}

}  // namespace

void register_map(py::module_& m) {
  m.def("map", &map, py::arg("scene"), py::arg("x"), py::arg("y"), py::arg("precision"), py::arg("threads"), py::arg("progress"),
        py::arg("checkpoint"), py::arg("overlay"));
  m.def("drop_map", &drop_map, py::arg("scene"), py::arg("x"), py::arg("y"), py::arg("precision"), py::arg("threads"), py::arg("checkpoint"),
        py::arg("overlay"));
}

}  // namespace superball::python
