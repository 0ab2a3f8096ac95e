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
    // Re-measured after the derivation's polynomial arithmetic was rewritten (user + system CPU seconds, `-j 1`):
    // near: one case 10: 0.77 s, 11: 2.23, 12: 5.92, 13: 17.6; every case 8: 1.03 s, 9: 4.35, 10: 16.1;
    // one case 11: 63 MB, 12: 201, 13: 625
    {{13, 17.3, 2.82}, {10, 15.7, 3.68}, {13, 635.0, 3.21}},
    // near2: one case 8: 1.12 s, 9: 5.79; every case 6: 1.12 s, 7: 3.28, 8: 10.6; one case 8: 51 MB, 9: 276
    {{9, 5.79, 5.17}, {8, 10.4, 3.07}, {9, 302.0, 7.19}},
    // near2 with couplings, re-measured after the derivation's polynomial arithmetic was rewritten (CPU seconds of
    // the tasks, `derive --task-cpu`, 2 workers, quiet machine): one case (`{}`) 7: 2.6 s, 8: 28 s; every case
    // 7: 8.6 s, 8: 80.6 s; the largest process (/usr/bin/time %M) 7: 150 MB, 8: 1.13 GB
    {{8, 28.0, 10.4}, {8, 80.6, 9.34}, {8, 1120.0, 7.3}},
    // all pairs (re-measured as the narrower ones): one case 6: 0.30 s, 7: 5.28; every case 6: 0.98 s, 7: 18.8;
    // one case 6: 8.6 MB, 7: 229
    {{7, 5.28, 17.6}, {7, 18.8, 19.2}, {7, 229.0, 26.6}},
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
