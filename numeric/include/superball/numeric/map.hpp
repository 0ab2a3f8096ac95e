#pragma once
/// \file map.hpp
/// Solutions over a grid of two parameters of a scene, and the boundaries
/// between the regions of each evolution case and of the superball, located
/// on the exact solution (the two-parameter form of sweep.hpp).

#include <cln/rational.h>

#include <Eigen/Core>

#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "superball/cases/parameter.hpp"
#include "superball/numeric/memory.hpp"
#include "superball/numeric/parallel.hpp"
#include "superball/numeric/precision.hpp"
#include "superball/numeric/scalar.hpp"
#include "superball/numeric/sweep.hpp"
#include "superball/numeric/export.hpp"
SUPERBALL_NUMERIC_API_BEGIN

namespace superball::numeric {

/// The most values a map takes along one axis (10⁴: a 10⁴ × 10⁴ map is
/// already 10⁸ solves).
inline constexpr int map_max_steps = 10000;

/// One axis of a map: \p steps equally spaced exact values of \p parameter
/// from \p from to \p to, ends included (linspace()).
struct Axis {
  /// The parameter along the axis.
  Parameter parameter;
  ///@{
  /// The first and the last value (exact).
  cln::cl_RA from, to;
  ///@}
  /// The number of values, ends included (2 … map_max_steps).
  int steps = 2;
  /// x_k = from + (to − from)·k/(steps − 1), k = 0 … steps − 1.
  std::vector<cln::cl_RA> values() const { return linspace(from, to, steps); }
  /// x_k alone (Grid).
  cln::cl_RA value(int k) const { return Grid(from, to, steps)(k); }
  /// The axis as KEY=FROM:TO:STEPS in canonical form: the parameter's key
  /// (Parameter::key(), "K.3-4" for "K.03-4") and the ends as exact
  /// fractions ("1/10" for "0.1"), so that two spellings of one axis give
  /// one text (a checkpoint's run is named by it, from either front).
  std::string text() const { return parameter.key() + "=" + to_string(from) + ":" + to_string(to) + ":" + std::to_string(steps); }
};

/// What decides a region of a map: the evolution case (the contacts that
/// stay closed) and the superball verdict U₁⁺ > |U₁⁻|.
struct Region {
  /// The evolution case: the contacts that stay closed.
  ContactSet closed;
  /// The superball verdict U₁⁺ > |U₁⁻|.
  bool superball = false;
  ///@{
  /// Same case and same verdict (and its negation).
  friend bool operator==(const Region& a, const Region& b) { return a.closed == b.closed && a.superball == b.superball; }
  friend bool operator!=(const Region& a, const Region& b) { return !(a == b); }
  ///@}
  /// Order by label(), for sorted outputs.
  friend bool operator<(const Region& a, const Region& b) { return a.label() < b.label(); }
  /// "{2-3,3-4}" or "{2-3,3-4} superball": the Label of a bisection.
  std::string label() const;
  /// The region of a label() for \p bodies bodies; throws std::invalid_argument.
  static Region parse(const std::string& label, int bodies);
  /// The region of an exact solution: its case, and U₁⁺ > |U₁⁻| (both in the
  /// solve's velocity unit, which is positive).
  static Region of(const ExactPoint& point);
};

/// One grid point of a map.
struct MapPoint {
  /// M is positive semi-definite here: the point is solved.  Where it is not
  /// the collision law does not apply; the point is marked, not solved, and
  /// the other fields keep their defaults.
  bool admissible = false;
  /// The solve's status (Status::Success unless the solve failed).
  Status status = Status::Success;
  /// The point's case and verdict.
  Region region;
  /// U₁⁺/|U₁⁻| in the map's precision (NaN when U₁⁻ = 0): the superball is U₁⁺/|U₁⁻| > 1.
  double ratio = 0;
};

/// A change of region between two neighbouring grid points, on the line
/// through them: (x_i, y_j) and (x_{i+1}, y_j) when \p along_x, else (x_i, y_j)
/// and (x_i, y_{j+1}).  The varying parameter's change lies in [low, high]
/// (low < high, whatever the direction of the axis), the region is `below`
/// at low and `above` at high, found by bisection on the exact solution.
/// Between a solved point and one where M is not positive semi-definite, the
/// edge of the PSD cone is located the same way (M's positive
/// semi-definiteness decided exactly at each midpoint); the side where M is
/// not PSD has psd false and no region, the other the region of the exact
/// solution at its end of the bracket.
struct MapBoundary {
  /// The two points are neighbours along x (else along y).
  bool along_x = true;
  ///@{
  /// The grid indices (x_i, y_j) of the first point.
  int i = 0, j = 0;
  ///@}
  ///@{
  /// The bracket of the change on the varying parameter, low < high.
  cln::cl_RA low, high;
  ///@}
  ///@{
  /// The region at low and at high (the default Region on a side where M is not PSD).
  Region below, above;
  ///@}
  ///@{
  /// M is positive semi-definite at low, at high.
  bool below_psd = true, above_psd = true;
  ///@}
};

/// A boundary curve: the boundary points where the case changes between two
/// given cases, or those where the superball verdict changes (the edge of
/// the superball region, whatever the cases on its sides), or those where M
/// stops being positive semi-definite, in the order in
/// which they chain through the grid's cells: in each cell, two such points
/// on its edges are joined (marching squares).  A point where both the case
/// and the verdict change is on a curve of each kind.
struct MapCurve {
  /// What changes along the curve.
  enum class Kind {
    Case,       ///< the case changes from first to second
    Superball,  ///< the superball verdict changes
    Psd         ///< M stops being positive semi-definite
  } kind = Kind::Case;
  /// \var superball::numeric::MapCurve::kind
  /// The kind of the curve.

