#include "superball/numeric/flight.hpp"

#include <stdexcept>

namespace superball::numeric {

std::vector<BodyFlight> free_flight(const std::vector<double>& velocities_after, double g) {
  if (!(g > 0)) throw std::invalid_argument("free_flight(): g must be > 0");
  std::vector<BodyFlight> out;
  for (double u : velocities_after) {
    BodyFlight f;
    f.velocity = u;
    if (u > 0) {
      f.apex_time = u / g;
      f.apex_height = u * u / (2 * g);
      f.landing_time = 2 * u / g;
    }
    out.push_back(f);
  }
  return out;
}

std::vector<double> trajectory(const BodyFlight& flight, double g, double duration, int samples, std::vector<double>* t) {
  if (samples < 2 || !(duration > 0)) throw std::invalid_argument("trajectory(): needs duration > 0 and at least 2 samples");
  std::vector<double> z;
  if (t) t->clear();
  for (int k = 0; k < samples; ++k) {
    const double time = duration * k / (samples - 1);
    const double height = time < flight.landing_time ? flight.velocity * time - g * time * time / 2 : 0.0;
    z.push_back(height);
    if (t) t->push_back(time);
  }
  return z;
}

}  // namespace superball::numeric
