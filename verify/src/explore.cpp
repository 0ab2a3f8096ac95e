#include "superball/verify/explore.hpp"

#include <cln/rational_io.h>
#include <ginac/ginac.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "superball/cases/scene_file.hpp"
#include "superball/cases/vocabulary.hpp"
#include "superball/numeric/collision.hpp"
#include "superball/symbolic/format.hpp"
#include "superball/verify/space.hpp"

namespace superball::verify {
namespace detail {
namespace {  // internal linkage: audit.cpp has functions of the same names

using cln::cl_RA;
using namespace superball::symbolic;

/// Objective value of every point where a condition of the case fails:
/// larger than the value −log(U₁⁺/a) or 1 − U₁⁺/a of any feasible point.
constexpr double infeasible_floor = 1e6;
/// The normalised value each condition must exceed in the search; the later
/// ones are the steps inward when the exact solve rejects a rounded point.
constexpr double margins[] = {1e-9, 1e-6, 1e-4, 1e-2};
/// Significant decimal digits of the rational point rounded from the search's.
constexpr int rounding_digits = 7;
/// ε of the regime points used as starts (m₁ ~ ε, K₁₄ ~ 1/ε).
constexpr int regime_inverse_epsilon = 100;
/// Initial Nelder–Mead step: in decades for masses and K's, in t for couplings.
constexpr double log_step = 0.5, coupling_step = 0.3;
/// A local search restarts when its simplex is smaller than this (box units).
constexpr double simplex_collapse = 1e-10;
/// Feasible local results tried by the exact confirmation, best first.
constexpr int confirmations = 6;
/// The certificate's linear programme: pivot tolerance, pivot limit, and the
/// rounding of its solution to fractions (denominator, distance).
constexpr double simplex_tolerance = 1e-9;
constexpr int simplex_max_pivots = 20000;
constexpr long rational_denominator = 1000;
constexpr double rational_tolerance = 1e-7;

[[noreturn]] void fail(const std::string& what) { throw std::invalid_argument("explore_case(): " + what); }

/// The sum of the absolute values of the terms of \p p.
GiNaC::ex absolute_terms(const GiNaC::ex& p, const Symbols& s) {
  GiNaC::ex out = 0;
  for (const Monomial& m : s.monomials(p)) {
    GiNaC::ex t = GiNaC::abs(m.coefficient);
    for (const auto& [k, e] : m.powers) t *= GiNaC::pow(s.all()[static_cast<std::size_t>(k)].symbol, e);
    out += t;
  }
  return out;
}

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
struct Objective {
  const Box& box;
  const std::vector<Constraint>& constraints;
  const Polynomial& u1_numerator;
  const Polynomial& u1_denominator;
  double margin = margins[0];
  int evaluations = 0;

