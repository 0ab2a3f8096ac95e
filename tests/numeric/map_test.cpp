// Maps over two parameters (issue 15): each solved point is the solve of the
// same scene, each point left out has M not positive semi-definite, each
// boundary bracket holds two different regions at its ends (exact solves),
// the curves chain through neighbouring cells, the map does not depend on
// the number of threads, and bad axes are refused before anything is solved.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <limits>
#include <optional>
#include <random>
#include <stdexcept>
#include <vector>
#include <string>

#include "superball/cases/error.hpp"
#include "superball/cases/parameter.hpp"
#include "superball/cases/scene_file.hpp"
#include "superball/numeric/map.hpp"
#include "map_internal.hpp"
#include "support.hpp"

namespace superball::testing {
namespace {

const std::string kPaper = std::string(SUPERBALL_CASES_DIR) + "/scenes/paper-4.4-alpha2.toml";
const std::string kFig5 = std::string(SUPERBALL_CASES_DIR) + "/scenes/paper-fig5-alpha2.toml";

numeric::Axis axis(const Scene& scene, const std::string& key, const cl_RA& from, const cl_RA& to, int steps) {
  return {Parameter::parse(key, scene), from, to, steps};
}

/// The scene at grid point (i, j) of \p m, through Parameter::set() (the loader's checks).
Scene scene_at(const Scene& scene, const numeric::Map& m, int i, int j) {
  return numeric::with_value(numeric::with_value(scene, m.x.parameter, m.x.values()[static_cast<std::size_t>(i)]), m.y.parameter,
                             m.y.values()[static_cast<std::size_t>(j)]);
}

/// The scene on the grid line of boundary \p b with its varying parameter at \p value.
Scene scene_on_line(const Scene& scene, const numeric::Map& m, const numeric::MapBoundary& b, const cl_RA& value) {
  const Scene line = b.along_x ? numeric::with_value(scene, m.y.parameter, m.y.values()[static_cast<std::size_t>(b.j)])
                               : numeric::with_value(scene, m.x.parameter, m.x.values()[static_cast<std::size_t>(b.i)]);
  return numeric::with_value(line, b.along_x ? m.x.parameter : m.y.parameter, value);
}

numeric::Region exact_region(const Scene& s) {
  auto problem = Problem<cl_RA>::from(ExactScene::from(s));
  auto solution = numeric::solve(problem);
  return numeric::Region::of({std::move(problem), std::move(solution)});
}

/// (K₃₄, α₂) at the §4.4 parameters, down to α₂ = −150 where M is no longer PSD.
numeric::Map paper_map(const Scene& scene, int threads, int nx = 13, int ny = 11) {
  numeric::MapSettings settings;
  settings.threads = threads;
  return numeric::map(scene, axis(scene, "K.3-4", 0, 20, nx), axis(scene, "alpha.2", -150, 0, ny), settings);
}

/// Each point of \p m is the solve of its scene from scratch (Parameter::set(),
/// ExactScene::from(), Problem<double>::from(), solve()), bit for bit, or M is
/// not positive semi-definite there; returns (solved, marked).
std::pair<int, int> expect_points_are_solves(const Scene& scene, const numeric::Map& m) {
  int solved = 0, marked = 0;
  for (int j = 0; j < m.y.steps; ++j)
    for (int i = 0; i < m.x.steps; ++i) {
      SCOPED_TRACE("point (" + std::to_string(i) + ", " + std::to_string(j) + ")");
      const Scene s = scene_at(scene, m, i, j);
      const numeric::MapPoint& p = m.at(i, j);
      if (!p.admissible) {
        ++marked;
        try {
          (void)ExactScene::from(s);
          ADD_FAILURE() << "marked, but the scene is admissible";
        } catch (const InputError& e) {
          EXPECT_NE(std::string(e.what()).find("not positive semi-definite"), std::string::npos) << e.what();
        }
        continue;
      }
      ++solved;
      const auto problem = Problem<double>::from(ExactScene::from(s));
      const auto sol = numeric::solve(problem);
      EXPECT_EQ(p.status, sol.status);
      EXPECT_EQ(p.region.closed, sol.closed);
      const double before = std::fabs(problem.u[0]);
      EXPECT_EQ(p.ratio, sol.velocities_after[0] / before);  // bit for bit
      EXPECT_EQ(p.region.superball, sol.velocities_after[0] > before);
    }
  return {solved, marked};
}

/// detail::extremes() finds what std::minmax_element() finds with CLN's
/// order (the first smallest, the last largest): values drawn from a few
/// (ties), values whose doubles are equal but not they (p/q and
/// p/q + 1/2⁸⁰), beyond double's range (10^±400), both signs.
TEST(Map, check_ExtremesAreTheExactOnes) {
  std::mt19937_64 draw(5);
  const cl_RA tiny = cln::expt(cl_RA(2), -80);
  for (int t = 0; t < 3000; ++t) {
    std::vector<cl_RA> values;
    const int n = 1 + static_cast<int>(draw() % 12);
    for (int k = 0; k < n; ++k) {
      cl_RA v = cl_RA(static_cast<int>(draw() % 7) - 3) / static_cast<int>(1 + draw() % 3);
      switch (draw() % 5) {
        case 0: v = v + tiny; break;
        case 1: v = v - tiny; break;
        case 2: v = (draw() % 2 == 0 ? 1 : -1) * cln::expt(cl_RA(10), draw() % 2 == 0 ? 400 : -400) + (draw() % 2 == 0 ? tiny : cl_RA(0)); break;
        default: break;
      }
      values.push_back(v);
    }
    const auto [low, high] = std::minmax_element(values.begin(), values.end());
    const auto got = numeric::detail::extremes(values);
    ASSERT_EQ(got.first, static_cast<std::size_t>(low - values.begin())) << t;
    ASSERT_EQ(got.second, static_cast<std::size_t>(high - values.begin())) << t;
  }
}

TEST(Map, EachPointIsTheSolveOfItsSceneOrHasMNotPsd) {
  // Two entries of M on the axes: each thread sets only them (detail::entry_points()).
  const Scene scene = load_scene(kPaper);
  const numeric::Map m = paper_map(scene, 2);
  ASSERT_EQ(m.points.size(), 13u * 11u);
  const auto [solved, marked] = expect_points_are_solves(scene, m);
  EXPECT_GT(solved, 0);
  EXPECT_GT(marked, 0);  // the grid crosses the edge of the PSD cone (α₂ ≈ −102.5)
}

TEST(Map, PointsOnTheEdgeOfTheConeAreDecidedExactly) {
  // K₁₂ K₁₄ = α₂² at (K₁₂, α₂) = (15, −150) with K₁₄ = 1500: M is singular there, PSD; floating
  // point cannot tell, the exact fallback does.  Beside it, K₁₂ = 14 is outside the cone.
  const Scene scene = load_scene(kPaper);
  numeric::MapSettings settings;
  settings.threads = 2;
  const numeric::Map m = numeric::map(scene, axis(scene, "K.1-2", 0, 30, 31), axis(scene, "alpha.2", -150, 0, 4), settings);
  EXPECT_TRUE(m.at(15, 0).admissible);
  EXPECT_FALSE(m.at(14, 0).admissible);
  expect_points_are_solves(scene, m);
}

TEST(Map, AxesOtherThanEntriesOfMSolveEachSceneFromScratch) {
  // A mass on an axis: each point's scene is converted on its own.
  const Scene scene = load_scene(kPaper);
  numeric::MapSettings settings;
  settings.threads = 2;
  const numeric::Map m = numeric::map(scene, axis(scene, "mass.2", 5, 20, 7), axis(scene, "alpha.2", -110, 0, 6), settings);
  const auto [solved, marked] = expect_points_are_solves(scene, m);
  EXPECT_GT(solved, 0);
  EXPECT_GT(marked, 0);
}

TEST(Map, TheFloatingPointFilterOfPsdDecidesOnlyClearCases) {
  Eigen::MatrixXd work;
  Eigen::MatrixXd M(2, 2);
  M << 7, -100, -100, 1500;  // det 500 > 0: inside the cone
  EXPECT_EQ(numeric::detail::psd_by_floating_point(M, work), std::optional<bool>(true));
  M << 7, -110, -110, 1500;  // det −1600 < 0: outside
  EXPECT_EQ(numeric::detail::psd_by_floating_point(M, work), std::optional<bool>(false));
  M << 15, -150, -150, 1500;  // det 0: on the edge, left to exact arithmetic
  EXPECT_EQ(numeric::detail::psd_by_floating_point(M, work), std::nullopt);
}

TEST(Map, EachBoundaryBracketHoldsTwoRegionsAtItsEnds) {
  const Scene scene = load_scene(kPaper);
  const numeric::Map m = paper_map(scene, 2);
  ASSERT_FALSE(m.boundaries.empty());
  bool case_change = false, superball_change = false, psd_edge = false;
  for (const numeric::MapBoundary& b : m.boundaries) {
    const auto [x, y] = numeric::position(m, b);
    SCOPED_TRACE("boundary at (" + std::to_string(x) + ", " + std::to_string(y) + ")");
    const numeric::Axis& along = b.along_x ? m.x : m.y;
    const cl_RA step = abs_q(along.to - along.from) / (along.steps - 1);
    EXPECT_TRUE(b.low < b.high);
    EXPECT_LE(b.high - b.low, step / cln::expt(cl_RA(2), 64)) << "bracket width " << approx(b.high - b.low);
    // Inside the segment between the two grid neighbours.
    const cl_RA a = along.values()[static_cast<std::size_t>(b.along_x ? b.i : b.j)];
    const cl_RA c = along.values()[static_cast<std::size_t>(b.along_x ? b.i + 1 : b.j + 1)];
    EXPECT_TRUE(max_q(a, c) >= b.high && b.low >= (a < c ? a : c));
    const Scene low = scene_on_line(scene, m, b, b.low), high = scene_on_line(scene, m, b, b.high);
    EXPECT_EQ(numeric::positive_semidefinite(ExactScene::from(low, ExactScene::MCheck::Caller)), b.below_psd);
    EXPECT_EQ(numeric::positive_semidefinite(ExactScene::from(high, ExactScene::MCheck::Caller)), b.above_psd);
    if (b.below_psd != b.above_psd) {
      psd_edge = true;
      continue;
    }
    ASSERT_TRUE(b.below_psd);
    EXPECT_NE(b.below, b.above);
    EXPECT_EQ(exact_region(low), b.below);
    EXPECT_EQ(exact_region(high), b.above);
    case_change = case_change || b.below.closed != b.above.closed;
    superball_change = superball_change || b.below.superball != b.above.superball;
  }
  EXPECT_TRUE(case_change && superball_change && psd_edge);
}

TEST(Map, CurvesChainThroughNeighbouringCells) {
  const Scene scene = load_scene(kPaper);
  const numeric::Map m = paper_map(scene, 2, 21, 21);
  ASSERT_FALSE(m.curves.empty());
  std::vector<int> on_curves(m.boundaries.size(), 0);
  for (const numeric::MapCurve& c : m.curves) {
    ASSERT_FALSE(c.points.empty());
    for (std::size_t k = 0; k < c.points.size(); ++k) {
      const numeric::MapBoundary& b = m.boundaries[c.points[k]];
      ++on_curves[c.points[k]];
      switch (c.kind) {
        case numeric::MapCurve::Kind::Psd: EXPECT_NE(b.below_psd, b.above_psd); break;
        case numeric::MapCurve::Kind::Superball: EXPECT_NE(b.below.superball, b.above.superball); break;
        case numeric::MapCurve::Kind::Case:
          EXPECT_TRUE((b.below.closed == c.first && b.above.closed == c.second) || (b.below.closed == c.second && b.above.closed == c.first));
      }
      if (k == 0) continue;
      const numeric::MapBoundary& a = m.boundaries[c.points[k - 1]];
      // Two points on edges of one cell: grid indices at most one apart.
      EXPECT_LE(std::abs(a.i - b.i), 1);
      EXPECT_LE(std::abs(a.j - b.j), 1);
    }
  }
  for (std::size_t k = 0; k < m.boundaries.size(); ++k) EXPECT_GE(on_curves[k], 1) << "boundary " << k << " is on no curve";
  // The superball edge crosses the map from K₃₄ = 0 to 20 as one curve.
  int edges = 0;
  for (const numeric::MapCurve& c : m.curves) edges += c.kind == numeric::MapCurve::Kind::Superball;
  EXPECT_EQ(edges, 1);
}

/// \p a and \p b hold the same points, field for field (ratios bit for bit,
/// NaN as NaN).
void expect_same_points(const std::vector<numeric::MapPoint>& a, const std::vector<numeric::MapPoint>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].admissible, b[k].admissible) << k;
    EXPECT_EQ(a[k].status, b[k].status) << k;
    EXPECT_EQ(a[k].region, b[k].region) << k;
    EXPECT_EQ(a[k].region.closed.contacts(), b[k].region.closed.contacts()) << k;
    if (std::isnan(a[k].ratio))
      EXPECT_TRUE(std::isnan(b[k].ratio)) << k;
    else
      EXPECT_EQ(std::memcmp(&a[k].ratio, &b[k].ratio, sizeof(double)), 0) << k << ": " << a[k].ratio << " " << b[k].ratio;
  }
}

