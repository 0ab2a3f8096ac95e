// Hard cases (issue 6, first part): mass ratios from 1e1 to 1e12 between
// neighbours.  In every precision the solver either returns the exact
// solution's case with velocities within the forward error bound of
// support.hpp (8 n κ(A) u), or reports that it cannot (a status other than
// Success).  A wrong case returned with status Success is a failure.
//
// The solver states no error bound on velocities yet (issue 6 asks for one
// per precision); its Success means that its residual check (1e6 u) passed.
// The largest error seen with Success is printed, in units of u.
#include <gtest/gtest.h>

#include <iostream>
#include <sstream>
#include <string>

#include "support.hpp"

namespace superball::testing {
namespace {

template <class S>
class HardCases : public ::testing::Test {};
TYPED_TEST_SUITE(HardCases, Scalars, ScalarNames);

/// A stack of n bodies whose masses alternate between 1 and 10^k, falling at
/// -1 onto a body at rest (finite, of the pattern's mass, or fixed), with or
/// without dissipation between neighbours and from the top to the bottom.
std::string mass_ratio_stack(int n, int k, bool heavy_top, bool fixed, bool dissipation) {
  std::ostringstream os;
  os << "fall_speed = 1\n";
  for (int i = 1; i <= n; ++i) {
    os << "[[body]]\n";
    if (i == n && fixed) {
      os << "mass = \"inf\"\n";
      continue;
    }
    os << "mass = " << (((i % 2 == 1) == heavy_top) ? "1e" + std::to_string(k) : std::string("1")) << "\n";
    if (i == n) os << "velocity = 0\n";
  }
  if (dissipation) {
    os << "[dissipation]\nK = {";
    for (int i = 1; i < n; ++i) os << (i > 1 ? ", " : " ") << '"' << i << "-" << i + 1 << "\" = " << i;
    if (n > 2) os << ", \"1-" << n << "\" = 5";
    os << " }\n";
  }
  return os.str();
}

TYPED_TEST(HardCases, MassRatiosBetweenNeighbours) {
  using S = TypeParam;
  int declined = 0, total = 0;
  cl_RA worst = 0;
  for (int n : {2, 3, 4, 7})
    for (int k = 1; k <= 12; ++k)
      for (bool heavy_top : {false, true})
        for (bool fixed : {false, true})
          for (bool dissipation : {false, true}) {
            const std::string toml = mass_ratio_stack(n, k, heavy_top, fixed, dissipation);
            SCOPED_TRACE(toml);
            const ExactScene scene = ExactScene::from(parse_scene(toml, "mass-ratio"));
            const auto pe = Problem<cl_RA>::from(scene);
            const auto se = numeric::solve(pe);
            ASSERT_EQ(se.status, numeric::Status::Success);
            const auto p = Problem<S>::from(scene, digits_of<S>());
            const auto s = numeric::solve(p);
            ++total;
            if (s.status != numeric::Status::Success) {
              ++declined;
              continue;
            }
            const Tolerances tol = tolerances(p);
            check_physics(p, s, tol, "mass ratio");
            const cl_RA err = relative_velocity_error(exact_vector(s.velocities_after), se.velocities_after, pe.u);
            EXPECT_TRUE(err <= tol.forward) << "status Success but the velocities are off by "
                                            << approx(err / unit_roundoff<S>()) << " u";
            if (!ScalarTraits<S>::exact) worst = max_q(worst, err / unit_roundoff<S>());
            if (complementarity_margin(pe, se) > tol.forward) {
              EXPECT_EQ(s.closed, se.closed) << "status Success with a wrong case";
            }
          }
  std::cout << "[ info ] " << ScalarNames::GetName<S>(0) << ": " << declined << " of " << total
            << " mass-ratio scenes declined (status not Success); largest velocity error with Success " << approx(worst)
            << " u\n";
}

TYPED_TEST(HardCases, BodiesMovingTogetherAreNotAnAlarm) {
  // Two bodies moving together (gap 0 before and after, every reaction 0:
  // the contact is on the edge).  Seed 47546 of the property test: long
  // double closed the contact with a reaction of 2.7e-16 of the wrong sign,
  // and the complementarity check, measuring reactions against the largest
  // reaction (that same 2.7e-16), reported NumericalIssue for an answer
  // right to the last bit.  Reactions are measured against the equations of
  // motion's terms (momenta of 3e4 N s here) since.
  using S = TypeParam;
  const std::string toml =
      "[[body]]\nmass = 510e1\nvelocity = \"-21/4\"\n[[body]]\nmass = 906e0\nvelocity = \"-21/4\"\n"
      "[dissipation]\nK = { \"1-2\" = \"24/5\" }\n";
  const auto p = problem_of<S>(parse_scene(toml, "moving-together"));
  const auto s = numeric::solve(p);
  EXPECT_EQ(s.status, numeric::Status::Success)
      << "residuals: motion " << s.residual_motion << ", complementarity " << s.residual_complementarity;
  const Tolerances tol = tolerances(p);
  const std::vector<cl_RA> unchanged(2, cl_RA(-21) / 4);
  EXPECT_TRUE(relative_velocity_error(exact_vector(s.velocities_after), unchanged, unchanged) <= tol.forward);
  check_physics(p, s, tol, "moving together");
}

}  // namespace
}  // namespace superball::testing

namespace superball::testing {
namespace {

TEST(HardCases, AccurateAnswerIsNotDeclined) {
  // 1e7 kg falling with 1 kg onto 1e7 kg at rest, no dissipation: a
  // perfectly plastic impact, all three leave at -10000001/20000001 m/s.
  // With CLN floats of 30 and 100 digits the velocities come out right to
  // (far) better than 1e-29, yet the solve reports NumericalIssue (the CLI
  // exits 3): its check compares the gap of each closed contact, whose
  // rounding error grows with κ(A) = 1e7, with 1e6 u whatever the precision,
  // so raising the precision never clears it.  The status must be Success
  // when the answer is right to the precision asked for.
  const std::string toml =
      "fall_speed = 1\n[[body]]\nmass = 1e7\n[[body]]\nmass = 1\n[[body]]\nmass = 1e7\nvelocity = 0\n";
  const ExactScene scene = ExactScene::from(parse_scene(toml, "plastic-stack"));
  const cl_RA exact = cl_RA(-10000001) / 20000001;
  EXPECT_EQ(numeric::solve(Problem<cl_RA>::from(scene)).velocities_after, std::vector<cl_RA>(3, exact));
  for (int digits : {30, 100}) {
    SCOPED_TRACE("digits:" + std::to_string(digits));
    const auto s = numeric::solve(Problem<cl_R>::from(scene, digits));
    for (const auto& w : s.velocities_after)
      EXPECT_TRUE(abs_q(exact_value(w) - exact) <= cln::expt(cl_RA(10), -digits + 1)) << approx(exact_value(w));
    EXPECT_EQ(s.status, numeric::Status::Success)
        << "declined an answer right to " << digits << " digits: residuals motion " << s.residual_motion
        << ", complementarity " << s.residual_complementarity;
  }
}

}  // namespace
}  // namespace superball::testing
