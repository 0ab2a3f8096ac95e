#pragma once
// Internal: the pieces of map() that sweep() and the tests use too — the
// entry of M an axis varies, the floating-point filter of M's positive
// semi-definiteness, the grid points of a map along two entries of M, and
// the plain text in which a MapSettings::runner's tasks come back.

#include <Eigen/Core>

#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "superball/numeric/map.hpp"

namespace superball::numeric::detail {

/// The values as text, written on the calling thread: tasks on other threads
/// parse their own copies and never touch the caller's CLN objects (sweep.cpp).
std::vector<std::string> as_text(const std::vector<cln::cl_RA>& values);

/// The smallest and the largest of \p values (not empty), exactly, as
/// std::minmax_element() finds them (the first smallest, the last largest):
/// by their nearest doubles, since rounding keeps the order (a smaller double
/// is a smaller value), and by CLN's comparison only between values whose
/// doubles are equal.
std::pair<std::size_t, std::size_t> extremes(const std::vector<cln::cl_RA>& values);

/// The index of the one entry of M in which the scenes \p a and \p b differ
/// (as ExactScene, M unchecked), nullopt when they differ in anything else
/// or in more than one entry: the axis of a map that varies that entry only.
std::optional<std::size_t> entry_changed(const Scene& a, const Scene& b);

/// \p v, a value converted into S, is held as Problem::from() requires: finite,
/// and not rounded to zero or to a subnormal number unless it is zero
/// (\p is_zero, the exact value's verdict).
template <class S>
bool held(const S& v, bool is_zero) {
  return std::isfinite(v) && (is_zero || std::fabs(v) >= std::numeric_limits<S>::min());
}

/// M's positive semi-definiteness from floating point when it is clear:
/// with τ = map_psd_margin·‖M‖_F, a Cholesky factorization of M − τI that
/// succeeds proves λ_min(M) >= τ − (its backward error) > 0 (true); one of
/// M + τI that fails proves λ_min(M) < −τ + (its backward error) < 0
/// (false); otherwise nullopt, to be decided exactly.  \p work is reused
/// storage.
std::optional<bool> psd_by_floating_point(const Eigen::MatrixXd& M, Eigen::MatrixXd& work);

/// The grid points a task of entry_points() solves in a row on one thread:
/// enough that the task's overhead is small beside them, few enough that
/// threads share a grid's last points evenly.
inline constexpr std::size_t map_run = 64;

/// The grid points of a map whose axes vary the entries \p kx and \p ky of
/// M of \p corner (the scene at (x_0, y_0)) in S (double or long double):
/// each thread converts the corner once into a Batch (batch.hpp) and then
/// sets only the two entries at each point, in S for the solve and, when
/// psd_by_floating_point() does not decide, exactly for
/// positive_semidefinite().  \p kx and \p ky differ.  The problem solved is
/// Problem<S>::from() of the point's scene, bit for bit, so the points are
/// those of solving each scene from scratch.
/// Only the grid points first … first + size − 1 (k = j·x.steps + i) are
/// solved and returned (a task of MapSettings::runner); the defaults: all.
template <class S>
std::vector<MapPoint> entry_points(const Scene& corner, std::size_t kx, std::size_t ky, const Axis& x, const Axis& y,
                                   const MapSettings& settings, std::size_t first = 0, std::size_t size = static_cast<std::size_t>(-1));

/// The exact polynomials that decide each case over the plane of two entries
/// \p kx and \p ky of M of \p corner (sweep.cpp), made on first use of a case
/// from exact solves at nodes spread over [x0, x1] × [y0, y1]: each line of a
/// map then has its cases' polynomials without a solve.  Not thread-safe
/// (CLN): one per thread.
struct PlaneSigns;
std::shared_ptr<PlaneSigns> plane_signs(const ExactScene& corner, std::size_t kx, std::size_t ky, const cln::cl_RA& x0, const cln::cl_RA& x1,
                                        const cln::cl_RA& y0, const cln::cl_RA& y1);

/// label_changes() between the values \p a and \p b of the entry \p entry of
/// M of \p line (an exact scene; M positive semi-definite from a to b), on
/// the calling thread: the exact labels at a and b, and when they differ,
/// the changes between them to 2^-bits of |b − a|, the same brackets and
/// labels as label_changes() of the scene along the parameter that is that
/// entry.  Nothing is parsed or copied per step: the exact solve sets the
/// entry of \p line; with \p plane (of a map whose lines \p line is one of),
/// the cases' polynomials come from it.  Throws std::invalid_argument unless
/// 1 <= bits <= max_bits.
std::vector<LabelChange> entry_label_changes(const ExactScene& line, std::size_t entry, const cln::cl_RA& a, const cln::cl_RA& b,
                                             const Label& label, const ProvenLabel& proven, int bits, PlaneSigns* plane = nullptr);

/// Grid points as plain text, for MapSettings::runner: one line per point,
/// "ADMISSIBLE STATUS SUPERBALL RATIO CLOSED" with the ratio as a C99
/// hexadecimal floating literal (exact, NaN as "nan") and CLOSED the
/// contacts' bits ("." for a set of no contact).  points_from_text() gives
/// back the same points, field for field.
std::string points_to_text(const std::vector<MapPoint>& points);
/// The points of points_to_text(); throws std::invalid_argument("points_from_text(): …") on a damaged text.
std::vector<MapPoint> points_from_text(const std::string& text);
/// Boundary points as plain text, one line each: "ALONG_X I J LOW HIGH
/// BELOW_PSD ABOVE_PSD BELOW_SUPERBALL ABOVE_SUPERBALL BELOW ABOVE", the
/// bracket's ends exact as p/q and the cases as in points_to_text().
std::string boundaries_to_text(const std::vector<MapBoundary>& boundaries);
/// The boundaries of boundaries_to_text(); throws std::invalid_argument("boundaries_from_text(): …") on a damaged text.
std::vector<MapBoundary> boundaries_from_text(const std::string& text);

}  // namespace superball::numeric::detail
