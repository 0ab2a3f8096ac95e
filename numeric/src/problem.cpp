#include "superball/numeric/problem.hpp"

#include <cln/rational_io.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "superball/cases/scene_file.hpp"

namespace superball::numeric {
namespace {

cln::cl_RA exact(const Number& x) { return parse_rational(x.fraction()); }

std::string text(const cln::cl_RA& x) {
  std::ostringstream os;
  cln::fprint(os, x);
  return os.str();
}

/// The sign of x·a + y for a = sqrt(a²) > 0, decided exactly.
int sign_with_root(const cln::cl_RA& x, const cln::cl_RA& y, const cln::cl_RA& a_squared) {
  const int sx = cln::signum(x) > 0 ? 1 : cln::zerop(x) ? 0 : -1;
  const int sy = cln::signum(y) > 0 ? 1 : cln::zerop(y) ? 0 : -1;
  if (sx == 0 || sy == 0 || sx == sy) return sx != 0 ? sx : sy;
  const cln::cl_RA lhs = x * x * a_squared, rhs = y * y;
  return lhs > rhs ? sx : lhs < rhs ? sy : 0;
}

/// Throws when an adjacent contact opens before the collision: D_c(U⁻) =
/// U⁻_i − U⁻_{i+1} > 0.  In Frémond's law the reaction's share of the
/// dissipation is P^reac · D_c(U⁻)/2 (paper §3, eq. 12: P^reac · D_c(U⁺) = 0),
/// which is >= 0 only when D_c(U⁻) <= 0; an opening contact can create energy.
void check_contacts_close(const ExactScene& s, const std::string& origin) {
  const cln::cl_RA a_squared = s.a_squared ? *s.a_squared : cln::cl_RA(0);
  for (int i = 0; i + 1 < s.n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const cln::cl_RA x = s.fall[k] - s.fall[k + 1], y = s.velocity[k] - s.velocity[k + 1];
    if (sign_with_root(x, y, a_squared) <= 0) continue;
    const double d = ScalarTraits<cln::cl_RA>::to_double(x) * std::sqrt(ScalarTraits<cln::cl_RA>::to_double(a_squared)) +
                     ScalarTraits<cln::cl_RA>::to_double(y);
    std::ostringstream os;
    os << origin << ": body[" << i + 2 << "].velocity: contact " << i + 1 << "-" << i + 2
       << " opens before the collision (U" << i + 1 << "- - U" << i + 2 << "- = " << d
       << " m/s > 0); the collision law needs every contact closing or at rest (each body falls at least as fast as the one below)";
    throw InputError(os.str());
  }
}

}  // namespace

std::optional<NegativeMinor> find_negative_minor(SymmetricRows M) {
  // Symmetric elimination in exact arithmetic, pivots in index order: after
  // eliminating the pivots P (all > 0), det M[P ∪ Q] = det M[P] · det S[Q]
  // for Q outside P, with S the Schur complement.  So a negative diagonal of
  // S, or a zero diagonal S_kk with some S_kj ≠ 0 (the 2×2 block (0 x; x s)
  // has determinant −x²), gives a negative principal minor of M.  Only the
  // nonzero entries are stored and updated: for a banded M (a chain) fill-in
  // stays inside the band and the cost is O(m b²).
  const int m = static_cast<int>(M.size());
  auto diagonal = [&](int i) {
    const auto it = M[static_cast<std::size_t>(i)].find(i);
    return it == M[static_cast<std::size_t>(i)].end() ? cln::cl_RA(0) : it->second;
  };
  std::vector<int> pivots;
  cln::cl_RA product = 1;
  auto minor = [&](std::initializer_list<int> more, const cln::cl_RA& det) {
    std::vector<int> idx = pivots;
    idx.insert(idx.end(), more);
    std::sort(idx.begin(), idx.end());
    return NegativeMinor{idx, det};
  };
  for (int i = 0; i < m; ++i)
    if (diagonal(i) < 0) return minor({i}, diagonal(i));
  // Gershgorin: a symmetric M whose every diagonal entry is at least the sum
  // of the magnitudes of its row's other entries is PSD.  Exact, O(nnz), and
  // it decides at once the usual chains, whose rationals would otherwise grow
  // along the elimination.
  const bool dominant = std::all_of(M.begin(), M.end(), [&](const std::map<int, cln::cl_RA>& row) {
    cln::cl_RA off = 0, diag = 0;
    for (const auto& [j, x] : row) (j == static_cast<int>(&row - M.data()) ? diag : off) += cln::abs(x);
    return off <= diag;
  });
  if (dominant) return std::nullopt;
  // The 2×2 principal minors next, so that the usual mistake (one coupling
  // too large for its two K's) is named by its two pairs.
  for (int i = 0; i < m; ++i)
    for (const auto& [j, x] : M[static_cast<std::size_t>(i)])
      if (j > i && diagonal(i) * diagonal(j) < x * x) return minor({i, j}, diagonal(i) * diagonal(j) - x * x);
  for (int k = 0; k < m; ++k) {
    auto& row = M[static_cast<std::size_t>(k)];
    const cln::cl_RA pivot = diagonal(k);
    if (cln::zerop(pivot)) {
      for (const auto& [j, x] : row)
        if (j != k && !cln::zerop(x)) return minor({k, j}, -product * x * x);
      continue;  // a zero row of S: no part of any negative minor
    }
    // S_ij -= S_ik S_kj / S_kk for i, j > k in row k; then drop row k.
    std::vector<std::pair<int, cln::cl_RA>> rest;
    for (const auto& [j, x] : row)
      if (j > k && !cln::zerop(x)) rest.emplace_back(j, x);
    for (const auto& [i, xi] : rest) {
      auto& ri = M[static_cast<std::size_t>(i)];
      ri.erase(k);
      const cln::cl_RA f = xi / pivot;
      for (const auto& [j, xj] : rest) ri[j] = ri[j] - f * xj;
    }
    product = product * pivot;
    pivots.push_back(k);
    for (const auto& [i, xi] : rest)
      if (diagonal(i) < 0) return minor({i}, product * diagonal(i));
  }
  return std::nullopt;
}

namespace {

/// The pairs that the entries of M involve, sorted, and M on them.
struct PairMatrix {
  std::vector<Pair> pairs;
  SymmetricRows M;
};
PairMatrix pair_matrix(const std::vector<Entry<cln::cl_RA>>& entries) {
  PairMatrix pm;
  for (const Entry<cln::cl_RA>& e : entries)
    for (const Pair& p : {Pair{e.i + 1, e.j + 1}, Pair{e.k + 1, e.l + 1}}) pm.pairs.push_back(p);
  std::sort(pm.pairs.begin(), pm.pairs.end());
  pm.pairs.erase(std::unique(pm.pairs.begin(), pm.pairs.end()), pm.pairs.end());
  auto index = [&](const Pair& p) { return static_cast<int>(std::lower_bound(pm.pairs.begin(), pm.pairs.end(), p) - pm.pairs.begin()); };
  pm.M.resize(pm.pairs.size());
  for (const Entry<cln::cl_RA>& e : entries) {
    const int a = index({e.i + 1, e.j + 1}), b = index({e.k + 1, e.l + 1});
    pm.M[static_cast<std::size_t>(a)][b] = e.value;
    pm.M[static_cast<std::size_t>(b)][a] = e.value;
  }
  return pm;
}

}  // namespace

bool positive_semidefinite(const ExactScene& scene) { return !find_negative_minor(pair_matrix(scene.entries).M); }

ExactScene ExactScene::from(const Scene& scene) { return from(scene, MCheck::PositiveSemidefinite); }

ExactScene ExactScene::from(const Scene& scene, MCheck m) {
  ExactScene s;
  s.origin = scene.origin;
  s.n = scene.size();
  if (s.n < 2) throw InputError(scene.origin + ": body: a scene needs at least 2 bodies");
  s.fixed_bottom = scene.bodies.back().infinite;
  if (scene.drop_height) s.a_squared = 2 * exact(scene.g) * exact(*scene.drop_height);
  if (scene.fall_speed) s.a_squared = exact(*scene.fall_speed) * exact(*scene.fall_speed);
  for (int i = 0; i < s.n; ++i) {
    const Body& b = scene.bodies[static_cast<std::size_t>(i)];
    if (b.infinite && i + 1 != s.n)
      throw InputError(scene.origin + ": body[" + std::to_string(i + 1) + "].mass: only the bottom body may be fixed");
    s.mass.push_back(b.infinite ? cln::cl_RA(0) : exact(b.mass));
    if (!b.infinite && !(s.mass.back() > 0))
      throw InputError(scene.origin + ": body[" + std::to_string(i + 1) + "].mass: must be > 0");
    if (b.velocity) {
      s.fall.push_back(0);
      s.velocity.push_back(exact(*b.velocity));
    } else if (b.infinite) {
      s.fall.push_back(0);
      s.velocity.push_back(0);
    } else {
      if (!s.a_squared)
        throw InputError(scene.origin + ": body[" + std::to_string(i + 1) +
                         "]: no velocity before the collision (give velocity, drop_height or fall_speed)");
      s.fall.push_back(-1);
      s.velocity.push_back(0);
    }
  }
  // Declared entries of M and the pairs they involve.
  for (const MatrixEntry& e : scene.entries) {
    for (const Pair& p : {e.first, e.second})
      if (p.i < 1 || p.j > s.n || p.i >= p.j)
        throw InputError(scene.origin + ": dissipation: pair " + p.name() + " is outside bodies 1.." + std::to_string(s.n));
    s.entries.push_back({e.first.i - 1, e.first.j - 1, e.second.i - 1, e.second.j - 1, exact(e.value)});
  }
  if (m == MCheck::PositiveSemidefinite) {
    const PairMatrix pm = pair_matrix(s.entries);
    if (const auto minor = find_negative_minor(pm.M)) {
      std::string names;
      for (int k : minor->indices) names += (names.empty() ? "" : ", ") + pm.pairs[static_cast<std::size_t>(k)].name();
      throw InputError(scene.origin + ": dissipation: M is not positive semi-definite: its principal minor on pairs (" + names +
                       ") is " + text(minor->determinant) + " < 0");
    }
  }
  check_contacts_close(s, scene.origin);
  // The dense solver's size limit, up front (solves_as_chain(): a banded
  // DᵀMD, 2b + 1 < n, goes to the chain solver, which has none).
  int b = 0;
  for (const Entry<cln::cl_RA>& e : s.entries) b = std::max(b, e.span());
  if (2 * b + 1 >= s.n && s.n > dense_solver_max_bodies)
    throw InputError(scene.origin + ": body: " + std::to_string(s.n) + " bodies with M coupling pairs " + std::to_string(b) +
                     " bodies apart: the dense solver takes at most " + std::to_string(dense_solver_max_bodies) +
                     " bodies (a longer chain needs M banded: couplings at most (n - 2)/2 bodies apart)");
  return s;
}

bool ExactScene::homogeneous() const {
  return std::all_of(velocity.begin(), velocity.end(), [](const cln::cl_RA& v) { return cln::zerop(v); });
}

cln::cl_RA ExactScene::unit_squared() const { return homogeneous() && a_squared ? *a_squared : cln::cl_RA(1); }

std::optional<std::vector<cln::cl_RA>> ExactScene::exact_u() const {
  if (homogeneous()) return fall;
  cln::cl_RA a = 0;
  const bool falls = std::any_of(fall.begin(), fall.end(), [](const cln::cl_RA& f) { return !cln::zerop(f); });
  if (falls && !cln::sqrtp(*a_squared, &a)) return std::nullopt;
  std::vector<cln::cl_RA> u;
  for (std::size_t i = 0; i < fall.size(); ++i) u.push_back(fall[i] * a + velocity[i]);
  return u;
}

template <class S>
Problem<S> Problem<S>::from(const ExactScene& s, int digits) {
  using T = ScalarTraits<S>;
  Problem<S> p;
  p.n = s.n;
  p.fixed_bottom = s.fixed_bottom;
  p.digits = digits;
  // x converted from r; a nonzero r that S rounds to zero, a subnormal or
  // infinity means S cannot hold the scene.
  auto held = [&](const S& x, bool nonzero) {
    if constexpr (std::is_floating_point<S>::value)
      if (!std::isfinite(x) || (nonzero && !(std::fabs(x) >= std::numeric_limits<S>::min()))) p.in_range = false;
    return x;
  };
  auto convert = [&](const cln::cl_RA& r) { return held(T::from(r, digits), !cln::zerop(r)); };
  for (const auto& m : s.mass) p.mass.push_back(convert(m));
  for (const auto& e : s.entries) p.entries.push_back({e.i, e.j, e.k, e.l, convert(e.value)});
  if (s.homogeneous()) {
    for (const auto& f : s.fall) p.u.push_back(convert(f));
    if (s.a_squared && !T::sqrt(*s.a_squared, digits, p.unit)) {
      p.unit = S(1);
      p.unit_exact = false;
    }
    held(p.unit, s.a_squared && !cln::zerop(*s.a_squared));
  } else if (const auto u = s.exact_u()) {
    for (const auto& x : *u) p.u.push_back(convert(x));
  } else if (T::exact) {
    throw InputError(s.origin + ": exact arithmetic needs rational velocities: the fall speed sqrt(" + text(*s.a_squared) +
                     ") is irrational and some bodies have their own velocity; give fall_speed, or choose another precision");
  } else {
    S a;
    T::sqrt(*s.a_squared, digits, a);
    held(a, !cln::zerop(*s.a_squared));
    for (std::size_t i = 0; i < s.fall.size(); ++i)
      p.u.push_back(held(T::from(s.fall[i], digits) * a + T::from(s.velocity[i], digits), !cln::zerop(s.velocity[i]) || !cln::zerop(s.fall[i])));
  }
  return p;
}

template <class S>
Problem<S> Problem<S>::scaled(const Scaling& k) const {
  Problem<S> p = *this;
  for (S& m : p.mass) m = times_power_of_two(m, -k.mass);
  for (Entry<S>& e : p.entries) e.value = times_power_of_two(e.value, -k.mass);
  for (S& x : p.u) x = times_power_of_two(x, -k.velocity);
  return p;
}

template <class S>
Scaling scaling_of(const Problem<S>& p) {
  Scaling k;
  if constexpr (std::is_floating_point<S>::value) {
    constexpr int w = safe_exponent<S>();
    // The smallest and largest nonzero magnitudes of a group (two compares
    // per datum: this runs before every solve), then their binary exponents
    // e (|x| = f·2^e, 1/2 <= f < 1): lo … hi; inside the window means −w < e <= w.
    struct Span {
      S smallest = std::numeric_limits<S>::infinity(), largest = S(0);
      void add(const S& x) {
        const S a = std::fabs(x);
        if (a < smallest && a > S(0)) smallest = a;
        if (a > largest) largest = a;
      }
    };
    Span masses, velocities;
    for (const S& m : p.mass) masses.add(m);
    for (const Entry<S>& e : p.entries) masses.add(e.value);
    for (const S& x : p.u) velocities.add(x);
    // Shifting by c = lo + ⌊(hi − lo)/2⌋ puts every exponent inside when hi − lo < 2w.
    auto centre = [&k](const Span& g, int& shift) {
      if (!(g.largest > S(0))) return;  // no nonzero datum
      int lo = 0, hi = 0;
      std::frexp(g.smallest, &lo);
      std::frexp(g.largest, &hi);
      if (lo > -w && hi <= w) return;
      if (hi - lo >= 2 * w) k.fits = false;
      shift = lo + (hi - lo) / 2;
    };
    centre(masses, k.mass);
    centre(velocities, k.velocity);
  } else {
    (void)p;
  }
  return k;
}

template <class S>
int Problem<S>::check(const char* who) const {
  auto fail = [who](const char* what) { throw std::invalid_argument(std::string(who) + ": " + what); };
  if (n < 2) fail("a problem needs at least 2 bodies");
  if (static_cast<int>(mass.size()) != n || static_cast<int>(u.size()) != n) fail("masses and velocities must have one entry per body");
  // One pass for both, with no branch per entry.  As unsigned numbers,
  // i < j < n holds exactly when 0 <= i < j < n (a negative i or j wraps
  // above n).
  bool outside = false;
  int b = 0;
  const auto un = static_cast<unsigned>(n);
  for (const Entry<S>& e : entries) {
    const auto i = static_cast<unsigned>(e.i), j = static_cast<unsigned>(e.j), k = static_cast<unsigned>(e.k),
               l = static_cast<unsigned>(e.l);
    outside |= (i >= j) | (j >= un) | (k >= l) | (l >= un);
    b = std::max(b, e.span());
  }
  if (outside) fail("an entry of M names a pair outside the bodies");
  if (!constrained.empty() && static_cast<int>(constrained.size()) != n - 1) fail("constrained must be empty or have one flag per contact");
  return b;
}

template SUPERBALL_NUMERIC_EXPORT Scaling scaling_of(const Problem<double>&);
template SUPERBALL_NUMERIC_EXPORT Scaling scaling_of(const Problem<long double>&);
template SUPERBALL_NUMERIC_EXPORT Scaling scaling_of(const Problem<cln::cl_R>&);
template SUPERBALL_NUMERIC_EXPORT Scaling scaling_of(const Problem<MpFloat>&);
template SUPERBALL_NUMERIC_EXPORT Scaling scaling_of(const Problem<cln::cl_RA>&);
template struct Problem<double>;
template struct Problem<long double>;
template struct Problem<cln::cl_R>;
template struct Problem<MpFloat>;
template struct Problem<cln::cl_RA>;

}  // namespace superball::numeric
