#include "map_internal.hpp"
#include "psd_filter.hpp"

#include <sys/mman.h>

#include <cln/integer.h>
#include <cln/rational.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "superball/cases/error.hpp"
#include "superball/numeric/batch.hpp"
#include "superball/numeric/parallel.hpp"
#include "superball/numeric/problem.hpp"

namespace superball::numeric {

std::string Region::label() const { return closed.to_string() + (superball ? " superball" : ""); }

Region Region::parse(const std::string& label, int bodies) {
  const std::string suffix = " superball";
  const bool sb = label.size() > suffix.size() && label.compare(label.size() - suffix.size(), suffix.size(), suffix) == 0;
  const std::string set = sb ? label.substr(0, label.size() - suffix.size()) : label;
  if (set.size() < 2 || set.front() != '{' || set.back() != '}') throw std::invalid_argument("Region::parse(): not a region: " + label);
  return {ContactSet::parse(set.substr(1, set.size() - 2), bodies), sb};
}

Region Region::of(const ExactPoint& point) {
  const cln::cl_RA& top_after = point.solution.velocities_after[0];
  const cln::cl_RA& top_before = point.problem.u[0];
  return {point.solution.closed, top_after > cln::abs(top_before)};
}

namespace {

/// "KEYX = X, KEYY = Y", for messages.
std::string where(const Axis& x, const cln::cl_RA& vx, const Axis& y, const cln::cl_RA& vy) {
  return x.parameter.key() + " = " + to_string(vx) + ", " + y.parameter.key() + " = " + to_string(vy);
}

/// \p p filled from the solution \p sol of \p problem: its case, U₁⁺/|U₁⁻|
/// and the superball verdict.
template <class S>
void solved(MapPoint& p, const Problem<S>& problem, const Solution<S>& sol) {
  using T = ScalarTraits<S>;
  p.admissible = true;
  p.status = sol.status;
  p.region.closed = sol.closed;
  // U₁⁺ and U₁⁻ in the same (positive) unit: their ratio needs no unit.
  const S top_after = sol.velocities_after[0], top_before = problem.u[0] < S(0) ? S(-problem.u[0]) : problem.u[0];
  p.region.superball = top_after > top_before;
  const double before = T::to_double(top_before);
  p.ratio = before == 0 ? std::numeric_limits<double>::quiet_NaN() : T::to_double(top_after) / before;
}

/// The grid point (i, j) of a thread's own copy \p s of the scene, solved in
/// the precision \p tag's type, or marked when M is not positive semi-definite.
template <class S>
MapPoint solve_point(const Scene& s, const Precision& precision) {
  const ExactScene exact = ExactScene::from(s, ExactScene::MCheck::Caller);
  MapPoint p;
  if (!positive_semidefinite(exact)) return p;
  const auto problem = Problem<S>::from(exact, precision.digits);
  solved(p, problem, solve(problem));
  return p;
}

/// The grid's exact values as text, made on the calling thread (tasks on
/// other threads parse their own copies; sweep.cpp).
std::vector<std::string> texts(const Axis& a) {
  std::vector<std::string> t;
  for (const auto& v : a.values()) t.push_back(to_string(v));
  return t;
}

/// The curve of each kind (MapCurve) through \p m's boundaries: in each grid
/// cell, the points of one kind on its four edges are joined two by two (in
/// the order bottom, right, top, left), and the joined points chain into
/// polylines: open ones from an end first, then loops.
std::vector<MapCurve> chain(const Map& m) {
  // The kind of curve a boundary point is on: the two cases, or the superball edge.
  std::map<std::string, std::vector<std::size_t>> kinds;
  std::deque<std::pair<ContactSet, std::string>> names;  // each case's name, made once (a deque: references stay valid)
  auto name = [&](const ContactSet& c) -> const std::string& {
    for (const auto& n : names)
      if (n.first == c) return n.second;
    names.push_back({c, c.to_string()});
    return names.back().second;
  };
  for (std::size_t k = 0; k < m.boundaries.size(); ++k) {
    const MapBoundary& b = m.boundaries[k];
    if (b.below_psd && b.above_psd && b.below.closed != b.above.closed) {
      const std::string &p = name(b.below.closed), &q = name(b.above.closed);
      kinds["case " + std::min(p, q) + " " + std::max(p, q)].push_back(k);
    }
    if (b.below_psd != b.above_psd)
      kinds["psd"].push_back(k);
    else if (b.below.superball != b.above.superball)
      kinds["superball"].push_back(k);
  }
  std::vector<MapCurve> curves;
  for (const auto& of_kind : kinds) {
    // Named, not a structured binding: the lambda below uses kind (C++17 lambdas cannot capture bindings).
    const std::string& kind = of_kind.first;
    const std::vector<std::size_t>& members = of_kind.second;
    std::map<std::tuple<bool, int, int>, std::vector<std::size_t>> on_edge;  // (along x, i, j) -> points
    for (std::size_t k : members) on_edge[{m.boundaries[k].along_x, m.boundaries[k].i, m.boundaries[k].j}].push_back(k);
    std::map<std::size_t, std::vector<std::size_t>> joined;
    for (std::size_t k : members) joined[k];
    // The cells with a member on an edge, row by row (j, then i): an edge
    // along x at (i, j) is the bottom of cell (i, j) and the top of (i, j − 1),
    // one along y the left of cell (i, j) and the right of (i − 1, j).
    std::set<std::pair<int, int>> cells;  // (j, i)
    for (std::size_t k : members) {
      const MapBoundary& b = m.boundaries[k];
      for (const auto& [ci, cj] : {std::pair<int, int>{b.i, b.j}, b.along_x ? std::pair<int, int>{b.i, b.j - 1} : std::pair<int, int>{b.i - 1, b.j}})
        if (ci >= 0 && cj >= 0 && ci + 1 < m.x.steps && cj + 1 < m.y.steps) cells.insert({cj, ci});
    }
    for (const auto& [j, i] : cells) {
      std::vector<std::size_t> in_cell;
      for (const auto& edge : {std::tuple<bool, int, int>{true, i, j}, {false, i + 1, j}, {true, i, j + 1}, {false, i, j}}) {
        const auto found = on_edge.find(edge);
        if (found != on_edge.end()) in_cell.insert(in_cell.end(), found->second.begin(), found->second.end());
      }
      for (std::size_t a = 0; a + 1 < in_cell.size(); a += 2) {
        joined[in_cell[a]].push_back(in_cell[a + 1]);
        joined[in_cell[a + 1]].push_back(in_cell[a]);
      }
    }
    std::map<std::size_t, bool> used;
    auto walk = [&](std::size_t start) {
      MapCurve c;
      c.kind = kind == "superball" ? MapCurve::Kind::Superball : kind == "psd" ? MapCurve::Kind::Psd : MapCurve::Kind::Case;
      if (c.kind == MapCurve::Kind::Case) {
        const MapBoundary& b = m.boundaries[start];
        const bool in_order = name(b.below.closed) < name(b.above.closed);
        c.first = in_order ? b.below.closed : b.above.closed;
        c.second = in_order ? b.above.closed : b.below.closed;
      }
      std::size_t at = start;
      used[at] = true;
      c.points.push_back(at);
      for (;;) {
        const auto& next = joined[at];
        const auto free = std::find_if(next.begin(), next.end(), [&](std::size_t k) { return !used[k]; });
        if (free == next.end()) {
          c.closed = c.points.size() > 2 && std::find(next.begin(), next.end(), start) != next.end();
          break;
        }
        at = *free;
        used[at] = true;
        c.points.push_back(at);
      }
      curves.push_back(std::move(c));
    };
    for (std::size_t k : members)  // open curves from one end
      if (!used[k] && joined[k].size() < 2) walk(k);
    for (std::size_t k : members)  // what is left are loops
      if (!used[k]) walk(k);
  }
  return curves;
}

/// Where each entry of M sits in M written on its pairs (sorted): (row,
/// column) per entry of \p entries, and the number of pairs.
std::pair<std::vector<std::pair<int, int>>, Eigen::Index> entry_positions(const std::vector<Entry<cln::cl_RA>>& entries) {
  std::vector<std::pair<int, int>> pairs, at;
  for (const auto& e : entries) pairs.push_back({e.i, e.j}), pairs.push_back({e.k, e.l});
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  auto index = [&](int i, int j) { return static_cast<int>(std::lower_bound(pairs.begin(), pairs.end(), std::make_pair(i, j)) - pairs.begin()); };
  for (const auto& e : entries) at.push_back({index(e.i, e.j), index(e.k, e.l)});
  return {at, static_cast<Eigen::Index>(pairs.size())};
}

/// The most pairs of an M whose PSD edge bisect_by_determinant() locates:
/// its exact determinant is a dense elimination, O(pairs³); beyond, the
/// edge is bisected on exact PSD checks.
constexpr Eigen::Index psd_edge_max_pairs = 16;

/// The determinant of the square \p a (overwritten), exactly: elimination
/// with the first nonzero pivot of each column.
cln::cl_RA determinant(std::vector<std::vector<cln::cl_RA>>& a) {
  const std::size_t n = a.size();
  cln::cl_RA det = 1;
  for (std::size_t k = 0; k < n; ++k) {
    std::size_t p = k;
    while (p < n && cln::zerop(a[p][k])) ++p;
    if (p == n) return 0;
    if (p != k) std::swap(a[p], a[k]), det = -det;
    det = det * a[k][k];
    for (std::size_t i = k + 1; i < n; ++i) {
      if (cln::zerop(a[i][k])) continue;
      const cln::cl_RA f = a[i][k] / a[k][k];
      for (std::size_t j = k + 1; j < n; ++j) a[i][j] = a[i][j] - f * a[k][j];
    }
  }
  return det;
}

/// The halvings of psd_edge() on a line along the entry \p entry of M of
/// \p line (set by this function), when M's determinant decides them.
/// q(v) = det M(v) is a polynomial of degree at most 2 (the entry sits at
/// two symmetric places of M, or on its diagonal): made exactly through
/// three values of the bracket and checked at a fourth.  λ_min(M(v)) is
/// concave, so inside the PSD interval it is positive unless M is singular
/// all along it (then q ≡ 0), and at the interval's end it is 0: when q > 0
/// at the bracket's PSD end and q < 0 at the other, q's one root between them
/// is the edge, and M is PSD at a value of the bracket exactly when q ≥ 0
/// there.  Each halving then takes the verdict positive_semidefinite() gives,
/// from the sign of an integer form of q at the midpoint: \p a and \p b
/// become the same bracket, and true is returned.  False, with \p a and \p b
/// unchanged, where q does not decide so (too many pairs, q ≡ 0, a root at
/// an end, an even number of roots between them, a failed check).
bool bisect_by_determinant(ExactScene& line, std::size_t entry, cln::cl_RA& a, cln::cl_RA& b, bool a_psd, int bits) {
  std::vector<std::pair<int, int>> at;  // not a structured binding: the lambda below captures it (C++17)
  Eigen::Index size = 0;
  std::tie(at, size) = entry_positions(line.entries);
  if (size > psd_edge_max_pairs) return false;
  const auto n = static_cast<std::size_t>(size);
  auto det = [&](const cln::cl_RA& v) {
    line.entries[entry].value = v;
    std::vector<std::vector<cln::cl_RA>> m(n, std::vector<cln::cl_RA>(n, 0));
    for (std::size_t k = 0; k < at.size(); ++k) {
      const auto r = static_cast<std::size_t>(at[k].first), c = static_cast<std::size_t>(at[k].second);
      m[r][c] = m[c][r] = line.entries[k].value;
    }
    return determinant(m);
  };
  const cln::cl_RA& in = a_psd ? a : b;  // the bracket's PSD end
  const cln::cl_RA& out = a_psd ? b : a;
  const cln::cl_RA t0 = in, t1 = out, t2 = (in + out) / 2, t3 = (3 * in + out) / 4;
  const cln::cl_RA d0 = det(t0), d1 = det(t1);
  if (!(d0 > 0 && d1 < 0)) return false;
  // Newton's form through (t0, d0), (t1, d1), (t2, d2), then q = c0 + c1·v + c2·v².
  const cln::cl_RA f01 = (d1 - d0) / (t1 - t0), f012 = ((det(t2) - d1) / (t2 - t1) - f01) / (t2 - t0);
  const cln::cl_RA c2 = f012, c1 = f01 - f012 * (t0 + t1), c0 = d0 - f01 * t0 + f012 * t0 * t1;
  if (c0 + t3 * (c1 + t3 * c2) != det(t3)) return false;
  // In integers: q(v) times the positive lcm of the denominators of its coefficients, at v = V/D.
  const cln::cl_I common = cln::lcm(cln::lcm(cln::denominator(c0), cln::denominator(c1)), cln::denominator(c2));
  const cln::cl_I q0 = cln::exquo(cln::numerator(c0) * common, cln::denominator(c0)),
                  q1 = cln::exquo(cln::numerator(c1) * common, cln::denominator(c1)),
                  q2 = cln::exquo(cln::numerator(c2) * common, cln::denominator(c2));
  cln::cl_I D = cln::lcm(cln::denominator(a), cln::denominator(b));
  cln::cl_I A = cln::exquo(cln::numerator(a) * D, cln::denominator(a)), B = cln::exquo(cln::numerator(b) * D, cln::denominator(b));
  for (; bits > 0; --bits) {
    // The midpoint (A + B)/(2D): the bracket's ends and D doubled.
    const cln::cl_I mid = A + B;
    A = cln::ash(A, 1), B = cln::ash(B, 1), D = cln::ash(D, 1);
    const bool psd = !cln::minusp(q0 * D * D + q1 * mid * D + q2 * mid * mid);
    (psd == a_psd ? A : B) = mid;
  }
  a = cln::cl_RA(A) / D;
  b = cln::cl_RA(B) / D;
  return true;
}

/// The edge of the PSD cone between \p a (where M is positive
/// semi-definite when \p a_psd) and \p b (where it is when !a_psd) on a line
/// whose exact scene (M unchecked) at a value v is \p at(v), to \p bits
/// halvings: along a line the PSD set is an interval, so there is one change.
/// When the line varies the entry \p entry of M of \p line (which at()
/// sets), the halvings are those of bisect_by_determinant() where it decides.
template <class At>
MapBoundary psd_edge(const At& at, cln::cl_RA a, cln::cl_RA b, bool a_psd, int bits, ExactScene* line = nullptr, std::size_t entry = 0) {
  if (!line || !bisect_by_determinant(*line, entry, a, b, a_psd, bits)) {
    Eigen::MatrixXd M, work;
    // M on its pairs in double, decided by detail::psd_by_floating_point() where it can, else exactly.
    auto psd = [&](const ExactScene& s) {
      const auto [at, size] = entry_positions(s.entries);
      M = Eigen::MatrixXd::Zero(size, size);
      for (std::size_t k = 0; k < at.size(); ++k) M(at[k].first, at[k].second) = M(at[k].second, at[k].first) = cln::double_approx(s.entries[k].value);
      const std::optional<bool> clear = detail::psd_by_floating_point(M, work);
      return clear ? *clear : positive_semidefinite(s);
    };
    for (; bits > 0; --bits) {
      const cln::cl_RA mid = (a + b) / 2;
      (psd(at(mid)) == a_psd ? a : b) = mid;
    }
  }
  MapBoundary e;
  e.low = a < b ? a : b;
  e.high = a < b ? b : a;
  e.below_psd = a < b ? a_psd : !a_psd;
  e.above_psd = !e.below_psd;
  // The region at the bracket's end inside the cone, from the exact solution there.
  const auto problem = Problem<cln::cl_RA>::from(at(a_psd ? a : b));
  (e.below_psd ? e.below : e.above) = Region::of(ExactPoint{problem, solve(problem)});
  return e;
}

}  // namespace

namespace detail {

std::optional<std::size_t> entry_changed(const Scene& a, const Scene& b) {
  const ExactScene p = ExactScene::from(a, ExactScene::MCheck::Caller), q = ExactScene::from(b, ExactScene::MCheck::Caller);
  if (p.n != q.n || p.fixed_bottom != q.fixed_bottom || p.mass != q.mass || p.fall != q.fall || p.velocity != q.velocity ||
      p.a_squared != q.a_squared || p.entries.size() != q.entries.size())
    return std::nullopt;
  std::optional<std::size_t> changed;
  for (std::size_t k = 0; k < p.entries.size(); ++k) {
    const auto &e = p.entries[k], &f = q.entries[k];
    if (e.i != f.i || e.j != f.j || e.k != f.k || e.l != f.l) return std::nullopt;
    if (e.value == f.value) continue;
    if (changed) return std::nullopt;
    changed = k;
  }
  return changed;
}

namespace {

/// Whether the LDLᵀ factorization of \p a (symmetric; overwritten: L
/// below the diagonal, L·D above it) meets only positive pivots D: the
/// plain unblocked algorithm without square roots, whose backward error is
/// that of a Cholesky factorization (a few n·u·‖a‖), without the blocked
/// machinery Eigen::LLT runs for a matrix of a few rows.
bool ldlt_succeeds(Eigen::MatrixXd& a) {
  const Eigen::Index n = a.rows();
  for (Eigen::Index j = 0; j < n; ++j) {
    double d = a(j, j);
    for (Eigen::Index k = 0; k < j; ++k) d -= a(j, k) * a(k, j);
    if (!(d > 0)) return false;
    for (Eigen::Index i = j + 1; i < n; ++i) {
      double s = a(i, j);
      for (Eigen::Index k = 0; k < j; ++k) s -= a(i, k) * a(k, j);
      a(j, i) = s;      // L_ij·D_j
      a(i, j) = s / d;  // L_ij
    }
  }
  return true;
}

}  // namespace

std::optional<bool> psd_by_floating_point(const Eigen::MatrixXd& M, Eigen::MatrixXd& work) {
  const double tau = map_psd_margin * M.norm();
  if (!std::isfinite(tau)) return std::nullopt;
  work = M;
  work.diagonal().array() -= tau;
  if (ldlt_succeeds(work)) return true;
  work = M;
  work.diagonal().array() += tau;
  if (!ldlt_succeeds(work)) return false;
  return std::nullopt;
}

/// \p n default points, in storage that the kernel may back with huge pages
/// (Linux's transparent huge pages, where they are enabled on request): a
/// large grid's points then take a few page faults instead of one per 4 KiB,
/// taken on one thread before the points are solved.  On a virtual machine a
/// fault costs tens of microseconds: 16.8 MB of points (512 x 512) took
/// 0.08–0.15 s of faults, a fifth of the whole map, and 0.014–0.04 s so.
std::vector<MapPoint> blank_points(std::size_t n) {
  std::vector<MapPoint> points;
  points.reserve(n);
#ifdef MADV_HUGEPAGE
  constexpr std::uintptr_t huge = std::uintptr_t{2} << 20;
  const auto start = reinterpret_cast<std::uintptr_t>(points.data()), end = start + n * sizeof(MapPoint);
  const std::uintptr_t from = (start + huge - 1) & ~(huge - 1), to = end & ~(huge - 1);
  if (from < to) (void)::madvise(reinterpret_cast<void*>(from), to - from, MADV_HUGEPAGE);  // advice only: no error to act on
#endif
  points.resize(n);
  return points;
}

template <class S>
std::vector<MapPoint> entry_points(const Scene& corner, std::size_t kx, std::size_t ky, const Axis& x, const Axis& y,
                                   const MapSettings& settings, std::size_t first, std::size_t size) {
  using T = ScalarTraits<S>;
  const int digits = settings.precision.digits;
  // The grid values as text (for the exact fallback) and in S, made on the calling thread.
  const std::vector<std::string> tx = texts(x), ty = texts(y);
  std::vector<S> sx, sy;
  std::vector<char> zx, zy;  // the exact value is 0
  for (const auto& v : x.values()) sx.push_back(T::from(v, digits)), zx.push_back(cln::zerop(v));
  for (const auto& v : y.values()) sy.push_back(T::from(v, digits)), zy.push_back(cln::zerop(v));
  struct State {
    ExactScene exact;  ///< the corner's, its two entries set at each exact fallback
    Batch<S> batch;    ///< the corner's problem, its two entries set at each point
    std::vector<std::pair<int, int>> at;  ///< entry k of M at (row, column) of the matrix on its pairs
    Eigen::MatrixXd M, work;
    std::optional<PsdFilter> filter;  ///< M in fixed arrays when it has at most PsdFilter::max_rows rows (psd_filter.hpp)
    std::vector<std::size_t> solve;   ///< the points of a row to solve (M positive semi-definite there)
  };
  auto make_state = [&] {
    const ExactScene exact = ExactScene::from(corner, ExactScene::MCheck::Caller);
    State st{exact, Batch<S>(exact, {kx, ky}, digits), {}, {}, {}, {}, {}};
    st.solve.reserve(map_run);
    Eigen::Index size = 0;
    std::tie(st.at, size) = entry_positions(st.exact.entries);
    st.M = Eigen::MatrixXd::Zero(size, size);
    st.work.resize(size, size);
    if (size <= PsdFilter::max_rows) st.filter.emplace(static_cast<int>(size));
    return st;
  };
  // The grid point k's two entries set in the batch.
  auto set_at = [&](State& st, std::size_t k) {
    st.batch.set(0, sx[k % tx.size()], zx[k % tx.size()]);
    st.batch.set(1, sy[k / tx.size()], zy[k / tx.size()]);
  };
  // M's positive semi-definiteness at the grid point k, the point's two entries set in the batch.
  auto psd_at = [&](State& st, std::size_t k) {
    const std::size_t i = k % tx.size(), j = k / tx.size();
    set_at(st, k);
    const Problem<S>& p = st.batch.problem();
    for (std::size_t e = 0; e < p.entries.size(); ++e) {
      const auto [r, c] = st.at[e];
      if (st.filter)
        st.filter->set(r, c, static_cast<double>(p.entries[e].value));
      else
        st.M(r, c) = st.M(c, r) = static_cast<double>(p.entries[e].value);
    }
    std::optional<bool> psd = st.filter ? st.filter->decide() : psd_by_floating_point(st.M, st.work);
    if (!psd) {  // too close to the edge of the cone for floating point: exactly
      st.exact.entries[kx].value = parse_rational(tx[i]);
      st.exact.entries[ky].value = parse_rational(ty[j]);
      psd = positive_semidefinite(st.exact);
    }
    return *psd;
  };
  const std::size_t count = tx.size() * ty.size();
  first = std::min(first, count);
  size = std::min(size, count - first);
  // Runs of map_run points per task, each point written in its place: a
  // task's overhead is shared by its run, and no slot per point is copied.
  // A run's points on one row of the grid differ in x alone, the value of
  // the entry kx of M itself: M is affine in it, and x between the row's
  // two ends, so M positive semi-definite at both ends is so at every point
  // between (the cone is convex), whose filter is then skipped.
  std::vector<MapPoint> points = blank_points(size);
  (void)parallel_map((size + map_run - 1) / map_run, settings.threads, make_state, [&](State& st, std::size_t r) {
    const std::size_t end = std::min(size, (r + 1) * map_run);
    for (std::size_t at = r * map_run; at < end;) {
      const std::size_t row_end = std::min(end, at + (tx.size() - (first + at) % tx.size()));
      const bool inside = row_end - at > 2 && psd_at(st, first + at) && psd_at(st, first + row_end - 1);
      // The row's points where M is positive semi-definite (the others stay
      // inadmissible, as blank_points() made them), solved several at once.
      st.solve.clear();
      for (; at < row_end; ++at)
        if (inside || psd_at(st, first + at)) st.solve.push_back(at);
      st.batch.solve_each(
          st.solve.size(), [&](std::size_t q) { set_at(st, first + st.solve[q]); },
          [&](std::size_t q, const Solution<S>& sol) { solved(points[st.solve[q]], st.batch.problem(), sol); });
    }
    return 0;
  });
  return points;
}

template std::vector<MapPoint> entry_points<double>(const Scene&, std::size_t, std::size_t, const Axis&, const Axis&, const MapSettings&,
                                                    std::size_t, std::size_t);
template std::vector<MapPoint> entry_points<long double>(const Scene&, std::size_t, std::size_t, const Axis&, const Axis&,
                                                         const MapSettings&, std::size_t, std::size_t);

namespace {

/// A contact set as its bits ("." for none: the default, empty set).
std::string bits(const ContactSet& c) {
  std::string s;
  for (int k = 0; k < c.contacts(); ++k) s += c.closed(k) ? '1' : '0';
  return s.empty() ? "." : s;
}

/// The words of one line of a task's text, read in order.
class Words {
 public:
  Words(const std::string& line, const char* function) : in_(line), function_(function), line_(line) {}
  std::string word() {
    std::string w;
    if (!(in_ >> w)) damaged("a field is missing");
    return w;
  }
  bool flag() {
    const std::string w = word();
    if (w != "0" && w != "1") damaged("'" + w + "' is not 0 or 1");
    return w == "1";
  }
  /// An integer from \p low to \p high.
  int number(long low = std::numeric_limits<int>::min(), long high = std::numeric_limits<int>::max()) {
    const std::string w = word();
    char* end = nullptr;
    const long n = std::strtol(w.c_str(), &end, 10);
    if (w.empty() || *end || n < low || n > high)
      damaged("'" + w + "' is not an integer from " + std::to_string(low) + " to " + std::to_string(high));
    return static_cast<int>(n);
  }
  double real() {
    const std::string w = word();
    char* end = nullptr;
    const double v = std::strtod(w.c_str(), &end);
    if (w.empty() || *end) damaged("'" + w + "' is not a number");
    return v;
  }
  cln::cl_RA rational() {
    const std::string w = word();
    try {
      return parse_rational(w);
    } catch (const std::exception&) {
      damaged("'" + w + "' is not a fraction");
    }
  }
  ContactSet contacts() {
    const std::string w = word();
    if (w == ".") return {};
    if (w.find_first_not_of("01") != std::string::npos) damaged("'" + w + "' is not the bits of a contact set");
    ContactSet c(static_cast<int>(w.size()) + 1);
    for (std::size_t k = 0; k < w.size(); ++k) c.set_closed(static_cast<int>(k), w[k] == '1');
    return c;
  }
  void end() {
    std::string more;
    if (in_ >> more) damaged("'" + more + "' after the last field");
  }
  /// Throws std::invalid_argument("FUNCTION: a damaged line, WHAT: LINE").
  [[noreturn]] void damaged(const std::string& what) const {
    throw std::invalid_argument(std::string(function_) + ": a damaged line, " + what + ": " + line_.substr(0, 120));
  }

