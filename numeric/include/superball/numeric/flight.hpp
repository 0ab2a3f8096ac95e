#pragma once
/// \file flight.hpp
/// What happens after the collision when a scene asks for it ([flight]):
/// each body flies freely under gravity from the collision point,
/// z_i(t) = U_i⁺ t − g t²/2.  Later collisions between the bodies are not
/// modelled (each body's flight is its own); a body with U_i⁺ ≤ 0 stays on
/// the ground.  Computed in double: these are derived quantities for
/// reading and plotting, not part of the exact collision.

#include <vector>
#include "superball/numeric/export.hpp"
SUPERBALL_NUMERIC_API_BEGIN

namespace superball::numeric {

/// The free flight of one body.
struct BodyFlight {
  double velocity = 0;     ///< U⁺ (m/s)
  double apex_height = 0;  ///< U⁺²/(2g) when U⁺ > 0, else 0 (m)
  double apex_time = 0;    ///< U⁺/g when U⁺ > 0, else 0 (s)
  double landing_time = 0; ///< 2U⁺/g when U⁺ > 0, else 0 (s)
};

/// The flights of bodies leaving with \p velocities_after under gravity \p g > 0;
/// throws std::invalid_argument("free_flight(): ...") for g <= 0.
std::vector<BodyFlight> free_flight(const std::vector<double>& velocities_after, double g);

/// Heights z(t) of body \p flight at \p samples times in [0, duration]
/// (0 after landing); times in \p t.
std::vector<double> trajectory(const BodyFlight& flight, double g, double duration, int samples, std::vector<double>* t = nullptr);

}  // namespace superball::numeric

SUPERBALL_NUMERIC_API_END
