// Extreme magnitudes: scenes whose masses, M and velocities lie far from 1
// (1e±20 to 1e±300), where products of the solve overflow or underflow
// double.  Every precision must give the exact answer within its stated
// bound (docs/ACCURACY.md: 8·n·κ(A)·u, and the certified bound where the
// certificate says the case is certain) or say that it did not (a status
// other than Success) — never a wrong or non-finite answer with Success.
//
// The random family here is a seed stream of its own (random_extreme_scene(),
// support.hpp), apart from the property family of random_scenes_test.cpp; its
// size is SUPERBALL_EXTREME_SCENES (default kDefaultExtremeScenes) from the
// seed SUPERBALL_EXTREME_FIRST_SEED (default 1), e.g.
//   SUPERBALL_EXTREME_SCENES=100000 build/tests/numeric/superball_numeric_tests --gtest_filter='ExtremeScenes/*'
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <stdexcept>
#include <string>

#include "support.hpp"

namespace superball::testing {
namespace {

constexpr std::uint64_t kDefaultExtremeScenes = 200;


template <class S>
class ExtremeScenes : public ::testing::Test {};
TYPED_TEST_SUITE(ExtremeScenes, Scalars, ScalarNames);

TYPED_TEST(ExtremeScenes, RightWithinTheBoundOrNotSuccess) {
  using S = TypeParam;
  const bool exact = ScalarTraits<S>::exact;
  const std::uint64_t scenes = positive_setting("SUPERBALL_EXTREME_SCENES", kDefaultExtremeScenes),
                      first = positive_setting("SUPERBALL_EXTREME_FIRST_SEED", 1);
  int declined = 0, certified = 0, scaled = 0, undecidable = 0;
  for (std::uint64_t seed = first; seed < first + scenes; ++seed) {
    const ExtremeScene x = random_extreme_scene(seed);
    SCOPED_TRACE(x.describe());
    const ExactScene base = ExactScene::from(x.base.scene());
    const ExactScene scene = x.exact(base);
    // The reference: the exact solve of the scaled scene, which must be the
    // base scene's scaled (the collision is invariant under m, M → λ·m, λ·M
    // and U⁻ → μ·U⁻; velocities after scale by μ, reactions by λμ).
    const auto pb = Problem<cl_RA>::from(base);
    const auto sb = numeric::CollisionSolver<cl_RA>().compute(pb);
    const auto pe = Problem<cl_RA>::from(scene);
    const auto se = numeric::CollisionSolver<cl_RA>().compute(pe);
    ASSERT_EQ(se.status, numeric::Status::Success) << "exact solve";
    const cl_RA mu = base.homogeneous() && base.a_squared ? cl_RA(1) : cln::expt(cl_RA(10), x.velocity_exponent);
    const cl_RA lambda_mu = cln::expt(cl_RA(10), x.mass_exponent) * mu;
    for (int i = 0; i < pe.n; ++i) {
      ASSERT_EQ(se.velocities_after[static_cast<std::size_t>(i)], sb.velocities_after[static_cast<std::size_t>(i)] * mu);
    }
    for (int c = 0; c + 1 < pe.n; ++c) {
      ASSERT_EQ(se.reactions[static_cast<std::size_t>(c)], sb.reactions[static_cast<std::size_t>(c)] * lambda_mu);
    }
    ASSERT_EQ(se.closed, sb.closed);

    const auto ps = Problem<S>::from(scene, digits_of<S>());
    const auto ss = numeric::solve(ps);
    if (exact) {
      EXPECT_EQ(ss.status, numeric::Status::Success);
      EXPECT_EQ(exact_vector(ss.velocities_after), se.velocities_after);
      continue;
    }
    scaled += !numeric::scaling_of(ps).identity();
    if (ss.status != numeric::Status::Success) {
      ++declined;
      continue;
    }
    // Success: a finite answer of data S holds, within the stated bound.
    ASSERT_TRUE(ps.in_range);
    ASSERT_TRUE(finite_answer(ss)) << "status Success with a value that is not finite";
    // κ(A) does not change under the scaling: that of the base scene.
    const cl_RA forward = unit_roundoff<S>() * rational_of(kForwardErrorFactor * pb.n * static_cast<double>(condition_number(pb)));
    const std::vector<cl_RA> W = exact_vector(ss.velocities_after);
    const cl_RA err = relative_velocity_error(W, se.velocities_after, pe.u);
    EXPECT_TRUE(err <= forward) << "relative velocity error " << approx(err) << " > bound " << approx(forward);
    const CaseVerdict v = expect_case_and_certificate(ps, ss, pe, se, forward);
    undecidable += !v.decidable;
    certified += v.certified;
  }
  if (exact) return;
  // long double and CLN floats hold every scene of the family (exponents to
  // ±300, spreads inside a scene as in the property family): they decline no
  // more often than there; double declines where an answer (an energy, a
  // velocity) is beyond its range, yet solves the scenes that need scaling.
  const double count = static_cast<double>(scenes);
  if (!std::is_same<S, double>::value) {
    EXPECT_LE(declined * 100.0, 10 * count);
  }
  if (std::is_same<S, double>::value) {
    EXPECT_GT(scaled, 0) << "no scene needed scaling";
  }
  EXPECT_LE(undecidable * 100.0, 10 * count);
  std::cout << "[ info ] " << ScalarNames::GetName<S>(0) << ", " << scenes << " extreme scenes (seeds " << first << " .. "
            << first + scenes - 1 << "): " << scaled << " scaled, " << declined << " not solved with status Success";
  if (kHasCertificate<S>) std::cout << ", case certified on " << certified;
  std::cout << "\n";
}

TYPED_TEST(ExtremeScenes, LightMassesUnderStiffMKeepTheirMomentumOrDecline) {
  // Three bodies of mass m under K of order 1 on every pair: as m/K → 0 each
  // relative velocity reverses (the dissipation vanishes) and momentum fixes
  // the common velocity, U⁺ = (−5/6, −5/6, −10/3)·a, exactly, for any m.
  // The rows of the equations of motion are dominated by the percussions of
  // M, so at m = 1e-200 they held to rounding in every float precision while
  // the common velocity was lost (U⁺ = 0, 0, −a with status success); the
  // momentum balance of each free group of bodies must see it.  At m = 1e-3
  // the float precisions must still solve it.
  using S = TypeParam;
  for (const char* mass : {"1e-200", "1e-3"}) {
    const std::string toml = std::string("fall_speed = 2.5\n") + "[[body]]\nmass = \"" + mass + "\"\n[[body]]\nmass = \"" + mass +
                             "\"\n[[body]]\nmass = \"" + mass + "\"\nvelocity = 0\n" +
                             "[dissipation]\nK = { \"1-2\" = \"1/10\", \"2-3\" = \"1/10\", \"1-3\" = 13 }\n";
    SCOPED_TRACE(toml);
    const ExactScene scene = ExactScene::from(parse_scene(toml, "light"));
    const auto pe = Problem<cl_RA>::from(scene);
    const auto se = numeric::CollisionSolver<cl_RA>().compute(pe);
    ASSERT_EQ(se.status, numeric::Status::Success);
    ASSERT_EQ(se.momentum_after, se.momentum_before);
    const auto ps = Problem<S>::from(scene, digits_of<S>());
    const auto ss = numeric::solve(ps);
    const bool light = std::string(mass) == "1e-200";
    if (!light || ScalarTraits<S>::exact) {
      EXPECT_EQ(ss.status, numeric::Status::Success);
    }
    if (ss.status != numeric::Status::Success) continue;
    const cl_RA err = relative_velocity_error(exact_vector(ss.velocities_after), se.velocities_after, pe.u);
    EXPECT_TRUE(err <= cl_RA(1) / 1000) << "status success with a relative velocity error of " << approx(err);
  }
}

TYPED_TEST(ExtremeScenes, ResidualsBelowTheRangeOfDoubleAreSeen) {
  // A body of 1e-308 kg falls at 1 m/s on 100 kg: the heavy body takes
  // U₂⁺ = −2e-310 m/s, whose momentum balances the light one's.  In CLN floats
  // every residual of this scene is about 1e-308, which the conversion to
  // double flushed to zero: digits:30 returned U₂⁺ = 0 (momentum not
  // conserved) with residuals 0 and status success.  The residuals are ratios
  // formed in S, so success now implies the momentum balance.
  using S = TypeParam;
  const ExactScene scene = ExactScene::from(parse_scene(
      "fall_speed = 1\n[[body]]\nmass = 1e-308\n[[body]]\nmass = 100\nvelocity = 0\n[dissipation]\nK = { \"1-2\" = 0.5 }\n", "light on heavy"));
  const auto pe = Problem<cl_RA>::from(scene);
  const auto ps = Problem<S>::from(scene, digits_of<S>());
  const auto ss = numeric::solve(ps);
  if (ScalarTraits<S>::exact) {
    EXPECT_EQ(ss.status, numeric::Status::Success);
  }
  if (ss.status != numeric::Status::Success) return;
  const std::vector<cl_RA> W = exact_vector(ss.velocities_after);
  cl_RA balance = 0, size = 0;
  for (int i = 0; i < pe.n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    balance += pe.mass[k] * (W[k] - pe.u[k]);
    size += pe.mass[k] * (cln::abs(W[k]) + cln::abs(pe.u[k]));
  }
  EXPECT_TRUE(cln::abs(balance) <= size / 1000) << "status success with momentum " << approx(balance) << " gained, of " << approx(size);
}

TEST(ExtremeScenes, ScalingIsTheIdentityOnThePropertyFamily) {
  // Why the property family's doubles are bit for bit what they were before
  // scaling existed: none of its scenes leaves the safe window.
  for (std::uint64_t seed = 1; seed <= 250; ++seed) {
    SCOPED_TRACE(seed);
    const ExactScene scene = ExactScene::from(random_scene(seed).scene());
    const numeric::Scaling d = numeric::scaling_of(Problem<double>::from(scene));
    const numeric::Scaling ld = numeric::scaling_of(Problem<long double>::from(scene));
    EXPECT_TRUE(d.identity() && d.fits && ld.identity() && ld.fits);
  }
}

TEST(ExtremeScenes, ScaledDataGiveTheScaledAnswerBitForBit) {
  // Masses and M times 2^700, velocities times 2^-500: outside the safe
  // window of double, so solve() scales them back by powers of two, and the
  // answer is the unscaled one's times 2^-500 (velocities), 2^200
  // (reactions), 2^-300 (energies), exactly.
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    const RandomScene r = random_scene(seed);
    SCOPED_TRACE(r.describe());
    const auto p = problem_of<double>(r.scene());
    const auto s = numeric::solve(p);
    const numeric::Scaling k{-700, 500, true};
    const auto big = p.scaled(k);
    EXPECT_FALSE(numeric::scaling_of(big).identity());
    const auto t = numeric::solve(big);
    EXPECT_EQ(t.status, s.status);
    EXPECT_EQ(t.closed, s.closed);
    for (std::size_t i = 0; i < s.velocities_after.size(); ++i) EXPECT_EQ(t.velocities_after[i], std::ldexp(s.velocities_after[i], -500));
    for (std::size_t c = 0; c < s.reactions.size(); ++c) EXPECT_EQ(t.reactions[c], std::ldexp(s.reactions[c], 200));
    EXPECT_EQ(t.kinetic_energy_before, std::ldexp(s.kinetic_energy_before, -300));
    EXPECT_EQ(t.dissipation, std::ldexp(s.dissipation, -300));
  }
}

TEST(ExtremeScenes, NonFiniteAnswerIsNeverSuccess) {
  // A NaN velocity makes every residual NaN, which compares as neither large
  // nor small: the check must fail it (it passed it before).
  Problem<double> p;
  p.n = 2;
  p.mass = {1, 1};
  p.entries = {{0, 1, 0, 1, 1.0}};
  p.u = {std::numeric_limits<double>::quiet_NaN(), 0};
  for (const auto& s : {numeric::solve(p), numeric::ChainSolver<double>().compute(p), numeric::CollisionSolver<double>().compute(p)}) {
    EXPECT_NE(s.status, numeric::Status::Success);
    EXPECT_FALSE(numeric::certify(p, s).case_certain);
  }
}

TEST(ExtremeScenes, DataBeyondTheRangeOfDoubleAreNotHeld) {
  // fall_speed = 1e400: double cannot hold the unit (auto certified NaN
  // velocities before); long double can, and auto stops there.
  const ExactScene scene = ExactScene::from(parse_scene(
      "fall_speed = \"1e400\"\n[[body]]\nmass = 1\n[[body]]\nmass = 2\nvelocity = 0\n[dissipation]\nK = { \"1-2\" = 1 }\n", "far.toml"));
  const auto pd = Problem<double>::from(scene);
  EXPECT_FALSE(pd.in_range);
  const auto sd = numeric::solve(pd);
  EXPECT_NE(sd.status, numeric::Status::Success);
  EXPECT_FALSE(numeric::certify(pd, sd).case_certain);
  EXPECT_TRUE(Problem<long double>::from(scene).in_range);
  const numeric::AutoChoice choice = numeric::choose_precision(scene, numeric::default_rtol);
  EXPECT_EQ(choice.precision.name(), "long-double");
}

TEST(ExtremeScenes, RtolMustBeANumberFrom0To1) {
  const ExactScene scene = ExactScene::from(random_scene(1).scene());
  for (double rtol : {std::numeric_limits<double>::quiet_NaN(), -1e-6, 2.0, std::numeric_limits<double>::infinity()})
    EXPECT_THROW(numeric::choose_precision(scene, rtol), std::invalid_argument) << rtol;
  EXPECT_NO_THROW(numeric::choose_precision(scene, 0.0));
}

TEST(ExtremeScenes, DenseSceneOverTheLimitIsRefusedByName) {
  // A scene whose M couples the first and the last pair is not banded: the
  // dense solver's size limit applies, and the message names the file.
  auto scene_of = [](int n) {
    std::ostringstream os;
    os << "fall_speed = 1\n";
    for (int i = 1; i <= n; ++i) os << "[[body]]\nmass = 1\n" << (i == n ? "velocity = 0\n" : "");
    os << "[dissipation]\nK = { \"1-2\" = 1, \"" << n - 1 << "-" << n << "\" = 1 }\n";
    os << "coupling = [ { pairs = [\"1-2\", \"" << n - 1 << "-" << n << "\"], value = \"1/2\" } ]\n";
    return parse_scene(os.str(), "wide.toml");
  };
  EXPECT_NO_THROW(ExactScene::from(scene_of(numeric::dense_solver_max_bodies)));
  try {
    ExactScene::from(scene_of(numeric::dense_solver_max_bodies + 1));
    ADD_FAILURE() << "a dense scene over the limit was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("wide.toml: ", 0), 0u) << e.what();
  }
}

}  // namespace
}  // namespace superball::testing