 private:
  std::istringstream in_;
  const char* function_;
  std::string line_;
};

/// One R from each line of \p text (each ended by '\n'), read by \p read
/// from the line's Words, which must hold nothing more.
template <class R, class Read>
std::vector<R> read_lines(const std::string& text, const char* function, const Read& read) {
  std::vector<R> out;
  std::size_t at = 0;
  while (at < text.size()) {
    const std::size_t eol = text.find('\n', at);
    if (eol == std::string::npos) throw std::invalid_argument(std::string(function) + ": the last line is cut");
    Words in(text.substr(at, eol - at), function);
    out.push_back(read(in));
    in.end();
    at = eol + 1;
  }
  return out;
}

}  // namespace

std::string points_to_text(const std::vector<MapPoint>& points) {
  std::string text;
  char ratio[64];
  for (const MapPoint& p : points) {
    std::snprintf(ratio, sizeof ratio, "%a", p.ratio);
    text += std::string(p.admissible ? "1 " : "0 ") + std::to_string(static_cast<int>(p.status)) + (p.region.superball ? " 1 " : " 0 ") +
            ratio + " " + bits(p.region.closed) + "\n";
  }
  return text;
}

std::vector<MapPoint> points_from_text(const std::string& text) {
  int contacts = -1;  // every solved point of a map has the same contacts
  return read_lines<MapPoint>(text, "points_from_text()", [&](Words& in) {
    MapPoint p;
    p.admissible = in.flag();
    p.status = static_cast<Status>(in.number(static_cast<int>(Status::Success), static_cast<int>(Status::NoConvergence)));
    p.region.superball = in.flag();
    p.ratio = in.real();
    p.region.closed = in.contacts();
    // What solved() can give: an unsolved point keeps every default; a
    // solved one has U1+/|U1-| on the side of 1 of its verdict (NaN when U1- = 0).
    if (!p.admissible && (p.status != Status::Success || p.region.superball || p.ratio != 0 || p.region.closed.contacts() != 0))
      in.damaged("a point not solved with the fields of a solved one");
    if (p.admissible && (p.region.superball ? p.ratio < 1 : p.ratio > 1))
      in.damaged("U1+/|U1-| against its verdict");
    if (p.admissible && contacts >= 0 && p.region.closed.contacts() != contacts) in.damaged("a case of another number of contacts");
    if (p.admissible) contacts = p.region.closed.contacts();
    return p;
  });
}

std::string boundaries_to_text(const std::vector<MapBoundary>& boundaries) {
  std::string text;
  for (const MapBoundary& b : boundaries)
    text += std::string(b.along_x ? "1 " : "0 ") + std::to_string(b.i) + " " + std::to_string(b.j) + " " + to_string(b.low) + " " +
            to_string(b.high) + (b.below_psd ? " 1" : " 0") + (b.above_psd ? " 1" : " 0") + (b.below.superball ? " 1" : " 0") +
            (b.above.superball ? " 1 " : " 0 ") + bits(b.below.closed) + " " + bits(b.above.closed) + "\n";
  return text;
}

std::vector<MapBoundary> boundaries_from_text(const std::string& text) {
  return read_lines<MapBoundary>(text, "boundaries_from_text()", [](Words& in) {
    MapBoundary b;
    b.along_x = in.flag();
    b.i = in.number(0, static_cast<long>(map_max_steps) - 1);
    b.j = in.number(0, static_cast<long>(map_max_steps) - 1);
    b.low = in.rational();
    b.high = in.rational();
    b.below_psd = in.flag();
    b.above_psd = in.flag();
    b.below.superball = in.flag();
    b.above.superball = in.flag();
    b.below.closed = in.contacts();
    b.above.closed = in.contacts();
    // A bracket, and a change across it.
    if (!(b.low < b.high)) in.damaged("a bracket whose low end is not below its high end");
    if (b.below_psd == b.above_psd && b.below.superball == b.above.superball && b.below.closed == b.above.closed) in.damaged("no change across the bracket");
    return b;
  });
}

}  // namespace detail

void check_axes(const Axis& x, const Axis& y) {
  if (x.parameter == y.parameter)
    throw std::invalid_argument("map(): --x " + x.parameter.spelling() + " and --y " + y.parameter.spelling() + " name the same parameter (" +
                                x.parameter.key() + "); a map needs two different parameters");
  for (const Axis* a : {&x, &y}) {
    if (a->steps < 2 || a->steps > map_max_steps)
      throw std::invalid_argument("map(): " + a->parameter.key() + ": " + std::to_string(a->steps) + " values; an axis takes 2 to " +
                                  std::to_string(map_max_steps));
    if (a->from == a->to) throw std::invalid_argument("map(): " + a->parameter.key() + ": FROM and TO are equal");
  }
}

void check_map(const Scene& scene, const Axis& x, const Axis& y) {
  refuse_drop(scene, "map()");
  check_axes(x, y);
  for (const cln::cl_RA& vx : {x.from, x.to})
    for (const cln::cl_RA& vy : {y.from, y.to}) {
      try {
        (void)ExactScene::from(with_value(with_value(scene, x.parameter, vx), y.parameter, vy), ExactScene::MCheck::Caller);
      } catch (const InputError& e) {
        // "ORIGIN: field: why" (or "ORIGIN: KEY = VALUE: field: why" from with_value) -> "ORIGIN: KEYX = X, KEYY = Y: ..."
        std::string what = e.what();
        const std::string prefix = scene.origin + ": ";
        if (what.rfind(prefix, 0) == 0) what = what.substr(prefix.size());
        for (const Axis* a : {&x, &y}) {
          const std::string set = a->parameter.key() + " = " + to_string(a == &x ? vx : vy) + ": ";
          if (what.rfind(set, 0) == 0) what = what.substr(set.size());
        }
        throw InputError(prefix + where(x, vx, y, vy) + ": " + what);
      }
    }
}

namespace {

/// The grid points of a map, solved a range at a time.
class GridSolver {
 public:
  /// The values of \p x and \p y and the corner scene, for points of \p scene in \p settings (all kept by reference).
  GridSolver(const Scene& scene, const Axis& x, const Axis& y, const MapSettings& settings)
      : tx(texts(x)), ty(texts(y)), scene_(scene), x_(x), y_(y), settings_(settings),
        // Two entries of M on the axes, in double or long double: only they change over the grid.
        corner_(with_value(with_value(scene, x.parameter, x.from), y.parameter, y.from)),
        kx_(detail::entry_changed(corner_, with_value(corner_, x.parameter, x.to))),
        ky_(detail::entry_changed(corner_, with_value(corner_, y.parameter, y.to))) {}

