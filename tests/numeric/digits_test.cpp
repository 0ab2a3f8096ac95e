// digits:N (MPFR floats of N decimal digits) for every N it accepts, against
// the exact solution (issue 25, point 1), and the warning of an explicit
// arithmetic whose answer the certificate does not prove (point 5).
//
// Every N from min_digits to 120 runs on the scenes of the hard catalogue
// with at most kEveryNBodies bodies; the larger ones (chains of 16 to 64
// bodies) run every kStride-th N and the N where the float format changes
// kind (10, 15 … 18, 19), so that the whole test stays within a few seconds.
// max_digits runs on the scenes of at most kLargestNBodies bodies.  Each N
// must answer or decline, never throw or crash: an answer with status
// Success has velocities within 8·n·κ(A)·u of the exact ones (u of its own
// format), the exact case unless it carries a warning, and where its
// certificate proves the case, the exact case within the certified bound.
#include <gtest/gtest.h>

#include <cln/float.h>

#include <string>
#include <vector>

#include "superball/numeric/certify.hpp"
#include "superball/numeric/precision.hpp"
#include "support.hpp"

namespace superball::testing {
namespace {

const std::string kHard = std::string(SUPERBALL_TEST_DATA_DIR) + "/hard/";

/// The catalogue as CMake saw it (generated from tests/data/hard/*.toml).
const std::vector<std::string> kCatalogue = {
#include "hard_scene_list.inc"
};

/// Largest N of the sweep over every N.
constexpr int kLargestSweptN = 120;
/// Scenes of at most this many bodies take every N; larger ones every kStride-th.
constexpr int kEveryNBodies = 8;
constexpr int kStride = 11;
/// Scenes of at most this many bodies also take N = max_digits.
constexpr int kLargestNBodies = 4;

/// The N a scene of \p n bodies is solved in.
std::vector<int> digits_for(int n) {
  std::vector<int> out;
  for (int d = numeric::min_digits; d <= kLargestSweptN; ++d)
    if (n <= kEveryNBodies || (d - numeric::min_digits) % kStride == 0 || (d >= 15 && d <= 19) || d == kLargestSweptN)
      out.push_back(d);
  if (n <= kLargestNBodies) out.push_back(numeric::max_digits);
  return out;
}

/// What digits:N did on one scene.
struct Outcome {
  bool success = false, warned = false, certified = false;
};

/// Solve \p scene in digits:\p digits and judge it against the exact solution (\p pe, \p se).
Outcome judge(const ExactScene& scene, int digits, const Problem<cl_RA>& pe, const Solution<cl_RA>& se) {
  SCOPED_TRACE("digits:" + std::to_string(digits));
  Outcome o;
  const auto p = Problem<numeric::MpFloat>::from(scene, digits);
  const auto s = numeric::solve(p);
  const std::vector<std::string> warnings = numeric::trust_warnings(p, s);
  o.warned = !warnings.empty();
  if (s.status != numeric::Status::Success) {
    EXPECT_FALSE(o.warned) << "a declined answer needs no warning";
    return o;
  }
  o.success = true;
  const cl_RA u = exact_value(ScalarTraits<numeric::MpFloat>::unit_roundoff(digits));
  EXPECT_TRUE(cln::plusp(u) && u <= cln::expt(cl_RA(10), -digits)) << "u = " << approx(u);
  const std::vector<cl_RA> W = exact_vector(s.velocities_after);
  const cl_RA rel = relative_velocity_error(W, se.velocities_after, pe.u);
  const cl_RA bound = u * rational_of(kForwardErrorFactor * p.n * static_cast<double>(condition_number(pe)));
  EXPECT_TRUE(rel <= bound) << "relative velocity error " << approx(rel) << " above 8 n kappa(A) u = " << approx(bound);
  if (!o.warned) {
    EXPECT_EQ(s.closed, se.closed) << "case " << s.closed.to_string() << " with no warning, exact " << se.closed.to_string();
  }
  const numeric::Certificate cert = numeric::certify(p, s);
  if (cert.case_certain) {
    o.certified = true;
    EXPECT_EQ(s.closed, se.closed) << "certified case " << s.closed.to_string() << ", exact " << se.closed.to_string();
    const cl_RA abs_err = max_difference(W, se.velocities_after);
    EXPECT_TRUE(abs_err <= rational_of(cert.velocity_error))
        << "error " << approx(abs_err) << " above the certified bound " << cert.velocity_error;
  }
  return o;
}

TEST(DigitsFormat, EveryAcceptedNIsALongFloatOfAtLeastNDigits) {
  // CLN's own float_format(N) is a double float for N <= 15 (IEEE exponent
  // range: 1e-200 squared raised floating_point_underflow) and a one-word
  // long float for N = 15 … 17 (float_epsilon() wrote past it: a crash).
  std::vector<int> all;
  for (int d = numeric::min_digits; d <= kLargestSweptN; ++d) all.push_back(d);
  all.push_back(numeric::max_digits);
  for (int d : all) {
    SCOPED_TRACE("digits:" + std::to_string(d));
    const cl_R third = ScalarTraits<cl_R>::from(cl_RA(1) / 3, d);
    // Two 64-bit words or more: a long float (double floats have 53 bits).
    EXPECT_GE(static_cast<double>(cln::float_digits(cln::the<cln::cl_F>(third))), 2 * 64.0);
    EXPECT_GE(static_cast<double>(cln::float_digits(cln::the<cln::cl_F>(third))), d * 3.3219);
    const cl_RA u = exact_value(ScalarTraits<cl_R>::unit_roundoff(d));
    EXPECT_TRUE(cln::plusp(u) && u <= cln::expt(cl_RA(10), -d));
    // The exponent range holds what double-floats do not.
    const cl_R tiny = ScalarTraits<cl_R>::from(cln::expt(cl_RA(10), -4000), d);
    EXPECT_EQ(cln::rational(tiny * tiny * tiny) > 0, true);
  }
  EXPECT_EQ(numeric::to_string(ScalarTraits<cl_R>::from(cl_RA(-cln::expt(cl_RA(10), 400)), 20), 6), "-1e+400");
}

class DigitsOnHardScene : public ::testing::TestWithParam<std::string> {};

TEST_P(DigitsOnHardScene, EveryNAnswersRightOrDeclines) {
  const ExactScene scene = ExactScene::from(load_scene(kHard + GetParam()));
  const auto pe = Problem<cl_RA>::from(scene);
  const auto se = numeric::solve(pe);
  ASSERT_EQ(se.status, numeric::Status::Success) << "exact solve";
  int answered = 0, declined = 0, warned = 0;
  const std::vector<int> digits = digits_for(scene.n);
  for (int d : digits) {
    const Outcome o = judge(scene, d, pe, se);
    (o.success ? answered : declined) += 1;
    warned += o.warned;
  }
  std::cout << "[ info ] " << GetParam() << ": " << digits.size() << " values of N, " << answered << " answered (" << warned
            << " with a warning), " << declined << " declined\n";
}

INSTANTIATE_TEST_SUITE_P(Catalogue, DigitsOnHardScene, ::testing::ValuesIn(kCatalogue), [](const auto& info) {
  std::string name = info.param.substr(0, info.param.size() - 5);
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
});

/// The scenes of the issue: every body falling at 1e-200 m/s (digits:10 …
/// 14 ended in "floating point underflow"), a mass of 1e-320, a fall speed
/// of 1e400, and a stack where the top falls faster at 1e-200 (a collision
/// whose energies are of order 1e-400).
const char* const kReproducers[] = {
    R"(fall_speed = "1e-200"
[[body]]
mass = 1
[[body]]
mass = 1
[[body]]
mass = 2
[dissipation]
K = { "1-2" = 1, "2-3" = 1 })",
    R"(fall_speed = 1
[[body]]
mass = "1e-320"
[[body]]
mass = 1
[[body]]
mass = 2
[dissipation]
K = { "1-2" = 1, "2-3" = 1 })",
    R"(fall_speed = "1e400"
[[body]]
mass = 1
[[body]]
mass = 1
[[body]]
mass = 2
[dissipation]
K = { "1-2" = 1, "2-3" = 1 })",
    R"([[body]]
