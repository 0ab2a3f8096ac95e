// ChainSolver (the banded formulation for chains) against the dense
// CollisionSolver: the same problem has one solution, so in exact
// arithmetic both must return the same case and the same velocities.
#include <gtest/gtest.h>

#include <random>

#include "superball/numeric/chain.hpp"
#include "support/falling_chain.hpp"

namespace superball::testing {
namespace {

using cln::cl_RA;
using numeric::Problem;

/// A random problem whose M couples pairs at most two bodies apart:
/// K on a random subset of (i, i+1) and (i, i+2), couplings between
/// consecutive declared pairs, M diagonally dominant hence positive definite.
Problem<cl_RA> banded(std::mt19937& rng, int n) {
  Problem<cl_RA> p;
  p.n = n;
  p.fixed_bottom = rng() % 2;
  for (int i = 0; i < n; ++i) {
    const bool fixed = p.fixed_bottom && i == n - 1;
    p.mass.push_back(fixed ? cl_RA(0) : cl_RA(1 + static_cast<int>(rng() % 100)) / (1 + static_cast<int>(rng() % 7)));
    p.u.push_back(fixed ? cl_RA(static_cast<int>(rng() % 3) - 1)
                        : cl_RA(-1 - static_cast<int>(rng() % 5)) + (rng() % 3 == 0 ? cl_RA(static_cast<int>(rng() % 5)) : cl_RA(0)));
  }
  std::vector<std::pair<int, int>> pairs;
  for (int i = 0; i < n; ++i)
    for (int d = 1; d <= 2 && i + d < n; ++d)
      if (rng() % 4) pairs.push_back({i, i + d});
  for (const auto& [i, j] : pairs) p.entries.push_back({i, j, i, j, cl_RA(10 + static_cast<int>(rng() % 20))});
  for (std::size_t a = 0; a + 1 < pairs.size(); ++a)
    if (rng() % 2)
      p.entries.push_back({pairs[a].first, pairs[a].second, pairs[a + 1].first, pairs[a + 1].second,
                           cl_RA(static_cast<int>(rng() % 9) - 4)});
  return p;
}

TEST(ChainSolver, EqualsTheDenseSolverExactly) {
  std::mt19937 rng(20261122);
  int closed = 0, open = 0;
  for (int t = 0; t < 150; ++t) {
    const int n = 2 + static_cast<int>(rng() % 24);
    const Problem<cl_RA> p = banded(rng, n);
    SCOPED_TRACE("problem " + std::to_string(t) + ", n = " + std::to_string(n));
    const auto dense = numeric::CollisionSolver<cl_RA>().compute(p);
    const auto chain = numeric::ChainSolver<cl_RA>().compute(p);
    ASSERT_EQ(dense.status, numeric::Status::Success);
    ASSERT_EQ(chain.status, numeric::Status::Success);
    EXPECT_EQ(chain.closed, dense.closed) << chain.closed.to_string() << " vs " << dense.closed.to_string();
    EXPECT_EQ(chain.velocities_after, dense.velocities_after);
    EXPECT_EQ(chain.reactions, dense.reactions);
    for (int c = 0; c + 1 < n; ++c) (dense.closed.closed(c) ? closed : open) += 1;
  }
  // Both kinds of contact occur, so the comparison says something.
  EXPECT_GT(closed, 100);
  EXPECT_GT(open, 100);
}

TEST(ChainSolver, LongChainInDoublePassesTheResidualCheck) {
  // 2000 light bodies falling at 1.9 … 1.0 m/s (the top fastest) onto a fixed
  // obstacle (the chain of bench/bench_chain.cpp): solve() picks the banded solver.
  const int n = 2000;
  const Problem<double> p = test::falling_chain(n);
  const auto s = numeric::solve(p);
  EXPECT_EQ(s.status, numeric::Status::Success) << s.residual_motion << " " << s.residual_complementarity;
  EXPECT_LE(s.pivots, 10) << "active-set iterations";
  // Every contact closes (the top falls fastest) and stays closed: the whole
  // chain stops on the obstacle and all of its kinetic energy is dissipated.
  for (int c = 0; c + 1 < n; ++c) EXPECT_TRUE(s.closed.closed(c)) << "contact " << c + 1 << "-" << c + 2;
  for (int i = 0; i < n; ++i) EXPECT_NEAR(s.velocities_after[static_cast<std::size_t>(i)], 0.0, 1e-12) << "body " << i + 1;
  EXPECT_LE(s.kinetic_energy_after, 1e-12 * s.kinetic_energy_before);
  EXPECT_GE(s.dissipation, -1e-9 * s.kinetic_energy_before);
}

TEST(ChainSolver, SolvePicksTheBandedFormulationExactlyWhenTheBandLeavesRoom) {
  // b = the largest body distance an entry of M couples; banded when 2b + 1 < n.
  auto problem = [](int n, std::vector<numeric::Entry<double>> entries) {
    Problem<double> p;
    p.n = n;
    p.mass.assign(static_cast<std::size_t>(n), 1.0);
    p.u.assign(static_cast<std::size_t>(n), -1.0);
    p.entries = std::move(entries);
    return p;
  };
  const auto nearest = problem(4, {{0, 1, 0, 1, 1.0}, {1, 2, 1, 2, 1.0}, {2, 3, 2, 3, 1.0}});  // b = 1
  EXPECT_EQ(nearest.bandwidth(), 1);
  EXPECT_TRUE(numeric::solves_as_chain(nearest));
  const auto three = problem(3, {{0, 1, 0, 1, 1.0}, {1, 2, 1, 2, 1.0}});  // b = 1, 2b + 1 = n
  EXPECT_FALSE(numeric::solves_as_chain(three));
  // The paper's K₁₄ couples bodies 1 and 4: b = 3, dense; and a coupling of
  // (1-2) with (3-4) spans the same distance through two pairs.
  EXPECT_EQ(problem(4, {{0, 3, 0, 3, 1.0}}).bandwidth(), 3);
  EXPECT_EQ(problem(8, {{0, 1, 2, 3, 1.0}}).bandwidth(), 3);
  EXPECT_FALSE(numeric::solves_as_chain(problem(4, {{0, 3, 0, 3, 1.0}})));
  EXPECT_TRUE(numeric::solves_as_chain(problem(8, {{0, 1, 2, 3, 1.0}})));
  EXPECT_EQ(problem(5, {}).bandwidth(), 0);
}

}  // namespace
}  // namespace superball::testing
