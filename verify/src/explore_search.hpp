#pragma once
// The local search of explore_case() (explore.hpp): the box of coordinates
// it searches, the conditions as penalties, the objective, and the
// Nelder–Mead optimiser (nelder_mead.cpp).  Private to the library.

#include <cln/rational.h>
#include <cln/integer.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <utility>
#include <vector>

#include "superball/verify/explore.hpp"
#include "superball/verify/space.hpp"

namespace superball::verify::detail::explore {

using cln::cl_RA;
using symbolic::SymbolKind;

/// Objective value of every point where a condition of the case fails:
/// larger than the value −log(U₁⁺/a) or 1 − U₁⁺/a of any feasible point.
constexpr double infeasible_floor = 1e6;
/// The normalised value each condition must exceed in the search; the later
/// ones are the steps inward when the exact solve rejects a rounded point.
constexpr double margins[] = {1e-9, 1e-6, 1e-4, 1e-2};
/// Significant decimal digits of the rational point rounded from the search's.
constexpr int rounding_digits = 7;

/// A condition of the case and its scale, for the penalty.
struct Constraint {
  CompiledCondition condition;
  Polynomial scale;  ///< absolute_terms of the numerator

  /// numerator/scale, with the sign of the denominator: in [−1, 1], > 0 where the condition holds.
  double normalised(const std::vector<double>& x) const {
    const double n = condition.numerator(x), s = scale(x);
    double v = s > 0 ? n / s : 0;
    if (!condition.denominator.is_zero()) {
      const double d = condition.denominator(x);
      if (!(d != 0)) return -1;
      if (d < 0) v = -v;
    }
    return std::isnan(v) ? -1 : v;
  }
};

/// The search coordinates: every coordinate of the space except a (= 1);
/// log10 of masses and K's in [log10 low, log10 high], couplings t ∈ [−1, 1]
/// times √(K_p K_q).
class Box {
 public:
  Box(const ParameterSpace& space, const ExploreOptions& o) : space_(space), low_(std::log10(o.box_low)), high_(std::log10(o.box_high)) {
    for (int k = 0; k < space.size(); ++k)
      if (k != space.fall_speed()) variables_.push_back(k);
  }
  int size() const { return static_cast<int>(variables_.size()); }
  bool coupling(int v) const { return kind(v) == SymbolKind::Coupling; }
  double lower(int v) const { return coupling(v) ? -1 : low_; }
  double upper(int v) const { return coupling(v) ? 1 : high_; }
  void clamp(std::vector<double>& y) const {
    for (int v = 0; v < size(); ++v) y[static_cast<std::size_t>(v)] = std::clamp(y[static_cast<std::size_t>(v)], lower(v), upper(v));
  }
  /// The point (one double per coordinate of the space) at \p y.
  std::vector<double> point(const std::vector<double>& y) const {
    std::vector<double> x(static_cast<std::size_t>(space_.size()), 1.0);
    for (int v = 0; v < size(); ++v)
      if (!coupling(v)) x[coordinate(v)] = std::pow(10.0, y[static_cast<std::size_t>(v)]);
    for (int v = 0; v < size(); ++v)
      if (coupling(v)) x[coordinate(v)] = y[static_cast<std::size_t>(v)] * bound(x, v);
    return x;
  }
  /// The box coordinates of the exact point \p x (clamped into the box).
  std::vector<double> coordinates_of(const Point& x) const {
    std::vector<double> xd;
    for (const cl_RA& value : x) xd.push_back(cln::double_approx(value));
    std::vector<double> y(static_cast<std::size_t>(size()));
    for (int v = 0; v < size(); ++v) {
      const double value = xd[coordinate(v)];
      y[static_cast<std::size_t>(v)] = coupling(v) ? value / bound(xd, v) : std::log10(value);
    }
    clamp(y);
    return y;
  }
  /// The rational point near \p y: masses and K's rounded to rounding_digits
  /// significant digits, each coupling t·√(K_p K_q) on the rounded K's,
  /// rounded toward zero; t shrinks until M is positive semi-definite exactly.
  std::optional<Point> exact(const std::vector<double>& y) const {
    Point x(static_cast<std::size_t>(space_.size()), cl_RA(1));
    std::vector<double> xd(x.size(), 1.0);
    for (int v = 0; v < size(); ++v)
      if (!coupling(v)) {
        x[coordinate(v)] = rounded(std::pow(10.0, y[static_cast<std::size_t>(v)]));
        xd[coordinate(v)] = cln::double_approx(x[coordinate(v)]);
      }
    for (double shrink = 1; shrink > 0.99; shrink -= 1e-3) {
      for (int v = 0; v < size(); ++v)
        if (coupling(v)) x[coordinate(v)] = rounded(shrink * y[static_cast<std::size_t>(v)] * bound(xd, v));
      if (space_.admissible(x)) return x;
    }
    return std::nullopt;
  }

