#include "superball/numeric/sweep.hpp"

#include <cln/integer.h>
#include <cln/rational_io.h>

#include <cstdio>
#include <cstdlib>
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>

#include "superball/cases/error.hpp"
#include "superball/numeric/batch.hpp"
#include "superball/numeric/certify.hpp"
#include "collision/cluster.hpp"
#include "map_internal.hpp"
#include "superball/numeric/parallel.hpp"
#include "superball/numeric/psd_along.hpp"

namespace superball::numeric {
namespace detail {

std::vector<std::string> as_text(const std::vector<cln::cl_RA>& values) {
  std::vector<std::string> texts;
  texts.reserve(values.size());
  for (const auto& v : values) texts.push_back(to_string(v));
  return texts;
}

std::pair<std::size_t, std::size_t> extremes(const std::vector<cln::cl_RA>& values) {
  std::size_t low = 0, high = 0;
  double dlow = ScalarTraits<double>::from(values[0], 0), dhigh = dlow;
  for (std::size_t k = 1; k < values.size(); ++k) {
    const double d = ScalarTraits<double>::from(values[k], 0);
    if (d < dlow || (d == dlow && values[k] < values[low])) low = k, dlow = d;
    if (d > dhigh || (d == dhigh && !(values[k] < values[high]))) high = k, dhigh = d;
  }
  return {low, high};
}

}  // namespace detail

namespace {

using detail::as_text;

/// A thread's own copy of the scene, with the parameter set to \p text, a
/// value inside a range that check_values() has passed.
const Scene& set_value(Scene& copy, const Parameter& parameter, const std::string& text) {
  parameter.assign(copy, Number::parse(text));
  return copy;
}

/// check_range(), returning the scenes at \p from and at \p to.
std::pair<Scene, Scene> checked_ends(const Scene& scene, const Parameter& parameter, const cln::cl_RA& from, const cln::cl_RA& to) {
  std::vector<Scene> ends;
  for (const cln::cl_RA& end : {from, to}) {
    ends.push_back(with_value(scene, parameter, end));
    const Scene& s = ends.back();
    try {
      (void)ExactScene::from(s);
    } catch (const InputError& e) {
      // "ORIGIN: field: why" -> "ORIGIN: KEY = VALUE: field: why"
      const std::string what = e.what(), prefix = scene.origin + ": ";
      throw InputError(prefix + parameter.key() + " = " + to_string(end) + ": " +
                       (what.rfind(prefix, 0) == 0 ? what.substr(prefix.size()) : what));
    }
  }
  return {std::move(ends[0]), std::move(ends[1])};
}

/// check_range() from the smallest to the largest of \p values: every value
/// a sweep sets lies between two that passed every check.
/// Returns the scenes at the smallest and the largest value (none without values).
std::optional<std::pair<Scene, Scene>> check_values(const Scene& scene, const Parameter& parameter, const std::vector<cln::cl_RA>& values) {
  if (values.empty()) return std::nullopt;
  const auto [low, high] = detail::extremes(values);
  return checked_ends(scene, parameter, values[low], values[high]);
}

ExactPoint solve_exact(const Scene& scene) {
  auto problem = Problem<cln::cl_RA>::from(ExactScene::from(scene));
  auto solution = solve(problem);
  return {std::move(problem), std::move(solution)};
}

}  // namespace

ExactPoint solve_exact_at(const Scene& scene, const Parameter& parameter, const cln::cl_RA& value) {
  return solve_exact(with_value(scene, parameter, value));
}

namespace {

/// A thread's copy of a line's problem in S (double or long double),
/// converted once, only the entry of M set at each value: the problem of
/// converting that value's scene, bit for bit (entry_sweep(), and the
/// shortcut of label_changes()).
template <class S>
struct EntryProblem {
  Problem<S> problem;
  std::size_t entry;
  bool in_range;  ///< Problem::from()'s verdict on everything but the entry

  EntryProblem(const ExactScene& exact, std::size_t k, int digits = 0)
      : problem(Problem<S>::from(exact, digits)), entry(k), in_range(true) {
    ExactScene one = exact;
    one.entries[k].value = 1;
    in_range = Problem<S>::from(one, digits).in_range;
  }

  /// The entry set to \p v, the value in S of an exact value that is zero
  /// when \p is_zero; Problem::in_range as Problem::from() would say.
  void set(const S& v, bool is_zero) {
    problem.entries[entry].value = v;
    problem.in_range = in_range && detail::held(v, is_zero);
  }

