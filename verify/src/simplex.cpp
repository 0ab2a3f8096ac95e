// Phase one of the simplex method (simplex.hpp).
#include "simplex.hpp"

#include <algorithm>

namespace superball::verify::detail::explore {
namespace {

/// Pivot tolerance and pivot limit of feasible_point().
constexpr double simplex_tolerance = 1e-9;
constexpr int simplex_max_pivots = 20000;

}  // namespace

std::optional<std::vector<double>> feasible_point(std::vector<std::vector<double>> eq, std::vector<double> b,
                                                  const std::vector<std::vector<double>>& le, std::size_t n) {
  const std::size_t m_eq = eq.size(), m = m_eq + le.size();
  const std::size_t slack0 = n, art0 = n + le.size(), rhs = art0 + m_eq, cols = rhs + 1;
  std::vector<std::vector<double>> t(m + 1, std::vector<double>(cols, 0.0));  // row m: reduced costs
  std::vector<std::size_t> basis(m);
  for (std::size_t r = 0; r < m_eq; ++r) {
    const double sign = b[r] < 0 ? -1 : 1;
    for (std::size_t j = 0; j < n; ++j) t[r][j] = sign * eq[r][j];
    t[r][art0 + r] = 1;
    t[r][rhs] = sign * b[r];
    basis[r] = art0 + r;
    for (std::size_t j = 0; j < cols; ++j)
      if (j < art0 || j == rhs) t[m][j] -= t[r][j];
  }
  for (std::size_t r = 0; r < le.size(); ++r) {
    for (std::size_t j = 0; j < n; ++j) t[m_eq + r][j] = le[r][j];
    t[m_eq + r][slack0 + r] = 1;
    basis[m_eq + r] = slack0 + r;
  }
  for (int pivots = 0; pivots < simplex_max_pivots; ++pivots) {
    std::size_t enter = art0;
    for (std::size_t j = 0; j < art0 && enter == art0; ++j)
      if (t[m][j] < -simplex_tolerance) enter = j;
    if (enter == art0) break;
    std::size_t leave = m;
    double best = 0;
    for (std::size_t r = 0; r < m; ++r) {
      if (t[r][enter] <= simplex_tolerance) continue;
      const double ratio = t[r][rhs] / t[r][enter];
      if (leave == m || ratio < best - simplex_tolerance || (ratio <= best + simplex_tolerance && basis[r] < basis[leave])) {
        leave = r;
        best = ratio;
      }
    }
    if (leave == m) return std::nullopt;  // unbounded cannot happen in phase one; treat as failure
    const double pivot = t[leave][enter];
    for (double& v : t[leave]) v /= pivot;
    for (std::size_t r = 0; r <= m; ++r) {
      if (r == leave || t[r][enter] == 0) continue;
      const double f = t[r][enter];
      for (std::size_t j = 0; j < cols; ++j) t[r][j] -= f * t[leave][j];
    }
    basis[leave] = enter;
  }
  if (-t[m][rhs] > simplex_tolerance) return std::nullopt;
  std::vector<double> x(n, 0.0);
  for (std::size_t r = 0; r < m; ++r)
    if (basis[r] < n) x[basis[r]] = std::max(0.0, t[r][rhs]);
  return x;
}

}  // namespace superball::verify::detail::explore
