#pragma once
/// \file map.hpp
/// A map over two parameters (numeric/map.hpp) as people and programs read
/// it: the grid and the boundary points as CSV, everything as JSON, a
/// summary as text, and the gnuplot data and script of its figure.  Shared by
/// the `superball` command and the Python module.

#include <nlohmann/json.hpp>

#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "superball/numeric/map.hpp"
#include "superball/present/export.hpp"
#include "superball/present/text_sink.hpp"
SUPERBALL_PRESENT_API_BEGIN

namespace superball::present {

/// The paper's name of a region's case (Vocabulary::paper().case_name()).
std::string case_name(const numeric::Region& r);

/// The grid as CSV, one row per point (x varies fastest): KEYX, KEYY,
/// psd (M positive semi-definite: 1, else 0 and the point is not solved),
/// case, closed, U1_over_a (U₁⁺/|U₁⁻|), superball (1/0), status.  The rows
/// are formatted on \p threads threads (0: all cores); the text does not
/// depend on them.
std::string map_csv(const numeric::Map& m, int threads = 1);
/// map_csv() given to \p sink a block of rows at a time, in order (the
/// memory held is that of a few blocks per thread).
void write_map_csv(const numeric::Map& m, int threads, const TextSink& sink);
/// The first line of map_csv().
std::string map_csv_header(const numeric::Axis& x, const numeric::Axis& y);
/// The rows of map_csv() of \p points, the grid points first,
/// first + 1, … (k = j·x.steps + i): map_csv() a block at a time, for a grid
/// written as it is computed (numeric::map_points()), on \p threads threads.
std::string map_csv_rows(const numeric::Axis& x, const numeric::Axis& y, std::size_t first, const std::vector<numeric::MapPoint>& points,
                         int threads = 1);
/// map_csv_rows() given to \p sink a block of rows at a time, in order.
void write_csv_rows(const numeric::Axis& x, const numeric::Axis& y, std::size_t first, const std::vector<numeric::MapPoint>& points, int threads,
                    const TextSink& sink);

/// The forms of a map's output, for map_output_bytes_per_point().
enum class MapOutput {
  Summary,  ///< map_summary() (and the boundary points): nothing per grid point
  Csv,      ///< map_csv() whole
  Json,     ///< map_json() and its text
  Figure,   ///< map_figure_data() and the scripts
  Arrays    ///< the Python module's result: an array of each field, (ny, nx), and its lists
};
/// The bytes per grid point that \p output holds beside the map at its
/// peak (for numeric::MapSettings::output_bytes_per_point), measured as
/// the peak resident size of 1000 x 1000 maps less the map's own (docs/MAPS.md).
double map_output_bytes_per_point(MapOutput output);

/// The boundary points as CSV, one row per point: along (the axis whose
/// parameter varies in the bracket), KEYX, KEYY (the bracket's middle on
/// that axis, the grid value on the other), bracket_width, then the case and
/// superball verdict at the bracket's low end and at its high end.
std::string boundaries_csv(const numeric::Map& m);

/// Everything, for programs: the scene, the axes (exact ends), every point,
/// every boundary point (exact bracket ends) and every curve.
nlohmann::ordered_json map_json(const numeric::Map& m, const Scene& scene, const std::string& precision);
/// The text of map_json() with the members of \p extra (an object) after its
/// own (`superball map --json --overlay` adds "overlay"): its dump(1) and a
/// line break, byte for byte, given to \p sink in pieces, in order, the
/// points formatted on \p threads threads (0: all cores) without holding the
/// whole document.
void write_map_json(const numeric::Map& m, const Scene& scene, const std::string& precision, const nlohmann::ordered_json& extra, int threads,
                    const TextSink& sink);

/// For people: the grid, each case present with its share of the solved
/// points and how many of them are superball, the superball's share, the
/// range of U₁⁺/a, the points where M is not positive semi-definite, and the
/// boundary curves (regions on each side, number of points, largest bracket).
std::string map_summary(const numeric::Map& m, const Scene& scene, const std::string& precision);

/// A point to mark on the figure (e.g. the paper's values).
struct MapMark {
  ///@{
  /// The point's coordinates, in the map's x and y parameters.
  double x = 0, y = 0;
  ///@}
  /// The text written beside it.
  std::string label;
};

/// The figure's data, read by map_figure_script(): the case regions as RGB
/// pixels, U₁⁺/a per point, the marks, the points \p derived (zeros of the
/// derived conditions, `--overlay`), each boundary curve.
std::string map_figure_data(const numeric::Map& m, const std::vector<MapMark>& marks,
                            const std::vector<std::pair<double, double>>& derived = {});

/// The gnuplot script of the figure, two panels side by side: left the case
/// regions in distinct colours (the superball part of each in its full
/// colour, the rest pale; M not positive semi-definite in grey) with the
/// exact boundary curves (superball edge thick black, case changes thin) and
/// a legend naming the cases as the paper does; right U₁⁺/a in colour with
/// its contour lines and the superball edge; with \p derived, the zeros of
/// the derived conditions as small red circles.  \p data is the data file's
/// name, \p terminal gnuplot's terminal, \p output a quoted file name or ""
/// for standard output.
std::string map_figure_script(const numeric::Map& m, const std::vector<MapMark>& marks, bool derived, const std::string& title,
                              const std::string& data, const std::string& terminal, const std::string& output);

/// The distinct labels of a drop map (numeric::drop_label()), numbered
/// L1, L2, … in the order first met along the grid (x fastest).
std::vector<std::string> drop_map_labels(const numeric::DropMap& m);
/// A drop map as CSV, one row per point (x varies fastest): KEYX, KEYY,
/// top_apex_ratio (17 digits), events, end, label.
std::string drop_map_csv(const numeric::DropMap& m);
/// A drop map for programs: scene, title, precision, the axes (exact ends),
/// "labels" (drop_map_labels()), "points" row by row, each with i, j, its
/// label's index into "labels", top_apex_ratio, events and end, and
/// "boundaries": the text saying why there are none.
nlohmann::ordered_json drop_map_json(const numeric::DropMap& m, const Scene& scene, const std::string& precision);
/// A drop map for people: the grid, each label (L1, …) with its number of
/// points and range of the top apex ratio, the whole range, the runs not
/// ended by an apex or a rest, and the neighbouring pairs whose labels
/// differ (no boundary is bisected: drop_map_no_boundaries).
std::string drop_map_summary(const numeric::DropMap& m, const Scene& scene, const std::string& precision);
/// Why a drop map or sweep has no bisected boundaries, as the outputs say it.
inline constexpr const char* drop_map_no_boundaries =
    "none bisected: a drop has no exact solution of one collision to bisect; its label changes between neighbouring points of different labels";
/// The data of a drop map's figure: index 0, x y r g b (each label's
/// colour); index 1, x y top apex ratio.
std::string drop_map_figure_data(const numeric::DropMap& m);
/// The gnuplot script of the figure of drop_map_figure_data(): two panels
/// side by side, the labels in distinct colours with a legend naming L1, …,
/// and the top apex ratio in colour; \p data, \p terminal and \p output
/// as in map_figure_script().
std::string drop_map_figure_script(const numeric::DropMap& m, const std::string& title, const std::string& data, const std::string& terminal,
                                   const std::string& output);

/// The axis label of a parameter key for gnuplot's enhanced text: alpha.2 ->
/// α_2, K.3-4 -> K_{34}, others as they are.
std::string axis_label(const std::string& key);

}  // namespace superball::present

SUPERBALL_PRESENT_API_END
