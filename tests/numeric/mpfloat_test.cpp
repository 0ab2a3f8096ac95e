// MpFloat, the MPFR arithmetic of digits:N: its numbers (exact integers,
// precision carried by each value, text), and its answers on random scenes
// against the exact solution within the certified bound, and against the CLN
// floats digits:N used before to N − 2 digits.
#include <gtest/gtest.h>

#include <cln/float.h>

#include <string>
#include <vector>

#include "superball/cases/scene_file.hpp"
#include "superball/numeric/certify.hpp"
#include "superball/numeric/precision.hpp"
#include "support.hpp"

namespace superball::testing {
namespace {

using numeric::MpFloat;

/// Random scenes per N in the comparisons below.
constexpr std::uint64_t kScenes = 40;
/// The N compared.
const std::vector<int> kDigits = {numeric::min_digits, 20, 50, 100, 150};

TEST(MpFloat, IntegersAreExactAndResultsTakeTheLargerPrecision) {
  for (long x : {0L, 1L, -1L, 2L, 1000000L, -123456789012345L, 0x7fffffffffffffffL}) {
    const MpFloat m(x);
    EXPECT_EQ(exact_value(m), cl_RA(cln::cl_I(x))) << x;
    EXPECT_EQ(m.precision(), 64);
  }
  const MpFloat third = ScalarTraits<MpFloat>::from(cl_RA(1) / 3, 50);
  EXPECT_EQ(third.precision(), numeric::digits_precision(50));
  const MpFloat sum = MpFloat(2) * third + MpFloat(0);  // the constants widen, the result keeps 191 bits
  EXPECT_EQ(sum.precision(), 191);
  EXPECT_TRUE(abs_q(exact_value(sum) - cl_RA(2) / 3) <= cln::expt(cl_RA(2), -191)) << approx(exact_value(sum));
  MpFloat acc;  // 0 at 64 bits, then a sum at the precision of its terms
  acc += third;
  acc -= MpFloat(1);
  EXPECT_EQ(acc.precision(), 191);
  EXPECT_TRUE(abs_q(exact_value(acc) - (exact_value(third) - 1)) <= cln::expt(cl_RA(2), -191));  // rounded once
  EXPECT_TRUE(MpFloat(-3) < MpFloat(0) && MpFloat(0) < third && !(MpFloat(0) < MpFloat(0)) && -third < MpFloat(0));
  EXPECT_EQ(exact_value(numeric::abs(-third)), exact_value(third));
  // Copies and moves beyond the significand held in the object (N > 113).
  MpFloat big = ScalarTraits<MpFloat>::from(cl_RA(1) / 7, 1000);
  const MpFloat copy = big;
  MpFloat moved = std::move(big);
  EXPECT_EQ(exact_value(copy), exact_value(moved));
  EXPECT_TRUE(abs_q(exact_value(copy) - cl_RA(1) / 7) <= cln::expt(cl_RA(10), -1000));
}

TEST(MpFloat, PrecisionIsAtLeastNDigitsAndUnitRoundoffIsItsOwn) {
  for (int d = numeric::min_digits; d <= 200; ++d) {
    const long p = numeric::digits_precision(d);
    EXPECT_GE(static_cast<double>(p), d * 3.3219) << d;
    EXPECT_EQ(p % 64, 63) << d;  // below whole words: MPFR's fast paths
    EXPECT_EQ(exact_value(ScalarTraits<MpFloat>::unit_roundoff(d)), cln::expt(cl_RA(2), -p)) << d;
  }
  EXPECT_EQ(numeric::digits_precision(20), 127);
  EXPECT_EQ(numeric::digits_precision(50), 191);
  EXPECT_EQ(numeric::digits_precision(100), 383);
}

TEST(MpFloat, TextReadsBackAndRoundsAsToDecimal) {
  const MpFloat third = ScalarTraits<MpFloat>::from(cl_RA(1) / 3, 20);
  const std::string all = numeric::to_string(third);
  EXPECT_EQ(all.rfind("0.333333333333333333333333333333333333", 0), 0u) << all;
  EXPECT_EQ(numeric::to_string(ScalarTraits<MpFloat>::from(cl_RA(-cln::expt(cl_RA(10), 400)), 20), 6), "-1e+400");
  EXPECT_EQ(numeric::to_string(ScalarTraits<MpFloat>::from(cl_RA(-313209) / 100000, 20), 6), "-3.13209");
  EXPECT_EQ(numeric::to_string(MpFloat(0)), "0");
  EXPECT_EQ(numeric::to_string(MpFloat(20)), "20");
  EXPECT_EQ(numeric::to_string(ScalarTraits<MpFloat>::from(cl_RA(-1741) / 100000000, 20)), "-1.741e-05");
}

/// digits:N on random scenes: the exact answer lies within the certified
/// bound wherever the certificate proves the case, and the CLN floats of the
/// same N (the arithmetic digits:N had before) agree to N − 2 digits.
TEST(MpFloat, RandomScenesAgreeWithExactAndWithClnFloats) {
  int certified = 0, compared = 0;
  for (std::uint64_t seed = 1; seed <= kScenes; ++seed) {
    const RandomScene rs = random_scene(seed);
    const ExactScene scene = ExactScene::from(rs.scene());
    SCOPED_TRACE(rs.origin());
    const auto pe = Problem<cl_RA>::from(scene);
    const auto se = numeric::solve(pe);
    ASSERT_EQ(se.status, numeric::Status::Success);
    for (int d : kDigits) {
      SCOPED_TRACE("digits:" + std::to_string(d));
      const auto pm = Problem<MpFloat>::from(scene, d);
      const auto sm = numeric::solve(pm);
      const auto pc = Problem<cl_R>::from(scene, d);
      const auto sc = numeric::solve(pc);
      ASSERT_EQ(sm.status, sc.status);
      if (sm.status != numeric::Status::Success) continue;
      const std::vector<cl_RA> W = exact_vector(sm.velocities_after), Wc = exact_vector(sc.velocities_after);
      const numeric::Certificate cert = numeric::certify(pm, sm);
      if (cert.case_certain) {
        ++certified;
        EXPECT_EQ(sm.closed, se.closed);
        EXPECT_TRUE(max_difference(W, se.velocities_after) <= rational_of(cert.velocity_error))
            << "error " << approx(max_difference(W, se.velocities_after)) << " above the certified " << cert.velocity_error;
      }
      EXPECT_EQ(sm.closed, sc.closed);
      const cl_RA rel = relative_velocity_error(W, Wc, pe.u);
      EXPECT_TRUE(rel <= cln::expt(cl_RA(10), -(d - 2))) << "MPFR and CLN differ by " << approx(rel);
      ++compared;
    }
  }
  EXPECT_GE(certified, static_cast<int>(kScenes * kDigits.size() / 2)) << "too few certified answers to test the bound";
  EXPECT_EQ(compared, static_cast<int>(kScenes * kDigits.size()));
}

/// One solver reused on problems whose data change one at a time (a velocity,
/// a mass, an entry of M), and back, answers each as a fresh solver does:
/// what a digits:N solver keeps between solves of the same data (the
/// assembly of A and b̃, the factors of A for the case with every contact
/// open) is not used for other data, and survives the pivots of a case
/// with closed contacts (paper-4.1-family and hard-mass-ratio-1e12 pivot).
TEST(MpFloat, ASolverReusedOnChangedDataAnswersAsAFreshOne) {
  for (const char* file : {"paper-4.4-alpha2.toml", "paper-4.1-family.toml", "hard-mass-ratio-1e12.toml"}) {
    for (int d : {20, 50, 100}) {
      SCOPED_TRACE(std::string(file) + " digits:" + std::to_string(d));
      const auto scene = ExactScene::from(load_scene(std::string(SUPERBALL_CASES_DIR) + "/scenes/" + file));
      const auto base = Problem<MpFloat>::from(scene, d);
      std::vector<Problem<MpFloat>> problems(4, base);
      problems[1].u[0] = problems[1].u[0] * MpFloat(2);
      problems[2].mass[2] = problems[2].mass[2] / MpFloat(3);
      problems[3].entries[0].value = problems[3].entries[0].value + MpFloat(1);
      numeric::CollisionSolver<MpFloat> reused(numeric::Settings<MpFloat>::defaults(d));
      for (int k : {0, 1, 0, 2, 2, 3, 0}) {
        SCOPED_TRACE("problem " + std::to_string(k));
        numeric::Solution<MpFloat> got, want;
        reused.compute(problems[static_cast<std::size_t>(k)], got);
        numeric::CollisionSolver<MpFloat>(numeric::Settings<MpFloat>::defaults(d)).compute(problems[static_cast<std::size_t>(k)], want);
        ASSERT_EQ(got.status, want.status);
        EXPECT_EQ(exact_vector(got.velocities_after), exact_vector(want.velocities_after));
        EXPECT_EQ(exact_vector(got.reactions), exact_vector(want.reactions));
        EXPECT_EQ(got.residual_motion, want.residual_motion);
      }
    }
  }
}

}  // namespace
}  // namespace superball::testing