void expect_same_boundaries(const std::vector<numeric::MapBoundary>& a, const std::vector<numeric::MapBoundary>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].along_x, b[k].along_x) << k;
    EXPECT_EQ(a[k].i, b[k].i) << k;
    EXPECT_EQ(a[k].j, b[k].j) << k;
    EXPECT_TRUE(a[k].low == b[k].low && a[k].high == b[k].high) << k;
    EXPECT_EQ(a[k].below, b[k].below) << k;
    EXPECT_EQ(a[k].above, b[k].above) << k;
    EXPECT_EQ(a[k].below.closed.contacts(), b[k].below.closed.contacts()) << k;
    EXPECT_EQ(a[k].above.closed.contacts(), b[k].above.closed.contacts()) << k;
    EXPECT_EQ(a[k].below_psd, b[k].below_psd) << k;
    EXPECT_EQ(a[k].above_psd, b[k].above_psd) << k;
  }
}

void expect_same_maps(const numeric::Map& a, const numeric::Map& b) {
  expect_same_points(a.points, b.points);
  expect_same_boundaries(a.boundaries, b.boundaries);
  ASSERT_EQ(a.curves.size(), b.curves.size());
  for (std::size_t k = 0; k < a.curves.size(); ++k) {
    EXPECT_EQ(a.curves[k].kind, b.curves[k].kind);
    EXPECT_EQ(a.curves[k].first, b.curves[k].first);
    EXPECT_EQ(a.curves[k].second, b.curves[k].second);
    EXPECT_EQ(a.curves[k].points, b.curves[k].points);
    EXPECT_EQ(a.curves[k].closed, b.curves[k].closed);
  }
}

