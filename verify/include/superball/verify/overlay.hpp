#pragma once
/// \file overlay.hpp
/// The derived conditions of the cases of a map (numeric/map.hpp) located on
/// the map's grid lines, and compared with the boundaries the exact solutions
/// gave (`superball map --overlay`): a verification run in two dimensions.
///
/// For each case present in the map, its conditions derived symbolically
/// (symbolic::Deriver on the pattern of the scene's M: superball, each open
/// contact's opening, each closed contact's reaction sign; with a finite
/// obstacle the finite-m_n forms, which are exact) are evaluated exactly at
/// every grid point; between two neighbours where a condition changes side,
/// its zero is located by bisection on the condition's exact value to the
/// map's bracket width.  Each boundary point of the map then has to lie, on
/// its grid segment, within the two brackets' widths of a zero of a
/// condition of one of the two cases on its sides: at a change of case or of
/// superball verdict, one of the conditions that decide them changes sign.
/// Its reports (text, JSON) are present/overlay.hpp's.

#include <cln/rational.h>

#include <string>
#include <utility>
#include <vector>

#include "superball/cases/model.hpp"
#include "superball/numeric/map.hpp"
#include "superball/symbolic/derivation.hpp"
#include "superball/verify/export.hpp"
SUPERBALL_VERIFY_API_BEGIN

namespace superball::verify {

/// A zero of one derived condition on a grid segment of the map (as
/// numeric::MapBoundary: along x from (x_i, y_j), else along y), bracketed by
/// [low, high] in the varying parameter; the condition holds at `holds_low`'s end.
struct DerivedZero {
  /// The two grid points are neighbours along x (else along y).
  bool along_x = true;
  ///@{
  /// The grid indices (x_i, y_j) of the first grid point.
  int i = 0, j = 0;
  ///@}
  ///@{
  /// The bracket of the zero on the varying parameter, low < high.
  cln::cl_RA low, high;
  ///@}
  ContactSet closed;       ///< the case whose condition it is
  /// The kind of the condition.
  symbolic::ConditionKind kind = symbolic::ConditionKind::Superball;
  std::string about;       ///< as in symbolic::Condition ("1-2", …)
  /// The condition holds at low (else at high).
  bool holds_low = false;
  /// Whether one end of its segment is a grid point of this case (the zero
  /// can bound the case's region there; the others lie where the case is not
  /// actual and its conditions say nothing).
  bool at_case = false;
  /// "superball", "contact 2-3": its kind and what it is about.
  std::string condition() const { return std::string(symbolic::to_string(kind)) + (about.empty() ? "" : " " + about); }
};

/// How one boundary point of the map compares with the derived zeros.
struct OverlayMatch {
  std::size_t boundary = 0;  ///< index into numeric::Map::boundaries
  bool found = false;        ///< a zero of a condition of either side's case is on the same segment
  std::size_t zero = 0;      ///< the nearest such zero (index into Overlay::zeros)
  cln::cl_RA distance;       ///< |middle of the boundary's bracket − middle of the zero's|
  cln::cl_RA allowed;        ///< the sum of the two brackets' widths
  /// True when a zero was found within the allowed distance.
  bool agrees() const { return found && distance <= allowed; }
};

/// The overlay of a map.
struct Overlay {
  std::vector<ContactSet> cases;  ///< the cases present in the map, whose conditions were derived
  int conditions = 0;             ///< how many conditions they have (PSD conditions left out)
  /// The zeros of those conditions on the grid's edges.
  std::vector<DerivedZero> zeros;
  std::vector<OverlayMatch> matches;  ///< one per boundary point between solved points (PSD edges left out)
  /// The largest distance of a match that was found, in units of the grid
  /// step of its axis, and the largest allowed (both 0 when there is none).
  ///@{
  /// Largest distance and largest allowed (see above).
  double largest_distance = 0, largest_allowed = 0;
  ///@}
  /// True when every boundary of the map has a derived zero within its allowed distance.
  bool agrees() const;
  /// The scene at the middle of a disagreeing boundary point's bracket.
  Scene scene_at(const Scene& scene, const numeric::Map& map, const OverlayMatch& match) const;
};

/// The overlay of \p map, a map of \p scene.  The scene must be of the form
/// the derivation takes: bodies 1..n−1 falling at −a with a rational fall
/// speed a, the bottom body at rest, and the map's keys among K, alpha,
/// coupling, mass and fall_speed (each coordinate of the derivation affine in
/// the map's parameters); throws std::invalid_argument("overlay(): …")
/// otherwise.  Exact throughout; \p bits as for the map's bisections.
Overlay overlay(const Scene& scene, const numeric::Map& map, int bits = 64);

/// The middle of \p z's bracket as the point (x, y) of \p map's plane, exact.
std::pair<cln::cl_RA, cln::cl_RA> position(const numeric::Map& map, const DerivedZero& z);

}  // namespace superball::verify

SUPERBALL_VERIFY_API_END
