// The Nelder–Mead optimiser of explore_case()'s local searches (explore_search.hpp).
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "explore_search.hpp"

namespace superball::verify::detail::explore {
namespace {

/// Initial Nelder–Mead step: in decades for masses and K's, in t for couplings.
constexpr double log_step = 0.5, coupling_step = 0.3;
/// A local search restarts when its simplex is smaller than this (box units).
constexpr double simplex_collapse = 1e-10;

}  // namespace

std::pair<std::vector<double>, double> nelder_mead(Objective& f, const Box& box, std::vector<double> start, int budget) {
  const std::size_t d = static_cast<std::size_t>(box.size());
  box.clamp(start);
  const int stop = f.evaluations + budget;
  std::vector<double> best = start;
  double best_value = f(start);
  while (f.evaluations < stop) {
    std::vector<std::vector<double>> s(d + 1, best);
    std::vector<double> v(d + 1, best_value);
    for (std::size_t i = 0; i < d; ++i) {
      const double step = box.coupling(static_cast<int>(i)) ? coupling_step : log_step;
      s[i + 1][i] += s[i + 1][i] + step <= box.upper(static_cast<int>(i)) ? step : -step;
      box.clamp(s[i + 1]);
      v[i + 1] = f(s[i + 1]);
    }
    while (f.evaluations < stop) {
      std::vector<std::size_t> order(d + 1);
      for (std::size_t i = 0; i <= d; ++i) order[i] = i;
      std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return v[a] < v[b]; });
      const std::size_t lo = order.front(), hi = order.back(), second = order[d - (d > 0 ? 1 : 0)];
      double size = 0;
      for (std::size_t i = 0; i <= d; ++i)
        for (std::size_t k = 0; k < d; ++k) size = std::max(size, std::fabs(s[i][k] - s[lo][k]));
      if (size < simplex_collapse) break;
      std::vector<double> centroid(d, 0.0);
      for (std::size_t i = 0; i <= d; ++i)
        if (i != hi)
          for (std::size_t k = 0; k < d; ++k) centroid[k] += s[i][k] / static_cast<double>(d);
      auto along = [&](double c) {
        std::vector<double> p(d);
        for (std::size_t k = 0; k < d; ++k) p[k] = centroid[k] + c * (s[hi][k] - centroid[k]);
        box.clamp(p);
        return p;
      };
      const std::vector<double> r = along(-1);
      const double fr = f(r);
      if (fr < v[lo]) {
        const std::vector<double> e = along(-2);
        const double fe = f(e);
        if (fe < fr) s[hi] = e, v[hi] = fe;
        else s[hi] = r, v[hi] = fr;
      } else if (fr < v[second]) {
        s[hi] = r, v[hi] = fr;
      } else {
        const std::vector<double> c = fr < v[hi] ? along(-0.5) : along(0.5);
        const double fc = f(c);
        if (fc < std::min(fr, v[hi])) {
          s[hi] = c, v[hi] = fc;
        } else {
          for (std::size_t i = 0; i <= d; ++i) {
            if (i == lo) continue;
            for (std::size_t k = 0; k < d; ++k) s[i][k] = s[lo][k] + 0.5 * (s[i][k] - s[lo][k]);
            v[i] = f(s[i]);
          }
        }
      }
    }
    const auto it = std::min_element(v.begin(), v.end());
    if (*it < best_value) {
      best_value = *it;
      best = s[static_cast<std::size_t>(it - v.begin())];
    } else if (f.evaluations < stop) {
      // The restart found nothing better: a smaller first step would only repeat it.
      break;
    }
  }
  return {best, best_value};
}

}  // namespace superball::verify::detail::explore