  /// Kind::Case: the two cases, first.to_string() < second.to_string().
  ContactSet first, second;     ///< Kind::Case: the two cases, first.to_string() < second.to_string()
  std::vector<std::size_t> points;  ///< indices into Map::boundaries
  bool closed = false;              ///< the last point joins the first
};

/// What map() computes and how.
struct MapSettings {
  Precision precision;  ///< arithmetic of the grid points (default: double)
  int bits = 64;     ///< bisection to 2^-bits of the grid step (as switch_points())
  int threads = 1;   ///< 0: all cores; the result does not depend on it
  /// Locate the boundaries and chain them into curves (false: grid points only).
  bool boundaries = true;
  /// Where the work runs, to spread one map over several processes (`mpirun
  /// -n P superball map …`); empty: here, on `threads`.  Called once for the
  /// grid points and once for the boundaries (when there are any to bisect),
  /// with a number of tasks T (at most map_tasks, consecutive points or
  /// neighbour pairs each, solved on `threads`) and a function computing task
  /// t as plain text (points_to_text(), boundaries_to_text() of numeric/src/map_internal.hpp);
  /// it must return the T texts in task order, in every process that calls
  /// map().  Each process then reads them back exactly, finds the pairs to
  /// bisect and chains the curves: the map is the same, bit for bit, whoever
  /// runs the tasks.
  TaskRunner runner;
  /// The memory the map may take; nullopt: available_memory() when map()
  /// starts (a test sets a small one).
  std::optional<Memory> memory;
  /// Bytes per grid point that the caller's output of the map holds beside
  /// it at its peak (its CSV text, JSON or figure data:
  /// present::map_output_bytes_per_point()), counted in the estimate.
  double output_bytes_per_point = 0;
  /// Called by map() on the calling thread as each of its stages ends, with
  /// the stage's name: "checks" (the settings, the corners, the memory),
  /// "grid" (the points), "neighbours" (the pairs to bisect), "bisections",
  /// "read back" (with a runner, each boundary checked against its grid
  /// step) and "curves";
  /// a front times them (`superball map --stage-times`).  Empty: not called.
  std::function<void(const char* stage)> stage_end;
  /// The bytes map() holds per grid point at its peak, with
  /// output_bytes_per_point: each point in the map and the heap block of its
  /// contact set, and while the points are solved their slots in
  /// parallel_map() or, with a runner (which solves a task at a time), all
  /// the tasks' text (points_to_text()).  The boundaries, a few per cell that a region
  /// edge crosses, are not counted: they grow with the length of the
  /// curves, not with the area of the grid.  Measured against the peak
  /// resident size of 1000 x 1000 maps in docs/MAPS.md.
  double bytes_per_point() const;
  /// Whether a map of \p x by \p y (bytes_per_point() for each point, and
  /// the stack of each of the threads) fits in #memory (like Ceres's
  /// Solver::Options::IsValid()): true, or false with one line saying why in
  /// \p why ("map(): a 10000 x 10000 grid holds about 16.8 GB (168 bytes
  /// per point, 2 threads); this machine has 5.1 GB available
  /// (MemAvailable); use a coarser grid …").
  bool fits(const Axis& x, const Axis& y, std::string* why = nullptr) const;
  /// Throws std::invalid_argument unless #threads passes check_threads() and
  /// #bits is from 1 to max_bits; map() and map_points() call it first.
  void check() const;
};

/// The most tasks of each phase of a map given to MapSettings::runner:
/// enough to share out over the ranks of a job, few enough that each task's
/// work outweighs sending its text.
inline constexpr std::size_t map_tasks = 64;

/// A map: every grid point, the boundaries between neighbours of different
/// region, and the curves they chain into.
struct Map {
  ///@{
  /// The two axes: x varies along a row, y from row to row.
  Axis x, y;
  ///@}
  std::vector<MapPoint> points;  ///< row by row: points[j·x.steps + i] is at (x_i, y_j)
  /// Every change of region between neighbouring grid points.
  std::vector<MapBoundary> boundaries;
  /// The boundary points chained into curves.
  std::vector<MapCurve> curves;
  /// The point at (x_i, y_j).
  const MapPoint& at(int i, int j) const { return points[static_cast<std::size_t>(j) * static_cast<std::size_t>(x.steps) + static_cast<std::size_t>(i)]; }
};

/// Refuse two axes that cannot make a map: the same parameter on both,
/// fewer than 2 or more than map_max_steps values on one, equal ends
/// (std::invalid_argument "map(): …"); check_map() and drop_map() call it.
void check_axes(const Axis& x, const Axis& y);

/// Refuse, before anything is solved, a map whose axes or rectangle cannot be
/// solved: the same parameter on both axes, fewer than 2 or more than
/// map_max_steps values on an axis, equal ends (std::invalid_argument
/// "map(): …"), or a corner of the rectangle that a scene file could not
/// hold or where a contact opens before the collision (InputError
/// "ORIGIN: KEYX = X, KEYY = Y: what is wrong"), and a scene with a [drop]
/// table (refuse_drop(): drop_map() maps drops).
///
/// The corners suffice: the loader's checks are signs of one value each, and
/// each D_c(U⁻) is affine in a velocity and monotone in a = sqrt(2 g h), so
/// along each axis it is monotone and its extremes over the rectangle lie at
/// corners.  M's positive semi-definiteness is decided at each point instead
/// (map()): the grid may cross the boundary of the PSD cone.
void check_map(const Scene& scene, const Axis& x, const Axis& y);

/// Solve \p scene at every point (x_i, y_j) of the grid in \p settings.precision,
/// after check_map() and settings.fits() (std::invalid_argument with its
/// reason when the map would not fit in memory).  A point where M is not positive semi-definite (decided
/// exactly) is marked and not solved; if no point is left, throws
/// InputError("ORIGIN: M is not positive semi-definite at any point of the
/// map …").  Then, when settings.boundaries, every pair of neighbours (along
/// x and along y) that are both solved and of different region is bisected on
/// the exact solution by label_changes() with Region::label() (the segment
/// between them is inside the PSD cone, which is convex), each pair of a
/// solved point and an unsolved one is bisected on M's positive
/// semi-definiteness (one change: the cone is convex), and the boundary
/// points are chained into curves (MapCurve).  Each point is solved
/// from the scene on its own and the bisections are independent, so the map
/// does not depend on settings.threads, bit for bit.
Map map(const Scene& scene, const Axis& x, const Axis& y, const MapSettings& settings = {});

/// The grid points of map() (without its boundaries) in order, a block of
/// at most \p block points at a time given to \p sink with the index of its
/// first point (k = j·x.steps + i), so that the memory held stays that of
/// one block whatever the size of the grid: for a grid too large to hold
/// (MapSettings::fits()), written out as it is computed.  Checks as map()
/// (check_map(), not the memory), solves the points as map() does (bit for
/// bit) on settings.threads, ignores settings.runner and throws
/// InputError as map() when no point is admissible, after the last block.
void map_points(const Scene& scene, const Axis& x, const Axis& y, const MapSettings& settings, std::size_t block,
                const std::function<void(std::size_t first, const std::vector<MapPoint>& points)>& sink);

/// The margin of the floating-point filter of M's positive
/// semi-definiteness at a map point (psd_by_floating_point() of numeric/src),
/// relative to M's Frobenius norm: far above the rounding of the entries and
/// of a Cholesky factorization (about n·u·‖M‖ for n pairs), so the filter
/// decides only points at least that far inside or outside the cone.
inline constexpr double map_psd_margin = 1e-9;

/// A map of a drop scene (a scene with a [drop] table): the DropPoint of
/// every grid point.  No boundaries: a drop has no exact solution to
/// bisect, its label changes where the order of its collisions does.
struct DropMap {
  ///@{
  /// The two axes: x varies along a row, y from row to row.
  Axis x, y;
  ///@}
  std::vector<DropPoint> points;  ///< row by row: points[j·x.steps + i] is at (x_i, y_j)
  /// The point at (x_i, y_j).
  const DropPoint& at(int i, int j) const { return points[static_cast<std::size_t>(j) * static_cast<std::size_t>(x.steps) + static_cast<std::size_t>(i)]; }
};

/// The drop of \p scene (with a [drop] table) at every point (x_i, y_j) of
/// the grid, in settings.precision on settings.threads, each its own run of
/// drop() as drop_sweep() runs one, so the map does not depend on the
/// threads, bit for bit.  Before anything is run: settings.check(), the
/// axes as check_map() takes them (two parameters, 2 … map_max_steps
/// values, distinct ends), the four corners set through Parameter::set()
/// and dropped (the admissible set is convex: each loader's check is a sign
/// of one value, M's positive semi-definiteness a convex cone), and
/// settings.fits() with each point's DropPoint.  settings.runner must be
/// empty (std::invalid_argument: a drop map is not spread over processes
/// nor checkpointed); settings.boundaries is not used.
DropMap drop_map(const Scene& scene, const Axis& x, const Axis& y, const MapSettings& settings = {});

/// The point of a boundary in the plane, in double: the middle of its bracket
/// on the varying axis, the grid value on the other.
std::pair<double, double> position(const Map& map, const MapBoundary& b);

}  // namespace superball::numeric

SUPERBALL_NUMERIC_API_END
