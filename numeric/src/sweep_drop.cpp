// Sweeps and maps of drop scenes: each value or grid point its own drop(),
// kept as its label (the sequence of collisions) and its top apex ratio.
#include <stdexcept>

#include "map_internal.hpp"
#include "superball/cases/error.hpp"
#include "superball/numeric/map.hpp"
#include "superball/numeric/parallel.hpp"
#include "superball/numeric/sweep.hpp"

namespace superball::numeric {
namespace {

/// One collision of a drop as its label writes it: CONTACTS:CASE.
std::string token(const DropEvent& e) {
  std::string t;
  for (const std::string& c : e.contacts) t += (t.empty() ? "" : ",") + c;
  return t + ":" + e.case_name;
}

using detail::as_text;

/// Set \p values of \p parameters through Parameter::set() and drop the
/// scene there: every check of a value, with its value in the message.
void check_drop_at(const Scene& scene, const std::vector<const Parameter*>& parameters, const std::vector<cln::cl_RA>& values,
                   const Precision& precision) {
  Scene s = scene;
  std::string where;
  for (std::size_t k = 0; k < parameters.size(); ++k) {
    where += (where.empty() ? "" : ", ") + parameters[k]->key() + " = " + to_string(values[k]);
    s = with_value(s, *parameters[k], values[k]);  // InputError "ORIGIN: KEY = VALUE: …"
  }
  try {
    (void)drop(s, precision);
  } catch (const InputError& e) {
    // "ORIGIN: what" -> "ORIGIN: KEY = VALUE: what"
    const std::string what = e.what(), prefix = scene.origin + ": ";
    throw InputError(prefix + where + ": " + (what.rfind(prefix, 0) == 0 ? what.substr(prefix.size()) : what));
  }
}

void check_drop_scene(const Scene& scene, const char* function) {
  if (!scene.drop.requested) throw std::invalid_argument(std::string(function) + ": " + scene.origin + " has no [drop] table");
}

}  // namespace

std::string drop_label(const DropResult& result) {
  std::string label;
  for (std::size_t k = 0; k < result.events.size();) {
    const std::string t = token(result.events[k]);
    std::size_t run = 1;
    while (k + run < result.events.size() && token(result.events[k + run]) == t) ++run;
    label += (label.empty() ? "" : " ") + t + (run > 1 ? "*" + std::to_string(run) : "");
    k += run;
  }
  return label.empty() ? "none" : label;
}

DropPoint drop_point(const DropResult& result) {
  return {drop_label(result), result.top_apex_ratio, static_cast<int>(result.events.size()), result.end};
}

void refuse_drop(const Scene& scene, const std::string& what) {
  if (scene.drop.requested)
    throw std::invalid_argument(what + ": " + scene.origin +
                                " has a [drop] table: a drop is a sequence of collisions, with no exact solution of one collision to "
                                "bisect (map and sweep give each value's drop: its sequence of collisions and top apex ratio)");
}

void refuse_distributed_drop(const Scene& scene, const std::string& what) {
  throw std::invalid_argument(what + ": " + scene.origin +
                              " has a [drop] table: a map or sweep of drops runs in one process, on its threads (no MPI ranks, no "
                              "--shard, no checkpoint)");
}

std::vector<DropPoint> drop_sweep(const Scene& scene, const Parameter& parameter, const std::vector<cln::cl_RA>& values,
                                  const Precision& precision, int threads) {
  check_threads(threads);
  check_drop_scene(scene, "drop_sweep()");
  if (values.empty()) throw std::invalid_argument("drop_sweep(): no value to run");
  const auto [low, high] = detail::extremes(values);
  for (std::size_t end : {low, high}) check_drop_at(scene, {&parameter}, {values[end]}, precision);
  const std::vector<std::string> texts = as_text(values);
  return parallel_map(values.size(), threads, [&scene] { return scene; }, [&](Scene& s, std::size_t k) {
    parameter.assign(s, Number::parse(texts[k]));
    return drop_point(drop(s, precision));
  });
}

DropMap drop_map(const Scene& scene, const Axis& x, const Axis& y, const MapSettings& settings) {
  settings.check();
  check_drop_scene(scene, "map()");
  if (settings.runner) refuse_distributed_drop(scene, "map()");
  check_axes(x, y);
  for (const cln::cl_RA& vx : {x.from, x.to})
    for (const cln::cl_RA& vy : {y.from, y.to}) check_drop_at(scene, {&x.parameter, &y.parameter}, {vx, vy}, settings.precision);
  MapSettings sized = settings;
  // A DropPoint in place of a MapPoint, and its label's heap block (a few tens of bytes for a few collisions).
  constexpr double label_block = 64;
  sized.output_bytes_per_point += static_cast<double>(sizeof(DropPoint)) + label_block;
  if (std::string why; !sized.fits(x, y, &why)) throw std::invalid_argument(why);
  const std::vector<std::string> tx = as_text(x.values()), ty = as_text(y.values());
  const std::size_t nx = tx.size();
  DropMap m{x, y, {}};
  m.points = parallel_map(nx * ty.size(), settings.threads, [&scene] { return scene; }, [&](Scene& s, std::size_t k) {
    x.parameter.assign(s, Number::parse(tx[k % nx]));
    y.parameter.assign(s, Number::parse(ty[k / nx]));
    return drop_point(drop(s, settings.precision));
  });
  return m;
}

}  // namespace superball::numeric
