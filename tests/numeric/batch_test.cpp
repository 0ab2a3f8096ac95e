// numeric::Batch (batch.hpp): each scene of a batch is numeric::solve() of
// the problem Problem<S>::from() makes of it, bit for bit, in double, long
// double and exact, whatever the scenes before it in the batch did (another
// case, pivots, a failed solve, a scaled solve, a datum out of range), one
// at a time or through solve_each(); and the fixed-size path in lanes
// (collision/lanes.hpp), each lane the fixed-size solve of its problem, in
// its AVX2 and its baseline copy.
#include <gtest/gtest.h>

#include <cln/rational.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <iostream>
#include <limits>
#include <optional>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "collision/lanes.hpp"
#include "collision/small_solver.hpp"
#include "map_internal.hpp"
#include "psd_filter.hpp"
#include "superball/numeric/batch.hpp"
#include "superball/numeric/collision.hpp"
#include "superball/numeric/map.hpp"
#include "superball/numeric/sweep.hpp"
#include "superball/numeric/problem.hpp"
#include "support.hpp"

namespace superball::testing {
namespace batch_test {

const std::string kPaperScene = std::string(SUPERBALL_CASES_DIR) + "/scenes/paper-4.4-alpha2.toml";

/// The same bits (memcmp) for floating values, equality for exact ones.
template <class S>
bool same(const S& a, const S& b) {
  if constexpr (std::is_floating_point<S>::value)
    return std::memcmp(&a, &b, sizeof(S)) == 0 || (std::isnan(a) && std::isnan(b));  // long double: 6 padding bytes
  else
    return a == b;
}

/// Field by field; floating fields compared by value bits (a long double's
/// padding bytes carry nothing).
template <class S>
bool same_value_bits(const S& a, const S& b) {
  if constexpr (std::is_same<S, long double>::value)
    return (std::isnan(a) && std::isnan(b)) || (a == b && std::signbit(a) == std::signbit(b));
  else
    return same(a, b);
}

template <class S>
void expect_identical(const Solution<S>& a, const Solution<S>& b) {
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.closed, b.closed) << a.closed.to_string() << " against " << b.closed.to_string();
  EXPECT_EQ(a.pivots, b.pivots);
  auto vectors = [](const std::vector<S>& x, const std::vector<S>& y, const char* what) {
    ASSERT_EQ(x.size(), y.size()) << what;
    for (std::size_t i = 0; i < x.size(); ++i) EXPECT_TRUE(same_value_bits(x[i], y[i])) << what << "[" << i << "]";
  };
  vectors(a.velocities_after, b.velocities_after, "velocities_after");
  vectors(a.reactions, b.reactions, "reactions");
  vectors(a.gaps, b.gaps, "gaps");
  EXPECT_TRUE(same_value_bits(a.kinetic_energy_before, b.kinetic_energy_before));
  EXPECT_TRUE(same_value_bits(a.kinetic_energy_after, b.kinetic_energy_after));
  EXPECT_TRUE(same_value_bits(a.dissipation, b.dissipation));
  EXPECT_TRUE(same_value_bits(a.momentum_before, b.momentum_before));
  EXPECT_TRUE(same_value_bits(a.momentum_after, b.momentum_after));
  EXPECT_TRUE(same(a.residual_motion, b.residual_motion)) << a.residual_motion << " against " << b.residual_motion;
  EXPECT_TRUE(same(a.residual_complementarity, b.residual_complementarity));
}

/// Solves \p values (one row per scene, one value per entry of \p varying)
/// with one Batch<S> on \p base (solve() then solve_each()), and each scene
/// from scratch; returns the
/// statuses, the cases and the pivot counts met, to show the branches taken.
template <class S>
std::vector<std::string> expect_batch_is_solve(const ExactScene& base, const std::vector<std::size_t>& varying,
                                               const std::vector<std::vector<cl_RA>>& values) {
  using T = ScalarTraits<S>;
  numeric::Batch<S> batch(base, varying), fresh(base, varying);
  std::vector<std::string> met;
  std::vector<Solution<S>> solutions;
  for (std::size_t row = 0; row < values.size(); ++row) {
    ExactScene scene = base;
    for (std::size_t k = 0; k < varying.size(); ++k) {
      scene.entries[varying[k]].value = values[row][k];
      batch.set(k, T::from(values[row][k], 0), cln::zerop(values[row][k]));
    }
    const Problem<S> problem = Problem<S>::from(scene);
    EXPECT_EQ(batch.problem().in_range, problem.in_range) << "scene " << row;
    const Solution<S> alone = numeric::solve(problem);
    SCOPED_TRACE("scene " + std::to_string(row));
    expect_identical(batch.solve(), alone);
    met.push_back(std::string(numeric::to_string(alone.status)) + " " + alone.closed.to_string() + " " + std::to_string(alone.pivots));
    solutions.push_back(alone);
  }
  // The same scenes through solve_each() (in double several at once, in
  // lanes whose outcomes differ: a pivot, a failure, a scaled solve), on a
  // fresh batch and on the one used above; every scene taken once, in order.
  for (numeric::Batch<S>* each : {&fresh, &batch}) {
    std::size_t next = 0;
    each->solve_each(
        values.size(),
        [&](std::size_t row) {
          for (std::size_t k = 0; k < varying.size(); ++k) each->set(k, T::from(values[row][k], 0), cln::zerop(values[row][k]));
        },
        [&](std::size_t row, const Solution<S>& s) {
          EXPECT_EQ(row, next++);
          SCOPED_TRACE("solve_each(), scene " + std::to_string(row));
          expect_identical(s, solutions[row]);
        });
    EXPECT_EQ(next, values.size());
  }
  return met;
}

/// Values of an entry around \p v: 0, fractions and multiples of it, one a
/// double rounds to zero (out of range) and one that needs scaling.
std::vector<cl_RA> around(const cl_RA& v) {
  const cl_RA x = cln::zerop(v) ? cl_RA(1) : v;
  return {x, 0, x / 2, x * 2, x * 10, -x, x / 100, x * cln::expt(cl_RA(10), 200), x * cln::expt(cl_RA(10), -400), x * 3 / 7, x};
}

TEST(Batch, EveryScenesOfAGridIsTheSolveOfItsSceneBitForBit) {
  // The paper scene over K34 and alpha_2: the three cases of its map ({},
  // {3-4} and {2-3}, one pivot or none), M not positive semi-definite below
  // alpha_2 ≈ -102.5, and K34 = 0.
  const ExactScene base = ExactScene::from(load_scene(kPaperScene));
  std::size_t k34 = base.entries.size(), alpha2 = base.entries.size();
  for (std::size_t e = 0; e < base.entries.size(); ++e) {
    const auto& x = base.entries[e];
    if (x.i == 2 && x.j == 3 && x.k == 2 && x.l == 3) k34 = e;
    if (x.i == 0 && x.j == 1 && x.k == 0 && x.l == 3) alpha2 = e;
  }
  ASSERT_LT(k34, base.entries.size());
  ASSERT_LT(alpha2, base.entries.size());
  std::vector<std::vector<cl_RA>> grid;
  for (int j = 0; j <= 12; ++j)
    for (int i = 0; i <= 20; ++i) grid.push_back({cl_RA(i), cl_RA(-120 + 10 * j)});
  const auto met = expect_batch_is_solve<double>(base, {k34, alpha2}, grid);
  std::set<std::string> cases(met.begin(), met.end());
  EXPECT_TRUE(cases.count("success {} 0")) << ::testing::PrintToString(cases);
  EXPECT_TRUE(cases.count("success {3-4} 1")) << ::testing::PrintToString(cases);
  EXPECT_TRUE(cases.count("success {2-3} 1")) << ::testing::PrintToString(cases);
  expect_batch_is_solve<long double>(base, {k34, alpha2}, grid);
  std::vector<std::vector<cl_RA>> coarse;
  for (std::size_t r = 0; r < grid.size(); r += 17) coarse.push_back(grid[r]);
  expect_batch_is_solve<cl_RA>(base, {k34, alpha2}, coarse);
}

TEST(Batch, RandomScenesWhateverBranchTheSceneBeforeTook) {
  // Scenes of 2 to 10 bodies (the fixed-size path, the general dense path,
  // the banded solver), one or two entries varied through values that take
  // other cases, lose the definiteness of A, need scaling or leave the range
  // of double; every scene follows a scene that took another branch.
  std::set<std::string> statuses;
  for (std::uint64_t seed = 9100; seed < 9160; ++seed) {
    const RandomScene r = random_scene(seed, {2, 10});
    SCOPED_TRACE(r.describe());
    const ExactScene base = ExactScene::from(r.scene());
    if (base.entries.empty()) continue;
    std::vector<std::size_t> varying{static_cast<std::size_t>(seed % base.entries.size())};
    if (base.entries.size() > 1) varying.push_back((varying[0] + 1) % base.entries.size());
    std::vector<std::vector<cl_RA>> rows;
    const std::vector<cl_RA> first = around(base.entries[varying[0]].value);
    for (std::size_t a = 0; a < first.size(); ++a) {
      std::vector<cl_RA> row{first[a]};
      if (varying.size() > 1) row.push_back(around(base.entries[varying[1]].value)[(a * 5) % first.size()]);
      rows.push_back(row);
    }
    for (const std::string& s : expect_batch_is_solve<double>(base, varying, rows)) statuses.insert(s.substr(0, s.find(' ')));
    expect_batch_is_solve<long double>(base, varying, rows);
    if (seed % 6 == 0) {  // exact: the data outside double's range are no concern of it; fewer scenes (its solves are slower)
      rows.resize(4);
      expect_batch_is_solve<cl_RA>(base, varying, rows);
    }
  }
  EXPECT_TRUE(statuses.count("success"));
  EXPECT_TRUE(statuses.count("numerical-issue"));  // out of range or A not positive definite: the failures are met too
}

TEST(Batch, ScenesWhoseOtherDataLeaveTheWindowOfDouble) {
  // Masses, M and velocities scaled by 10^±20 to 10^±300: the batch's check
  // of the window on the varying entries alone must send the same scenes
  // to solve()'s scaled solve as scaling_of() of the whole problem.
  int scaled = 0;
  for (std::uint64_t seed = 300; seed < 340; ++seed) {
    const ExtremeScene x = random_extreme_scene(seed);
    SCOPED_TRACE(x.describe());
    const ExactScene base = x.exact(ExactScene::from(x.base.scene()));
    if (base.entries.empty()) continue;
    const std::vector<std::size_t> varying{static_cast<std::size_t>(seed % base.entries.size())};
    std::vector<std::vector<cl_RA>> rows;
    for (const cl_RA& v : around(base.entries[varying[0]].value)) rows.push_back({v});
    expect_batch_is_solve<double>(base, varying, rows);
    expect_batch_is_solve<long double>(base, varying, rows);
    if (!numeric::scaling_of(Problem<double>::from(base)).identity()) ++scaled;
  }
  EXPECT_GT(scaled, 10);  // most of these scenes are solved scaled
}

TEST(Batch, TheEntriesMustExistAndBeDistinct) {
  const ExactScene base = ExactScene::from(load_scene(kPaperScene));
  EXPECT_THROW(numeric::Batch<double>(base, {base.entries.size()}), std::invalid_argument);
  EXPECT_THROW(numeric::Batch<double>(base, {1, 1}), std::invalid_argument);
  numeric::Batch<double> batch(base, {0});
  EXPECT_THROW(batch.set(1, 1.0, false), std::out_of_range);
  // Until set, an entry holds the scene's value: the batch solves the scene itself.
  expect_identical(batch.solve(), numeric::solve(Problem<double>::from(base)));
}

TEST(PsdFilter, GivesTheVerdictsOfPsdByFloatingPoint) {
  // A map point's filter of M's positive semi-definiteness (psd_filter.hpp)
  // is detail::psd_by_floating_point() bit for bit: the same verdict on
  // random symmetric matrices of 1 to 8 rows, on Gram matrices B·Bᵀ of
  // deficient rank (the edge of the cone) and on those shifted by multiples
  // of the margin τ near ±τ, where the verdict turns from true to "decide
  // exactly" to false.
  std::mt19937_64 rng(2808);
  std::uniform_real_distribution<double> unit(-1, 1);
  std::set<int> verdicts;  // 1 true, 0 false, -1 nullopt
  Eigen::MatrixXd work;
  auto expect_same = [&](const Eigen::MatrixXd& M) {
    const int n = static_cast<int>(M.rows());
    numeric::detail::PsdFilter filter(n);
    for (int r = 0; r < n; ++r)
      for (int c = 0; c <= r; ++c) filter.set(r, c, M(r, c));
    const std::optional<bool> want = numeric::detail::psd_by_floating_point(M, work), got = filter.decide();
    EXPECT_EQ(got, want) << M;
    verdicts.insert(want ? int(*want) : -1);
  };
  for (int trial = 0; trial < 4000; ++trial) {
    const int n = 1 + trial % numeric::detail::PsdFilter::max_rows;
    Eigen::MatrixXd M(n, n);
    for (int r = 0; r < n; ++r)
      for (int c = 0; c <= r; ++c) M(r, c) = M(c, r) = 100 * unit(rng);
    if (trial % 2 == 1) {  // B·Bᵀ with B of rank n − 1 (n > 1), shifted near ±τ
      Eigen::MatrixXd B(n, std::max(n - 1, 1));
      for (Eigen::Index k = 0; k < B.size(); ++k) B(k) = 10 * unit(rng);
      M = B * B.transpose();
      const double tau = numeric::map_psd_margin * M.norm();
      const double shifts[] = {0, 2, 1 + 1e-6, 1 - 1e-6, 0.5, -0.5, -1 + 1e-6, -1 - 1e-6, -2};
      M.diagonal().array() += shifts[(trial / 2) % 9] * tau;
    }
    expect_same(M);
  }
  Eigen::MatrixXd M = Eigen::MatrixXd::Identity(3, 3);
  M(1, 2) = M(2, 1) = std::numeric_limits<double>::infinity();  // ‖M‖ not finite: left to exact arithmetic
  expect_same(M);
  EXPECT_EQ(verdicts, (std::set<int>{-1, 0, 1}));
}

TEST(PsdFilter, AMapSkipsItOnlyBetweenPointsWhereMIsPsd) {
  // The grid points of a map over two entries of M (entry_points()): a
  // row's run of points whose two ends have M positive semi-definite skips
  // the filter (M is affine in the entry, the cone convex).  Rows along
  // alpha_2 that cross the edge of the cone, both ways, of 19 points cut
  // by runs of 64 and by ranges of points (a runner's tasks): each point is
  // still marked exactly where M is not positive semi-definite, and
  // otherwise is the solve of its scene, bit for bit.
  const Scene scene = load_scene(kPaperScene);
  for (const bool rising : {true, false}) {
    const numeric::Axis x{Parameter::parse("alpha.2", scene), rising ? -130 : 0, rising ? 0 : -130, 19},
        y{Parameter::parse("K.3-4", scene), 0, 20, 13};
    const std::vector<cl_RA> xs = x.values(), ys = y.values();
    const Scene corner_scene = numeric::with_value(numeric::with_value(scene, x.parameter, xs[0]), y.parameter, ys[0]);
    const ExactScene corner = ExactScene::from(corner_scene, ExactScene::MCheck::Caller);
    std::size_t kx = 0, ky = 0;
    for (std::size_t e = 0; e < corner.entries.size(); ++e) {
      const auto& c = corner.entries[e];
      if (c.i == 0 && c.j == 1 && c.k == 0 && c.l == 3) kx = e;
      if (c.i == 2 && c.j == 3 && c.k == 2 && c.l == 3) ky = e;
    }
    for (const std::size_t first : {std::size_t{0}, std::size_t{37}}) {
      const auto points = numeric::detail::entry_points<double>(corner_scene, kx, ky, x, y, numeric::MapSettings{}, first, 150);
      ASSERT_EQ(points.size(), 150u);
      int marked = 0, solved = 0;
      for (std::size_t at = 0; at < points.size(); ++at) {
        const std::size_t k = first + at, i = k % xs.size(), j = k / xs.size();
        SCOPED_TRACE("grid point " + std::to_string(i) + ", " + std::to_string(j));
        ExactScene e = corner;
        e.entries[kx].value = xs[i], e.entries[ky].value = ys[j];
        ASSERT_EQ(points[at].admissible, numeric::positive_semidefinite(e));
        if (!points[at].admissible) {
          ++marked;
          continue;
        }
        ++solved;
        const auto problem = Problem<double>::from(e);
        const auto sol = numeric::solve(problem);
        EXPECT_EQ(points[at].status, sol.status);
        EXPECT_EQ(points[at].region.closed, sol.closed);
        const double ratio = sol.velocities_after[0] / std::fabs(problem.u[0]);
        EXPECT_TRUE(same(points[at].ratio, ratio)) << points[at].ratio << " " << ratio;
      }
      EXPECT_GT(marked, 20);
      EXPECT_GT(solved, 50);
    }
  }
}

/// \p p with each entry of M varied as a lane of a map or sweep may vary it:
/// kept, scaled by 1/2 to 10, and (when \p zeros) some set to zero.
Problem<double> varied(const Problem<double>& p, Rng& rng, bool zeros) {
  Problem<double> q = p;
  for (auto& e : q.entries) {
    switch (rng.below(4)) {
      case 0: break;
      case 1: e.value *= 0.5 + rng.below(1000) / 1000.0; break;
      case 2: e.value *= rng.between(1, 10); break;
      default: e.value = zeros && rng.chance(50) ? 0.0 : e.value; break;
    }
  }
  return q;
}

TEST(Lanes, EachLaneSolvedIsTheFixedSizeSolveOfItsProblemBitForBit) {
  // Random scenes of 2 to 8 bodies, 4 variations of M's values a group of
  // lanes, in both compiled copies.  A lane solved is the fixed-size path's
  // solve of its problem alone (small_solver_for()), status Success, in
  // every field; the first lane asked is solved exactly when that solve
  // succeeds; a lane given the first one's values is solved with it; and
  // lanes are solved through pivots and left when they branch otherwise.
  using numeric::detail::lane_width;
  std::cout << "[          ] lanes on this processor: " << (numeric::detail::lanes_use_avx2() ? "AVX2" : "baseline") << "\n";
  const numeric::Settings<double> settings = numeric::Settings<double>::defaults();
  for (const auto code : {numeric::detail::LaneCode::Best, numeric::detail::LaneCode::Baseline}) {
    int solved_lanes = 0, solved_pivoting = 0, left = 0, failing = 0, idle = 0, twins = 0;
    for (std::uint64_t seed = 1; seed <= 1500; ++seed) {
      const RandomScene r = random_scene(seed, {2, numeric::detail::small_max_bodies});
      SCOPED_TRACE(r.describe());
      Rng rng(seed);
      auto p = Problem<double>::from(ExactScene::from(r.scene()));
      ASSERT_TRUE(numeric::scaling_of(p).identity()) << "the generator's data lie in the safe window";
      // The generator's bodies all close their contacts, so nearly every
      // scene pivots: half the scenes get velocities that part the bodies
      // (u decreasing from top to bottom) and M smaller by up to 2^12
      // (which then reverses fewer of them), many of whose lanes need no pivot.
      const int free_bodies = p.fixed_bottom ? p.n - 1 : p.n;
      if (seed % 2 == 1) {
        const int exponent = rng.between(-4, 4);
        for (int i = 0; i < free_bodies; ++i) p.u[static_cast<std::size_t>(i)] = std::ldexp(static_cast<double>(free_bodies - i), exponent);
        const int smaller = rng.between(0, 12);
        for (auto& e : p.entries) e.value = std::ldexp(e.value, -smaller);
      }
      const int band = p.check("test");
      const auto lanes = numeric::detail::lanes_solver_for(p.n, code);
      const auto small = numeric::detail::small_solver_for<double>(p.n);
      ASSERT_NE(lanes, nullptr);
      const unsigned todo = seed % 3 == 0 ? static_cast<unsigned>(rng.between(1, 15)) : 15u;  // some lanes idle
      const int first = __builtin_ctz(todo), last = 31 - __builtin_clz(todo);
      const bool twin = seed % 4 == 0 && last != first;  // the last lane asked gets the first one's values
      std::vector<Problem<double>> problems;
      std::vector<double> values(p.entries.size() * lane_width);
      for (int q = 0; q < lane_width; ++q) {
        problems.push_back(q == 0 ? p : twin && q == last ? problems[static_cast<std::size_t>(first)] : varied(p, rng, seed % 5 == 0));
        for (std::size_t e = 0; e < p.entries.size(); ++e) values[e * lane_width + static_cast<std::size_t>(q)] = problems.back().entries[e].value;
      }
      Solution<double> out[lane_width], alone;
      const unsigned solved = lanes(p, band, values.data(), todo, settings, out);
      for (int q = 0; q < lane_width; ++q) {
        SCOPED_TRACE("lane " + std::to_string(q));
        const Problem<double>& pq = problems[static_cast<std::size_t>(q)];
        const bool is_solved = ((solved >> q) & 1u) != 0;
        if (!((todo >> q) & 1u)) {
          EXPECT_FALSE(is_solved);
          ++idle;
          continue;
        }
        const bool succeeds = small(pq, band, settings, alone) && alone.status == numeric::Status::Success;
        if (q == first) {
          EXPECT_EQ(is_solved, succeeds);
        }
        if (twin && q == last) {
          EXPECT_EQ(is_solved, ((solved >> first) & 1u) != 0);
          ++twins;
        }
        if (is_solved) {
          ASSERT_TRUE(succeeds);
          expect_identical(out[q], alone);
          ++solved_lanes;
          solved_pivoting += alone.pivots > 0;
        } else {
          left += succeeds;
          failing += !succeeds;
        }
      }
    }
    // Every outcome met: lanes solved (through pivots too), left for
    // branching otherwise than the first lane, failing alone, idle.
    std::cout << "[          ] lanes solved " << solved_lanes << " (" << solved_pivoting << " through pivots), left for other branches " << left
              << ", failing " << failing << ", idle " << idle << ", twins " << twins << "\n";
    EXPECT_GT(solved_lanes, 2000);
    EXPECT_GT(solved_pivoting, 1000);
    EXPECT_GT(left, 500);
    EXPECT_GT(idle, 100);
    EXPECT_GT(twins, 200);
  }
  EXPECT_EQ(numeric::detail::lanes_solver_for(1), nullptr);
  EXPECT_EQ(numeric::detail::lanes_solver_for(numeric::detail::small_max_bodies + 1, numeric::detail::LaneCode::Baseline), nullptr);
}

}  // namespace batch_test
}  // namespace superball::testing