  /// What the solve at \p value proves about the exact solution there, or
  /// nothing when its case is not certain.  The superball verdict is proven
  /// when U₁⁺ − |U₁⁻| exceeds the certified bound on U₁⁺ plus the rounding
  /// of U₁⁻ and of the comparison (proven_verdict_rounding).
  std::optional<ProvenPoint> prove(const cln::cl_RA& value) {
    using T = ScalarTraits<S>;
    const S v = T::from(value, 0);
    if (!detail::held(v, cln::zerop(value))) return std::nullopt;
    set(v, cln::zerop(value));
    const Solution<S> sol = solve(problem);
    const Certificate c = certify(problem, sol);
    if (!c.case_certain || !std::isfinite(c.relative_error)) return std::nullopt;
    ProvenPoint p{sol.closed, std::nullopt};
    S largest = 0;
    for (const S& w : sol.velocities_after) largest = std::max(largest, S(std::fabs(w)));
    const S after = sol.velocities_after[0], before = std::fabs(problem.u[0]);
    const S bound = S(c.relative_error) * largest + S(proven_verdict_rounding) * T::unit_roundoff(0) * (std::fabs(after) + before + largest);
    if (after - before > bound) p.superball = true;
    if (before - after > bound) p.superball = false;
    return p;
  }
};

/// The signs that decide whether a case holds along a line, and the
/// superball verdict there, as polynomials in the value t of the entry of M
/// that varies: for each contact c, Δ·λ_c where it is closed and
/// Δ·(W_c − W_{c+1}) where it is open, and Δ·(W_1 − |u_1|), with
/// Δ = det(Zᵀ A Z) > 0 the determinant of the case's reduced system.  A(t)
/// is affine in t with a slope of rank at most 2 (one entry of M adds
/// t[(e_i − e_j)(e_k − e_l)ᵀ + transpose]) and b̃(t) is affine, so Δ has
/// degree at most 2, Δ·W at most 3 (cofactors of degree 2 times b̃), and
/// Δ·λ, a running sum of rows of A(t)·ΔW − Δ·b̃, at most 4
/// (case_signs_degree).  Each polynomial is interpolated exactly through
/// case_signs_degree + 1 values of t in the checked range and checked at one
/// more; its coefficients are then integers (a positive factor cleared), and
/// its sign at t = p/q (q > 0) is that of Σ a_k p^k q^(d−k): products of
/// integers, no gcd.
/// \p n as a long double, its magnitude cut to 64 bits: within 2^-63·|n|
/// (two units of roundoff) of n; infinite beyond the range of long double.
long double truncated(const cln::cl_I& n) {
  const cln::cl_I m = cln::abs(n);
  const long shift = std::min(std::max(0L, static_cast<long>(cln::integer_length(m)) - 64), 1L << 20);
  const long double v = std::ldexp(static_cast<long double>(cln::cl_I_to_UQ(cln::ash(m, -shift))), static_cast<int>(shift));
  return cln::minusp(n) ? -v : v;
}

/// The rounding allowed when CaseSigns::sign_near() evaluates a polynomial of
/// degree d = CaseSigns::degree in long double, in units of its unit roundoff
/// u times Σ|a_k||t|^k: coefficients within 2u (truncated()), t within 5u (a
/// quotient of two truncated integers), so t^k within 5ku, and Horner's
/// rounding within γ_2d; in all (2 + 5d + 2d)u = 30u at d = 4, doubled for
/// the rounding of Σ|a_k||t|^k itself and room.
constexpr long double sign_filter_rounding = 64;

struct CaseSigns {
  static constexpr int degree = 4;
  ContactSet closed;
  bool valid = false;                          ///< interpolated and checked at the extra point
  std::vector<std::vector<cln::cl_I>> polys;  ///< per contact, then the superball's: a_0 … a_degree
  std::vector<std::vector<long double>> near;  ///< the same coefficients, truncated()

  /// Append the polynomial of coefficients \p a.
  void add(std::vector<cln::cl_I> a) {
    near.emplace_back();
    for (const auto& x : a) near.back().push_back(truncated(x));
    polys.push_back(std::move(a));
  }

  /// Sign of polynomial \p k at t, from \p t_near (t within 5u), when long
  /// double decides it: the value beyond sign_filter_rounding·u·Σ|a_k||t|^k.
  std::optional<int> sign_near(std::size_t k, long double t_near) const {
    long double v = 0, size = 0;
    const long double at = std::fabs(t_near);
    for (int j = degree; j >= 0; --j) {
      const long double a = near[k][static_cast<std::size_t>(j)];
      v = v * t_near + a;
      size = size * at + std::fabs(a);
    }
    if (size == 0) return 0;  // every coefficient is 0 (truncated() keeps 0 and only 0)
    // Far from overflow and underflow, or exactly.
    if (!std::isfinite(v) || !std::isfinite(size) || size < std::ldexp(std::numeric_limits<long double>::min(), 128)) return std::nullopt;
    const long double bound = sign_filter_rounding * ScalarTraits<long double>::unit_roundoff(0) * size;
    if (v > bound) return 1;
    if (v < -bound) return -1;
    return std::nullopt;
  }

  /// Sign of polynomial \p k at p/q (q > 0), given p^j and q^j for j = 0 … degree.
  int sign_at(std::size_t k, const std::vector<cln::cl_I>& pp, const std::vector<cln::cl_I>& qq) const {
    cln::cl_I sum = 0;
    for (int j = 0; j <= degree; ++j) {
      const cln::cl_I& a = polys[k][static_cast<std::size_t>(j)];
      if (!cln::zerop(a)) sum = sum + a * pp[static_cast<std::size_t>(j)] * qq[static_cast<std::size_t>(degree - j)];
    }
    return cln::minusp(sum) ? -1 : cln::zerop(sum) ? 0 : 1;
  }
};

/// The coefficients c_0 … c_d (d = t.size() − 1) of the polynomial through
/// (t_j, y_j), by Newton's divided differences.
std::vector<cln::cl_RA> through(const std::vector<cln::cl_RA>& t, std::vector<cln::cl_RA> dd) {
  const std::size_t d = t.size() - 1;
  for (std::size_t level = 1; level <= d; ++level)
    for (std::size_t j = d; j >= level; --j) dd[j] = (dd[j] - dd[j - 1]) / (t[j] - t[j - level]);
  std::vector<cln::cl_RA> c(d + 1, 0);
  c[0] = dd[d];
  for (std::size_t j = d; j-- > 0;) {  // c(t) <- c(t)·(t − t_j) + dd_j
    for (std::size_t m = d; m >= 1; --m) c[m] = c[m - 1] - t[j] * c[m];
    c[0] = dd[j] - t[j] * c[0];
  }
  return c;
}

/// The value at \p t of the polynomial of coefficients \p c.
cln::cl_RA value_at(const std::vector<cln::cl_RA>& c, const cln::cl_RA& t) {
  cln::cl_RA at = 0;
  for (std::size_t m = c.size(); m-- > 0;) at = at * t + c[m];
  return at;
}

/// \p c times the positive lcm of its denominators: integers of the same signs.
std::vector<cln::cl_I> cleared(const std::vector<cln::cl_RA>& c) {
  cln::cl_I common = 1;
  for (const auto& x : c) common = cln::lcm(common, cln::denominator(x));
  std::vector<cln::cl_I> a;
  for (const auto& x : c) a.push_back(cln::exquo(cln::numerator(x) * common, cln::denominator(x)));
  return a;
}

/// An exact problem and the storage of its cluster solves.
struct CaseSolver {
  Problem<cln::cl_RA> problem;
  int bandwidth;
  detail::ClusterSystem<cln::cl_RA> system;
  std::vector<cln::cl_RA> W, lambda;
  std::vector<char> flags;