TEST(Map, TheMapDoesNotDependOnTheThreads) {
  const Scene scene = load_scene(kFig5);
  numeric::MapSettings one, two;
  two.threads = 2;
  const auto x = axis(scene, "alpha.2", -200, 100, 17), y = axis(scene, "alpha.5", -10, 10, 9);
  const numeric::Map a = numeric::map(scene, x, y, one), b = numeric::map(scene, x, y, two);
  EXPECT_FALSE(a.boundaries.empty());
  expect_same_maps(a, b);
}


/// The regions as map() labels them, exactly and from a proven solve.
const numeric::Label by_region = [](const numeric::ExactPoint& e) { return numeric::Region::of(e).label(); };
const numeric::ProvenLabel proven_region = [](const numeric::ProvenPoint& p) -> std::optional<std::string> {
  if (!p.superball) return std::nullopt;
  return numeric::Region{p.closed, *p.superball}.label();
};

TEST(Map, ABoundaryAlongAnEntryOfMIsTheBisectionOfExactSolves) {
  // The map's bisection (one exact scene, the entry set per value, labels
  // proven in double or by the cases met last) against label_changes() with
  // every label from an exact solve of the scene written with its value:
  // the same brackets and regions, ascending and descending.
  const Scene scene = load_scene(kPaper);
  const Parameter k34 = Parameter::parse("K.3-4", scene), alpha2 = Parameter::parse("alpha.2", scene);
  int compared = 0;
  for (const int alpha : {-100, -40, -15}) {
    const Scene line = numeric::with_value(scene, alpha2, alpha);
    const auto entry = numeric::detail::entry_changed(line, numeric::with_value(line, k34, 20));
    ASSERT_TRUE(entry);
    const ExactScene exact = ExactScene::from(line, ExactScene::MCheck::Caller);
    const auto values = numeric::linspace(0, 20, 9);
    for (std::size_t k = 0; k + 1 < values.size(); ++k)
      for (const bool ascending : {true, false}) {
        const cl_RA& a = ascending ? values[k] : values[k + 1];
        const cl_RA& b = ascending ? values[k + 1] : values[k];
        const auto reference = numeric::label_changes(line, k34, {a, b}, by_region, 64, 1);
        const auto fast = numeric::detail::entry_label_changes(exact, *entry, a, b, by_region, proven_region, 64);
        ASSERT_EQ(fast.size(), reference.size()) << "alpha.2 = " << alpha << ", K.3-4 from " << approx(a);
        for (std::size_t c = 0; c < fast.size(); ++c) {
          EXPECT_TRUE(fast[c].low == reference[c].low && fast[c].high == reference[c].high);
          EXPECT_EQ(fast[c].below, reference[c].below);
          EXPECT_EQ(fast[c].above, reference[c].above);
          ++compared;
        }
      }
  }
  EXPECT_GE(compared, 6);  // each line crosses a boundary: case or superball edge, both directions
  EXPECT_THROW(numeric::detail::entry_label_changes(ExactScene::from(scene), 0, 0, 1, by_region, proven_region, 0), std::invalid_argument);
}

