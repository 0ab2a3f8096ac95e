// compute_case(): the collision solved with an evolution case imposed (the
// paper's way, §4.1).  For the actual case it is compute(); for every other
// case some sign condition fails (a gap < 0 on an open contact or a reaction
// > 0 on a closed one) — the uniqueness of the solution.  lcp(): the LCP
// the solver builds is the one the exact solution solves.
#include <gtest/gtest.h>

#include <cstdint>
#include <stdexcept>
#include <string>

#include "superball/numeric/chain.hpp"
#include "support.hpp"

namespace superball::testing {
namespace {

template <class S>
class ComputeCase : public ::testing::Test {};
TYPED_TEST_SUITE(ComputeCase, Scalars, ScalarNames);

constexpr std::uint64_t kFirstSeed = 5000, kSeeds = 60;

TYPED_TEST(ComputeCase, TheActualCaseGivesTheSolution) {
  using S = TypeParam;
  numeric::CollisionSolver<S> solver(numeric::Settings<S>::defaults(digits_of<S>()));
  for (std::uint64_t seed = kFirstSeed; seed < kFirstSeed + kSeeds; ++seed) {
    const RandomScene r = random_scene(seed, {2, 8});
    SCOPED_TRACE(r.describe());
    const ExactScene scene = ExactScene::from(r.scene());
    const auto pe = Problem<cl_RA>::from(scene);
    const auto se = numeric::solve(pe);
    const auto p = Problem<S>::from(scene, digits_of<S>());
    Solution<S> free, imposed;
    solver.compute(p, free);
    solver.compute_case(p, se.closed, imposed);
    EXPECT_EQ(imposed.status, numeric::Status::Success);
    EXPECT_EQ(imposed.closed, se.closed);
    const Tolerances tol = tolerances(p);
    const cl_RA err = relative_velocity_error(exact_vector(imposed.velocities_after), exact_vector(free.velocities_after),
                                              exact_vector(p.u));
    EXPECT_TRUE(err <= tol.forward) << "compute_case differs from compute by " << approx(err);
    check_physics(p, imposed, tol, "compute_case");
    if (ScalarTraits<S>::exact) {
      EXPECT_EQ(imposed.velocities_after, free.velocities_after);
      EXPECT_EQ(imposed.reactions, free.reactions);
    }
  }
}

TEST(ComputeCase, EveryOtherCaseViolatesASignCondition) {
  numeric::CollisionSolver<cl_RA> solver;
  int cases_checked = 0;
  for (std::uint64_t seed = kFirstSeed; seed < kFirstSeed + kSeeds; ++seed) {
    const RandomScene r = random_scene(seed, {2, 7});
    SCOPED_TRACE(r.describe());
    const auto p = problem_of<cl_RA>(r.scene());
    const auto actual = numeric::solve(p);
    for (std::uint64_t mask = 0; mask < (std::uint64_t{1} << (p.n - 1)); ++mask) {
      const ContactSet closed = ContactSet::from_mask(mask, p.n);
      Solution<cl_RA> s;
      solver.compute_case(p, closed, s);
      ASSERT_EQ(s.status, numeric::Status::Success) << closed.to_string();
      EXPECT_EQ(s.closed, closed);
      // The imposed case holds by construction: closed gaps 0, open reactions 0.
      bool admissible = true;
      for (int c = 0; c + 1 < p.n; ++c) {
        const auto k = static_cast<std::size_t>(c);
        if (closed.closed(c)) {
          EXPECT_EQ(s.gaps[k], 0);
          admissible = admissible && s.reactions[k] <= 0;
        } else {
          EXPECT_EQ(s.reactions[k], 0);
          admissible = admissible && s.gaps[k] >= 0;
        }
      }
      ++cases_checked;
      // Exactly one solution: an admissible case gives the solution (several
      // cases are admissible only at a switch point, where they coincide).
      if (admissible) {
        EXPECT_EQ(s.velocities_after, actual.velocities_after) << "a second admissible case " << closed.to_string();
        EXPECT_EQ(s.reactions, actual.reactions) << closed.to_string();
      }
      if (closed == actual.closed) {
        EXPECT_TRUE(admissible) << "the actual case fails its own conditions";
      }
    }
  }
  EXPECT_GT(cases_checked, 500);
}

TEST(ComputeCase, ThePapersCaseOneForTheAlpha2Scene) {
  // Imposing case 1 on eq. (16)'s scene (whose actual case is 3.3) gives a
  // solution that breaks a sign condition: a negative gap or a pulling reaction.
  const auto p = problem_of<cl_RA>(load_scene(std::string(SUPERBALL_CASES_DIR) + "/scenes/paper-4.4-alpha2.toml"));
  numeric::CollisionSolver<cl_RA> solver;
  Solution<cl_RA> s;
  solver.compute_case(p, ContactSet::parse("2-3,3-4", 4), s);
  EXPECT_TRUE(s.reactions[1] > 0 || s.reactions[2] > 0 || s.gaps[0] < 0);
}

TEST(ComputeCase, RejectsACaseForAnotherNumberOfBodies) {
  const auto p = problem_of<double>(load_scene(std::string(SUPERBALL_CASES_DIR) + "/scenes/paper-4.4-alpha2.toml"));
  numeric::CollisionSolver<double> solver;
  Solution<double> s;
  try {
    solver.compute_case(p, ContactSet(5), s);
    ADD_FAILURE() << "accepted a 5-body case for 4 bodies";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("CollisionSolver::compute_case(): ", 0), 0u) << e.what();
  }
}

TEST(Lcp, TheExactSolutionSolvesTheLcpTheSolverReturns) {
  // lcp() gives w = q + Nλ and W = W0 + Gλ; in exact rationals the solution
  // satisfies both exactly, with w the gaps and λ = −R, and N is symmetric
  // with positive leading principal minors (positive definite).
  numeric::CollisionSolver<cl_RA> solver;
  int pivoted = 0;
  for (std::uint64_t seed = kFirstSeed; seed < kFirstSeed + kSeeds; ++seed) {
    const RandomScene r = random_scene(seed, {2, 8});
    SCOPED_TRACE(r.describe());
    const auto p = problem_of<cl_RA>(r.scene());
    const auto s = solver.compute(p);
    const auto lcp = solver.lcp(p);
    const int nc = p.n - 1, nf = p.fixed_bottom ? p.n - 1 : p.n;
    ASSERT_EQ(lcp.N.rows(), nc);
    ASSERT_EQ(lcp.q.size(), nc);
    ASSERT_EQ(lcp.G.rows(), nf);
    pivoted += s.pivots > 0;
    for (int c = 0; c < nc; ++c) {
      cl_RA w = lcp.q(c);
      for (int d = 0; d < nc; ++d) {
        w = w - lcp.N(c, d) * s.reactions[static_cast<std::size_t>(d)];
        EXPECT_TRUE(lcp.N(c, d) == lcp.N(d, c));
      }
      EXPECT_TRUE(w == s.gaps[static_cast<std::size_t>(c)]) << "contact " << c;
    }
    for (int i = 0; i < nf; ++i) {
      cl_RA W = lcp.W0(i);
      for (int d = 0; d < nc; ++d) W = W - lcp.G(i, d) * s.reactions[static_cast<std::size_t>(d)];
      EXPECT_TRUE(W == s.velocities_after[static_cast<std::size_t>(i)]) << "body " << i;
    }
    Eigen::Matrix<cl_RA, Eigen::Dynamic, Eigen::Dynamic> L = lcp.N;  // Gaussian elimination: positive pivots
    for (int k = 0; k < nc; ++k) {
      ASSERT_TRUE(L(k, k) > 0) << "pivot " << k;
      for (int i = k + 1; i < nc; ++i)
        for (int j = k + 1; j < nc; ++j) L(i, j) = L(i, j) - L(i, k) * L(k, j) / L(k, k);
    }
  }
  EXPECT_GT(pivoted, 10);  // cases with closed contacts, not only q >= 0
}

TEST(Compute, RejectsInconsistentProblems) {
  numeric::CollisionSolver<double> solver;
  Solution<double> s;
  Problem<double> p;
  p.n = 1;
  p.mass = {1};
  p.u = {0};
  EXPECT_THROW(solver.compute(p, s), std::invalid_argument);
  p.n = 2;
  EXPECT_THROW(solver.compute(p, s), std::invalid_argument);  // one mass for two bodies
  p.mass = {1, 1};
  p.u = {-1, 0};
  p.entries.push_back({0, 2, 0, 2, 1.0});  // pair 1-3 of 2 bodies
  EXPECT_THROW(solver.compute(p, s), std::invalid_argument);
  // Every way an entry can leave the bodies or its order, for both solvers.
  numeric::ChainSolver<double> chain;
  const numeric::Entry<double> bad[] = {
      {1, 0, 1, 0, 1.0},  {0, 0, 0, 1, 1.0}, {-1, 1, 0, 1, 1.0}, {0, -1, 0, 1, 1.0},
      {0, 1, -1, 1, 1.0}, {0, 1, 0, 2, 1.0}, {0, 1, 1, 0, 1.0},  {0, 1, 1, 1, 1.0},
  };
  for (const auto& e : bad) {
    p.entries = {{0, 1, 0, 1, 1.0}, e};
    SCOPED_TRACE(std::to_string(e.i) + "-" + std::to_string(e.j) + ", " + std::to_string(e.k) + "-" + std::to_string(e.l));
    EXPECT_THROW(solver.compute(p, s), std::invalid_argument);
    EXPECT_THROW(chain.compute(p, s), std::invalid_argument);
  }
  p.entries.clear();
  EXPECT_NO_THROW(solver.compute(p, s));
  EXPECT_EQ(s.status, numeric::Status::Success);
  // Two equal masses, plastic: both move at the mean velocity.
  EXPECT_DOUBLE_EQ(s.velocities_after[0], -0.5);
  EXPECT_DOUBLE_EQ(s.velocities_after[1], -0.5);
}

}  // namespace
}  // namespace superball::testing
