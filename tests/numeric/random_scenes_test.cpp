// Properties of the collision solver on seeded random scenes, in every
// arithmetic: the physics of the paper (momentum, energy balance, second
// law, impenetrability and complementarity) and agreement with the exact
// solution (same evolution case, velocities within the stated error; in
// double and long double, within the certificate's bound wherever it
// certifies the case).
//
// The number of scenes is a setting: SUPERBALL_PROPERTY_SCENES (default
// kDefaultScenes, what the suite runs), from the seed SUPERBALL_PROPERTY_FIRST_SEED
// (default 1), so that a long run can be split into seed ranges and resumed
// (scripts/property-run.sh); docs/ACCURACY.md records a run with 10^5 or more, e.g.
//   SUPERBALL_PROPERTY_SCENES=100000 SUPERBALL_PROPERTY_FIRST_SEED=100001
//     build/tests/numeric/superball_numeric_tests --gtest_filter='RandomScenes/double.Physics*'
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <stdexcept>
#include <string>

#include "support.hpp"

namespace superball::testing {
namespace {

/// Seeds 1 .. property_scenes(); a failure names the seed and prints the scene.
constexpr std::uint64_t kDefaultScenes = 250;
/// The coverage of the generator (both obstacles, closed contacts, ...) is
/// checked on runs of at least this many scenes.
constexpr std::uint64_t kMinScenesForCoverage = 100;

/// How many seeds the property test runs: SUPERBALL_PROPERTY_SCENES, else kDefaultScenes.
std::uint64_t property_scenes() { return positive_setting("SUPERBALL_PROPERTY_SCENES", kDefaultScenes); }
/// The first of them: SUPERBALL_PROPERTY_FIRST_SEED, else 1.
std::uint64_t first_seed() { return positive_setting("SUPERBALL_PROPERTY_FIRST_SEED", 1); }

/// The evolution case is compared only when the exact solution is strictly
/// complementary by more than this multiple of the forward error bound (a
/// contact whose gap and reaction are both within rounding of zero sits on a
/// switch point, where either case is as good as the other).  At most
/// kMaxUndecidablePercent of the scenes may be that close to a switch point:
/// the generator is not meant to produce them.
constexpr double kDecidableMarginFactor = 1;
constexpr int kMaxUndecidablePercent = 10;

template <class S>
class RandomScenes : public ::testing::Test {};
TYPED_TEST_SUITE(RandomScenes, Scalars, ScalarNames);

TYPED_TEST(RandomScenes, PhysicsHoldsAndAgreesWithTheExactSolution) {
  using S = TypeParam;
  const bool exact = ScalarTraits<S>::exact;
  const std::uint64_t scenes = property_scenes(), first = first_seed();
  int undecidable = 0, finite = 0, fixed = 0, moving = 0, closed_contacts = 0, not_success = 0, certified = 0, banded = 0;
  cl_RA worst = 0;  // largest error / (n κ u)
  double worst_certified = 0;  // largest error / certified bound
  std::uint64_t worst_seed = 0;
  for (std::uint64_t seed = first; seed < first + scenes; ++seed) {
    const RandomScene r = random_scene(seed);
    SCOPED_TRACE(r.describe());
    ExactScene scene;
    ASSERT_NO_THROW(scene = ExactScene::from(r.scene())) << "the generator made an inadmissible scene";
    const auto pe = Problem<cl_RA>::from(scene);
    // The reference is the dense exact solve whichever formulation solve()
    // picks (the banded one for banded M, solves_as_chain()).
    const auto se = numeric::CollisionSolver<cl_RA>().compute(pe);
    ASSERT_EQ(se.status, numeric::Status::Success) << "exact solve";
    const auto ps = Problem<S>::from(scene, digits_of<S>());
    const auto ss = numeric::solve(ps);
    banded += numeric::solves_as_chain(ps);
    const Tolerances tol = tolerances(ps);
    const double n_kappa = ps.n * static_cast<double>(condition_number(ps));
    SCOPED_TRACE("n kappa(A) = " + std::to_string(n_kappa) + ", status " + numeric::to_string(ss.status));
    if (exact || n_kappa <= kMustSucceedNKappa) {
      EXPECT_EQ(ss.status, numeric::Status::Success)
          << "residuals: motion " << ss.residual_motion << ", complementarity " << ss.residual_complementarity;
    }
    not_success += ss.status != numeric::Status::Success;
    check_physics(ps, ss, tol, ScalarNames::GetName<S>(0));
    (ps.fixed_bottom ? fixed : finite) += 1;
    moving += r.moving_obstacle;
    for (int c = 0; c + 1 < pe.n; ++c) closed_contacts += se.closed.closed(c);
    if (exact) {
      // The exact solve is the reference: nothing to compare, but the energy
      // balance of the solver's own fields must be an identity (when no
      // moving obstacle does work on the bodies).
      if (!r.moving_obstacle) {
        EXPECT_EQ(ss.kinetic_energy_before - ss.kinetic_energy_after, ss.dissipation);
      }
      // A is positive definite, so the velocities after are unique: both
      // formulations must give the same fractions.
      EXPECT_EQ(exact_vector(ss.velocities_after), se.velocities_after);
      EXPECT_EQ(ss.closed, se.closed);
      continue;
    }
    const cl_RA err = relative_velocity_error(exact_vector(ss.velocities_after), se.velocities_after, pe.u);
    EXPECT_TRUE(err <= tol.forward) << "relative velocity error " << approx(err) << " > bound " << approx(tol.forward);
    const cl_RA ratio = err / (unit_roundoff<S>() * rational_of(n_kappa));
    if (worst < ratio) worst = ratio, worst_seed = seed;
    // The case wherever it is decidable; where the certificate certifies it,
    // the exact case within the certified bound.
    const CaseVerdict v = expect_case_and_certificate(ps, ss, pe, se, tol.forward * rational_of(kDecidableMarginFactor));
    undecidable += !v.decidable;
    certified += v.certified;
    worst_certified = std::max(worst_certified, v.error_over_certified_bound);
  }
  // The generator covers both kinds of obstacle and both kinds of contact.
  const double count = static_cast<double>(scenes);
  if (scenes >= kMinScenesForCoverage) {
    EXPECT_GT(finite, count / 4);
    EXPECT_GT(fixed, count / 4);
    EXPECT_GT(moving, count / 50);
    EXPECT_GT(closed_contacts, count);
    EXPECT_GT(banded, count / 20) << "solve() must meet banded scenes too";
  }
  EXPECT_LE(undecidable * 100.0, kMaxUndecidablePercent * count);
  EXPECT_LE(not_success * 100.0, 10 * count) << "too many scenes the solver declined";
  if (!exact) {
    std::cout << "[ info ] " << ScalarNames::GetName<S>(0) << ", " << scenes << " scenes (seeds " << first << " .. "
              << first + scenes - 1 << "): largest velocity error "
              << approx(worst) << " n kappa(A) u (seed " << worst_seed << "); " << undecidable
              << " scenes within rounding of a switch point; " << not_success << " not solved with status Success; " << banded
              << " solved as banded chains";
    if (kHasCertificate<S>)
      std::cout << "; case certified on " << certified << ", largest error / certified bound " << worst_certified;
    std::cout << "\n";
  }
}

TYPED_TEST(RandomScenes, RepeatedSolvesReuseTheSolverAndGiveTheSameResult) {
  // One solver, many problems of different sizes, one Solution reused: the
  // result must not depend on what the solver or the output held before.
  using S = TypeParam;
  numeric::CollisionSolver<S> solver(numeric::Settings<S>::defaults(digits_of<S>()));
  Solution<S> reused;
  for (std::uint64_t seed = 1000; seed < 1040; ++seed) {
    const RandomScene r = random_scene(seed);
    SCOPED_TRACE(r.describe());
    const auto p = problem_of<S>(r.scene());
    solver.compute(p, reused);
    const auto fresh = numeric::solve(p);
    EXPECT_EQ(reused.status, fresh.status);
    EXPECT_EQ(reused.closed, fresh.closed);
    EXPECT_EQ(exact_vector(reused.velocities_after), exact_vector(fresh.velocities_after));
    EXPECT_EQ(exact_vector(reused.reactions), exact_vector(fresh.reactions));
  }
}

TYPED_TEST(RandomScenes, FallingStacksOfEverySize) {
  // The paper's setting for n = 2 .. 12: all bodies but the bottom fall at
  // -a onto a body at rest, finite (5e6 kg) or fixed; every property of
  // check_physics holds.
  using S = TypeParam;
  for (int n = 2; n <= 12; ++n)
    for (bool fixed_bottom : {false, true}) {
      std::ostringstream os;
      os << "fall_speed = 2\n";
      for (int i = 1; i <= n; ++i) {
        os << "[[body]]\n";
        if (i == n && fixed_bottom) {
          os << "mass = \"inf\"\n";
          continue;
        }
        os << "mass = " << (i == n ? "5e6" : std::to_string(i * i)) << "\n";
        if (i == n) os << "velocity = 0\n";
      }
      os << "[dissipation]\nK = {";
      for (int i = 1; i < n; ++i) os << (i > 1 ? ", " : " ") << '"' << i << "-" << i + 1 << "\" = " << 2 * i + 1;
      if (n > 2) os << ", \"1-" << n << "\" = 50";
      os << " }\n";
      const std::string toml = os.str();
      SCOPED_TRACE(toml);
      const auto p = problem_of<S>(parse_scene(toml, "stack"));
      const auto s = numeric::solve(p);
      EXPECT_EQ(s.status, numeric::Status::Success);
      check_physics(p, s, tolerances(p), "stack");
    }
}

}  // namespace
}  // namespace superball::testing