TEST(Map, TheBoundaryStageDoesNotDependOnTheThreadsAlongEntriesOfMOrNot) {
  // The paper map along two entries of M (case boundaries, the superball and
  // the PSD edges), and one along a mass (each line a scene): 1 and 3 threads
  // give the same map, and every boundary of the first is the bisection of
  // exact solves along its grid step.
  const Scene scene = load_scene(kPaper);
  numeric::MapSettings one, three;
  three.threads = 3;
  const auto x = axis(scene, "K.3-4", 20, 0, 9), y = axis(scene, "alpha.2", -150, 0, 7);
  const numeric::Map a = numeric::map(scene, x, y, one), b = numeric::map(scene, x, y, three);
  expect_same_maps(a, b);
  int bisected = 0;
  for (const numeric::MapBoundary& c : a.boundaries) {
    if (c.below_psd != c.above_psd) continue;
    const Scene line = c.along_x ? numeric::with_value(scene, y.parameter, y.values()[static_cast<std::size_t>(c.j)])
                                 : numeric::with_value(scene, x.parameter, x.values()[static_cast<std::size_t>(c.i)]);
    const numeric::Axis& along = c.along_x ? x : y;
    const std::size_t at = static_cast<std::size_t>(c.along_x ? c.i : c.j);
    const auto reference = numeric::label_changes(line, along.parameter, {along.values()[at], along.values()[at + 1]}, by_region, 64, 1);
    const bool found = std::any_of(reference.begin(), reference.end(), [&](const numeric::LabelChange& r) {
      return r.low == c.low && r.high == c.high && r.below == c.below.label() && r.above == c.above.label();
    });
    EXPECT_TRUE(found) << "boundary (" << c.i << ", " << c.j << ")";
    ++bisected;
  }
  EXPECT_GT(bisected, 0);
  const auto m = axis(scene, "mass.1", 1, 3, 5);
  expect_same_maps(numeric::map(scene, m, y, one), numeric::map(scene, m, y, three));
}