  double ratio(const std::vector<double>& x) const { return u1_numerator(x) / u1_denominator(x); }
  double operator()(const std::vector<double>& y) {
    ++evaluations;
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

// ---------------------------------------------------------------------------- clash

/// One condition of the case usable in a certificate: a numerator of proved sign.
struct Usable {
  const Condition* condition;
  const ConditionForm* form;
};

std::string signed_pairs(const std::vector<int>& x, const std::vector<Pair>& pairs) {
  std::string v;
  for (std::size_t r = 0; r < pairs.size(); ++r)
    if (x[r]) v += (v.empty() ? "" : ", ") + std::string(x[r] > 0 ? "+" : "-") + "e(" + pairs[r].name() + ")";
  return v;
}

/// xᵀMx for x ∈ {−1, 0, 1} on \p pairs, expanded.
GiNaC::ex quadratic_form(const std::vector<int>& x, const std::vector<Pair>& pairs, const Symbols& sy) {
  GiNaC::ex form = 0;
  for (std::size_t r = 0; r < pairs.size(); ++r)
    for (std::size_t c = 0; c < pairs.size(); ++c)
      if (x[r] && x[c]) form += x[r] * x[c] * sy.entry(pairs[r], pairs[c]);
  return GiNaC::expand(form);
}

/// Step \p x through {−1, 0, 1}^k (first digit fastest); false after the last.
bool next_signs(std::vector<int>& x) {
  std::size_t i = 0;
  while (i < x.size() && x[i] == 1) x[i++] = -1;
  if (i == x.size()) return false;
  ++x[i];
  return true;
}

/// The form Σ_c μ_c·(K_p + K_q ± 2c) over the couplings c (of pairs p, q)
/// that cancels every term of \p p linear in a coupling: μ_c = |P_c|/2 with
/// P_c the coefficient of c¹ in p, when P_c has one certain sign (then each
/// μ_c >= 0 and each bracket is a quadratic form of the 2×2 minor of M on
/// p, q, >= 0 when M is positive semi-definite).  nullopt when some P_c has
/// no certain sign or the pattern has no coupling.
std::optional<std::pair<GiNaC::ex, std::string>> minor_multiples(const GiNaC::ex& p, const Symbols& sy) {
  GiNaC::ex value = 0;
  std::string text;
  for (const PairCoupling& c : sy.pattern().couplings) {
    if (!sy.pattern().has_diagonal(c.first) || !sy.pattern().has_diagonal(c.second)) return std::nullopt;
    const GiNaC::ex& alpha = sy.coupling(c.first, c.second);
    const GiNaC::ex linear = GiNaC::expand(p.coeff(alpha, 1));
    if (linear.is_zero()) continue;
    int sign = 0;
    if (certainly_nonnegative(linear, sy)) sign = 1;
    else if (certainly_nonnegative(GiNaC::expand(-linear), sy)) sign = -1;
    else return std::nullopt;
    const GiNaC::ex mu = GiNaC::expand(sign * linear / 2);
    const GiNaC::ex bracket = sy.diagonal(c.first) + sy.diagonal(c.second) + 2 * sign * alpha;
    value += mu * bracket;
    text += (text.empty() ? "" : " + ") + std::string("(") + format_polynomial(mu, sy, Style::Text) + ")·(" +
            format_polynomial(GiNaC::expand(bracket), sy, Style::Text) + ")";
  }
  if (text.empty()) return std::nullopt;
  return std::make_pair(GiNaC::expand(value), text);
}

/// The clash of the conditions \p usable weighted by \p multipliers (0 for
/// unused ones; numbers or polynomials >= 0), with −Σ multiplierᵢ·Nᵢ = Q + rest.
Clash make_clash(const std::vector<Usable>& usable, const std::vector<GiNaC::ex>& multipliers, const std::string& q_text,
                 const GiNaC::ex& rest, bool asymptotic, const Symbols& sy) {
  Clash clash;
  clash.asymptotic = asymptotic;
  std::string names;
  for (std::size_t i = 0; i < usable.size(); ++i) {
    if (multipliers[i].is_zero()) continue;
    const Condition& c = *usable[i].condition;
    clash.superball = clash.superball || c.kind == ConditionKind::Superball;
    const std::string name = "N" + std::to_string(clash.conditions.size() + 1);
    const bool number = GiNaC::is_a<GiNaC::numeric>(multipliers[i]);
    const std::string factor = format_polynomial(multipliers[i], sy, Style::Text);
    clash.conditions.push_back(name + " (" + (number ? "weight " : "multiplier ") + factor + "), " + condition_title(c, Style::Text) + ": " +
                               format_condition(*usable[i].form, c.relation, sy, Style::Text));
    const bool one = number && (multipliers[i] - 1).is_zero();
    names += (names.empty() ? "" : " + ") + (one ? "" : number ? factor + "·" : "(" + factor + ")·") + name;
  }
  clash.identity = "with each Nᵢ the condition's polynomial (Nᵢ > 0 or >= 0 as stated): −(" + names + ") = " + (q_text.empty() ? "" : "Q + ") +
                   "(" + format_polynomial(rest, sy, Style::Text) + ")" + (q_text.empty() ? "" : ", Q = " + q_text) +
                   "; every term of the bracket is >= 0" + (q_text.empty() ? "" : " and Q >= 0 when M is positive semi-definite") +
                   ", each multiplier is >= 0, so " + names + " <= 0, while the conditions make it > 0";
  return clash;
}

/// Phase one of the simplex method (dense tableau, Bland's rule): some x >= 0
/// with eq·x = b and le·x <= 0 (rows over \p n unknowns), or nullopt.
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

/// \p v as a fraction of denominator at most rational_denominator (continued
/// fractions), or nullopt when none is within rational_tolerance.
std::optional<GiNaC::numeric> small_fraction(double v) {
  if (std::fabs(v) < rational_tolerance) return GiNaC::numeric(0);
  long p0 = 0, q0 = 1, p1 = 1, q1 = 0;
  double x = v;
  for (int k = 0; k < 40; ++k) {
    const double a = std::floor(x);
    if (std::fabs(a) > static_cast<double>(rational_denominator) * 1e6) break;  // also keeps the casts in range
    const long p2 = static_cast<long>(a) * p1 + p0, q2 = static_cast<long>(a) * q1 + q0;
    if (q2 > rational_denominator) break;
    p0 = p1, q0 = q1, p1 = p2, q1 = q2;
    if (std::fabs(v - static_cast<double>(p1) / static_cast<double>(q1)) < rational_tolerance) return GiNaC::numeric(p1, q1);
    if (x - a < 1e-300) break;
    x = 1 / (x - a);
  }
  return std::nullopt;
}

/// The certificate of find_clash() with polynomial multipliers, as a linear
/// programme: unknowns λ >= 0 on the products μ·Nᵢ (μ = 1 or one positive
/// symbol) and μ·(K_p + K_q ± 2c) (the 2×2 minor forms of the couplings c);
/// −Σ λ·products must have a zero coefficient on every monomial with an odd
/// power of a coupling and a nonnegative one elsewhere, and the strict
/// conditions' λ sum to 1.  The double solution is rounded to small fractions
/// and the identity checked exactly (certainly_nonnegative); nullopt otherwise.
std::optional<Clash> lp_clash(const std::vector<Usable>& usable, bool asymptotic, bool with_superball, const Symbols& sy) {
  std::vector<GiNaC::ex> mus{GiNaC::ex(1)};
  for (const SymbolInfo& i : sy.all())
    if (i.kind != SymbolKind::Coupling && i.kind != SymbolKind::FallSpeed) mus.push_back(i.symbol);
  struct Product {
    GiNaC::ex value, mu;
    int condition;  ///< index in usable, or −1 for a minor form
    bool strict;
    std::string bracket;  ///< minor form: "K₁₂ + K₁₃ + 2α₁"
    GiNaC::ex form;
  };
  std::vector<Product> products;
  bool any_strict = false, has_superball = false;
  for (std::size_t i = 0; i < usable.size(); ++i) {
    const bool superball = usable[i].condition->kind == ConditionKind::Superball;
    if (superball && !with_superball) continue;
    has_superball = has_superball || superball;
    const bool strict = usable[i].condition->relation == Relation::Greater;
    any_strict = any_strict || strict;
    for (const GiNaC::ex& mu : mus) products.push_back({GiNaC::expand(mu * usable[i].form->numerator), mu, static_cast<int>(i), strict, "", 0});
  }
  if (!any_strict || (with_superball && !has_superball)) return std::nullopt;
  for (const PairCoupling& c : sy.pattern().couplings) {
    if (!sy.pattern().has_diagonal(c.first) || !sy.pattern().has_diagonal(c.second)) continue;
    for (int sign : {1, -1}) {
      const GiNaC::ex form = sy.diagonal(c.first) + sy.diagonal(c.second) + 2 * sign * sy.coupling(c.first, c.second);
      for (const GiNaC::ex& mu : mus)
        products.push_back({GiNaC::expand(mu * form), mu, -1, false, format_polynomial(GiNaC::expand(form), sy, Style::Text), form});
    }
  }
  // Rows: one per monomial; a product enters with its coefficient.
  std::map<std::vector<std::pair<int, int>>, std::vector<double>> rows;
  for (std::size_t j = 0; j < products.size(); ++j)
    for (Monomial& m : sy.monomials(products[j].value)) {
      std::sort(m.powers.begin(), m.powers.end());  // GiNaC's order of the factors varies between runs
      auto& row = rows[m.powers];
      row.resize(products.size(), 0.0);
      row[j] += m.coefficient.to_double();
    }
  std::vector<std::vector<double>> eq, le;
  std::vector<double> b;
  for (auto& [powers, row] : rows) {
    row.resize(products.size(), 0.0);
    bool odd = false;
    for (const auto& [k, e] : powers) odd = odd || (sy.all()[static_cast<std::size_t>(k)].kind == SymbolKind::Coupling && e % 2);
    if (odd) {
      eq.push_back(row);
      b.push_back(0);
    } else {
      le.push_back(row);  // Σ λ·coefficient <= 0: the negation's coefficient is >= 0
    }
  }
  std::vector<double> normal(products.size(), 0.0);
  // Normalisation: the strict conditions' λ sum to 1 (a nonzero multiplier is a sum of positive terms, so > 0).
  for (std::size_t j = 0; j < products.size(); ++j) normal[j] = products[j].strict ? 1 : 0;
  eq.push_back(normal);
  b.push_back(1);
  const auto x = feasible_point(eq, b, le, products.size());
  if (!x) return std::nullopt;
  // Exact check with the rounded multipliers, scaled to integers.
  std::vector<GiNaC::numeric> lambdas;
  GiNaC::numeric common = 1;
  for (std::size_t j = 0; j < products.size(); ++j) {
    const auto lambda = small_fraction((*x)[j]);
    if (!lambda || *lambda < 0) return std::nullopt;
    lambdas.push_back(*lambda);
    common = GiNaC::lcm(common, lambda->denom());
  }
  std::vector<GiNaC::ex> multipliers(usable.size(), GiNaC::ex(0));
  std::map<std::string, std::pair<GiNaC::ex, GiNaC::ex>> forms;  // bracket text → (its multiplier, the bracket)
  GiNaC::ex sum = 0, q = 0;
  for (std::size_t j = 0; j < products.size(); ++j) {
    const GiNaC::numeric lambda_j = lambdas[j] * common;
    const GiNaC::numeric* lambda = &lambda_j;
    if (lambda->is_zero()) continue;
    const Product& p = products[j];
    if (p.condition >= 0) {
      multipliers[static_cast<std::size_t>(p.condition)] += *lambda * p.mu;
      sum += *lambda * p.value;
    } else {
      auto& slot = forms[p.bracket];
      slot.first += *lambda * p.mu;
      slot.second = p.form;
      q += *lambda * p.value;
    }
  }
  bool strict = false;
  for (std::size_t i = 0; i < usable.size(); ++i) {
    multipliers[i] = GiNaC::expand(multipliers[i]);
    strict = strict || (usable[i].condition->relation == Relation::Greater && certainly_positive(multipliers[i], sy));
  }
  // A strict condition with a multiplier > 0 (nonzero sum of 1 and positive symbols) makes the sum > 0.
  if (!strict) return std::nullopt;
  const GiNaC::ex rest = GiNaC::expand(-sum - q);
  if (!certainly_nonnegative(rest, sy)) return std::nullopt;
  std::string q_text;
  for (const auto& [bracket, f] : forms)
    q_text += (q_text.empty() ? "" : " + ") + std::string("(") + format_polynomial(GiNaC::expand(f.first), sy, Style::Text) + ")·(" + bracket + ")";
  return make_clash(usable, multipliers, q_text, rest, asymptotic, sy);
}

/// Search weights w ∈ {0, 1, 2} on the case's conditions and a form Q >= 0
/// on M ⪰ 0 — t·xᵀMx (t ∈ {0, 1, 2}, x ∈ {−1, 0, 1} on the coupled pairs up
/// to sign) or minor_multiples() — with −Σ wᵢNᵢ − Q certainly nonnegative
/// and some strict condition weighted; then lp_clash() (polynomial
/// multipliers).  Without the superball condition first: a clash there
/// proves the case never actual.
std::optional<Clash> find_clash(const Derivation& d, const Symbols& sy, bool asymptotic) {
  std::vector<Usable> usable;
  for (const Condition& c : d.conditions) {
    if (c.kind == ConditionKind::Psd) continue;
    const ConditionForm& form = asymptotic ? c.asymptotic : c.exact;
    if (form.sign_proved()) usable.push_back({&c, &form});
  }
  std::stable_partition(usable.begin(), usable.end(), [](const Usable& u) { return u.condition->kind != ConditionKind::Superball; });
  // The quadratic forms: only coupled pairs matter (an uncoupled pair adds t·K_p to the bracket's negative side).
  std::vector<Pair> pairs;
  for (const PairCoupling& c : sy.pattern().couplings)
    for (const Pair& p : {c.first, c.second})
      if (std::find(pairs.begin(), pairs.end(), p) == pairs.end()) pairs.push_back(p);
  std::sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) { return a.name() < b.name(); });
  struct Form {
    GiNaC::ex value;
    std::string text;  ///< "" for 0, else "t·xᵀMx, x = …"
  };
  std::vector<Form> forms{{GiNaC::ex(0), ""}};
  if (!pairs.empty() && pairs.size() <= 8) {
    std::vector<int> x(pairs.size(), -1);
    do {
      const auto first = std::find_if(x.begin(), x.end(), [](int v) { return v != 0; });
      if (first == x.end() || *first < 0) continue;  // x and −x give the same form
      const GiNaC::ex q = quadratic_form(x, pairs, sy);
      for (int t : {1, 2}) forms.push_back({GiNaC::expand(t * q), std::to_string(t) + "·xᵀMx, x = " + signed_pairs(x, pairs)});
    } while (next_signs(x));
  }
  const std::size_t n = usable.size();
  std::vector<std::vector<int>> weights;
  std::vector<int> w(n, 0);
  for (;;) {
    std::size_t i = 0;
    while (i < n && w[i] == 2) w[i++] = 0;
    if (i == n) break;
    ++w[i];
    weights.push_back(w);
  }
  // Fewer conditions first, the superball condition last (it is the last usable one).
  auto key = [&](const std::vector<int>& v) {
    int used = 0, total = 0;
    for (int x : v) used += x > 0, total += x;
    const bool superball = n > 0 && usable.back().condition->kind == ConditionKind::Superball && v.back() > 0;
    return std::make_tuple(superball, used, total);
  };
  std::stable_sort(weights.begin(), weights.end(), [&](const auto& a, const auto& b) { return key(a) < key(b); });
  // Without the superball condition first: a clash there proves the case never actual.
  for (const bool with_superball : {false, true}) {
    for (const std::vector<int>& wt : weights) {
      if (std::get<0>(key(wt)) != with_superball) continue;
      bool strict = false;
      GiNaC::ex sum = 0;
      for (std::size_t i = 0; i < n; ++i)
        if (wt[i]) {
          sum += wt[i] * usable[i].form->numerator;
          strict = strict || usable[i].condition->relation == Relation::Greater;
        }
      if (!strict) continue;
      sum = GiNaC::expand(sum);
      std::vector<Form> candidates = forms;
      if (const auto m = minor_multiples(-sum, sy)) candidates.push_back({m->first, m->second});
      for (const Form& q : candidates) {
        const GiNaC::ex rest = GiNaC::expand(-sum - q.value);
        if (!certainly_nonnegative(rest, sy)) continue;
        std::vector<GiNaC::ex> multipliers(wt.begin(), wt.end());
        return make_clash(usable, multipliers, q.text, rest, asymptotic, sy);
      }
    }
    if (auto clash = lp_clash(usable, asymptotic, with_superball, sy)) return clash;
  }
  return std::nullopt;
}

/// The couplings of \p sy in \p style, ", "-separated (text) or ","-separated (ASCII).
std::string couplings_text(const Symbols& sy, Style style) {
  std::string s;
  for (const SymbolInfo& i : sy.all())
    if (i.kind == SymbolKind::Coupling) s += (s.empty() ? "" : style == Style::Ascii ? "," : ", ") + i.name(style);
  return s.empty() ? (style == Style::Ascii ? "none" : "no coupling") : s;
}

}  // namespace
}  // namespace detail

std::string impossibility_certificate(const GiNaC::ex& s_poly, const symbolic::Symbols& sy) {
  const std::vector<Pair> pairs = sy.pattern().pairs();
  const std::size_t k = pairs.size();
  if (k > 10) return "";
  std::vector<int> x(k, -1);
  do {
    const GiNaC::ex form = detail::quadratic_form(x, pairs, sy);
    if (!form.is_zero())
      for (int t : {1, 2}) {
        const GiNaC::ex rest = GiNaC::expand(-s_poly - t * form);
        if (symbolic::certainly_nonnegative(rest, sy))
          return "the superball condition reads S > 0 with -S = " + std::to_string(t) + "·xᵀMx + (" +
                 symbolic::format_polynomial(rest, sy, symbolic::Style::Text) + "), x = " + detail::signed_pairs(x, pairs) +
                 ": every term of the bracket is >= 0 and xᵀMx >= 0 when M is positive semi-definite, so S <= 0";
      }
  } while (detail::next_signs(x));
  return "";
}

std::string describe_box(const ExploreOptions& o) {
  return "every mass and K in [" + numeric::to_string(o.box_low, 6) + ", " + numeric::to_string(o.box_high, 6) +
         "] (log scale), each coupling t·√(K_p K_q) with t in [-1, 1], a = 1, bottom body fixed";
}

const char* to_string(Reach r) {
  switch (r) {
    case Reach::Yes: return "yes";
    case Reach::Impossible: return "no (proved)";
    case Reach::CaseImpossible: return "case impossible";
    case Reach::NotFound: break;
  }
  return "not found";
}

ExploreResult explore_case(const symbolic::Deriver& deriver, const ContactSet& closed, const ExploreOptions& o) {
  using namespace superball::symbolic;
  using cln::cl_RA;
  if (deriver.symbols().obstacle() != Obstacle::Infinite) detail::fail("the search needs a fixed obstacle (m_n = infinity)");
  if (closed.bodies() != deriver.symbols().bodies()) detail::fail("the case is for " + std::to_string(closed.bodies()) + " bodies");
  o.check();
  const Symbols& sy = deriver.symbols();
  const Derivation d = deriver.derive(closed);
  const ParameterSpace space(deriver);
  ExploreResult out;
  out.pattern = detail::couplings_text(sy, Style::Text);
  out.pattern_ascii = detail::couplings_text(sy, Style::Ascii);
  out.case_name = d.case_name;
  out.closed = closed;
  out.box = describe_box(o);
  out.seed = o.seed;

  // The feasible set: the case's evolution and contact conditions and M ⪰ 0.
  std::vector<detail::Constraint> constraints;
  for (const Condition& c : d.conditions)
    if (c.kind != ConditionKind::Superball)
      constraints.push_back({CompiledCondition(c, c.exact, sy), Polynomial(detail::absolute_terms(c.exact.numerator, sy), sy)});
  const Fraction& u1 = d.velocities.front();
  const Polynomial u1_numerator(u1.numerator, sy), u1_denominator(u1.denominator, sy);
  const detail::Box box(space, o);
  detail::Objective f{box, constraints, u1_numerator, u1_denominator};

  // Multi-start local search.
  RegimeSampler sampler(space, cl_RA(1) / detail::regime_inverse_epsilon, o.seed);
  std::mt19937_64 rng(o.seed);
  std::vector<std::pair<std::vector<double>, double>> ends;
  for (int s = 0; s < o.starts; ++s) {
    std::vector<double> y(static_cast<std::size_t>(box.size()));
    std::optional<Point> regime;
    if (s % 2 == 0) regime = sampler.draw();
    if (regime) {
      y = box.coordinates_of(*regime);
    } else {
      for (int v = 0; v < box.size(); ++v) y[static_cast<std::size_t>(v)] = std::uniform_real_distribution<double>(box.lower(v), box.upper(v))(rng);
    }
    ends.push_back(detail::nelder_mead(f, box, y, o.evaluations));
    ++out.stats.starts;
    if (ends.back().second < detail::infeasible_floor) {
      ++out.stats.feasible_starts;
      const double r = f.ratio(box.point(ends.back().first));
      out.stats.best_double = std::max(out.stats.best_double, r);
      if (r > 1) ++out.stats.superball_starts;
    }
  }
  std::stable_sort(ends.begin(), ends.end(), [](const auto& a, const auto& b) { return a.second < b.second; });

  // Exact confirmation of the best feasible ends, stepping inward when the rounded point fails.
  numeric::CollisionSolver<cl_RA> solver;
  int tried = 0;
  for (const auto& [y0, value] : ends) {
    if (value >= detail::infeasible_floor || tried++ >= detail::confirmations || !out.witness.empty()) break;
    const bool wants_superball = f.ratio(box.point(y0)) > 1;
    std::vector<double> y = y0;
    for (double margin : detail::margins) {
      if (margin > detail::margins[0]) {
        ++out.stats.inward_steps;
        detail::Objective inward{box, constraints, u1_numerator, u1_denominator, margin};
        y = detail::nelder_mead(inward, box, y, o.evaluations / 2).first;
        f.evaluations += inward.evaluations;
      }
      const std::optional<Point> x = box.exact(y);
      if (!x) continue;
      const numeric::Problem<cl_RA> problem = space.problem(*x);
      numeric::Solution<cl_RA> sol;
      solver.compute(problem, sol);
      ++out.stats.exact_solves;
      const cl_RA a = -problem.u.front();
      if (sol.status != numeric::Status::Success || sol.closed != closed) continue;
      if (wants_superball && !(sol.velocities_after[0] > a)) continue;
      out.witness = space.named(*x);
      out.scene = space.scene(*x, "explore: " + out.pattern + ", case " + out.case_name);
      out.u1 = sol.velocities_after[0];
      out.ratio = out.u1 / a;
      break;
    }
  }
  out.stats.evaluations = f.evaluations;
  if (!out.witness.empty() && out.ratio > 1) {
    out.reach = Reach::Yes;
    return out;
  }
  out.clash = detail::find_clash(d, sy, false);
  out.asymptotic_clash = detail::find_clash(d, sy, true);
  if (out.clash) out.reach = out.clash->superball ? Reach::Impossible : Reach::CaseImpossible;
  return out;
}

std::vector<std::vector<int>> table_patterns() { return {{1}, {2}, {3}, {4}, {5}, {6}, {7}, {1, 6}}; }

PatternTable explore_all_patterns(const ExploreOptions& options) {
  options.check();
  PatternTable t;
  t.options = options;
  t.patterns = table_patterns();
  for (const NamedCase& c : Vocabulary::paper().cases()) t.cases.push_back(c.name);
  for (const std::vector<int>& alphas : t.patterns) {
    const symbolic::Deriver deriver(symbolic::Pattern::paper(alphas), symbolic::Obstacle::Infinite);
    std::vector<ExploreResult> row;
    for (const NamedCase& c : Vocabulary::paper().cases()) row.push_back(explore_case(deriver, c.closed, options));
    t.cells.push_back(std::move(row));
  }
  return t;
}

std::string cell_text(const ExploreResult& r) {
  if (r.reach == Reach::Yes) {
    // Four significant digits, more when fewer would round the ratio (> 1) to 1.
    const double ratio = cln::double_approx(r.ratio);
    int digits = 4;
    while (digits < 17 && std::stod(numeric::to_string(ratio, digits)) <= 1) ++digits;
    return "yes U₁⁺/a = " + numeric::to_string(ratio, digits);
  }
  if (r.reach != Reach::NotFound) return to_string(r.reach);
  std::string notes;
  if (!r.witness.empty()) notes = "best U₁⁺/a = " + numeric::to_string(cln::double_approx(r.ratio), 6);
  if (r.asymptotic_clash) notes += std::string(notes.empty() ? "" : "; ") + "leading order clashes";
  return notes.empty() ? "not found" : "not found (" + notes + ")";
}

std::string to_text(const ExploreResult& r) {
  std::ostringstream os;
  os << "pattern " << r.pattern << ", case " << r.case_name << " (closed contacts: "
     << (r.closed.closed_names().empty() ? std::string("none") : r.closed.to_string()) << ")\n";
  os << "  verdict: " << to_string(r.reach);
  switch (r.reach) {
    case Reach::Yes: os << ": the case is the actual evolution with U₁⁺ > a at the witness (exact solve)\n"; break;
    case Reach::Impossible: os << ": the case's conditions and U₁⁺ > a cannot hold together for any M positive semi-definite\n"; break;
    case Reach::CaseImpossible: os << ": the case's conditions cannot hold together for any M positive semi-definite\n"; break;
    case Reach::NotFound: os << ": no witness with U₁⁺ > a in the box, and no proof of impossibility\n"; break;
  }
  os << "  box: " << r.box << "\n";
  if (!r.witness.empty()) {
    os << "  " << (r.reach == Reach::Yes ? "largest U₁⁺/a found in the box" : "largest U₁⁺/a found with the case actual") << ": "
       << numeric::to_string(cln::double_approx(r.ratio), 8) << " = " << to_string(r.ratio) << " (exact solve; double search "
       << numeric::to_string(r.stats.best_double, 8) << ")\n";
    std::string point;
    for (const auto& [name, v] : r.witness) point += (point.empty() ? "" : ", ") + name + " = " + to_string(v);
    os << "  witness: " << point << "\n";
    os << "  exact solve there: case " << r.case_name << " actual, U1+ = " << to_string(r.u1) << "\n";
  } else {
    os << "  the case was never actual at a searched point\n";
  }
  const ExploreStats& s = r.stats;
  os << "  search: seed " << r.seed << ", " << s.starts << " starts, " << s.evaluations << " evaluations, " << s.feasible_starts
     << " ended with the case's conditions holding (" << s.superball_starts << " with U₁⁺ > a), " << s.exact_solves << " exact solves, "
     << s.inward_steps << " steps inward\n";
  for (const std::optional<Clash>* c : {&r.clash, &r.asymptotic_clash}) {
    if (!*c) continue;
    os << "  clash of the " << ((*c)->asymptotic ? "leading-order (asymptotic)" : "exact") << " conditions:\n";
    for (const std::string& line : (*c)->conditions) os << "    " << line << "\n";
    os << "    " << (*c)->identity << "\n";
  }
  if (r.reach != Reach::Yes) {
    if (!r.clash) os << "  no clash of the exact conditions found (weights {0, 1, 2}, t·xᵀMx with x in {-1, 0, 1} on the coupled pairs)\n";
    if (!r.asymptotic_clash) os << "  no clash of the leading-order conditions found\n";
  }
  return os.str();
}

RenderedCell render(const ExploreResult& r) { return {r.pattern, cell_text(r), to_json(r)}; }

namespace {

std::vector<std::vector<RenderedCell>> render_cells(const PatternTable& t) {
  std::vector<std::vector<RenderedCell>> cells;
  for (const auto& row : t.cells) {
    cells.emplace_back();
    for (const ExploreResult& c : row) cells.back().push_back(render(c));
  }
  return cells;
}

}  // namespace

std::string to_text(const PatternTable& t) { return to_text(t, render_cells(t)); }

std::string to_text(const PatternTable& t, const std::vector<std::vector<RenderedCell>>& cells) {
  std::ostringstream os;
  os << "| pattern |";
  for (const std::string& c : t.cases) os << " case " << c << " |";
  os << "\n|---|";
  for (std::size_t k = 0; k < t.cases.size(); ++k) os << "---|";
  os << "\n";
  for (std::size_t r = 0; r < t.patterns.size(); ++r) {
    os << "| " << (cells[r].empty() ? std::string() : cells[r].front().pattern) << " |";
    for (const RenderedCell& c : cells[r]) os << " " << c.text << " |";
    os << "\n";
  }
  os << "\nbox: " << describe_box(t.options) << "; per cell: seed " << t.options.seed << ", " << t.options.starts << " starts of at most "
     << t.options.evaluations << " evaluations (Nelder–Mead), the best ends confirmed by exact solves; \"no (proved)\" and \"case impossible\" "
     << "are proofs (a clash of the exact conditions), \"not found\" is neither a witness nor a proof\n";
  return os.str();
}

nlohmann::ordered_json to_json(const ExploreResult& r) {
  nlohmann::ordered_json j;
  j["pattern"] = r.pattern_ascii;
  j["case"] = r.case_name;
  j["closed_contacts"] = r.closed.closed_names();
  j["reach"] = to_string(r.reach);
  j["box"] = r.box;
  j["seed"] = r.seed;
  if (!r.witness.empty()) {
    nlohmann::ordered_json point = nlohmann::ordered_json::object();
    for (const auto& [name, v] : r.witness) point[name] = to_string(v);
    j["witness"] = point;
    j["U1"] = to_string(r.u1);
    j["ratio"] = to_string(r.ratio);
    j["ratio_decimal"] = cln::double_approx(r.ratio);
  }
  const ExploreStats& s = r.stats;
  j["stats"] = {{"starts", s.starts},           {"evaluations", s.evaluations},   {"feasible_starts", s.feasible_starts},
                {"superball_starts", s.superball_starts}, {"exact_solves", s.exact_solves}, {"inward_steps", s.inward_steps},
                {"best_double", s.best_double}};
  for (const auto& [key, c] : {std::make_pair("clash", &r.clash), std::make_pair("asymptotic_clash", &r.asymptotic_clash)})
    if (*c) j[key] = {{"superball", (*c)->superball}, {"conditions", (*c)->conditions}, {"identity", (*c)->identity}};
  return j;
}

nlohmann::ordered_json to_json(const PatternTable& t) { return to_json(t, render_cells(t)); }

nlohmann::ordered_json to_json(const PatternTable& t, const std::vector<std::vector<RenderedCell>>& cells) {
  nlohmann::ordered_json j;
  j["box"] = describe_box(t.options);
  j["seed"] = t.options.seed;
  j["starts"] = t.options.starts;
  j["evaluations"] = t.options.evaluations;
  j["cases"] = t.cases;
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (std::size_t r = 0; r < t.patterns.size(); ++r) {
    nlohmann::ordered_json row = nlohmann::ordered_json::array();
    for (const RenderedCell& c : cells[r]) row.push_back(c.json);
    rows.push_back({{"alphas", t.patterns[r]}, {"cells", row}});
  }
  j["rows"] = rows;
  return j;
}

std::string witness_file(const ExploreResult& r, const std::string& command) {
  if (!r.scene) throw std::invalid_argument("witness_file(): the result has no witness");
  const std::string comment = "Found by `" + command + "`: multi-start Nelder-Mead on the derived conditions of case " + r.case_name +
                              " in the box (" + r.box + "), rounded to rationals.\nExact solve (CollisionSolver over rationals, case not imposed): case " +
                              r.case_name + " is the actual evolution, U1+ = " + to_string(r.u1) + " = " +
                              numeric::to_string(cln::double_approx(r.ratio), 10) + " a" + (r.ratio > 1 ? " > a (superball)" : " <= a (no superball)") +
                              ".\nCheck: superball solve FILE --precision exact";
  return write_scene(*r.scene, comment);
}

}  // namespace superball::verify