mass = 1
velocity = "-3e-200"
[[body]]
mass = 1
velocity = "-1e-200"
[[body]]
mass = 2
velocity = 0
[dissipation]
K = { "1-2" = 1, "2-3" = "1e-300" })",
};

TEST(DigitsReproducers, TinyAndHugeExponentsAnswerInEveryN) {
  for (const char* text : kReproducers) {
    SCOPED_TRACE(text);
    const ExactScene scene = ExactScene::from(parse_scene(text, "reproducer.toml"));
    const auto pe = Problem<cl_RA>::from(scene);
    const auto se = numeric::solve(pe);
    ASSERT_EQ(se.status, numeric::Status::Success);
    for (int d = numeric::min_digits; d <= kLargestSweptN; ++d) EXPECT_TRUE(judge(scene, d, pe, se).success);
  }
}

// ---------------------------------------------------------------------------
// Point 5: an explicit arithmetic's answer that the certificate does not
// prove carries a warning.

/// The issue's scene: exact gives every body at −0.008167 m/s, case {1-2, 2-3};
/// double said success with U⁺ = (+0.008167, +0.008167, −0.008167), case {1-2}.
const char* const kUntrusted = R"(fall_speed = 8.167e-3
[[body]]
mass = 6.421e-9
[[body]]
mass = 1.239e-23
[[body]]
mass = 2.367e17
[dissipation]
K = { "1-2" = 6.929e20, "2-3" = 7.628e-4 }
coupling = [ { pairs = ["1-2", "2-3"], value = 2.246e8 } ])";

