#pragma once
/// \file present.hpp
/// A solution as people and programs read it (superball/present/solution.hpp,
/// shared with the Python module), and its flight drawn with gnuplot.

#include <string>

#include "gnuplot.hpp"
#include "superball/numeric/drop_limit.hpp"
#include "superball/present/solution.hpp"

namespace superball::cli {

using present::Presented;
using present::solve_scene;
using present::solve_scene_auto;
using present::to_json;
using present::to_text;

/// Draw the flights of \p p (which must have them) as DIR/trajectories.png and .svg.
void draw_flight(const Presented& p, const std::string& dir);

/// The figure of a drop as its gaps go to 0 (drop --gaps-to-zero --plot,
/// reproduce): each body's velocity after the first cascade over the landing
/// speed against the top gap of \p scene times each step's scale (log), the
/// simultaneous collision's as dashed lines.
Plot gap_limit_plot(const numeric::GapLimit& limit, const Scene& scene, const std::string& title);

}  // namespace superball::cli