TEST(Map, ThePsdEdgeIsTheHalvingOfExactPsdChecks) {
  // Along entries of M the edge of the cone is bisected on the sign of det M
  // (a polynomial in the entry): each bracket must be the one that 64
  // halvings on positive_semidefinite() at every midpoint give, on an
  // off-diagonal entry (α₂ on a straight edge, and α₂ with α₅ on a curved
  // one) and on a diagonal entry (K₁₂).
  const Scene paper = load_scene(kPaper), fig5 = load_scene(kFig5);
  struct Case {
    const Scene& scene;
    numeric::Axis x, y;
  };
  const std::vector<Case> cases = {{paper, axis(paper, "K.3-4", 0, 20, 5), axis(paper, "alpha.2", -130, 0, 6)},
                                   {paper, axis(paper, "alpha.2", 0, -130, 7), axis(paper, "K.1-2", 0, 10, 4)},
                                   {fig5, axis(fig5, "alpha.2", -200, 100, 9), axis(fig5, "alpha.5", -10, 10, 3)}};
  for (const Case& c : cases) {
    const numeric::Map m = numeric::map(c.scene, c.x, c.y);
    int edges = 0;
    for (const numeric::MapBoundary& b : m.boundaries) {
      if (b.below_psd == b.above_psd) continue;
      ++edges;
      SCOPED_TRACE(c.x.text() + " " + c.y.text() + ": boundary (" + std::to_string(b.i) + ", " + std::to_string(b.j) + ")");
      const numeric::Axis& along = b.along_x ? m.x : m.y;
      const std::size_t at = static_cast<std::size_t>(b.along_x ? b.i : b.j);
      cl_RA first = along.values()[at], second = along.values()[at + 1];
      const auto psd = [&](const cl_RA& v) {
        return numeric::positive_semidefinite(ExactScene::from(scene_on_line(c.scene, m, b, v), ExactScene::MCheck::Caller));
      };
      const bool first_psd = psd(first);
      ASSERT_NE(first_psd, psd(second));
      for (int k = 0; k < 64; ++k) {
        const cl_RA mid = (first + second) / 2;
        (psd(mid) == first_psd ? first : second) = mid;
      }
      EXPECT_TRUE(b.low == (first < second ? first : second)) << approx(b.low);
      EXPECT_TRUE(b.high == (first < second ? second : first)) << approx(b.high);
    }
    EXPECT_GT(edges, 0) << c.x.text() << " " << c.y.text();
  }
}