  /// The grid points first … first + size − 1 (k = j·nx + i), on settings.threads.
  std::vector<MapPoint> operator()(std::size_t first, std::size_t size) const {
    const bool entries = kx_ && ky_ && *kx_ != *ky_;
    if (entries && settings_.precision.kind == Precision::Kind::Double)
      return detail::entry_points<double>(corner_, *kx_, *ky_, x_, y_, settings_, first, size);
    if (entries && settings_.precision.kind == Precision::Kind::LongDouble)
      return detail::entry_points<long double>(corner_, *kx_, *ky_, x_, y_, settings_, first, size);
    const std::size_t nx = tx.size();
    return parallel_map(size, settings_.threads, [this] { return scene_; }, [&](Scene& s, std::size_t at) {
      const std::size_t k = first + at;
      x_.parameter.assign(s, Number::parse(tx[k % nx]));
      y_.parameter.assign(s, Number::parse(ty[k / nx]));
      return with_scalar(settings_.precision, [&](auto tag) { return solve_point<decltype(tag)>(s, settings_.precision); });
    });
  }

  /// InputError: M is not positive semi-definite at any point.
  [[noreturn]] void nowhere_psd() const {
    throw InputError(scene_.origin + ": M is not positive semi-definite at any point of the map (" + x_.parameter.key() + " from " +
                     to_string(x_.from) + " to " + to_string(x_.to) + ", " + y_.parameter.key() + " from " + to_string(y_.from) + " to " +
                     to_string(y_.to) + "): nothing to solve");
  }

