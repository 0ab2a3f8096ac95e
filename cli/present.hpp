#pragma once
/// \file present.hpp
/// A solution as people and programs read it (superball/present/solution.hpp,
/// shared with the Python module), and its flight drawn with gnuplot.

#include <string>

#include "superball/present/solution.hpp"

namespace superball::cli {

using present::Presented;
using present::solve_scene;
using present::solve_scene_auto;
using present::to_json;
using present::to_text;

/// Draw the flights of \p p (which must have them) as DIR/trajectories.png and .svg.
void draw_flight(const Presented& p, const std::string& dir);

}  // namespace superball::cli