 private:
  std::size_t coordinate(int v) const { return static_cast<std::size_t>(variables_[static_cast<std::size_t>(v)]); }
  SymbolKind kind(int v) const { return space_.coordinates()[coordinate(v)].kind; }
  /// √(K_p K_q) for the coupling variable \p v (10^high when a K is not declared: the PSD penalty bounds it).
  double bound(const std::vector<double>& x, int v) const {
    const Coordinate& c = space_.coordinates()[coordinate(v)];
    if (c.first_diagonal < 0 || c.second_diagonal < 0) return std::pow(10.0, high_);
    return std::sqrt(x[static_cast<std::size_t>(c.first_diagonal)] * x[static_cast<std::size_t>(c.second_diagonal)]);
  }
  /// \p v rounded to rounding_digits significant digits, toward zero.
  static cl_RA rounded(double v) {
    if (v == 0 || !std::isfinite(v)) return 0;
    const int places = rounding_digits - 1 - static_cast<int>(std::floor(std::log10(std::fabs(v))));
    const double scaled = std::trunc(v * std::pow(10.0, places));
    const cl_RA m = cln::cl_I(static_cast<long>(scaled));
    return places >= 0 ? m / cln::expt(cl_RA(10), places) : m * cln::expt(cl_RA(10), -places);
  }

  const ParameterSpace& space_;
  double low_, high_;
  std::vector<int> variables_;
};

/// The function the local searches minimise: infeasible_floor plus the
/// total violation where a condition fails (normalised value below the
/// margin), else h(U₁⁺/a) = −log r (r >= 1) or 1 − r (r < 1), decreasing in r.
/// \p poll (may be empty) is called every explore_progress_evaluations
/// evaluations: ExploreOptions::progress, which may throw.
struct Objective {
  const Box& box;
  const std::vector<Constraint>& constraints;
  const Polynomial& u1_numerator;
  const Polynomial& u1_denominator;
  double margin = margins[0];
  int evaluations = 0;
  std::function<void()> poll{};  ///< called every explore_progress_evaluations evaluations, when set

  double ratio(const std::vector<double>& x) const { return u1_numerator(x) / u1_denominator(x); }
  double operator()(const std::vector<double>& y) {
    if (++evaluations % explore_progress_evaluations == 0 && poll) poll();
    const std::vector<double> x = box.point(y);
    double violation = 0;
    for (const Constraint& c : constraints) violation += std::max(0.0, margin - c.normalised(x));
    if (violation > 0) return infeasible_floor + violation;
    const double r = ratio(x);
    if (!std::isfinite(r)) return infeasible_floor;
    return r >= 1 ? -std::log(r) : 1 - r;
  }
};

/// Nelder–Mead (reflection 1, expansion 2, contraction ½, shrink ½) in the
/// box from \p start, at most \p budget evaluations, restarting around the
/// best vertex when the simplex collapses.  Returns the best vertex and value.
std::pair<std::vector<double>, double> nelder_mead(Objective& f, const Box& box, std::vector<double> start, int budget);

}  // namespace superball::verify::detail::explore