TEST(Map, PointsAndBoundariesAsTextReadBackExactly) {
  // Hand-made fields at the edges of what the text must carry: ratios that
  // 17 digits of %g would not all keep, NaN, −0, subnormal, the largest
  // double; sets of 4 contacts (the empty one too); every status; points not
  // solved (every field at its default, as the decoder demands) between
  // solved ones whose verdict agrees with their ratio; brackets of fractions
  // 2^-70 wide.
  std::vector<numeric::MapPoint> points;
  const double ratios[] = {1.0 / 3, std::nan(""), -0.0, std::numeric_limits<double>::denorm_min(), std::numeric_limits<double>::max(),
                           std::nextafter(1.0, 0.0), 0.1 + 0.2, std::nextafter(1.0, 2.0)};
  int k = 0;
  for (double r : ratios) {
    numeric::MapPoint p;
    p.admissible = k % 3 != 2;
    if (p.admissible) {
      p.status = static_cast<numeric::Status>(k % 3);
      p.region.superball = r > 1;
      p.region.closed = ContactSet::from_mask(static_cast<std::uint64_t>(k), 5);
      p.ratio = r;
    }
    points.push_back(p);
    ++k;
  }
  const std::string text = numeric::detail::points_to_text(points);
  expect_same_points(points, numeric::detail::points_from_text(text));
  EXPECT_EQ(numeric::detail::points_to_text(numeric::detail::points_from_text(text)), text);

  std::vector<numeric::MapBoundary> boundaries(3);
  const cl_RA tiny = cln::expt(cl_RA(2), -70);
  boundaries[0] = {true, 3, 7, cl_RA(-1025) / 7, cl_RA(-1025) / 7 + tiny, {ContactSet::parse("2-3", 4), true}, {ContactSet::parse("", 4), false}};
  boundaries[1] = {false, 0, 12, cl_RA(1) / 3 - tiny, cl_RA(1) / 3, {ContactSet::parse("3-4", 4), false}, {}, true, false};
  boundaries[2] = {false, 9999, 0, 0, tiny, {}, {ContactSet::parse("2-3,3-4", 4), true}, false, true};
  const std::string lines = numeric::detail::boundaries_to_text(boundaries);
  expect_same_boundaries(boundaries, numeric::detail::boundaries_from_text(lines));
  EXPECT_EQ(numeric::detail::boundaries_to_text(numeric::detail::boundaries_from_text(lines)), lines);

  // A map's own points and boundaries, across the edge of the PSD cone.
  const Scene scene = load_scene(kPaper);
  const numeric::Map m = paper_map(scene, 1);
  ASSERT_FALSE(m.boundaries.empty());
  expect_same_points(m.points, numeric::detail::points_from_text(numeric::detail::points_to_text(m.points)));
  expect_same_boundaries(m.boundaries, numeric::detail::boundaries_from_text(numeric::detail::boundaries_to_text(m.boundaries)));

  // Damaged texts are refused, not read as something else.
  for (const char* bad : {"1 0 0 0x1p+0\n", "1 0 0 0x1p+0 01", "1 3 0 0x1p+0 01\n", "2 0 0 0x1p+0 01\n", "1 0 0 0x1p+0 012\n",
                                 "1 0 0 0x1p+0x 01\n", "1 0 0 0x1p+0 01 1\n"})
    EXPECT_THROW(numeric::detail::points_from_text(bad), std::invalid_argument) << bad;
  for (const char* bad : {"1 0 0 1/3 1/2 1 1 0 0 . \n", "1 0 0 1/3 1/2 1 1 0 0 . 1/2\n", "1 0 x 1/3 1/2 1 1 0 0 . .\n"})
    EXPECT_THROW(numeric::detail::boundaries_from_text(bad), std::invalid_argument) << bad;
}

