// The residual check's sizes in digits:N and exact (numeric/src/collision/complete.hpp):
// Magnitude, a double and an exponent of any size, against exact values over
// ranges far beyond double's, its zeros, infinities and NaN; MpFloat's frexp;
// and the residuals a digits:N answer and the exact check give the same
// numbers, against those the definition gives in exact rationals.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "collision/cluster.hpp"
#include "collision/complete.hpp"
#include "superball/numeric/precision.hpp"
#include "support.hpp"

#include <cln/rational.h>

namespace superball::testing {
namespace {

using numeric::MpFloat;
using numeric::detail::Magnitude;

/// 2^k·(odd of 40 bits) as an MpFloat of \p digits: exponents far beyond double's.
MpFloat wide(Rng& rng, int digits, int max_exponent) {
  const cl_RA odd = cl_RA(cln::cl_I(static_cast<long>((rng.next() >> 24) | 1)));
  const int k = rng.below(2 * max_exponent) - max_exponent;
  cl_RA x = odd * cln::expt(cl_RA(2), k);
  if (rng.chance(50)) x = -x;
  return ScalarTraits<MpFloat>::from(x, digits);
}

/// |a / b − 1| for two magnitudes whose quotient double holds.
double relative_gap(const Magnitude& a, const Magnitude& b) { return std::fabs((a / b).to_double() - 1); }

TEST(Magnitude, check_SumsProductsQuotientsAndOrderAreThoseOfTheValuesToAFewUlps) {
  Rng rng(2026);
  constexpr double ulps = 8 * std::numeric_limits<double>::epsilon();
  for (int trial = 0; trial < 4000; ++trial) {
    const int range = trial % 2 == 0 ? 60 : 6000;  // near 1, and far outside double
    const MpFloat x = wide(rng, 40, range), y = wide(rng, 40, range);
    const Magnitude X(x), Y(y);
    SCOPED_TRACE(text(exact_value(x)) + " and " + text(exact_value(y)));
    EXPECT_LE(relative_gap(X + Y, Magnitude(numeric::abs(x) + numeric::abs(y))), ulps);
    EXPECT_LE(relative_gap(X * Y, Magnitude(x * y)), ulps);
    EXPECT_LE(relative_gap(X / Y, Magnitude(x / y)), ulps);
    const cl_RA ax = abs_q(exact_value(x)), ay = abs_q(exact_value(y));
    // An exact rational's magnitude: its numerator's and denominator's leading bits.
    const cl_RA q = exact_value(x) / (exact_value(y) * 3 + (cln::zerop(exact_value(y)) ? 1 : 0));
    EXPECT_LE(relative_gap(Magnitude(q), Magnitude(ScalarTraits<MpFloat>::from(q, 40))), ulps);
    EXPECT_EQ(X < Y, ax < ay);
    EXPECT_EQ(X > Y, ax > ay);
    EXPECT_FALSE(X < X);
  }
}

TEST(Magnitude, exam_ZeroInfinityAndNaNBehaveAsTheyDoInTheNumbers) {
  const Magnitude zero, two(MpFloat(2)), huge(ScalarTraits<MpFloat>::from(cln::expt(cl_RA(2), 5000), 30));
  const Magnitude inf{MpFloat(std::numeric_limits<double>::infinity())};
  const Magnitude nan{MpFloat(std::numeric_limits<double>::quiet_NaN())};
  EXPECT_EQ((zero + two).to_double(), 2);
  EXPECT_EQ((two + zero).to_double(), 2);
  EXPECT_EQ((zero * huge).to_double(), 0);
  EXPECT_EQ((two / zero).to_double(), std::numeric_limits<double>::infinity());
  EXPECT_EQ((two / inf).to_double(), 0);
  EXPECT_EQ((huge + inf).to_double(), std::numeric_limits<double>::infinity());
  EXPECT_EQ(huge.to_double(), std::numeric_limits<double>::infinity());  // beyond double: +inf, as a conversion
  EXPECT_EQ((two / huge).to_double(), 0);
  EXPECT_EQ(((huge * two) / huge).to_double(), 2);  // the range is kept
  EXPECT_TRUE(zero < two && two < huge && huge < inf);
  EXPECT_FALSE(zero < zero || zero > zero);
  for (const Magnitude& x : {zero, two, huge, inf, nan}) {
    EXPECT_FALSE(nan < x || x < nan || nan > x || x > nan);
    EXPECT_TRUE(std::isnan((nan + x).to_double()) && std::isnan((x + nan).to_double()));
    EXPECT_TRUE(std::isnan((nan * x).to_double()) && std::isnan((x / nan).to_double()));
  }
  EXPECT_TRUE(std::isnan((zero * inf).to_double()));
  EXPECT_TRUE(std::isnan((zero / zero).to_double()));
}

TEST(MpFloat, exam_FrexpIsTheLeadingWordRoundedWithItsExponent) {
  long e = 99;
  EXPECT_EQ(frexp(MpFloat(12), &e), 0.75);
  EXPECT_EQ(e, 4);
  EXPECT_EQ(frexp(MpFloat(-1), &e), -0.5);
  EXPECT_EQ(e, 1);
  EXPECT_EQ(frexp(MpFloat(0), &e), 0.0);
  EXPECT_EQ(e, 0);
  EXPECT_EQ(frexp(MpFloat(std::numeric_limits<double>::infinity()), &e), std::numeric_limits<double>::infinity());
  EXPECT_TRUE(std::isnan(frexp(MpFloat(std::numeric_limits<double>::quiet_NaN()), &e)));
  // 2^64 − 1: a word of ones rounds up to 1, given as 1/2 and one more in the exponent.
  const MpFloat ones = ScalarTraits<MpFloat>::from(cl_RA(cln::expt(cln::cl_I(2), 64) - 1), 30);
  EXPECT_EQ(frexp(ones, &e), 0.5);
  EXPECT_EQ(e, 65);
  // Far below double: 3·2^-4000 = 0.75·2^-3998.
  EXPECT_EQ(frexp(ScalarTraits<MpFloat>::from(3 * cln::expt(cl_RA(2), -4000), 30), &e), 0.75);
  EXPECT_EQ(e, -3998);
}

/// \p p with every value replaced by that of \p held (the same scene): the
/// exact problem of the numbers the digits:N problem holds.
Problem<cl_RA> exactly(Problem<cl_RA> p, const Problem<MpFloat>& held) {
  for (std::size_t i = 0; i < p.mass.size(); ++i) p.mass[i] = exact_value(held.mass[i]);
  for (std::size_t i = 0; i < p.u.size(); ++i) p.u[i] = exact_value(held.u[i]);
  for (std::size_t k = 0; k < p.entries.size(); ++k) p.entries[k].value = exact_value(held.entries[k].value);
  return p;
}

/// complete_solution() of \p p for the velocities \p W, reactions \p R and case \p closed.
template <class S>
Solution<S> checked(const Problem<S>& p, const std::vector<S>& W, const std::vector<S>& R, const ContactSet& closed) {
  numeric::detail::ClusterSystem<S> system;
  system.assemble(p, p.check("checked()"));
  numeric::detail::CheckWorkspace<S> work;
  std::vector<S> lambda;
  std::vector<char> active;
  for (std::size_t c = 0; c < R.size(); ++c) {
    lambda.push_back(-R[c]);
    active.push_back(closed.closed(static_cast<int>(c)) ? 1 : 0);
  }
  Solution<S> out;
  out.velocities_after = W;
  numeric::detail::complete_solution(p, system, lambda, active, false, numeric::Settings<S>::defaults(p.digits), work, out);
  return out;
}

/// The motion residual by its definition, in exact rationals: per free body,
/// the row m(W − u) + DᵀMD(W + u) − Cᵀλ over the sum of the magnitudes of its
/// terms (|y| counted as |W| + |u|); per group of bodies joined by M or by a
/// closed contact and free of the obstacle, |Σ m(W − u)| / Σ m(|W| + |u|).
/// The largest of them.
cl_RA motion_residual(const Problem<cl_RA>& p, const std::vector<cl_RA>& W, const std::vector<cl_RA>& lambda, const ContactSet& closed) {
  const int n = p.n, nf = p.fixed_bottom ? n - 1 : n;
  const auto at = [](int i) { return static_cast<std::size_t>(i); };
  std::vector<cl_RA> row(at(n)), size(at(n)), y(at(n)), ay(at(n));
  for (int i = 0; i < n; ++i) y[at(i)] = W[at(i)] + p.u[at(i)], ay[at(i)] = abs_q(W[at(i)]) + abs_q(p.u[at(i)]);
  const auto term = [&](int to, int from_a, int from_b, const cl_RA& v, int sign) {
    row[at(to)] += sign * v * (y[at(from_a)] - y[at(from_b)]);
    size[at(to)] += abs_q(v) * (ay[at(from_a)] + ay[at(from_b)]);
  };
  std::vector<int> group(at(n));
  for (int i = 0; i < n; ++i) group[at(i)] = i;
  const auto join = [&group, n](int a, int b) {
    const int from = group[static_cast<std::size_t>(a)], to = group[static_cast<std::size_t>(b)];
    for (int i = 0; i < n; ++i)
      if (group[static_cast<std::size_t>(i)] == from) group[static_cast<std::size_t>(i)] = to;
  };
  for (const auto& e : p.entries) {
    term(e.i, e.k, e.l, e.value, 1), term(e.j, e.k, e.l, e.value, -1);
    if (!e.diagonal()) term(e.k, e.i, e.j, e.value, 1), term(e.l, e.i, e.j, e.value, -1);
    if (!cln::zerop(e.value)) join(e.i, e.j), join(e.k, e.l), join(e.i, e.k);
  }
  cl_RA worst = 0;
  std::vector<cl_RA> change(at(n)), weight(at(n));
  for (int i = 0; i < nf; ++i) {
    const cl_RA m = p.mass[at(i)];
    row[at(i)] += m * (W[at(i)] - p.u[at(i)]);
    size[at(i)] += m * ay[at(i)];
    if (i < n - 1) row[at(i)] -= lambda[at(i)], size[at(i)] += abs_q(lambda[at(i)]);
    if (i > 0) row[at(i)] += lambda[at(i - 1)], size[at(i)] += abs_q(lambda[at(i - 1)]);
    if (!cln::zerop(size[at(i)])) worst = max_q(worst, abs_q(row[at(i)]) / size[at(i)]);
  }
  for (int c = 0; c + 1 < n; ++c)
    if (closed.closed(c)) join(c, c + 1);
  for (int i = 0; i < nf; ++i) {
    change[at(group[at(i)])] += p.mass[at(i)] * (W[at(i)] - p.u[at(i)]);
    weight[at(group[at(i)])] += p.mass[at(i)] * ay[at(i)];
  }
  for (int g = 0; g < n; ++g) {
    const bool anchored = p.fixed_bottom && group[at(n - 1)] == g;
    if (!anchored && !cln::zerop(weight[at(g)])) worst = max_q(worst, abs_q(change[at(g)]) / weight[at(g)]);
  }
  return worst;
}

TEST(ResidualCheck, check_DigitsResidualsAreTheExactResidualsOfTheSameNumbers) {
  int compared = 0;
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    const RandomScene rs = random_scene(seed);
    SCOPED_TRACE(rs.origin());
    const ExactScene scene = ExactScene::from(rs.scene());
    for (int d : {20, 100}) {
      const auto pm = Problem<MpFloat>::from(scene, d);
      const auto sm = numeric::solve(pm);
      if (sm.status != numeric::Status::Success) continue;
      const auto pe = exactly(Problem<cl_RA>::from(scene), pm);
      // The answer moved by 2^-30 of the top body's velocity: residuals far
      // above rounding, which the sizes scale.
      std::vector<MpFloat> W = sm.velocities_after;
      W[0] = W[0] + (W[0].is_zero() ? MpFloat(1) : W[0]) * ScalarTraits<MpFloat>::from(cln::expt(cl_RA(2), -30), d);
      std::vector<cl_RA> We, Re;
      for (const MpFloat& w : W) We.push_back(exact_value(w));
      for (const MpFloat& r : sm.reactions) Re.push_back(exact_value(r));
      const Solution<MpFloat> got = checked(pm, W, sm.reactions, sm.closed);
      const Solution<cl_RA> want = checked(pe, We, Re, sm.closed);
      std::vector<cl_RA> lambda;
      for (const cl_RA& r : Re) lambda.push_back(-r);
      const double exact = approx(motion_residual(pe, We, lambda, sm.closed));
      ASSERT_GT(exact, 0);
      EXPECT_NEAR(got.residual_motion / exact, 1, 1e-12) << got.residual_motion << " " << exact;
      EXPECT_NEAR(want.residual_motion / exact, 1, 1e-12) << want.residual_motion << " " << exact;
      if (want.residual_complementarity > 0)
        EXPECT_NEAR(got.residual_complementarity / want.residual_complementarity, 1, 1e-12);
      else
        EXPECT_EQ(got.residual_complementarity, 0);
      EXPECT_EQ(got.status, numeric::Status::NumericalIssue);
      ++compared;
    }
  }
  EXPECT_GE(compared, 60);
}

}  // namespace
}  // namespace superball::testing
