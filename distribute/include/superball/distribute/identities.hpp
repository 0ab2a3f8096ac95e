#pragma once
/// \file identities.hpp
/// The identity of a checkpoint's run, for the commands whose run both
/// fronts name the same way (the `superball` command's --checkpoint and the
/// Python module's checkpoint=): built from the library's typed values in
/// canonical form, so that a folder written by one front is taken by the
/// other for the same computation.  Header-only: it uses numeric/, which
/// superball_distribute does not link; its users (the fronts) do.

#include "superball/cases/scene_file.hpp"
#include "superball/distribute/distribute.hpp"
#include "superball/numeric/map.hpp"
#include "superball/numeric/precision.hpp"

namespace superball::distribute {

/// The run of a map of \p scene over \p x and \p y in \p precision: the axes
/// as numeric::Axis::text(), the precision's name, the scene's canonical
/// text (write_scene(), so its file name and spelling do not count).  The
/// output's form (text, CSV, JSON, a figure, an overlay) is not part of it:
/// the tasks are the grid points and the bisections.
inline RunIdentity map_identity(const Scene& scene, const numeric::Axis& x, const numeric::Axis& y, const numeric::Precision& precision) {
  return typed_identity("map", {{"x", x.text()}, {"y", y.text()}, {"precision", precision.name()}}, {{"scene", write_scene(scene)}});
}

}  // namespace superball::distribute
