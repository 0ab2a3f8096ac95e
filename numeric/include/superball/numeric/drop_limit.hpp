#pragma once
/// \file drop_limit.hpp
/// A drop as its gaps go to 0, against the simultaneous collision of the
/// same stack: the two views of a falling stack that researchers compare.
///
/// The scene's gaps are multiplied by 10⁻ᵏ, k = 0 … decades (drop_height
/// unchanged), and each drop is followed by numeric::drop(); the drop with
/// every gap 0 is the simultaneous one: the whole stack lands at once and
/// its first collision is the Frémond collision of the whole touching
/// cluster (numeric::solve of the stack at the landing speed).
///
/// What is compared is the first cascade of each drop: the collisions from
/// the first one to the one after which the bodies, flying on in straight
/// lines, would never meet again (every body moves up at least as fast as
/// the body below it: U_i ≥ U_{i+1}, the fixed obstacle at 0).  As the gaps
/// shrink the cascade takes less and less time and gravity acts less and
/// less during it, so its velocities after have a limit; that limit depends
/// on the ratios of the gaps (which contact closes first), not on their
/// size.  Whether it is the simultaneous collision's answer is the question:
/// GapLimit::converges.

#include <string>
#include <vector>

#include "superball/cases/model.hpp"
#include "superball/numeric/drop.hpp"
#include "superball/numeric/precision.hpp"
#include "superball/numeric/export.hpp"
SUPERBALL_NUMERIC_API_BEGIN

namespace superball::numeric {

/// Two bodies whose velocities after a collision differ by less than this
/// fraction of the landing speed move together (the cascade's ordering test).
inline constexpr double drop_cascade_tolerance = 1e-9;
/// The gapped drops converge to the simultaneous collision when the
/// velocities after the cascade of the smallest gaps are within this
/// fraction of the landing speed of the simultaneous collision's.
inline constexpr double drop_limit_tolerance = 1e-6;

/// The first cascade of a drop: its collisions until the bodies separate.
struct DropCascade {
  /// The number of collisions in it (0 when the drop had none).
  int events = 0;
  /// True when the bodies separated (U_i ≥ U_{i+1} for every contact,
  /// within drop_cascade_tolerance); false when the drop ended before.
  bool complete = false;
  /// Each collision's bodies and case, "2-4 {3-4}" (the paper's name for
  /// the whole paper stack), in time order.
  std::vector<std::string> collisions;
  /// Every body's velocity after it (m/s, upward positive; the fixed obstacle's 0).
  std::vector<double> velocities;
  /// From its first collision to its last (s).
  double duration = 0;
};

/// The first cascade of \p drop (see DropCascade): \p speed is the landing
/// speed that scales the ordering test's tolerance.
DropCascade first_cascade(const DropResult& drop, double speed);

/// How far gaps_to_zero() takes the gaps.
struct GapLimitOptions {
  /// The gaps are multiplied by 10⁻ᵏ for k = 0 … decades.
  int decades = 8;
  /// The largest number of decades: past it the gaps' closing times come
  /// within roundoff of one another in double (drop_tie_ulps).
  static constexpr int max_decades = 12;
  /// Throws std::invalid_argument("GapLimitOptions::check(): decades must be
  /// a whole number from 1 to 12, got …").
  void check() const;
};

/// One drop of the series.
struct GapLimitStep {
  /// The factor on the scene's gaps (10⁻ᵏ; 0 for the simultaneous drop).
  double scale = 1;
  /// The drop.
  DropResult drop;
  /// Its first cascade.
  DropCascade cascade;
  /// max_i |U_i − U_i(simultaneous)| over the free bodies after the
  /// cascades, over the landing speed (0 for the simultaneous drop itself;
  /// +∞ when a cascade is not complete).
  double deviation = 0;
};

/// What the series says of the limit of the gapped drops.
enum class GapVerdict {
  Converges,  ///< the smallest gaps' cascade ends within drop_limit_tolerance of the simultaneous collision
  Differs,    ///< it ends farther
  Undecided   ///< a drop ended (until, max_events, nothing more collides) before its first cascade did
};

/// "converges", "differs", "undecided".
const char* to_string(GapVerdict v);

/// The series of gapped drops and the simultaneous one.
struct GapLimit {
  /// The speed of the lowest free body when the simultaneous stack lands (m/s).
  double landing_speed = 0;
  /// The drop with every gap 0.
  GapLimitStep simultaneous;
  /// The gapped drops, scale 1, 10⁻¹, … 10⁻ᵈᵉᶜᵃᵈᵉˢ.
  std::vector<GapLimitStep> steps;
  /// Whether the smallest gaps' cascade ends within drop_limit_tolerance of
  /// the simultaneous collision (deviation of the last step).
  GapVerdict verdict = GapVerdict::Undecided;
};

/// The drops of \p scene (with a [drop] table and at least one gap > 0)
/// with its gaps multiplied by 10⁻ᵏ, k = 0 … options.decades, and with
/// every gap 0, in \p precision (double or long double, as drop()).
/// Throws superball::InputError naming the scene when it has no gap, or
/// when the gaps of a step are below what \p precision resolves (its first
/// collision joins a contact that had a gap, as if it touched: the message
/// says how many decades can be taken), and what drop() and
/// GapLimitOptions::check() throw.
GapLimit gaps_to_zero(const Scene& scene, const Precision& precision, const GapLimitOptions& options = {});

}  // namespace superball::numeric

SUPERBALL_NUMERIC_API_END