 const std::vector<std::string> tx, ty;  ///< the grid's exact values as text

 private:
  const Scene& scene_;
  const Axis &x_, &y_;
  const MapSettings& settings_;
  const Scene corner_;
  const std::optional<std::size_t> kx_, ky_;
};

/// The heap block of a contact set of a few contacts: glibc's malloc gives
/// at least 32 bytes (its smallest chunk) to the std::vector<bool> in it.
constexpr double contact_set_block = 32;
/// The address space of a thread's stack (glibc's default, `ulimit -s`
/// 8192), which `ulimit -v` counts.
constexpr double thread_stack_bytes = 8 << 20;
/// A point's line in detail::points_to_text(): "1 0 1 0x1.91eb851eb851fp+0 011\n".
constexpr double point_text_bytes = 32;

}  // namespace

double MapSettings::bytes_per_point() const {
  // Each point in the map with its contact set's block; while solved, also
  // its slot in parallel_map(); with a runner, which solves a task at a time,
  // the text of all the tasks instead, read back into the map.
  const double held = sizeof(MapPoint) + contact_set_block;
  return held + (runner ? point_text_bytes : sizeof(std::optional<MapPoint>)) + output_bytes_per_point;
}

bool MapSettings::fits(const Axis& x, const Axis& y, std::string* why) const {
  const double points = static_cast<double>(x.steps) * static_cast<double>(y.steps), per = bytes_per_point();
  const int workers = thread_count(threads);
  try {
    check_memory("map()", "a " + std::to_string(x.steps) + " x " + std::to_string(y.steps) + " grid",
                 points * per + workers * thread_stack_bytes,
                 std::to_string(static_cast<long long>(std::ceil(per))) + " bytes per point, " + std::to_string(workers) + " threads",
                 memory ? *memory : available_memory(),
                 "use a coarser grid (the grid alone as CSV, superball map --csv without --checkpoint, is written as it is computed)");
  } catch (const std::invalid_argument& e) {
    if (why) *why = e.what();
    return false;
  }
  return true;
}

void MapSettings::check() const {
  check_threads(threads);
  if (bits < 1 || bits > max_bits)
    throw std::invalid_argument("MapSettings::check(): bits must be a whole number from 1 to " + std::to_string(max_bits) + ", got " + std::to_string(bits));
}

void map_points(const Scene& scene, const Axis& x, const Axis& y, const MapSettings& settings, std::size_t block,
                const std::function<void(std::size_t first, const std::vector<MapPoint>& points)>& sink) {
  settings.check();
  check_map(scene, x, y);
  const GridSolver solve_range(scene, x, y, settings);
  const std::size_t count = static_cast<std::size_t>(x.steps) * static_cast<std::size_t>(y.steps);
  block = std::max<std::size_t>(block, 1);
  bool any = false;
  for (std::size_t first = 0; first < count; first += block) {
    const std::vector<MapPoint> points = solve_range(first, std::min(block, count - first));
    any = any || std::any_of(points.begin(), points.end(), [](const MapPoint& p) { return p.admissible; });
    sink(first, points);
  }
  if (!any) solve_range.nowhere_psd();
}

Map map(const Scene& scene, const Axis& x, const Axis& y, const MapSettings& settings) {
  const auto stage_end = [&](const char* stage) {
    if (settings.stage_end) settings.stage_end(stage);
  };
  settings.check();
  check_map(scene, x, y);
  if (std::string why; !settings.fits(x, y, &why)) throw std::invalid_argument(why);
  stage_end("checks");
  Map m{x, y, {}, {}, {}};
  const GridSolver points(scene, x, y, settings);
  const std::vector<std::string>& tx = points.tx;
  const std::vector<std::string>& ty = points.ty;
  const std::size_t count = tx.size() * ty.size();
  // At most map_tasks tasks of consecutive points when a runner spreads them.
  auto per_task = [](std::size_t n) { return (n + map_tasks - 1) / map_tasks; };
  m.points = in_tasks<MapPoint>(settings.runner, count, per_task(count), "map()", points, detail::points_to_text, detail::points_from_text);
  if (m.points.size() != count)
    throw std::logic_error("map(): the runner's results hold " + std::to_string(m.points.size()) + " of " + std::to_string(count) + " points");
  if (std::none_of(m.points.begin(), m.points.end(), [](const MapPoint& p) { return p.admissible; })) points.nowhere_psd();
  stage_end("grid");
  if (!settings.boundaries) return m;
  // The neighbours to bisect: along x row by row, then along y column by column.
  struct Pending {
    bool along_x;
    int i, j;
  };
  std::vector<Pending> pending;
  const int ix = x.steps, iy = y.steps;
  // Two neighbours differ when one is solved and the other not, or both are, in different regions.
  auto differ = [](const MapPoint& a, const MapPoint& b) { return a.admissible != b.admissible || (a.admissible && a.region != b.region); };
  // Each row, then each column, scanned on settings.threads (no CLN object read).
  auto scan = [&](bool along_x) {
    const std::size_t lines = static_cast<std::size_t>(along_x ? iy : ix);
    return parallel_map(lines, settings.threads, [] { return 0; }, [&](int&, std::size_t line) {
      std::vector<Pending> found;
      const int l = static_cast<int>(line), n = along_x ? ix : iy;
      for (int k = 0; k + 1 < n; ++k)
        if (along_x ? differ(m.at(k, l), m.at(k + 1, l)) : differ(m.at(l, k), m.at(l, k + 1)))
          found.push_back(along_x ? Pending{true, k, l} : Pending{false, l, k});
      return found;
    });
  };
  for (const bool along_x : {true, false})
    for (const auto& found : scan(along_x)) pending.insert(pending.end(), found.begin(), found.end());
  stage_end("neighbours");
  const Label by_region = [](const ExactPoint& e) { return Region::of(e).label(); };
  const ProvenLabel proven_region = [](const ProvenPoint& p) -> std::optional<std::string> {
    if (!p.superball) return std::nullopt;
    return Region{p.closed, *p.superball}.label();
  };
  const int bodies = scene.size();
  // Both axes entries of M (the usual map): each thread converts the corner
  // once and sets the two entries at each line; else each line is a scene.
  const Scene corner = with_value(with_value(scene, x.parameter, x.from), y.parameter, y.from);
  const std::optional<std::size_t> kx = detail::entry_changed(corner, with_value(corner, x.parameter, x.to));
  const std::optional<std::size_t> ky = kx ? detail::entry_changed(corner, with_value(corner, y.parameter, y.to)) : std::nullopt;
  struct Lines {
    std::optional<ExactScene> corner;              ///< this thread's, when kx and ky
    std::shared_ptr<detail::PlaneSigns> plane;  ///< its cases' polynomials over the map
  };
  auto make_lines = [&] {
    Lines lines;
    if (!kx || !ky) return lines;
    lines.corner = ExactScene::from(corner, ExactScene::MCheck::Caller);
    // The ends from their texts: a thread never touches the caller's CLN objects.
    lines.plane = detail::plane_signs(*lines.corner, *kx, *ky, parse_rational(tx.front()), parse_rational(tx.back()), parse_rational(ty.front()),
                                      parse_rational(ty.back()));
    return lines;
  };
  const auto bisect = [&](Lines& lines, std::size_t k) {
    const Pending& p = pending[k];
    // The line through the two neighbours: the other parameter fixed at its grid value.
    const Axis& along = p.along_x ? x : y;
    const Axis& fixed = p.along_x ? y : x;
    const std::string& fixed_text = p.along_x ? ty[static_cast<std::size_t>(p.j)] : tx[static_cast<std::size_t>(p.i)];
    const cln::cl_RA a = parse_rational(p.along_x ? tx[static_cast<std::size_t>(p.i)] : ty[static_cast<std::size_t>(p.j)]);
    const cln::cl_RA b = parse_rational(p.along_x ? tx[static_cast<std::size_t>(p.i) + 1] : ty[static_cast<std::size_t>(p.j) + 1]);
    std::vector<MapBoundary> out;
    const MapPoint& first = m.at(p.i, p.j);
    const MapPoint& second = p.along_x ? m.at(p.i + 1, p.j) : m.at(p.i, p.j + 1);
    std::optional<ExactScene> exact = lines.corner;
    const std::size_t entry = exact ? (p.along_x ? *kx : *ky) : 0;
    if (exact) exact->entries[p.along_x ? *ky : *kx].value = parse_rational(fixed_text);
    std::optional<Scene> line;
    if (!exact) line = with_value(scene, fixed.parameter, parse_rational(fixed_text));
    if (first.admissible != second.admissible) {
      if (exact)
        out.push_back(psd_edge([&](const cln::cl_RA& v) -> const ExactScene& { return exact->entries[entry].value = v, *exact; }, a, b,
                               first.admissible, settings.bits, &*exact, entry));
      else
        out.push_back(psd_edge([&](const cln::cl_RA& v) {
          along.parameter.assign(*line, Number::parse(to_string(v)));
          return ExactScene::from(*line, ExactScene::MCheck::Caller);
        }, a, b, first.admissible, settings.bits));
      out.back().along_x = p.along_x;
      out.back().i = p.i;
      out.back().j = p.j;
      return out;
    }
    const std::vector<LabelChange> changes = exact ? detail::entry_label_changes(*exact, entry, a, b, by_region, proven_region, settings.bits, lines.plane.get())
                                                   : label_changes(*line, along.parameter, {a, b}, by_region, settings.bits, 1, proven_region);
    for (const LabelChange& c : changes)
      out.push_back({p.along_x, p.i, p.j, c.low, c.high, Region::parse(c.below, bodies), Region::parse(c.above, bodies)});
    return out;
  };
  // The boundaries of the pairs first … first + size − 1, in order, on settings.threads.
  auto boundaries = [&](std::size_t first, std::size_t size) {
    const auto found = parallel_map(size, settings.threads, make_lines, [&](Lines& lines, std::size_t at) { return bisect(lines, first + at); });
    std::vector<MapBoundary> all;
    for (const auto& f : found) all.insert(all.end(), f.begin(), f.end());
    return all;
  };
  m.boundaries = in_tasks<MapBoundary>(settings.runner, pending.size(), per_task(pending.size()), "map()", boundaries, detail::boundaries_to_text,
                                       detail::boundaries_from_text);
  stage_end("bisections");
  // Each boundary read back (a runner's text, a checkpoint) lies between the
  // two grid points it was bisected between (those bisected here do).
  if (settings.runner) {
    std::set<std::tuple<bool, int, int>> bisected;
    for (const Pending& p : pending) bisected.insert({p.along_x, p.i, p.j});
    for (const MapBoundary& b : m.boundaries) {
      if (!bisected.count({b.along_x, b.i, b.j}))
        throw std::invalid_argument("map(): a damaged result: a boundary between grid points (" + std::to_string(b.i) + ", " + std::to_string(b.j) +
                                    ") that were not bisected");
      const cln::cl_RA a = parse_rational(b.along_x ? tx[static_cast<std::size_t>(b.i)] : ty[static_cast<std::size_t>(b.j)]);
      const cln::cl_RA c = parse_rational(b.along_x ? tx[static_cast<std::size_t>(b.i) + 1] : ty[static_cast<std::size_t>(b.j) + 1]);
      if (b.low < cln::min(a, c) || b.high > cln::max(a, c))
        throw std::invalid_argument("map(): a damaged result: a bracket [" + to_string(b.low) + ", " + to_string(b.high) +
                                    "] outside the grid step it was bisected in [" + to_string(cln::min(a, c)) + ", " + to_string(cln::max(a, c)) + "]");
    }
  }
  stage_end("read back");
  m.curves = chain(m);
  stage_end("curves");
  return m;
}

std::pair<double, double> position(const Map& map, const MapBoundary& b) {
  const double along = cln::double_approx((b.low + b.high) / 2);
  const double fixed = cln::double_approx(b.along_x ? map.y.value(b.j) : map.x.value(b.i));
  return b.along_x ? std::pair<double, double>{along, fixed} : std::pair<double, double>{fixed, along};
}

}  // namespace superball::numeric