TEST(TrustWarnings, DoubleWrongWithSuccessWarns) {
  const ExactScene scene = ExactScene::from(parse_scene(kUntrusted, "untrusted.toml"));
  const auto pd = Problem<double>::from(scene);
  const auto sd = numeric::solve(pd);
  const auto se = numeric::solve(Problem<cl_RA>::from(scene));
  ASSERT_EQ(sd.status, numeric::Status::Success);
  ASSERT_NE(sd.closed, se.closed) << "the reproducer no longer gives double the wrong case";
  const std::vector<std::string> w = numeric::trust_warnings(pd, sd);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0].rfind("double: the case {1-2} is not certified", 0), 0u) << w[0];
  EXPECT_NE(w[0].find("--precision auto or exact"), std::string::npos) << w[0];
  // auto, on the same certificate, does not stop at double.
  EXPECT_EQ(numeric::choose_precision(scene, numeric::default_rtol).precision.name(), "exact");
  // Nothing to warn of in exact arithmetic.
  EXPECT_TRUE(numeric::trust_warnings(Problem<cl_RA>::from(scene), se).empty());
}

TEST(TrustWarnings, PaperSceneIsTrustedInEveryArithmetic) {
  const ExactScene scene = ExactScene::from(load_scene(std::string(SUPERBALL_CASES_DIR) + "/scenes/paper-4.4-alpha2.toml"));
  const auto pd = Problem<double>::from(scene);
  EXPECT_TRUE(numeric::trust_warnings(pd, numeric::solve(pd)).empty());
  const auto pl = Problem<long double>::from(scene);
  EXPECT_TRUE(numeric::trust_warnings(pl, numeric::solve(pl)).empty());
  for (int d : {numeric::min_digits, 16, 30, 100}) {
    const auto pc = Problem<numeric::MpFloat>::from(scene, d);
    EXPECT_TRUE(numeric::trust_warnings(pc, numeric::solve(pc)).empty()) << "digits:" << d;
  }
}

TEST(TrustWarnings, CertificateOfDigitsIsTighterThanLongDouble) {
  // certify() in digits:N uses its own unit roundoff: on the paper
  // scene its bound is far below long double's.
  const ExactScene scene = ExactScene::from(load_scene(std::string(SUPERBALL_CASES_DIR) + "/scenes/paper-4.4-alpha2.toml"));
  const auto pl = Problem<long double>::from(scene);
  const auto pc = Problem<numeric::MpFloat>::from(scene, 50);
  const numeric::Certificate l = numeric::certify(pl, numeric::solve(pl)), c = numeric::certify(pc, numeric::solve(pc));
  ASSERT_TRUE(l.case_certain && c.case_certain);
  EXPECT_LT(c.relative_error, l.relative_error * 1e-25);
}

}  // namespace
}  // namespace superball::testing
