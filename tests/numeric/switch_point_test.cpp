// Scenes exactly on a switch point (issue 6): a contact on the edge of
// closing, its gap w and its reaction R both exactly 0.
//
// Where the switching contact is c and the parameter p enters A = diag(m) +
// DᵀMD through one rank-one term (a diagonal entry K_ij of M: p·d dᵀ with
// d = e_i − e_j; a mass: p·e_i e_iᵀ), the gap of c in the case on its open
// side is, by the Sherman–Morrison formula on the reduced system, a Möbius
// function (α + βp)/(1 + γp) of p with rational α, β, γ: its numerator is of
// degree one (the p² terms cancel).  So the switch point p* = −α/β is
// rational.  The test finds α, β, γ from three exact solves of that case,
// and then checks, independently of that argument, that the exact solution at
// p* has w = 0 and R = 0 on c.
//
// The label at the switch point itself: the exact solver labels a contact
// whose gap is exactly 0 as closed (numeric/src/collision/complete.cpp), so the case
// at p* is the case of the side where c is closed (docs/ACCURACY.md).
#include <gtest/gtest.h>

#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "superball/cases/parameter.hpp"
#include "superball/numeric/certify.hpp"
#include "superball/numeric/sweep.hpp"
#include "support.hpp"

namespace superball::testing {
namespace {

const std::string kScenes = std::string(SUPERBALL_CASES_DIR) + "/scenes/";
const std::string kHard = std::string(SUPERBALL_TEST_DATA_DIR) + "/hard/";

/// Exponents k of the approach p* ± 2^-k.
constexpr int kApproachFrom = 10, kApproachTo = 60;

ExactScene scene_at(const Scene& scene, const Parameter& parameter, const cl_RA& value) {
  return ExactScene::from(numeric::with_value(scene, parameter, value));
}

/// The gap of contact \p c in the evolution case \p forced, exact.
cl_RA forced_gap(const Scene& scene, const Parameter& parameter, const cl_RA& value, const ContactSet& forced, int c) {
  const auto p = Problem<cl_RA>::from(scene_at(scene, parameter, value));
  numeric::CollisionSolver<cl_RA> solver;
  Solution<cl_RA> s;
  solver.compute_case(p, forced, s);
  EXPECT_EQ(s.status, numeric::Status::Success);
  return s.gaps[static_cast<std::size_t>(c)];
}

/// The root of the Möbius function g(p) = (α + βp)/(1 + γp) through the three
/// points (p_k, g_k): g_k + γ p_k g_k = α + β p_k, solved by Cramer's rule.
cl_RA moebius_root(const cl_RA p[3], const cl_RA g[3]) {
  // Unknowns (α, β, γ): rows [1, p_k, −p_k g_k] · (α, β, γ) = g_k.
  auto det3 = [](const cl_RA m[3][3]) {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  };
  cl_RA a[3][3], aa[3][3], ab[3][3];
  for (int k = 0; k < 3; ++k) {
    a[k][0] = 1, a[k][1] = p[k], a[k][2] = -p[k] * g[k];
    for (int j = 0; j < 3; ++j) aa[k][j] = ab[k][j] = a[k][j];
    aa[k][0] = g[k];
    ab[k][1] = g[k];
  }
  const cl_RA d = det3(a);
  EXPECT_FALSE(cln::zerop(d)) << "the three points do not determine a Möbius function";
  const cl_RA alpha = det3(aa) / d, beta = det3(ab) / d;
  EXPECT_FALSE(cln::zerop(beta)) << "the gap does not depend on the parameter";
  return -alpha / beta;
}

/// A floating-point solve near the switch: the right answer within its
/// bound, or flagged (status not Success, or the certificate not certain).
template <class S>
std::string float_near_switch(const ExactScene& scene, const Problem<cl_RA>& pe, const Solution<cl_RA>& se) {
  SCOPED_TRACE(ScalarTraits<S>::name());
  const auto p = Problem<S>::from(scene);
  const auto s = numeric::solve(p);
  if (s.status != numeric::Status::Success) return std::string("flagged (status ") + numeric::to_string(s.status) + ")";
  const cl_RA rel = relative_velocity_error(exact_vector(s.velocities_after), se.velocities_after, pe.u);
  const cl_RA bound = unit_roundoff<S>() * rational_of(kForwardErrorFactor * p.n * static_cast<double>(condition_number(p)));
  EXPECT_TRUE(rel <= bound) << "velocity error " << approx(rel) << " above 8 n kappa(A) u = " << approx(bound);
  const numeric::Certificate cert = numeric::certify(p, s);
  if (!cert.case_certain) return "flagged (case not certain)";
  EXPECT_EQ(s.closed, se.closed) << "certified case " << s.closed.to_string() << ", exact " << se.closed.to_string();
  const cl_RA abs_err = max_difference(exact_vector(s.velocities_after), se.velocities_after);
  EXPECT_TRUE(abs_err <= rational_of(cert.velocity_error)) << "error " << approx(abs_err) << " above the certificate";
  return "right";
}

struct SwitchCase {
  std::string scene;    ///< path
  std::string parameter;
  cl_RA open_side;      ///< a value where contact c is open (the forced case is taken there)
  cl_RA closed_side;    ///< a value where contact c is closed
  int contact;          ///< c: contact (c+1, c+2)
};

void check_switch(const SwitchCase& sc) {
  const Scene scene = load_scene(sc.scene);
  const Parameter parameter = Parameter::parse(sc.parameter, scene);
  const int c = sc.contact;
  const auto at = [&](const cl_RA& v) { return numeric::solve(Problem<cl_RA>::from(scene_at(scene, parameter, v))); };
  const Solution<cl_RA> open = at(sc.open_side), closed = at(sc.closed_side);
  ASSERT_FALSE(open.closed.closed(c));
  ASSERT_TRUE(closed.closed.closed(c));

  // p*: the root of the gap of c in the case of the open side.
  cl_RA pts[3], gaps[3];
  for (int k = 0; k < 3; ++k) {
    pts[k] = sc.open_side + k;
    gaps[k] = forced_gap(scene, parameter, pts[k], open.closed, c);
  }
  const cl_RA star = moebius_root(pts, gaps);
  std::cout << "[ info ] " << std::filesystem::path(sc.scene).filename().string() << ": " << sc.parameter << " = " << text(star) << " = " << approx(star)
            << " puts contact " << c + 1 << "-" << c + 2 << " on the edge\n";
  // The Möbius form holds at a fourth point (a check of the argument).
  EXPECT_EQ(forced_gap(scene, parameter, star, open.closed, c), 0);

  // At p*: w = 0 and R = 0 on c; the other contacts strictly complementary;
  // the label is closed on c (the convention), the rest as on either side.
  const ExactScene at_star = scene_at(scene, parameter, star);
  const auto pe = Problem<cl_RA>::from(at_star);
  const Solution<cl_RA> se = numeric::solve(pe);
  ASSERT_EQ(se.status, numeric::Status::Success);
  check_physics(pe, se, tolerances(pe), "exact at the switch point");
  const auto k = static_cast<std::size_t>(c);
  EXPECT_EQ(se.gaps[k], 0);
  EXPECT_EQ(se.reactions[k], 0);
  EXPECT_TRUE(se.closed.closed(c)) << "the label at a switch point is closed: " << se.closed.to_string();
  EXPECT_EQ(se.closed, closed.closed) << "the case at the point is the case of the closed side";
  for (int other = 0; other + 1 < pe.n; ++other) {
    if (other == c) continue;
    const auto o = static_cast<std::size_t>(other);
    EXPECT_TRUE(se.closed.closed(other) ? cln::minusp(se.reactions[o]) : cln::plusp(se.gaps[o]))
        << "contact " << other + 1 << "-" << other + 2 << " is degenerate too";
  }

  // Both sides converge to the value at the point: |U(p* ± h) − U(p*)| <= C h,
  // C twice the largest slope seen at the widest step (on the closed side of
  // a K_ij switch the slope is 0: K_ij acts inside one cluster); the case on
  // each side is that side's.
  const bool closed_below = sc.closed_side < sc.open_side;
  cl_RA C = 0;
  for (int kk = kApproachFrom; kk <= kApproachTo; ++kk) {
    const cl_RA h = cln::expt(cl_RA(2), -kk);
    for (int side : {-1, 1}) {
      SCOPED_TRACE("p* " + std::string(side < 0 ? "-" : "+") + " 2^-" + std::to_string(kk));
      const cl_RA value = star + side * h;
      const ExactScene sc_near = scene_at(scene, parameter, value);
      const auto pn = Problem<cl_RA>::from(sc_near);
      const Solution<cl_RA> sn = numeric::solve(pn);
      ASSERT_EQ(sn.status, numeric::Status::Success);
      EXPECT_EQ(sn.closed, (side < 0) == closed_below ? closed.closed : open.closed);
      const cl_RA slope = max_difference(sn.velocities_after, se.velocities_after) / h;
      if (kk == kApproachFrom) C = max_q(C, 2 * slope);
      EXPECT_TRUE(slope <= C) << "|U(p*±h) − U(p*)| / h = " << approx(slope) << " > C = " << approx(C);
      // Double and long double near the switch: right within their bound, or flagged.
      if (kk % 10 == 0) {
        float_near_switch<double>(sc_near, pn, sn);
        float_near_switch<long double>(sc_near, pn, sn);
      }
    }
  }
  // At the point itself, floating point cannot tell the label: it must be
  // right within its bound or flag it, and auto must end exact or certified.
  const std::string d = float_near_switch<double>(at_star, pe, se), ld = float_near_switch<long double>(at_star, pe, se);
  const numeric::AutoChoice choice = numeric::choose_precision(at_star, numeric::default_rtol);
  std::string tried;
  for (const auto& t : choice.tried) tried += (tried.empty() ? "" : "; ") + t;
  std::cout << "[ info ]   at the point: double " << d << ", long double " << ld << "; auto tried: " << tried << "\n";
  if (d != "right" && ld != "right") {
    EXPECT_EQ(choice.precision.kind, numeric::Precision::Kind::Exact);
  }
}

TEST(SwitchPoint, Fig7ContactThreeFourOnTheEdge) {
  // Case 2.2 {3-4} below K34* ≈ 6.4287, case 3.3 {} above.
  check_switch({kScenes + "paper-4.4-alpha2.toml", "K.3-4", 8, 5, 2});
}

TEST(SwitchPoint, Fig7ContactTwoThreeOnTheEdge) {
  // Case 3.3 {} below K34* ≈ 13.412, case 3.2 {2-3} above.
  check_switch({kScenes + "paper-4.4-alpha2.toml", "K.3-4", 11, 15, 1});
}

TEST(SwitchPoint, MassOfTheTopBallOnAFixedObstacle) {
  // Three balls on a fixed obstacle: the top ball bounces off (case {2-3})
  // while m1 < m1*, and stays on ball 2 (case {1-2,2-3}) above.
  check_switch({kHard + "mass-ratio-light-on-heavy.toml", "mass.1", 1, 2, 0});
}

TEST(SwitchPoint, TheSweepBracketsTheExactPoints) {
  // The bisection of `superball sweep --switch-points` brackets both exact
  // switch points found above.
  const Scene scene = load_scene(kScenes + "paper-4.4-alpha2.toml");
  const Parameter k34 = Parameter::parse("K.3-4", scene);
  const numeric::Precision exact{numeric::Precision::Kind::Exact, 0};
  const auto switches = numeric::switch_points(scene, k34, numeric::sweep(scene, k34, numeric::linspace(0, 20, 41), exact));
  ASSERT_EQ(switches.size(), 2u);
  const int contact[2] = {2, 1};
  const cl_RA open_side[2] = {8, 11};
  for (int s = 0; s < 2; ++s) {
    const ContactSet all_open(4);
    cl_RA pts[3], gaps[3];
    for (int k = 0; k < 3; ++k) {
      pts[k] = open_side[s] + k;
      gaps[k] = forced_gap(scene, k34, pts[k], all_open, contact[s]);
    }
    const cl_RA star = moebius_root(pts, gaps);
    EXPECT_TRUE(switches[static_cast<std::size_t>(s)].low <= star && star <= switches[static_cast<std::size_t>(s)].high)
        << approx(star) << " not in [" << approx(switches[static_cast<std::size_t>(s)].low) << ", "
        << approx(switches[static_cast<std::size_t>(s)].high) << "]";
  }
}

}  // namespace
}  // namespace superball::testing
