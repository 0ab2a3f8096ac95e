#pragma once
/// \file psd_along.hpp
/// Where M stays positive semi-definite along one parameter of a scene: the
/// values a sweep can solve, the others marked as a map marks its points.

#include <cln/rational.h>

#include <cstddef>
#include <vector>

#include "superball/cases/parameter.hpp"

#include "superball/numeric/export.hpp"
SUPERBALL_NUMERIC_API_BEGIN

namespace superball::numeric {

/// Whether M of \p scene with \p parameter set to each of \p values is
/// positive semi-definite, decided exactly (positive_semidefinite()).  Along
/// one parameter M(p) = M₀ + p·E, so M is PSD on an interval of p (the cone
/// is convex): in increasing value the PSD values are consecutive.  The
/// values are sampled (at most psd_along_samples of them, evenly in
/// increasing order) and, once one is PSD, each edge of the interval is
/// found by bisection between sampled neighbours; when no sample is PSD every
/// value is checked.  A value where the scene fails another check (a mass ≤ 0,
/// a contact opening before the collision) counts as PSD here: check_range()
/// refuses it with its own message.  A parameter that is not an entry of M
/// gives the scene's verdict at every value.
std::vector<bool> psd_along(const Scene& scene, const Parameter& parameter, const std::vector<cln::cl_RA>& values);

/// The most values psd_along() checks before it bisects the edges.
inline constexpr std::size_t psd_along_samples = 1024;

}  // namespace superball::numeric

SUPERBALL_NUMERIC_API_END
