#pragma once
/// \file map.hpp
/// The figure of a map (present/map.hpp's data and script, drawn by gnuplot),
/// for `superball map --plot` and `superball reproduce`.

#include <string>
#include <utility>
#include <vector>

#include "superball/numeric/map.hpp"
#include "superball/present/map.hpp"

namespace superball::cli {

/// Write PREFIX.dat and PREFIX.gp and draw PREFIX.png and PREFIX.svg, every
/// file through Output: the map \p m under \p title, the points \p marks
/// marked, the zeros \p derived of the derived conditions when not empty.
/// Throws OutputError when gnuplot fails or a file cannot be written.
void draw_map(const std::string& prefix, const numeric::Map& m, const std::string& title, const std::vector<present::MapMark>& marks,
              const std::vector<std::pair<double, double>>& derived);

}  // namespace superball::cli
