#pragma once
// Internal: detail::psd_by_floating_point() for the grid points of a map, on
// a matrix of a few rows held in fixed arrays and set entry by entry (a
// map's point changes two entries of M): the same verdicts from the same
// operations in the same order, without the dynamic matrices, their copies
// and their index arithmetic (a fifth of a map point in double before).

#include <Eigen/Core>

#include <cmath>
#include <optional>

#include "map_internal.hpp"

namespace superball::numeric::detail {

/// M on its pairs (symmetric, at most max_rows rows) and
/// psd_by_floating_point() of it, bit for bit: τ = map_psd_margin·‖M‖_F
/// from Eigen's own norm of the same column-major, aligned storage, then the
/// unblocked LDLᵀ of map.cpp's ldlt_succeeds() on M − τI and M + τI.
/// tests/numeric/map_test.cpp compares the verdicts with
/// psd_by_floating_point() on random matrices, at the edge of the cone too.
class PsdFilter {
 public:
  /// The most rows held (a map of more pairs uses psd_by_floating_point()).
  static constexpr int max_rows = 8;

  /// M of \p rows rows (1 <= rows <= max_rows), every entry 0.
  explicit PsdFilter(int rows) : n_(rows) {
    for (double& x : m_) x = 0;
  }
  /// M(r, c) = M(c, r) = v.
  void set(int r, int c, double v) { m_[r + c * n_] = m_[c + r * n_] = v; }
  /// psd_by_floating_point() of M.
  std::optional<bool> decide() {
    const double tau = map_psd_margin * Eigen::Map<const Eigen::MatrixXd, Eigen::Aligned16>(m_, n_, n_).norm();
    if (!std::isfinite(tau)) return std::nullopt;
    if (shifted_ldlt_succeeds(-tau)) return true;
    if (!shifted_ldlt_succeeds(tau)) return false;
    return std::nullopt;
  }

 private:
  /// ldlt_succeeds() (map.cpp) of M + shift·I: L below the diagonal, L·D above it.
  bool shifted_ldlt_succeeds(double shift) {
    const int n = n_;
    if (n < 1 || n > max_rows) __builtin_unreachable();
    for (int k = 0; k < n * n; ++k) a_[k] = m_[k];
    for (int j = 0; j < n; ++j) a_[j + j * n] += shift;
    const auto a = [this, n](int i, int j) -> double& { return a_[i + j * n]; };
    for (int j = 0; j < n; ++j) {
      double d = a(j, j);
      for (int k = 0; k < j; ++k) d -= a(j, k) * a(k, j);
      if (!(d > 0)) return false;
      for (int i = j + 1; i < n; ++i) {
        double s = a(i, j);
        for (int k = 0; k < j; ++k) s -= a(i, k) * a(k, j);
        a(j, i) = s;      // L_ij·D_j
        a(i, j) = s / d;  // L_ij
      }
    }
    return true;
  }

  int n_;
  alignas(16) double m_[max_rows * max_rows];
  double a_[max_rows * max_rows];
};

}  // namespace superball::numeric::detail