  explicit CaseSolver(const ExactScene& exact) : problem(Problem<cln::cl_RA>::from(exact, 0)), bandwidth(problem.bandwidth()) {}

  /// Solve case \p closed by its cluster system at the problem's entries as
  /// set: the quantities whose signs decide it (CaseSigns), times Δ when \p
  /// times_determinant.
  bool quantities(const ContactSet& closed, bool times_determinant, std::vector<cln::cl_RA>& q) {
    system.assemble(problem, bandwidth);
    flags.assign(static_cast<std::size_t>(closed.contacts()), 0);
    for (int c = 0; c < closed.contacts(); ++c) flags[static_cast<std::size_t>(c)] = closed.closed(c);
    if (!system.solve(problem, flags, W, lambda)) return false;
    const cln::cl_RA delta = times_determinant ? system.determinant() : cln::cl_RA(1);
    q.clear();
    for (int c = 0; c < closed.contacts(); ++c) {
      const auto k = static_cast<std::size_t>(c);
      q.push_back(delta * (closed.closed(c) ? lambda[k] : W[k] - W[k + 1]));
    }
    q.push_back(delta * (W[0] - cln::abs(problem.u[0])));
    return true;
  }
};

}  // namespace

namespace detail {

/// The polynomials of CaseSigns over the plane of two entries ex and ey of M
/// (a map whose two axes are entries of M), per case: each Δ·quantity is a
/// polynomial of degree at most CaseSigns::degree in each of the two entries
/// (the argument of CaseSigns, for either entry), interpolated exactly on a
/// grid of (degree + 1)² nodes and checked at two more points; along a line
/// of the map (one entry fixed) it gives that line's CaseSigns without a
/// solve.  A case whose nodes do not all solve, or that fails a check, is not
/// valid, and its lines make their own.
struct PlaneSigns {
  static constexpr int degree = 4;
  CaseSolver solver;
  std::size_t ex, ey;
  std::vector<cln::cl_RA> xs, ys;  ///< the nodes
  std::array<std::pair<cln::cl_RA, cln::cl_RA>, 2> checks;
  struct Case {
    ContactSet closed;
    bool valid = false;
    std::vector<std::vector<std::vector<cln::cl_RA>>> c;  ///< c[k][m][n]: of x^m y^n in quantity k
  };
  std::vector<Case> cases;

  PlaneSigns(const ExactScene& exact, std::size_t kx, std::size_t ky, const cln::cl_RA& x0, const cln::cl_RA& x1, const cln::cl_RA& y0,
             const cln::cl_RA& y1)
      : solver(exact), ex(kx), ey(ky) {
    for (int j = 0; j <= degree; ++j) xs.push_back(x0 + (x1 - x0) * j / degree), ys.push_back(y0 + (y1 - y0) * j / degree);
    checks = {std::pair<cln::cl_RA, cln::cl_RA>{x0 + (x1 - x0) * 3 / 8, y0 + (y1 - y0) * 5 / 8}, {x0 + (x1 - x0) * 7 / 8, y0 + (y1 - y0) / 8}};
  }

  bool quantities(const ContactSet& closed, const cln::cl_RA& x, const cln::cl_RA& y, std::vector<cln::cl_RA>& q) {
    solver.problem.entries[ex].value = x;
    solver.problem.entries[ey].value = y;
    return solver.quantities(closed, true, q);
  }

  const Case& of(const ContactSet& closed) {
    for (const Case& c : cases)
      if (c.closed == closed) return c;
    Case made;
    made.closed = closed;
    const std::size_t n = static_cast<std::size_t>(degree) + 1;
    std::vector<std::vector<std::vector<cln::cl_RA>>> y(n, std::vector<std::vector<cln::cl_RA>>(n));  // y[i][j][k] at (xs_i, ys_j)
    bool solved = true;
    for (std::size_t i = 0; i < n && solved; ++i)
      for (std::size_t j = 0; j < n && solved; ++j) solved = quantities(closed, xs[i], ys[j], y[i][j]);
    if (solved) {
      made.valid = true;
      const std::size_t count = y[0][0].size();
      for (std::size_t k = 0; k < count; ++k) {
        // Along x at each ys_j, then each coefficient along y.
        std::vector<std::vector<cln::cl_RA>> along_x(n);  // along_x[j][m]
        for (std::size_t j = 0; j < n; ++j) {
          std::vector<cln::cl_RA> v;
          for (std::size_t i = 0; i < n; ++i) v.push_back(y[i][j][k]);
          along_x[j] = through(xs, v);
        }
        std::vector<std::vector<cln::cl_RA>> c(n);
        for (std::size_t m = 0; m < n; ++m) {
          std::vector<cln::cl_RA> v;
          for (std::size_t j = 0; j < n; ++j) v.push_back(along_x[j][m]);
          c[m] = through(ys, v);
        }
        made.c.push_back(std::move(c));
      }
      std::vector<cln::cl_RA> q;
      for (const auto& [cx, cy] : checks) {
        if (!made.valid || !quantities(closed, cx, cy, q)) {
          made.valid = false;
          break;
        }
        for (std::size_t k = 0; k < count && made.valid; ++k) made.valid = at(made.c[k], cx, cy) == q[k];
      }
    }
    cases.push_back(std::move(made));
    return cases.back();
  }

