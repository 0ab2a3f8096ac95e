#include "superball/numeric/problem.hpp"

#include <cln/rational_io.h>

#include <algorithm>
#include <sstream>

#include "superball/cases/scene_file.hpp"

namespace superball::numeric {
namespace {

cln::cl_RA exact(const Number& x) { return parse_rational(x.fraction()); }

std::string text(const cln::cl_RA& x) {
  std::ostringstream os;
  cln::fprint(os, x);
  return os.str();
}

}  // namespace

std::optional<NegativeMinor> find_negative_minor(const std::vector<std::vector<cln::cl_RA>>& M) {
  // Symmetric pivoted elimination in exact arithmetic: after eliminating the
  // pivots P (all > 0), det M[P ∪ Q] = det M[P] · det S[Q] with S the Schur
  // complement, so a negative diagonal of S, or a 2×2 block (0 x; x 0) of S
  // with x ≠ 0, gives a negative principal minor of M.
  const int m = static_cast<int>(M.size());
  std::vector<std::vector<cln::cl_RA>> S = M;
  std::vector<int> pivots, rest(static_cast<std::size_t>(m));
  for (int i = 0; i < m; ++i) rest[static_cast<std::size_t>(i)] = i;
  cln::cl_RA product = 1;
  while (!rest.empty()) {
    for (int i : rest)
      if (S[i][i] < 0) {
        std::vector<int> idx = pivots;
        idx.push_back(i);
        std::sort(idx.begin(), idx.end());
        return NegativeMinor{idx, product * S[i][i]};
      }
    int best = rest.front();
    for (int i : rest)
      if (S[i][i] > S[best][best]) best = i;
    if (cln::zerop(S[best][best])) {
      for (int i : rest)
        for (int j : rest)
          if (i < j && !cln::zerop(S[i][j])) {
            std::vector<int> idx = pivots;
            idx.push_back(i);
            idx.push_back(j);
            std::sort(idx.begin(), idx.end());
            return NegativeMinor{idx, -product * S[i][j] * S[i][j]};
          }
      return std::nullopt;
    }
    rest.erase(std::find(rest.begin(), rest.end(), best));
    for (int i : rest)
      for (int j : rest) S[i][j] = S[i][j] - S[i][best] * S[best][j] / S[best][best];
    product = product * S[best][best];
    pivots.push_back(best);
  }
  return std::nullopt;
}

ExactScene ExactScene::from(const Scene& scene) {
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
  std::vector<Pair> pairs;
  for (const MatrixEntry& e : scene.entries) {
    for (const Pair& p : {e.first, e.second}) {
      if (p.i < 1 || p.j > s.n || p.i >= p.j)
        throw InputError(scene.origin + ": dissipation: pair " + p.name() + " is outside bodies 1.." + std::to_string(s.n));
      if (std::find(pairs.begin(), pairs.end(), p) == pairs.end()) pairs.push_back(p);
    }
    s.entries.push_back({e.first.i - 1, e.first.j - 1, e.second.i - 1, e.second.j - 1, exact(e.value)});
  }
  std::sort(pairs.begin(), pairs.end());
  auto index = [&](const Pair& p) { return static_cast<std::size_t>(std::find(pairs.begin(), pairs.end(), p) - pairs.begin()); };
  std::vector<std::vector<cln::cl_RA>> M(pairs.size(), std::vector<cln::cl_RA>(pairs.size(), cln::cl_RA(0)));
  for (const MatrixEntry& e : scene.entries) {
    const std::size_t a = index(e.first), b = index(e.second);
    M[a][b] = M[b][a] = exact(e.value);
  }
  if (const auto minor = find_negative_minor(M)) {
    std::string names;
    for (int k : minor->indices) names += (names.empty() ? "" : ", ") + pairs[static_cast<std::size_t>(k)].name();
    throw InputError(scene.origin + ": dissipation: M is not positive semi-definite: its principal minor on pairs (" + names +
                     ") is " + text(minor->determinant) + " < 0");
  }
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
  for (const auto& m : s.mass) p.mass.push_back(T::from(m, digits));
  for (const auto& e : s.entries) p.entries.push_back({e.i, e.j, e.k, e.l, T::from(e.value, digits)});
  if (s.homogeneous()) {
    for (const auto& f : s.fall) p.u.push_back(T::from(f, digits));
    if (s.a_squared && !T::sqrt(*s.a_squared, digits, p.unit)) {
      p.unit = S(1);
      p.unit_exact = false;
    }
  } else if (const auto u = s.exact_u()) {
    for (const auto& x : *u) p.u.push_back(T::from(x, digits));
  } else if (T::exact) {
    throw InputError(s.origin + ": exact arithmetic needs rational velocities: the fall speed sqrt(" + text(*s.a_squared) +
                     ") is irrational and some bodies have their own velocity; give fall_speed, or choose another precision");
  } else {
    S a;
    T::sqrt(*s.a_squared, digits, a);
    for (std::size_t i = 0; i < s.fall.size(); ++i) p.u.push_back(T::from(s.fall[i], digits) * a + T::from(s.velocity[i], digits));
  }
  return p;
}

template struct Problem<double>;
template struct Problem<long double>;
template struct Problem<cln::cl_R>;
template struct Problem<cln::cl_RA>;

}  // namespace superball::numeric
