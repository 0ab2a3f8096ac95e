// A derivation's expected time and memory from its measured growth (estimate.hpp).
#include "superball/symbolic/estimate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace superball::symbolic {

int pattern_width(const Pattern& p) {
  int r = 1;
  for (const Pair& q : p.diagonal) r = std::max(r, q.j - q.i);
  for (const PairCoupling& c : p.couplings) r = std::max({r, c.first.j - c.first.i, c.second.j - c.second.i});
  return r + (p.couplings.empty() ? 0 : 1);
}

namespace {

/// A measured point and the growth per body after it: value(n) = value·growth^(n − bodies).
struct Growth {
  int bodies;
  double value, growth;
  double at(int n) const { return value * std::pow(growth, n - bodies); }
};

/// The measurements per width class (1, 2, 3, 4 and more), on the project's
/// 2-core machine, one process (docs/SYMBOLIC.md, "Limits"), each fitted by
/// least squares on the logarithms: seconds of one case (`--closed none`)
/// and of every case (`--all`); megabytes above the process's own of the
/// largest case (peak resident memory, /usr/bin/time %M, less 13 MB).
/// Width 4 and more is fitted on --pairs all, whose width is n − 1.
struct WidthClass {
  Growth one_case, every_case, megabytes;
};
constexpr WidthClass kMeasured[] = {
    // near: one case 9: 1.0 s, 10: 3.2, 11: 6.1, 12: 11.5, 13: 43.8; every case 7: 0.5 s, 8: 1.9, 9: 8.5, 10: 41.4; 9: 14 MB, 10: 42, 11: 117
    {{13, 36.8, 2.42}, {10, 39.1, 4.37}, {11, 119.0, 2.93}},
    // near2: one case 6: 0.3 s, 7: 0.5, 8: 2.8, 9: 17.8; every case 6: 1.2 s, 7: 4.7, 8: 25.4; 7: 19 MB, 8: 101
    {{9, 13.4, 4.04}, {8, 24.1, 4.6}, {8, 101.0, 5.3}},
    // near2 with couplings, re-measured after the derivation's polynomial arithmetic was rewritten (CPU seconds of
    // the tasks, `derive --task-cpu`, 2 workers, quiet machine): one case (`{}`) 7: 2.6 s, 8: 28 s; every case
    // 7: 8.6 s, 8: 80.6 s; the largest process (/usr/bin/time %M) 7: 150 MB, 8: 1.13 GB
    {{8, 28.0, 10.4}, {8, 80.6, 9.34}, {8, 1120.0, 7.3}},
    // all pairs: one case 5: 0.1 s, 6: 0.6, 7: 15.5; every case 5: 0.2 s, 6: 2.4, 7: 48.3; 5: 1.5 MB, 6: 23
    {{7, 12.2, 12.5}, {7, 44.3, 15.5}, {6, 23.2, 15.5}},
};
constexpr double kProcessBytes = 13e6;      ///< a derive process before its first case (measured 12.8–13.4 MB)
constexpr double kFiniteObstacleTime = 3;   ///< a finite obstacle against the fixed one (bench_symbolic: 2.3 to 3.8)

}  // namespace

Estimate estimate_derivation(const Pattern& pattern, Obstacle obstacle, std::size_t cases, bool every_case) {
  Estimate e;
  e.width = pattern_width(pattern);
  const WidthClass& m = kMeasured[std::min(std::max(e.width, 1), 4) - 1];
  const int n = pattern.bodies;
  e.seconds = (every_case ? m.every_case.at(n) : static_cast<double>(cases) * m.one_case.at(n)) *
              (obstacle == Obstacle::Finite ? kFiniteObstacleTime : 1.0);
  e.process_bytes = kProcessBytes + 1e6 * m.megabytes.at(n);
  return e;
}

std::string duration_text(double seconds) {
  char buffer[64];
  if (!(seconds < 1e12)) return "longer than anyone can wait";
  if (seconds < 10)
    std::snprintf(buffer, sizeof buffer, "%.1f s", seconds);
  else if (seconds < 60)
    std::snprintf(buffer, sizeof buffer, "%.0f s", seconds);
  else if (seconds < 3600)
    std::snprintf(buffer, sizeof buffer, "%d min %d s", static_cast<int>(seconds / 60), static_cast<int>(std::fmod(seconds, 60)));
  else if (seconds < 86400 * 2)
    std::snprintf(buffer, sizeof buffer, "%d h %d min", static_cast<int>(seconds / 3600), static_cast<int>(std::fmod(seconds, 3600) / 60));
  else if (seconds < 86400 * 365.25 * 2)
    std::snprintf(buffer, sizeof buffer, "%.0f days", seconds / 86400);
  else
    std::snprintf(buffer, sizeof buffer, "%.3g years", seconds / (86400 * 365.25));
  return buffer;
}

}  // namespace superball::symbolic