  static cln::cl_RA at(const std::vector<std::vector<cln::cl_RA>>& c, const cln::cl_RA& x, const cln::cl_RA& y) {
    std::vector<cln::cl_RA> in_x;
    for (const auto& row : c) in_x.push_back(value_at(row, y));
    return value_at(in_x, x);
  }

  /// The CaseSigns of \p closed along the line where entry \p entry (ex or
  /// ey) varies and the other is \p fixed.
  CaseSigns along(const ContactSet& closed, std::size_t entry, const cln::cl_RA& fixed) {
    CaseSigns s;
    s.closed = closed;
    const Case& plane = of(closed);
    s.valid = plane.valid;
    if (!s.valid) return s;
    const std::size_t n = static_cast<std::size_t>(degree) + 1;
    for (const auto& c : plane.c) {
      std::vector<cln::cl_RA> line(n);
      for (std::size_t v = 0; v < n; ++v) {
        std::vector<cln::cl_RA> other(n);
        for (std::size_t w = 0; w < n; ++w) other[w] = entry == ex ? c[v][w] : c[w][v];
        line[v] = value_at(other, fixed);
      }
      s.add(cleared(line));
    }
    return s;
  }
};

}  // namespace detail

namespace {

/// The exact problem of a line, only the entry of M set at each value, for
/// the shortcut of label_changes() where floating point cannot decide: the
/// two cases met last are checked at the value.  A case whose every closed
/// contact has a reaction < 0 and every open one a gap > 0, exactly, is the
/// exact solution's case: the velocities after the collision are unique and
/// strict complementarity fixes the closed set, so a solve finds the same
/// case and the same velocities.  Each case is checked by its CaseSigns,
/// made once per line from its cluster system (detail::ClusterSystem: one
/// banded solve, no pivoting) at CaseSigns::degree + 2 values, or, where
/// those do not check out, by its cluster system at the value itself.
struct ExactCases {
  CaseSolver solver;
  std::size_t entry;
  cln::cl_RA low, high;  ///< the checked range: M positive semi-definite on it
  detail::PlaneSigns* plane;  ///< the polynomials over the map's plane, when the line is one of its lines
  std::vector<ContactSet> recent;  ///< the cases met last, the latest first
  std::vector<CaseSigns> signs;    ///< per case met on this line
  std::vector<cln::cl_I> pp, qq;   ///< powers of the value's numerator and denominator

  ExactCases(const ExactScene& exact, std::size_t k, const cln::cl_RA& from, const cln::cl_RA& to, detail::PlaneSigns* in_plane = nullptr)
      : solver(exact), entry(k), low(from), high(to), plane(in_plane) {}

  /// Remember \p closed as the latest case met (two are kept: a bisection's
  /// bracket has a case at each end).
  void met(const ContactSet& closed) {
    const auto at = std::find(recent.begin(), recent.end(), closed);
    if (at != recent.end()) recent.erase(at);
    recent.insert(recent.begin(), closed);
    if (recent.size() > 2) recent.pop_back();
  }

  /// Solve case \p closed at \p value by its cluster system (CaseSolver::quantities()).
  bool quantities(const ContactSet& closed, const cln::cl_RA& value, bool times_determinant, std::vector<cln::cl_RA>& q) {
    solver.problem.entries[entry].value = value;
    return solver.quantities(closed, times_determinant, q);
  }

  /// The CaseSigns of \p closed on this line, made on first use: from the
  /// plane's when it has a valid one, else interpolated on the line.
  const CaseSigns& signs_of(const ContactSet& closed) {
    for (const CaseSigns& s : signs)
      if (s.closed == closed) return s;
    if (plane) {
      const std::size_t fixed = entry == plane->ex ? plane->ey : plane->ex;
      CaseSigns s = plane->along(closed, entry, solver.problem.entries[fixed].value);
      if (s.valid) {
        signs.push_back(std::move(s));
        return signs.back();
      }
    }
    CaseSigns s;
    s.closed = closed;
    constexpr int d = CaseSigns::degree;
    std::vector<cln::cl_RA> t;
    std::vector<std::vector<cln::cl_RA>> y;  // y[j][k]: quantity k at t_j
    bool solved = true;
    for (int j = 0; j <= d + 1 && solved; ++j) {
      t.push_back(low + (high - low) * j / (d + 1));
      y.emplace_back();
      solved = quantities(closed, t.back(), true, y.back());
    }
    if (solved) {
      s.valid = true;
      const std::vector<cln::cl_RA> nodes(t.begin(), t.begin() + d + 1);
      for (std::size_t k = 0; k < y[0].size() && s.valid; ++k) {
        std::vector<cln::cl_RA> v;
        for (int j = 0; j <= d; ++j) v.push_back(y[static_cast<std::size_t>(j)][k]);
        const std::vector<cln::cl_RA> c = through(nodes, v);
        // The check at the extra value t_{d+1}.
        if (value_at(c, t[static_cast<std::size_t>(d + 1)]) != y[static_cast<std::size_t>(d + 1)][k]) s.valid = false;
        s.add(cleared(c));
      }
    }
    signs.push_back(std::move(s));
    return signs.back();
  }

