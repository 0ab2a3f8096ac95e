// The paper's numbers (§4.4): eq. (16) from the reading with the coupling
// -100 on alpha_2, the as-printed reading (alpha_4) that does not give it,
// and the case changes of Fig. 7 along K34 located by bisection.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "superball/cases/parameter.hpp"
#include "superball/cases/vocabulary.hpp"
#include "superball/numeric/sweep.hpp"
#include "support.hpp"

namespace superball::numeric {
/// gtest prints a precision by its CLI name.
inline void PrintTo(Precision::Kind k, std::ostream* os) { *os << Precision{k, k == Precision::Kind::Digits ? 30 : 0}.name(); }
}  // namespace superball::numeric

namespace superball::testing {
namespace {

const std::string kScenes = std::string(SUPERBALL_CASES_DIR) + "/scenes/";

/// A number as printed in the paper and half a unit of its last digit.
struct Printed {
  cl_RA value, half_ulp;
};
Printed printed(const std::string& text) {
  const auto dot = text.find('.');
  const long decimals = dot == std::string::npos ? 0 : static_cast<long>(text.size() - dot - 1);
  return {numeric::parse_rational(Number::parse(text).fraction()), cln::expt(cl_RA(10), -decimals) / 2};
}

/// Eq. (16), §4.4: U⁺ = (3.3069, 0.4478, 0.2849, -0.000017) m/s, case 3.3.
const char* const kEq16[4] = {"3.3069", "0.4478", "0.2849", "-0.000017"};

template <class S>
class PaperScenes : public ::testing::Test {};
TYPED_TEST_SUITE(PaperScenes, Scalars, ScalarNames);

TYPED_TEST(PaperScenes, Eq16FromTheAlpha2Reading) {
  using S = TypeParam;
  const auto p = problem_of<S>(load_scene(kScenes + "paper-4.4-alpha2.toml"));
  const auto s = numeric::solve(p);
  ASSERT_EQ(s.status, numeric::Status::Success);
  check_physics(p, s, tolerances(p), "eq. 16");
  EXPECT_EQ(Vocabulary::paper().case_name(s.closed), "3.3");
  const auto U = velocities_si(p, s);
  for (int i = 0; i < 4; ++i) {
    const Printed x = printed(kEq16[i]);
    EXPECT_TRUE(abs_q(U[static_cast<std::size_t>(i)] - x.value) <= x.half_ulp)
        << "U" << i + 1 << "+ = " << approx(U[static_cast<std::size_t>(i)]) << ", paper " << kEq16[i];
  }
  // The superball: ball 1 leaves faster than it fell (a = 3.13209 m/s).
  EXPECT_TRUE(U[0] > printed("3.13209").value);
  // Impenetrability as the paper remarks: U1+ > U2+ > U3+ > U4+.
  EXPECT_TRUE(U[0] > U[1] && U[1] > U[2] && U[2] > U[3]);
}

TYPED_TEST(PaperScenes, AsPrintedDoesNotGiveEq16) {
  using S = TypeParam;
  const auto p = problem_of<S>(load_scene(kScenes + "paper-4.4-as-printed.toml"));
  const auto s = numeric::solve(p);
  ASSERT_EQ(s.status, numeric::Status::Success);
  check_physics(p, s, tolerances(p), "as printed");
  const auto U = velocities_si(p, s);
  // U1+ = 3.1467 (exactly 1425207149882365049811/430982092965922100000 = 3.14666...), not 3.3069.
  const Printed u1 = printed("3.1467");
  EXPECT_TRUE(abs_q(U[0] - u1.value) <= u1.half_ulp) << "U1+ = " << approx(U[0]);
  int matches = 0;
  for (int i = 0; i < 4; ++i) {
    const Printed x = printed(kEq16[i]);
    matches += abs_q(U[static_cast<std::size_t>(i)] - x.value) <= x.half_ulp;
  }
  EXPECT_LT(matches, 4) << "the as-printed reading reproduces eq. (16)";
  EXPECT_TRUE(abs_q(U[0] - printed(kEq16[0]).value) > cl_RA(1) / 10);
}

TEST(PaperScenes, ExactEq16VelocitiesAreTheExactFractions) {
  // The exact solution of the alpha_2 reading, in units of a = 3.13209: a
  // rational, and (as a check of the exact pipeline end to end) the same
  // value whether the unit is applied before or after the solve.
  const Scene scene = load_scene(kScenes + "paper-4.4-alpha2.toml");
  const auto p = problem_of<cl_RA>(scene);
  EXPECT_TRUE(p.unit_exact);
  EXPECT_EQ(p.unit, cl_RA(313209) / 100000);
  const auto s = numeric::solve(p);
  Scene explicit_velocities = scene;
  explicit_velocities.fall_speed.reset();
  for (int i = 0; i < 3; ++i) explicit_velocities.bodies[static_cast<std::size_t>(i)].velocity = Number::parse("-3.13209");
  const auto q = problem_of<cl_RA>(explicit_velocities);
  EXPECT_EQ(q.unit, 1);
  const auto t = numeric::solve(q);
  EXPECT_EQ(velocities_si(p, s), velocities_si(q, t));
  EXPECT_EQ(s.closed, t.closed);
}

// ---------------------------------------------------------------------------
// Fig. 7: K34 varies, the other parameters as in eq. (16).

/// The exact case and velocities (in units of a) at K34 = value.
Solution<cl_RA> exact_at(const Scene& scene, const Parameter& k34, const cl_RA& value) {
  return numeric::solve(Problem<cl_RA>::from(ExactScene::from(numeric::with_value(scene, k34, value))));
}

class Fig7 : public ::testing::TestWithParam<numeric::Precision::Kind> {};

TEST_P(Fig7, TwoSwitchPointsAlongK34) {
  const Scene scene = load_scene(kScenes + "paper-4.4-alpha2.toml");
  const Parameter k34 = Parameter::parse("K.3-4", scene);
  const auto values = numeric::linspace(0, 20, 41);
  const cl_RA step = cl_RA(1) / 2;
  const numeric::Precision precision{GetParam(), GetParam() == numeric::Precision::Kind::Digits ? kClnDigits : 0};
  const auto points = numeric::sweep(scene, k34, values, precision);
  ASSERT_EQ(points.size(), values.size());
  const auto switches = numeric::switch_points(scene, k34, points);
  ASSERT_EQ(switches.size(), 2u);
  // The paper reads 6.45 (ball 3 starts to stay on the obstacle, case 2.2
  // below) and 13.5 (balls 2 and 3 start to stay together, case 3.2 above)
  // off its figure; the exact bisection gives 6.4287... and 13.4119...
  const cl_RA expected[2] = {cl_RA(643) / 100, cl_RA(1341) / 100};
  const ContactSet below[2] = {ContactSet::parse("3-4", 4), ContactSet(4)};
  const ContactSet above[2] = {ContactSet(4), ContactSet::parse("2-3", 4)};
  // Lipschitz constant of U+(K34) along the sweep, from exact solutions.
  cl_RA slope = 0;
  std::vector<std::vector<cl_RA>> U;
  for (const auto& v : values) U.push_back(exact_at(scene, k34, v).velocities_after);
  for (std::size_t k = 1; k < values.size(); ++k) slope = max_q(slope, max_difference(U[k], U[k - 1]) / step);
  for (int k = 0; k < 2; ++k) {
    const numeric::SwitchPoint& s = switches[static_cast<std::size_t>(k)];
    SCOPED_TRACE("switch " + std::to_string(k + 1) + ": [" + text(s.low) + ", " + text(s.high) + "]");
    EXPECT_TRUE(s.low < s.high);
    EXPECT_TRUE(abs_q((s.low + s.high) / 2 - expected[k]) < cl_RA(1) / 200) << approx((s.low + s.high) / 2);
    // 64 bisections below the sweep step.
    EXPECT_TRUE(s.high - s.low <= step / cln::expt(cl_RA(2), 64)) << approx(s.high - s.low);
    EXPECT_EQ(s.below, below[k]) << s.below.to_string();
    EXPECT_EQ(s.above, above[k]) << s.above.to_string();
    // The exact cases at the ends of the bracket are the ones reported.
    const auto lo = exact_at(scene, k34, s.low), hi = exact_at(scene, k34, s.high);
    EXPECT_EQ(lo.closed, s.below);
    EXPECT_EQ(hi.closed, s.above);
    // The solution is continuous across the switch: the velocities at the
    // two ends differ by at most the slope times the bracket width.
    EXPECT_TRUE(max_difference(lo.velocities_after, hi.velocities_after) <= 2 * slope * (s.high - s.low))
        << "jump " << approx(max_difference(lo.velocities_after, hi.velocities_after)) << " over a bracket of "
        << approx(s.high - s.low);
    // The contact that changes is on the edge: its reaction (closed side)
    // and its gap (open side) both vanish to the bracket width.
    const int c = k == 0 ? 2 : 1;  // contact 3-4, then 2-3
    const auto& closed_side = k == 0 ? lo : hi;
    const auto& open_side = k == 0 ? hi : lo;
    EXPECT_TRUE(closed_side.closed.closed(c));
    EXPECT_FALSE(open_side.closed.closed(c));
    EXPECT_TRUE(abs_q(open_side.gaps[static_cast<std::size_t>(c)]) <= 2 * slope * (s.high - s.low));
    EXPECT_TRUE(closed_side.reactions[static_cast<std::size_t>(c)] < 0);
  }
  // Between the switches the case is 3.3 and eq. (16) is at K34 = 10.
  EXPECT_EQ(Vocabulary::paper().case_name(exact_at(scene, k34, 10).closed), "3.3");
  // The sweep's own cases agree with the exact ones at every point.
  for (std::size_t k = 0; k < values.size(); ++k)
    EXPECT_EQ(points[k].closed, exact_at(scene, k34, values[k]).closed) << "K34 = " << approx(values[k]);
}

INSTANTIATE_TEST_SUITE_P(Precisions, Fig7,
                         ::testing::Values(numeric::Precision::Kind::Double, numeric::Precision::Kind::Digits,
                                           numeric::Precision::Kind::Exact),
                         [](const auto& info) {
                           return info.param == numeric::Precision::Kind::Double   ? std::string("double")
                                  : info.param == numeric::Precision::Kind::Digits ? std::string("digits")
                                                                                   : std::string("exact");
                         });

TEST(SwitchPoints, NoneWhereTheCaseDoesNotChange) {
  const Scene scene = load_scene(kScenes + "paper-4.4-alpha2.toml");
  const Parameter k34 = Parameter::parse("K.3-4", scene);
  const numeric::Precision exact{numeric::Precision::Kind::Exact, 0};
  const auto points = numeric::sweep(scene, k34, numeric::linspace(7, 13, 7), exact);
  EXPECT_TRUE(numeric::switch_points(scene, k34, points).empty());
  for (const auto& p : points) EXPECT_EQ(p.closed, ContactSet(4));
}

TEST(SwitchPoints, LinspaceIsExact) {
  const auto v = numeric::linspace(0, 20, 401);
  ASSERT_EQ(v.size(), 401u);
  EXPECT_EQ(v.front(), 0);
  EXPECT_EQ(v.back(), 20);
  for (std::size_t k = 1; k < v.size(); ++k) EXPECT_EQ(v[k] - v[k - 1], cl_RA(1) / 20);
  EXPECT_EQ(numeric::linspace(cl_RA(1) / 3, cl_RA(-1) / 3, 3)[1], 0);
  EXPECT_THROW(numeric::linspace(0, 1, 1), std::invalid_argument);
  // One grid for linspace(), its chunks and a map's axis: x_k = from + (to − from)·k/(steps − 1) exactly.
  const cl_RA from = cl_RA(-7) / 3, to = cl_RA(11) / 5;
  const numeric::Grid x(from, to, 37);
  const auto all = numeric::linspace(from, to, 37), chunk = numeric::linspace(from, to, 37, 10, 5);
  for (int k = 0; k < 37; ++k) EXPECT_EQ(x(k), from + (to - from) * k / 36) << k;
  for (int k = 0; k < 37; ++k) EXPECT_EQ(all[static_cast<std::size_t>(k)], x(k)) << k;
  for (int k = 0; k < 5; ++k) EXPECT_EQ(chunk[static_cast<std::size_t>(k)], x(10 + k)) << k;
  EXPECT_EQ(x(0), from);
  EXPECT_EQ(x(36), to);
}

}  // namespace
}  // namespace superball::testing
