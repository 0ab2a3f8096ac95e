#include "superball/verify/overlay.hpp"

#include <algorithm>
#include <map>
#include <stdexcept>
#include <tuple>

#include "superball/cases/vocabulary.hpp"
#include "superball/numeric/problem.hpp"
#include "superball/numeric/scalar.hpp"
#include "superball/symbolic/pattern.hpp"
#include "superball/verify/space.hpp"

namespace superball::verify {
namespace {

using numeric::Map;
using numeric::MapBoundary;

/// M's entry on pairs (\p p, \p q) of \p s, 0 when it is not declared.
cln::cl_RA entry(const numeric::ExactScene& s, const Pair& p, const Pair& q) {
  for (const auto& e : s.entries) {
    const Pair a{e.i + 1, e.j + 1}, b{e.k + 1, e.l + 1};
    if ((a == p && b == q) || (a == q && b == p)) return e.value;
  }
  return 0;
}

/// The coordinates of \p space at the scene \p s (ExactScene of a scene of the derivation's form).
Point point_of(const ParameterSpace& space, const numeric::ExactScene& s) {
  Point x;
  for (const Coordinate& c : space.coordinates()) switch (c.kind) {
      case symbolic::SymbolKind::Mass: x.push_back(s.mass[static_cast<std::size_t>(c.body - 1)]); break;
      case symbolic::SymbolKind::Diagonal: x.push_back(entry(s, c.first, c.first)); break;
      case symbolic::SymbolKind::Coupling: x.push_back(entry(s, c.first, c.second)); break;
      case symbolic::SymbolKind::FallSpeed: {
        cln::cl_RA a = 0;
        if (!s.a_squared || !cln::sqrtp(*s.a_squared, &a))
          throw std::invalid_argument("overlay(): the fall speed a is not rational (give fall_speed as a number)");
        x.push_back(a);
        break;
      }
    }
  return x;
}

/// The grid line's parameter at fraction \p t from grid index \p k to k + 1 of \p a.
cln::cl_RA at(const numeric::Axis& a, int k, const cln::cl_RA& t) { return a.from + (a.to - a.from) * (k + t) / (a.steps - 1); }

}  // namespace

bool Overlay::agrees() const {
  return std::all_of(matches.begin(), matches.end(), [](const OverlayMatch& m) { return m.agrees(); });
}

Scene Overlay::scene_at(const Scene& scene, const Map& map, const OverlayMatch& match) const {
  const MapBoundary& b = map.boundaries[match.boundary];
  const Scene line = b.along_x ? numeric::with_value(scene, map.y.parameter, at(map.y, b.j, 0))
                               : numeric::with_value(scene, map.x.parameter, at(map.x, b.i, 0));
  return numeric::with_value(line, b.along_x ? map.x.parameter : map.y.parameter, (b.low + b.high) / 2);
}

Overlay overlay(const Scene& scene, const Map& map, int bits) {
  for (const numeric::Axis* a : {&map.x, &map.y}) {
    const std::string& key = a->parameter.key();
    if (!(key.rfind("K.", 0) == 0 || key.rfind("alpha.", 0) == 0 || key.rfind("coupling.", 0) == 0 || key.rfind("mass.", 0) == 0 ||
          key == "fall_speed"))
      throw std::invalid_argument("overlay(): " + key +
                                  ": the derivation's coordinates are not affine in it (an overlay takes K, alpha, coupling, mass, fall_speed)");
  }
  // The pattern with both parameters declared (an entry the scene leaves out is added by Parameter::set()).
  auto corner = [&](int i, int j) {
    return numeric::with_value(numeric::with_value(scene, map.x.parameter, at(map.x, i, 0)), map.y.parameter, at(map.y, j, 0));
  };
  const Scene base = corner(0, 0);
  const bool finite = !base.bodies.back().infinite;
  const symbolic::Deriver deriver(symbolic::Pattern::from_scene(base), finite ? symbolic::Obstacle::Finite : symbolic::Obstacle::Infinite);
  const ParameterSpace space(deriver);
  // Each coordinate is affine in the two parameters: P(i, j) = P00 + i·DX + j·DY on the grid.
  auto exact_of = [](const Scene& s) { return numeric::ExactScene::from(s, numeric::ExactScene::MCheck::Caller); };
  const Point p00 = point_of(space, exact_of(base));
  const Point p10 = point_of(space, exact_of(corner(map.x.steps - 1, 0)));
  const Point p01 = point_of(space, exact_of(corner(0, map.y.steps - 1)));
  Point dx, dy;
  for (std::size_t k = 0; k < p00.size(); ++k) {
    dx.push_back((p10[k] - p00[k]) / (map.x.steps - 1));
    dy.push_back((p01[k] - p00[k]) / (map.y.steps - 1));
  }
  auto point = [&](const cln::cl_RA& i, const cln::cl_RA& j) {
    Point x;
    for (std::size_t k = 0; k < p00.size(); ++k) x.push_back(p00[k] + dx[k] * i + dy[k] * j);
    return x;
  };
  // The derivation's collision is the scene's: at the first solved point, the same exact velocities after (m/s).
  for (int j = 0, found = 0; j < map.y.steps && !found; ++j)
    for (int i = 0; i < map.x.steps && !found; ++i) {
      if (!map.at(i, j).admissible) continue;
      found = 1;
      const auto derived = numeric::solve(space.problem(point(i, j)));
      const auto problem = numeric::Problem<cln::cl_RA>::from(numeric::ExactScene::from(corner(i, j)));
      const auto solved = numeric::solve(problem);
      bool same = derived.closed == solved.closed && derived.velocities_after.size() == solved.velocities_after.size();
      for (std::size_t k = 0; same && k < solved.velocities_after.size(); ++k)
        same = problem.unit_exact && derived.velocities_after[k] == solved.velocities_after[k] * problem.unit;
      if (!same)
        throw std::invalid_argument(
            "overlay(): the scene is not of the form the derivation takes (bodies 1..n-1 falling at -a with a rational fall speed a, "
            "the bottom body at rest)");
    }
  Overlay o;
  // The cases present: at the grid points and on either side of a boundary.
  for (const auto& p : map.points)
    if (p.admissible && std::find(o.cases.begin(), o.cases.end(), p.region.closed) == o.cases.end()) o.cases.push_back(p.region.closed);
  for (const MapBoundary& b : map.boundaries)
    for (const auto& [psd, r] : {std::pair<bool, const numeric::Region&>{b.below_psd, b.below}, {b.above_psd, b.above}})
      if (psd && std::find(o.cases.begin(), o.cases.end(), r.closed) == o.cases.end()) o.cases.push_back(r.closed);
  std::sort(o.cases.begin(), o.cases.end(), [](const ContactSet& a, const ContactSet& b) {
    const Vocabulary& v = Vocabulary::paper();
    return std::make_pair(v.case_name(a), a.to_string()) < std::make_pair(v.case_name(b), b.to_string());
  });
  const int nx = map.x.steps, ny = map.y.steps;
  for (const ContactSet& closed : o.cases) {
    const symbolic::Derivation d = deriver.derive(closed);
    for (const symbolic::Condition& c : d.conditions) {
      if (c.kind == symbolic::ConditionKind::Psd) continue;
      ++o.conditions;
      const CompiledCondition cond(c, c.finite ? *c.finite : c.exact, deriver.symbols());
      std::vector<char> holds(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny), 0);
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) holds[static_cast<std::size_t>(j * nx + i)] = map.at(i, j).admissible && cond.holds(point(i, j));
      auto in_case = [&](int i, int j) { return map.at(i, j).admissible && map.at(i, j).region.closed == closed; };
      // Between two solved neighbours where the condition changes side: its zero by bisection on t in [0, 1].
      auto locate = [&](bool along_x, int i, int j) {
        const int i2 = along_x ? i + 1 : i, j2 = along_x ? j : j + 1;
        if (!map.at(i, j).admissible || !map.at(i2, j2).admissible) return;
        const bool h0 = holds[static_cast<std::size_t>(j * nx + i)], h1 = holds[static_cast<std::size_t>(j2 * nx + i2)];
        if (h0 == h1) return;
        cln::cl_RA t0 = 0, t1 = 1;
        for (int b = 0; b < bits; ++b) {
          const cln::cl_RA mid = (t0 + t1) / 2;
          (cond.holds(along_x ? point(i + mid, j) : point(i, j + mid)) == h0 ? t0 : t1) = mid;
        }
        const numeric::Axis& a = along_x ? map.x : map.y;
        const int k = along_x ? i : j;
        const cln::cl_RA v0 = at(a, k, t0), v1 = at(a, k, t1);
        const bool ascending = v0 < v1;
        o.zeros.push_back({along_x, i, j, ascending ? v0 : v1, ascending ? v1 : v0, closed, c.kind, c.about, ascending ? h0 : h1,
                           in_case(i, j) || in_case(i2, j2)});
      };
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i + 1 < nx; ++i) locate(true, i, j);
      for (int i = 0; i < nx; ++i)
        for (int j = 0; j + 1 < ny; ++j) locate(false, i, j);
    }
  }
  // Each boundary point between solved points against the zeros on its segment.
  std::map<std::tuple<bool, int, int>, std::vector<std::size_t>> on_edge;
  for (std::size_t z = 0; z < o.zeros.size(); ++z) on_edge[{o.zeros[z].along_x, o.zeros[z].i, o.zeros[z].j}].push_back(z);
  for (std::size_t k = 0; k < map.boundaries.size(); ++k) {
    const MapBoundary& b = map.boundaries[k];
    if (!b.below_psd || !b.above_psd) continue;
    OverlayMatch m;
    m.boundary = k;
    const cln::cl_RA mid = (b.low + b.high) / 2;
    const auto found = on_edge.find({b.along_x, b.i, b.j});
    if (found != on_edge.end())
      for (std::size_t z : found->second) {
        const DerivedZero& zero = o.zeros[z];
        if (zero.closed != b.below.closed && zero.closed != b.above.closed) continue;
        const cln::cl_RA distance = cln::abs(mid - (zero.low + zero.high) / 2);
        if (!m.found || distance < m.distance) {
          m.found = true;
          m.zero = z;
          m.distance = distance;
          m.allowed = (b.high - b.low) + (zero.high - zero.low);
        }
      }
    if (m.found) {
      const numeric::Axis& a = b.along_x ? map.x : map.y;
      const cln::cl_RA step = cln::abs(a.to - a.from) / (a.steps - 1);
      o.largest_distance = std::max(o.largest_distance, cln::double_approx(m.distance / step));
      o.largest_allowed = std::max(o.largest_allowed, cln::double_approx(m.allowed / step));
    }
    o.matches.push_back(std::move(m));
  }
  return o;
}

std::pair<cln::cl_RA, cln::cl_RA> position(const Map& map, const DerivedZero& z) {
  const cln::cl_RA mid = (z.low + z.high) / 2;
  const cln::cl_RA fixed = z.along_x ? at(map.y, z.j, 0) : at(map.x, z.i, 0);
  return z.along_x ? std::pair{mid, fixed} : std::pair{fixed, mid};
}

}  // namespace superball::verify