  /// The exact case and superball verdict at \p value when one of the
  /// cases met last holds there strictly, else nothing.
  std::optional<ProvenPoint> prove(const cln::cl_RA& value) {
    const cln::cl_I p = cln::numerator(value), q = cln::denominator(value);
    const long double t = truncated(p) / truncated(q);
    // t within 5u of p/q: neither overflowed nor (unless 0) underflowed.
    const bool t_held = std::isfinite(t) && (cln::zerop(p) || std::fabs(t) >= std::ldexp(std::numeric_limits<long double>::min(), 64));
    pp.clear(), qq.clear();
    // The sign in long double where it decides, else exactly (the powers made once).
    auto sign = [&](const CaseSigns& s, std::size_t k) {
      if (t_held)
        if (const std::optional<int> near = s.sign_near(k, t)) return *near;
      if (pp.empty()) {
        pp.assign(1, 1), qq.assign(1, 1);
        for (int j = 1; j <= CaseSigns::degree; ++j) pp.push_back(pp.back() * p), qq.push_back(qq.back() * q);
      }
      return s.sign_at(k, pp, qq);
    };
    std::vector<cln::cl_RA> at;
    for (const ContactSet& closed : recent) {
      const CaseSigns& s = signs_of(closed);
      const std::size_t contacts = static_cast<std::size_t>(closed.contacts());
      bool strict = true;
      if (s.valid) {
        for (std::size_t k = 0; k < contacts && strict; ++k) strict = sign(s, k) > 0;
        if (strict) return ProvenPoint{closed, sign(s, contacts) > 0};
        continue;
      }
      if (!quantities(closed, value, false, at)) continue;
      for (std::size_t k = 0; k < contacts && strict; ++k) strict = cln::plusp(at[k]);
      if (strict) return ProvenPoint{closed, cln::plusp(at[contacts])};
    }
    return std::nullopt;
  }
};

/// A thread's means of labelling the exact solution at a value: its own copy
/// of the line (a scene and the parameter, or an exact scene and the entry of
/// M that varies) for the exact solve, and, with a ProvenLabel along an entry
/// of M, the shortcuts tried first: a certified double solve, then the cases
/// met last checked exactly.  Labels are numbered as they are met (ids), so
/// that a bisection compares numbers and makes no text but for the labels
/// themselves; a proven label is remembered by what was proven.
struct Labeller {
  Scene scene;                        ///< the line, when it is a scene and a parameter
  const Parameter* parameter = nullptr;
  std::optional<ExactScene> line;     ///< the line, when it is an exact scene and an entry of M
  std::size_t line_entry = 0;
  const Label& label;
  const ProvenLabel& proven;
  std::optional<EntryProblem<double>> in_double;
  std::optional<ExactCases> exactly;
  std::array<std::atomic<std::size_t>, 3>& found_by;  ///< in double, by a case, solved
  std::vector<std::string> names;     ///< the labels met, by id
  std::vector<std::pair<ProvenPoint, std::optional<std::size_t>>> known;  ///< what proven() said of each point proven so far
  /// Try a certified double solve first.  A bisection starts with it and
  /// stops trying when it fails: the midpoints after that one lie nearer the
  /// change, where double cannot prove a case either (on the paper's map,
  /// four tries in five failed).  The labels do not depend on it.
  bool try_double = true;

  /// Along \p p of the scene \p s, from \p low to \p high; \p entry: the entry of M \p p is, if it is one.
  Labeller(const Scene& s, const Parameter& p, const Label& l, const ProvenLabel& pl, std::optional<std::size_t> entry,
           const cln::cl_RA& low, const cln::cl_RA& high, std::array<std::atomic<std::size_t>, 3>& counts)
      : scene(s), parameter(&p), label(l), proven(pl), found_by(counts) {
    if (entry && proven) shortcuts(ExactScene::from(scene), *entry, low, high);
  }

  /// Along the entry \p entry of M of \p exact, from \p low to \p high (M positive semi-definite between them).
  /// \p plane: the case polynomials over a map's plane this line lies in, or none.
  Labeller(const ExactScene& exact, std::size_t entry, const Label& l, const ProvenLabel& pl, const cln::cl_RA& low,
           const cln::cl_RA& high, std::array<std::atomic<std::size_t>, 3>& counts, detail::PlaneSigns* plane)
      : line(exact), line_entry(entry), label(l), proven(pl), found_by(counts) {
    if (proven) shortcuts(exact, entry, low, high, plane);
  }

  void shortcuts(const ExactScene& exact, std::size_t entry, const cln::cl_RA& low, const cln::cl_RA& high, detail::PlaneSigns* plane = nullptr) {
    in_double.emplace(exact, entry);
    exactly.emplace(exact, entry, low, high, plane);
  }

  /// The id of the label \p name.
  std::size_t id(const std::string& name) {
    const auto at = std::find(names.begin(), names.end(), name);
    if (at != names.end()) return static_cast<std::size_t>(at - names.begin());
    names.push_back(name);
    return names.size() - 1;
  }

  /// What proven() says of \p p, as an id.
  std::optional<std::size_t> proven_id(const ProvenPoint& p) {
    for (const auto& [q, l] : known)
      if (q.closed == p.closed && q.superball == p.superball) return l;
    const std::optional<std::string> l = proven(p);
    known.push_back({p, l ? std::optional<std::size_t>(id(*l)) : std::nullopt});
    return known.back().second;
  }

  /// The exact solution at \p value.
  ExactPoint solve_at(const cln::cl_RA& value) {
    if (!line) return solve_exact(set_value(scene, *parameter, to_string(value)));
    line->entries[line_entry].value = value;
    auto problem = Problem<cln::cl_RA>::from(*line);
    auto solution = solve(problem);
    return {std::move(problem), std::move(solution)};
  }

