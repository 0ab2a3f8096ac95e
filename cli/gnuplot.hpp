#pragma once
/// \file gnuplot.hpp
/// Figures drawn by gnuplot (Debian's gnuplot-nox): the data and the script
/// are written beside the figure, so every figure can be redrawn by hand.

#include <string>
#include <vector>

namespace superball::cli {

/// One curve or point set.
struct Series {
  std::string title;
  std::vector<double> x, y;
  bool points = false;  ///< points instead of lines
};

/// A vertical or horizontal marker line with a label.
struct Marker {
  double at = 0;
  std::string label;
  bool vertical = true;
  bool dashed = true;
  double label_height = 0.97;  ///< where a vertical marker's label ends, as a fraction of the graph
  bool label_right = false;     ///< label on the right of a vertical marker (else left)
};

struct Plot {
  std::string title, xlabel, ylabel;
  bool logx = false, logy = false;
  std::string key = "inside top right box opaque spacing 1.4";  ///< gnuplot's `set key` arguments
  std::vector<Series> series;
  std::vector<Marker> markers;
};

/// Write DIR/STEM.dat and DIR/STEM.gp and run gnuplot to make DIR/STEM.png
/// and DIR/STEM.svg, every file through Output (gnuplot prints each figure on
/// its standard output).  Throws OutputError("DIR/STEM.png: ...") when gnuplot
/// is missing or fails, or a file cannot be written.
void draw(const std::string& dir, const std::string& stem, const Plot& plot);

/// Run gnuplot on the script \p gp, which draws one figure on its standard
/// output (`set output` without a name), and write that figure to \p path
/// through Output.  Throws OutputError("PATH: ...") when gnuplot is missing
/// or fails.
void render(const std::string& gp, const std::string& path);

}  // namespace superball::cli
