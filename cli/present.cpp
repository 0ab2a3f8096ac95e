#include "present.hpp"

#include "gnuplot.hpp"

namespace superball::cli {

void draw_flight(const Presented& p, const std::string& dir) {
  Plot plot{"Free flight after the collision (" + p.origin + ")", "time after the collision (s)", "height above the collision point (m)",
            false, false, "inside top right box opaque spacing 1.4", {}, {}};
  for (std::size_t i = 0; i < p.flight.size(); ++i) {
    Series s{"body " + std::to_string(i + 1), {}, {}, false};
    s.y = numeric::trajectory(p.flight[i], p.g, p.flight_duration, 400, &s.x);
    plot.series.push_back(std::move(s));
  }
  draw(dir, "trajectories", plot);
}

}  // namespace superball::cli