TEST(Map, TasksOfARunnerGiveTheSameMapFieldForField) {
  // A runner that computes its tasks last to first, each through its text:
  // the map is the one computed in one call, field for field.
  const Scene scene = load_scene(kPaper);
  std::vector<std::size_t> calls;
  numeric::MapSettings settings;
  settings.threads = 2;
  settings.runner = [&](std::size_t tasks, const std::function<std::string(std::size_t)>& task) {
    calls.push_back(tasks);
    std::vector<std::string> texts(tasks);
    for (std::size_t t = tasks; t-- > 0;) texts[t] = task(t);
    return texts;
  };
  const auto x = axis(scene, "K.3-4", 0, 20, 13), y = axis(scene, "alpha.2", -150, 0, 11);
  const numeric::Map whole = numeric::map(scene, x, y), tasks = numeric::map(scene, x, y, settings);
  ASSERT_EQ(calls.size(), 2u);  // the points, then the boundaries
  EXPECT_EQ(calls[0], 48u);     // 143 points, 3 per task (at most map_tasks = 64 tasks)
  EXPECT_GT(calls[1], 1u);
  EXPECT_LE(calls[1], numeric::map_tasks);
  EXPECT_FALSE(whole.boundaries.empty());
  expect_same_maps(whole, tasks);
  // Also the path that solves each scene from scratch (an axis that is not an entry of M).
  calls.clear();
  const auto g = axis(scene, "g", 1, 20, 7);
  expect_same_maps(numeric::map(scene, x, g), numeric::map(scene, x, g, settings));
  EXPECT_GE(calls.size(), 1u);
}

