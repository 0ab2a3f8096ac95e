// --precision auto: the certificate must hold where it certifies (checked
// against the exact solution), and must refuse where double is wrong.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <vector>

#include "superball/cases/scene_file.hpp"
#include "superball/numeric/certify.hpp"

namespace superball::testing {
namespace {

using cln::cl_RA;

numeric::ExactScene scene(const std::string& name) {
  return numeric::ExactScene::from(load_scene(std::string(SUPERBALL_CASES_DIR) + "/scenes/" + name + ".toml"));
}

/// max_i |U_i − exact U_i| / max_i |exact U_i|, in rationals.
double error_against_exact(const numeric::ExactScene& s) {
  const auto exact = numeric::solve(numeric::Problem<cl_RA>::from(s));
  const auto d = numeric::solve(numeric::Problem<double>::from(s));
  cl_RA err = 0, scale = 0;
  for (std::size_t i = 0; i < exact.velocities_after.size(); ++i) {
    err = std::max(err, cln::abs(cln::rational(cln::cl_float(d.velocities_after[i])) - exact.velocities_after[i]));
    scale = std::max(scale, cln::abs(exact.velocities_after[i]));
  }
  return cln::double_approx(err / scale);
}

TEST(Certify, TheBoundHoldsWhereItCertifies) {
  for (const char* name : {"paper-4.4-alpha2", "paper-4.4-as-printed", "paper-fig5-alpha2", "chain-32", "hard-mass-ratio-1e12"}) {
    SCOPED_TRACE(name);
    const auto s = scene(name);
    const auto p = numeric::Problem<double>::from(s);
    const auto sol = numeric::solve(p);
    const auto cert = numeric::certify(p, sol);
    if (!cert.case_certain) continue;
    EXPECT_EQ(sol.closed, numeric::solve(numeric::Problem<cl_RA>::from(s)).closed) << "a certified case must be the exact one";
    EXPECT_LE(error_against_exact(s), cert.relative_error) << "the certified bound must bound the error";
  }
}

TEST(Certify, AutoPicksDoubleOnThePaperSceneAndExactOnTheHardOne) {
  const auto paper = numeric::choose_precision(scene("paper-4.4-alpha2"), numeric::default_rtol);
  EXPECT_EQ(paper.precision.kind, numeric::Precision::Kind::Double);
  EXPECT_LE(paper.relative_error, numeric::default_rtol);
  // Double gets the case of the eps = 1e-8 family wrong (its residual check
  // says so): auto must not stop there.
  const auto hard = numeric::choose_precision(scene("hard-eps-1e-8"), numeric::default_rtol);
  EXPECT_EQ(hard.precision.kind, numeric::Precision::Kind::Exact);
  ASSERT_FALSE(hard.tried.empty());
  EXPECT_NE(hard.tried.front().find("double"), std::string::npos);
}

TEST(Certify, BoundsAreWrittenAsPrintfWritesThem) {
  // to_string(double, digits) writes the bounds of AutoChoice::tried with
  // std::to_chars; its text must be printf's "%.*g" for every kind of double.
  std::vector<double> values = {0.0, -0.0, 1.0, -1.0, 0.5, 9.995, 9.9949999, 1e-5, 1e-4, 123456.0, 1e300, -2.5e-310,
                                std::numeric_limits<double>::min(), std::numeric_limits<double>::max(),
                                std::numeric_limits<double>::denorm_min(), std::numeric_limits<double>::infinity(),
                                -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN()};
  std::uint64_t state = 88172645463325252ull;
  for (int k = 0; k < 2000; ++k) {  // xorshift64: bit patterns over the whole range of double
    state ^= state << 13, state ^= state >> 7, state ^= state << 17;
    double x;
    std::memcpy(&x, &state, sizeof x);
    values.push_back(x);
  }
  for (double x : values)
    for (int digits = 1; digits <= 17; ++digits) {
      char expected[64];
      std::snprintf(expected, sizeof expected, "%.*g", digits, x);
      EXPECT_EQ(numeric::to_string(x, digits), expected) << digits << " digits";
    }
}

}  // namespace
}  // namespace superball::testing