  /// The id of the label of the exact solution at \p value: proven in
  /// double (while try_double), else by the cases met last, else from the
  /// exact solve.
  std::size_t operator()(const cln::cl_RA& value) {
    if (exactly) {
      std::optional<std::size_t> l;
      std::optional<ProvenPoint> p;
      std::size_t by = try_double ? 0 : 1;
      for (; by < 2 && !l; ++by) {
        p = by == 0 ? in_double->prove(value) : exactly->prove(value);
        if (p) l = proven_id(*p);
        if (by == 0 && !l) try_double = false;
      }
      if (l) {
        ++found_by[by - 1];
        exactly->met(p->closed);
        return *l;
      }
    }
    ++found_by[2];
    const ExactPoint e = solve_at(value);
    if (exactly) exactly->met(e.solution.closed);
    return id(label(e));
  }
};

/// A change of label, the labels as Labeller ids.
struct IdChange {
  cln::cl_RA low, high;
  std::size_t below, above;
};

/// Every change of label inside \p c (c.below at c.low, c.above at
/// c.high, different), found by \p bits halvings, appended to \p out from
/// c.low to c.high: where the midpoint's label is neither end's, both halves
/// hold a change and both are searched.
void bisect(Labeller& label_at, IdChange c, int bits, std::vector<LabelChange>& out) {
  for (; bits > 0; --bits) {
    const cln::cl_RA mid = (c.low + c.high) / 2;
    const std::size_t l = label_at(mid);
    if (l == c.below) {
      c.low = mid;
    } else if (l == c.above) {
      c.high = mid;
    } else {
      bisect(label_at, {c.low, mid, c.below, l}, bits - 1, out);
      c.low = mid;
      c.below = l;
    }
  }
  out.push_back({c.low, c.high, label_at.names[c.below], label_at.names[c.above]});
}

void check_bits(int bits, const char* function) {
  if (bits < 1 || bits > max_bits)
    throw std::invalid_argument(std::string(function) + ": bits must be a whole number from 1 to " + std::to_string(max_bits) + ", got " +
                                std::to_string(bits));
}

}  // namespace

std::vector<LabelChange> label_changes(const Scene& scene, const Parameter& parameter, const std::vector<cln::cl_RA>& values,
                                       const Label& label, int bits, int threads, const ProvenLabel& proven, LabelCounts* counts) {
  check_threads(threads);
  refuse_drop(scene, "label_changes()");
  check_bits(bits, "label_changes()");
  for (std::size_t k = 1; k < values.size(); ++k)
    if (values[k] == values[k - 1] || (values[k] > values[k - 1]) != (values[1] > values[0]))
      throw std::invalid_argument("label_changes(): the values must be strictly increasing or strictly decreasing");
  const auto ends = check_values(scene, parameter, values);
  // In increasing value: a descending sweep has the same brackets, read backwards.
  const bool descending = values.size() > 1 && values.back() < values.front();
  std::vector<std::string> texts = as_text(values);
  if (descending) std::reverse(texts.begin(), texts.end());
  // The shortcut needs the parameter to be one entry of M along the whole range.
  std::optional<std::size_t> entry;
  if (proven && ends && texts.front() != texts.back()) entry = detail::entry_changed(ends->first, ends->second);
  const Scene& first = ends ? ends->first : scene;
  std::array<std::atomic<std::size_t>, 3> found_by{};
  // One labeller per thread, made on it; on one thread, one for both passes
  // (the cases met at the values are the first the bisections try).
  const bool one_thread = thread_count(threads) == 1 || values.size() < 2;
  std::shared_ptr<Labeller> only;
  auto make = [&] {
    return std::make_shared<Labeller>(first, parameter, label, proven, entry, parse_rational(texts.front()), parse_rational(texts.back()), found_by);
  };
  if (one_thread) only = make();
  auto make_labeller = [&] { return one_thread ? only : make(); };
  using Own = std::shared_ptr<Labeller>;
  const std::vector<std::string> labels = parallel_map(texts.size(), threads, make_labeller, [&](Own& label_at, std::size_t k) {
    label_at->try_double = true;
    return label_at->names[(*label_at)(parse_rational(texts[k]))];
  });
  std::vector<std::size_t> changes;  // k: the label changes between values k − 1 and k
  for (std::size_t k = 1; k < texts.size(); ++k)
    if (labels[k - 1] != labels[k]) changes.push_back(k);
  const auto found = parallel_map(changes.size(), threads, make_labeller, [&](Own& label_at, std::size_t m) {
    const std::size_t k = changes[m];
    std::vector<LabelChange> out;
    label_at->try_double = true;
    bisect(*label_at, {parse_rational(texts[k - 1]), parse_rational(texts[k]), label_at->id(labels[k - 1]), label_at->id(labels[k])}, bits, out);
    return out;
  });
  std::vector<LabelChange> all;
  for (const auto& f : found) all.insert(all.end(), f.begin(), f.end());
  if (counts) *counts = {found_by[0], found_by[1], found_by[2]};
  return all;
}

namespace detail {

std::shared_ptr<PlaneSigns> plane_signs(const ExactScene& corner, std::size_t kx, std::size_t ky, const cln::cl_RA& x0, const cln::cl_RA& x1,
                                        const cln::cl_RA& y0, const cln::cl_RA& y1) {
  return std::make_shared<PlaneSigns>(corner, kx, ky, x0, x1, y0, y1);
}

std::vector<LabelChange> entry_label_changes(const ExactScene& line, std::size_t entry, const cln::cl_RA& a, const cln::cl_RA& b,
                                             const Label& label, const ProvenLabel& proven, int bits, PlaneSigns* plane) {
  check_bits(bits, "entry_label_changes()");
  const cln::cl_RA& low = a < b ? a : b;
  const cln::cl_RA& high = a < b ? b : a;
  std::array<std::atomic<std::size_t>, 3> found_by{};
  Labeller label_at(line, entry, label, proven, low, high, found_by, plane);
  const std::size_t below = label_at(low);
  label_at.try_double = true;
  const std::size_t above = label_at(high);
  label_at.try_double = true;
  std::vector<LabelChange> out;
  if (below != above) bisect(label_at, {low, high, below, above}, bits, out);
  return out;
}

}  // namespace detail

std::vector<cln::cl_RA> linspace(const cln::cl_RA& from, const cln::cl_RA& to, int steps, int first, int count) {
  if (steps < 2) throw std::invalid_argument("linspace(): steps must be at least 2, got " + std::to_string(steps));
  if (from == to) throw std::invalid_argument("linspace(): start and stop are equal");
  if (count < 0) count = steps - first;
  if (first < 0 || count < 0 || first > steps - count)
    throw std::invalid_argument("linspace(): values " + std::to_string(first) + " .. " + std::to_string(first + count - 1) +
                                " are not among the " + std::to_string(steps));
  std::vector<cln::cl_RA> v;
  v.reserve(static_cast<std::size_t>(count));
  const Grid x(from, to, steps);
  for (int k = first; k < first + count; ++k) v.push_back(x(k));
  return v;
}

Scene with_value(const Scene& scene, const Parameter& parameter, const cln::cl_RA& value) {
  Scene s = scene;
  parameter.set(s, Number::parse(to_string(value)));
  return s;
}

void check_range(const Scene& scene, const Parameter& parameter, const cln::cl_RA& from, const cln::cl_RA& to) {
  (void)checked_ends(scene, parameter, from, to);
}

namespace {

/// sweep() of a parameter that is the entry \p entry of M of \p first (the
/// scene at the first value), in S (double or long double): each thread
/// converts \p first once into a Batch and sets only that entry at each value.  The
/// problem solved is Problem<S>::from() of the value's scene, so the points
/// are those of converting each scene, bit for bit; M stays positive
/// semi-definite between the checked ends (check_range()).
template <class S>
std::vector<SweepPoint> entry_sweep(const Scene& first, std::size_t entry, const std::vector<cln::cl_RA>& values,
                                    const Precision& precision, int threads) {
  using T = ScalarTraits<S>;
  std::vector<S> converted;
  std::vector<char> zero;
  for (const auto& v : values) converted.push_back(T::from(v, precision.digits)), zero.push_back(cln::zerop(v));
  struct State {
    Batch<S> line;
    double unit = 1;
  };
  auto make_state = [&] {
    const ExactScene exact = ExactScene::from(first);
    State st{Batch<S>(exact, {entry}, precision.digits), 1};
    const Problem<S>& p = st.line.problem();
    st.unit = p.unit_exact ? T::to_double(p.unit) : std::sqrt(cln::double_approx(exact.unit_squared()));
    return st;
  };
  // Runs of detail::map_run values per task, each point written in its
  // place, as a map's grid points.
  std::vector<SweepPoint> points(values.size());
  (void)parallel_map((values.size() + detail::map_run - 1) / detail::map_run, threads, make_state, [&](State& st, std::size_t r) {
    const std::size_t from = r * detail::map_run, to = std::min(values.size(), from + detail::map_run);
    st.line.solve_each(
        to - from, [&](std::size_t q) { st.line.set(0, converted[from + q], zero[from + q]); },
        [&](std::size_t q, const Solution<S>& sol) {
          SweepPoint& p = points[from + q];
          p.closed = sol.closed;
          p.status = sol.status;
          p.velocities_after.reserve(sol.velocities_after.size());  // one allocation, not one per body
          for (const auto& w : sol.velocities_after) p.velocities_after.push_back(T::to_double(w) * st.unit);
        });
    return 0;
  });
  // The values, copied on the calling thread (the workers never touch the caller's CLN objects).
  for (std::size_t k = 0; k < points.size(); ++k) points[k].value = values[k];
  return points;
}

}  // namespace

std::vector<SweepPoint> sweep(const Scene& scene, const Parameter& parameter, const std::vector<cln::cl_RA>& values,
                              const Precision& precision, int threads) {
  check_threads(threads);
  refuse_drop(scene, "sweep()");
  if (values.empty()) throw std::invalid_argument("sweep(): no value to solve");
  check_values(scene, parameter, values);
  if (values.size() > 1 && (precision.kind == Precision::Kind::Double || precision.kind == Precision::Kind::LongDouble)) {
    const Scene first = with_value(scene, parameter, values.front());
    const auto other = std::find_if(values.begin(), values.end(), [&](const cln::cl_RA& v) { return v != values.front(); });
    const auto entry = other == values.end() ? std::nullopt : detail::entry_changed(first, with_value(scene, parameter, *other));
    if (entry && precision.kind == Precision::Kind::Double) return entry_sweep<double>(first, *entry, values, precision, threads);
    if (entry) return entry_sweep<long double>(first, *entry, values, precision, threads);
  }
  const std::vector<std::string> texts = as_text(values);
  return parallel_map(values.size(), threads, [&scene] { return scene; }, [&](Scene& s, std::size_t k) {
    const auto exact = ExactScene::from(set_value(s, parameter, texts[k]));
    return with_scalar(precision, [&](auto tag) {
      using S = decltype(tag);
      using T = ScalarTraits<S>;
      const auto problem = Problem<S>::from(exact, precision.digits);
      const auto sol = solve(problem);
      SweepPoint p{parse_rational(texts[k]), {}, sol.closed, sol.status};
      const double unit = problem.unit_exact ? T::to_double(problem.unit) : std::sqrt(cln::double_approx(exact.unit_squared()));
      p.velocities_after.reserve(sol.velocities_after.size());
      for (const auto& w : sol.velocities_after) p.velocities_after.push_back(T::to_double(w) * unit);
      return p;
    });
  });
}

std::vector<bool> sweep_marking_psd(const Scene& scene, const Parameter& parameter, const std::vector<cln::cl_RA>& values,
                                    const Precision& precision, int threads,
                                    const std::function<void(std::size_t, const SweepPoint&)>& deliver,
                                    const std::function<void(std::size_t, std::size_t)>& progress, const TaskRunner& runner) {
  check_threads(threads);
  refuse_drop(scene, "sweep()");
  if (values.empty()) throw std::invalid_argument("sweep(): no value to solve");
  const std::vector<bool> psd = psd_along(scene, parameter, values);
  std::vector<std::size_t> solved;
  for (std::size_t k = 0; k < psd.size(); ++k)
    if (psd[k]) solved.push_back(k);
  if (solved.empty()) {
    const auto [low, high] = detail::extremes(values);
    throw InputError(scene.origin + ": M is not positive semi-definite at any value of the sweep (" + parameter.key() + " from " +
                     to_string(values[low]) + " to " + to_string(values[high]) + "): nothing to solve");
  }
  {
    std::vector<cln::cl_RA> kept;
    kept.reserve(solved.size());
    for (std::size_t k : solved) kept.push_back(values[k]);
    const auto [low, high] = detail::extremes(kept);
    check_range(scene, parameter, kept[low], kept[high]);
  }
  const std::size_t total = solved.size();
  auto solve = [&](std::size_t first, std::size_t size) {
    std::vector<cln::cl_RA> chunk;
    chunk.reserve(size);
    for (std::size_t j = 0; j < size; ++j) chunk.push_back(values[solved[first + j]]);
    return sweep(scene, parameter, chunk, precision, threads);
  };
  if (runner) {
    const std::vector<SweepPoint> points = in_tasks<SweepPoint>(
        runner, total, sweep_chunk_values, "sweep_marking_psd()", solve, write_sweep_points,
        [&](const std::string& text) { return read_sweep_points(text, scene.size()); });
    if (points.size() != total) throw std::invalid_argument("sweep_marking_psd(): a damaged result (not the rows of its values)");
    for (std::size_t j = 0; j < total; ++j) {
      SweepPoint p = points[j];
      p.value = values[solved[j]];
      deliver(solved[j], p);
    }
    return psd;
  }
  for (std::size_t first = 0; first < total; first += sweep_chunk_values) {
    if (progress) progress(first, total);
    const std::size_t size = std::min(total, first + sweep_chunk_values) - first;
    const std::vector<SweepPoint> points = solve(first, size);
    for (std::size_t j = 0; j < size; ++j) deliver(solved[first + j], points[j]);
  }
  if (progress) progress(total, total);
  return psd;
}

std::vector<SwitchPoint> switch_points(const Scene& scene, const Parameter& parameter, const std::vector<SweepPoint>& points,
                                       int bits, int threads) {
  std::vector<cln::cl_RA> values;
  for (const auto& p : points) values.push_back(p.value);
  return switch_points(scene, parameter, values, bits, threads);
}

std::vector<SwitchPoint> switch_points(const Scene& scene, const Parameter& parameter, const std::vector<cln::cl_RA>& values,
                                       int bits, int threads) {
  refuse_drop(scene, "switch_points()");
  if (values.size() < 2) throw std::invalid_argument("switch_points(): at least two values are needed");
  const Label by_case = [](const ExactPoint& e) { return e.solution.closed.to_string(); };
  const ProvenLabel proven_case = [](const ProvenPoint& p) -> std::optional<std::string> { return p.closed.to_string(); };
  // The label back to the case: "{2-3,3-4}" without its braces.
  auto as_case = [&](const std::string& label) { return ContactSet::parse(label.substr(1, label.size() - 2), scene.size()); };
  std::vector<SwitchPoint> out;
  for (const auto& c : label_changes(scene, parameter, values, by_case, bits, threads, proven_case))
    out.push_back({c.low, c.high, as_case(c.below), as_case(c.above)});
  return out;
}

std::string write_sweep_points(const std::vector<SweepPoint>& points) {
  std::string text;
  char number[40];
  for (const SweepPoint& p : points) {
    for (double w : p.velocities_after) {
      std::snprintf(number, sizeof number, "%.17g ", w);
      text += number;
    }
    const std::vector<std::string> closed = p.closed.closed_names();
    std::string names;
    for (const std::string& c : closed) names += (names.empty() ? "" : ",") + c;
    text += (names.empty() ? "none" : names) + " " + to_string(p.status) + "\n";
  }
  return text;
}

std::vector<SweepPoint> read_sweep_points(const std::string& text, int bodies) {
  auto damaged = [&](const std::string& what) { return std::invalid_argument("read_sweep_points(): a damaged result (" + what + ")"); };
  static const Status statuses[] = {Status::Success, Status::NumericalIssue, Status::NoConvergence};
  std::vector<SweepPoint> out;
  std::size_t at = 0;
  while (at < text.size()) {
    const std::size_t eol = text.find('\n', at);
    if (eol == std::string::npos) throw damaged("its last line is cut");
    std::vector<std::string> f;
    for (std::size_t from = at;;) {
      const std::size_t space = text.find(' ', from);
      const std::size_t end = space == std::string::npos || space > eol ? eol : space;
      f.push_back(text.substr(from, end - from));
      if (end == eol) break;
      from = end + 1;
    }
    at = eol + 1;
    if (f.size() != static_cast<std::size_t>(bodies) + 2) throw damaged("a row of the wrong fields");
    SweepPoint row;
    for (int i = 0; i < bodies; ++i) {
      const std::string& w = f[static_cast<std::size_t>(i)];
      char* end = nullptr;
      const double v = w.empty() ? 0 : std::strtod(w.c_str(), &end);
      if (w.empty() || *end) throw damaged("'" + printable(w.substr(0, 40)) + "' is not a number");
      row.velocities_after.push_back(v);
    }
    try {
      const std::string& c = f[static_cast<std::size_t>(bodies)];
      if (c.empty()) throw std::invalid_argument("empty");
      row.closed = ContactSet::parse(c, bodies);
    } catch (const std::invalid_argument&) {
      throw damaged("'" + printable(f[static_cast<std::size_t>(bodies)].substr(0, 40)) + "' is not a case of this scene");
    }
    const std::string& s = f.back();
    bool known = false;
    for (Status st : statuses)
      if (s == to_string(st)) row.status = st, known = true;
    if (!known) throw damaged("'" + printable(s.substr(0, 40)) + "' is not a status");
    out.push_back(std::move(row));
  }
  return out;
}

}  // namespace superball::numeric