TEST(Map, BadAxesAreRefusedBeforeAnythingIsSolved) {
  const Scene scene = load_scene(kPaper);
  auto refused = [&](const numeric::Axis& x, const numeric::Axis& y, const std::string& expected) {
    try {
      (void)numeric::map(scene, x, y);
      ADD_FAILURE() << "not refused: " << expected;
    } catch (const std::exception& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  };
  const auto k34 = axis(scene, "K.3-4", 0, 20, 5);
  refused(k34, axis(scene, "K.3-4", 1, 2, 5), "--x K.3-4 and --y K.3-4 name the same parameter (K.3-4)");
  // One entry under two spellings is one parameter (issue 25).
  refused(k34, axis(scene, "K.03-4", 1, 2, 5), "--x K.3-4 and --y K.03-4 name the same parameter (K.3-4); a map needs two different parameters");
  refused(axis(scene, "coupling.1-4/1-2", -1, 0, 3), axis(scene, "alpha.2", -2, 0, 3),
          "--x coupling.1-4/1-2 and --y alpha.2 name the same parameter (alpha.2)");
  refused(k34, axis(scene, "alpha.2", -1, 0, 1), "an axis takes 2 to 10000");
  refused(axis(scene, "alpha.2", -1, 0, 10001), k34, "an axis takes 2 to 10000");
  refused(k34, axis(scene, "g", -1, 10, 5), "g = -1");
  refused(k34, axis(scene, "velocity.3", 0, -5, 5), "opens before the collision");
  // M is PSD nowhere on the grid: α₂ <= −200 is far beyond the edge at −102.5.
  refused(k34, axis(scene, "alpha.2", -400, -200, 5), "not positive semi-definite at any point of the map");
}

TEST(Map, AGridLargerThanTheMemoryIsRefusedAtOnce) {
  // The documented maximum, 10⁴ × 10⁴ points, against 1 GB: refused with the
  // estimate in well under a second, before anything is solved.
  const Scene scene = load_scene(kPaper);
  numeric::MapSettings settings;
  settings.memory = numeric::Memory{1e9, "a test's limit"};
  const auto x = axis(scene, "K.3-4", 0, 20, numeric::map_max_steps), y = axis(scene, "alpha.2", -110, 0, numeric::map_max_steps);
  std::string why;
  EXPECT_FALSE(settings.fits(x, y, &why));
  const auto start = std::chrono::steady_clock::now();
  try {
    (void)numeric::map(scene, x, y, settings);
    ADD_FAILURE() << "not refused";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(e.what(), why);
    EXPECT_EQ(why.rfind("map(): a 10000 x 10000 grid holds about ", 0), 0u) << why;
    EXPECT_NE(why.find("this machine has 1.0 GB available (a test's limit); use a coarser grid"), std::string::npos) << why;
  }
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
  // The estimate counts at least the points themselves, and what the output holds beside them.
  EXPECT_GE(settings.bytes_per_point(), static_cast<double>(sizeof(numeric::MapPoint)));
  const double alone = settings.bytes_per_point();
  settings.output_bytes_per_point = 100;
  EXPECT_EQ(settings.bytes_per_point(), alone + 100);
  // A grid that fits is solved.
  EXPECT_TRUE(settings.fits(axis(scene, "K.3-4", 0, 20, 5), axis(scene, "alpha.2", -110, 0, 5)));
}

TEST(Memory, TheProbeAndTheRefusalSayHowMuchAndWhy) {
  const numeric::Memory here = numeric::available_memory();
  EXPECT_GT(here.bytes, 0);
  EXPECT_FALSE(here.source.empty());
  EXPECT_EQ(numeric::bytes_text(512), "512 B");
  EXPECT_EQ(numeric::bytes_text(9.6e9), "9.6 GB");
  EXPECT_EQ(numeric::bytes_text(11e6), "11.0 MB");
  EXPECT_NO_THROW(numeric::check_memory("f()", "it", 1e9, "1 byte each", {1e9, "test"}, "ask less"));
  try {
    numeric::check_memory("f()", "a list of 10⁹", 2e9, "2 bytes each", {1e9, "ulimit -v"}, "ask less");
    ADD_FAILURE() << "not refused";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "f(): a list of 10⁹ holds about 2.0 GB (2 bytes each); this machine has 1.0 GB available (ulimit -v); ask less");
  }
}

TEST(Map, StreamedPointsAreTheMapsPoints) {
  // map_points() block by block (blocks that end inside a row) gives map()'s points, bit for bit, in order.
  const Scene scene = load_scene(kPaper);
  const auto x = axis(scene, "K.3-4", 0, 20, 13), y = axis(scene, "alpha.2", -150, 0, 11);
  numeric::MapSettings settings;
  const numeric::Map m = numeric::map(scene, x, y, settings);
  std::vector<numeric::MapPoint> streamed;
  std::vector<std::size_t> firsts;
  numeric::map_points(scene, x, y, settings, 7, [&](std::size_t first, const std::vector<numeric::MapPoint>& points) {
    EXPECT_LE(points.size(), 7u);
    firsts.push_back(first);
    streamed.insert(streamed.end(), points.begin(), points.end());
  });
  expect_same_points(m.points, streamed);
  ASSERT_EQ(firsts.size(), (13u * 11 + 6) / 7);
  for (std::size_t b = 0; b < firsts.size(); ++b) EXPECT_EQ(firsts[b], 7 * b);
  // As map(): bad axes, and a grid with no admissible point (after its last block).
  EXPECT_THROW(numeric::map_points(scene, x, x, settings, 7, [](std::size_t, const std::vector<numeric::MapPoint>&) {}),
               std::invalid_argument);
  EXPECT_THROW(numeric::map_points(scene, x, axis(scene, "alpha.2", -400, -200, 5), settings, 7,
                                   [](std::size_t, const std::vector<numeric::MapPoint>&) {}),
               InputError);
}

}  // namespace
}  // namespace superball::testing
