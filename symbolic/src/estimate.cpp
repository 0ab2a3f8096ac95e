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
/// and of every case (`--all`); megabytes (10^6 bytes) above the process's
/// own of the largest case (peak resident memory, /usr/bin/time %M, less
/// 13 MB).  Width 4 and more is fitted on --pairs all, whose width is n − 1.
struct WidthClass {
  Growth one_case, every_case, megabytes;
};
constexpr WidthClass kMeasured[] = {
    // Re-measured after the derivation's coprimality proofs and checks moved to one pass modulo 2^61 − 1 (user +
    // system CPU seconds, `-j 1`; medians of 6 runs in two passes for runs under 10 s, of 2 for longer ones: the
    // host's speed moved by up to 1.5 times between passes):
    // near: one case 10: 0.32 s, 11: 0.86, 12: 2.90, 13: 9.02; every case 8: 1.23 s, 9: 3.92, 10: 15.6;
    // one case 11: 64 MB, 12: 201, 13: 595
    {{13, 8.86, 3.09}, {10, 15.0, 3.55}, {13, 601.0, 3.05}},
    // near2: one case 8: 0.75 s, 9: 4.21; every case 6: 1.59 s, 7: 4.42, 8: 13.2; one case 8: 52 MB, 9: 281
    {{9, 4.21, 5.61}, {8, 13.0, 2.88}, {9, 281.0, 5.44}},
    // near2 with couplings, re-measured as the narrower ones (CPU seconds of the tasks, `derive --task-cpu`,
    // 2 workers): one case (`{}`) 7: 1.64 s, 8: 16.4 s; every case 7: 7.05 s (the median of 12 runs, 5.2 to
    // 8.0), 8: 66.9 s; the largest process of every case (/usr/bin/time %M) 7: 161 MB, 8: 1.43 GB
    {{8, 16.4, 10.0}, {8, 66.9, 9.48}, {8, 1430.0, 8.91}},
    // all pairs (re-measured as the narrower ones): one case 6: 0.14 s, 7: 3.65; every case 6: 0.98 s, 7: 13.7;
    // one case 6: 9.2 MB, 7: 238
    {{7, 3.65, 27.0}, {7, 13.7, 13.9}, {7, 238.0, 26.0}},
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
