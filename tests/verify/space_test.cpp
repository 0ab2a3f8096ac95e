// The parameter space of a pattern: compiled polynomials equal GiNaC's
// substitution, sampled points are admissible and reproducible, a point's
// scene file solves to the point's problem, the derived exact conditions of
// a case agree with the exact solution at every sampled point, and clones
// evaluate the same in parallel threads.
#include <gtest/gtest.h>

#include <thread>

#include "superball/cases/scene_file.hpp"
#include "superball/numeric/collision.hpp"
#include "superball/verify/space.hpp"

namespace superball::verify {
namespace {

using cln::cl_RA;
using symbolic::Deriver;
using symbolic::Obstacle;
using symbolic::Pattern;

GiNaC::exmap substitution(const symbolic::Symbols& s, const Point& x) {
  GiNaC::exmap m;
  for (std::size_t k = 0; k < x.size(); ++k) m[s.all()[k].symbol] = GiNaC::numeric(cln::cl_N(x[k]));
  return m;
}

TEST(Space, check_CompiledPolynomialEqualsSubstitution) {
  const Deriver d(Pattern::paper({2, 5}), Obstacle::Finite);
  const ParameterSpace space(d);
  const symbolic::Derivation case1 = d.derive(ContactSet::parse("2-3,3-4", 4));
  RegimeSampler sampler(space, cl_RA(1) / 100, 7);
  for (int k = 0; k < 20; ++k) {
    const auto x = sampler.draw();
    ASSERT_TRUE(x);
    const GiNaC::exmap at = substitution(d.symbols(), *x);
    for (const symbolic::Condition& c : case1.conditions) {
      const Polynomial p(c.exact.numerator, d.symbols());
      const GiNaC::ex expected = c.exact.numerator.subs(at, GiNaC::subs_options::no_pattern);
      EXPECT_TRUE((GiNaC::numeric(cln::cl_N(p(*x))) - GiNaC::ex_to<GiNaC::numeric>(expected)).is_zero()) << c.about;
      EXPECT_TRUE((GiNaC::numeric(cln::cl_N(p.clone()(*x))) - GiNaC::ex_to<GiNaC::numeric>(expected)).is_zero());
      std::vector<double> xd;
      for (const cl_RA& v : *x) xd.push_back(cln::double_approx(v));
      const double exact = cln::double_approx(p(*x));
      EXPECT_NEAR(p(xd), exact, 1e-9 * (1 + std::abs(exact)) + 1e-6 * std::abs(exact)) << c.about;
    }
  }
}

/// The sign of the exact value of \p p at \p x.
int exact_sign(const Polynomial& p, const Point& x) {
  const cl_RA v = p(x);
  return cln::zerop(v) ? 0 : cln::minusp(v) ? -1 : 1;
}

TEST(Space, check_SignInDoubleIsTheExactSignEvenAtAndNearZeros) {
  // The derived conditions of two cases at drawn points of three regimes, and of every
  // exact factor of M's PSD check: sign() is the sign of the exact value.
  const Deriver d(Pattern::paper({2, 5}), Obstacle::Finite);
  const ParameterSpace space(d);
  int compared = 0;
  for (const char* closed : {"2-3,3-4", "3-4"}) {
    const symbolic::Derivation c = d.derive(ContactSet::parse(closed, 4));
    for (const cl_RA& eps : {cl_RA(1) / 10, cl_RA(1) / 1000, cl_RA(1) / 1000000}) {
      RegimeSampler sampler(space, eps, 11);
      for (int k = 0; k < 40; ++k) {
        const auto x = sampler.draw();
        ASSERT_TRUE(x);
        for (const symbolic::Condition& cond : c.conditions) {
          const Polynomial p(cond.exact.numerator, d.symbols());
          EXPECT_EQ(p.sign(*x), exact_sign(p, *x)) << cond.about;
          ++compared;
        }
      }
    }
  }
  EXPECT_GT(compared, 200);
  // Cancellation: (m1 − m2)^3 (m1 + m2) expanded, at m1 = m2 exactly, 1 ulp away and near; a sum whose terms
  // cancel to far below their size; coordinates of 10^±200.
  const GiNaC::ex m1 = d.symbols().mass(1), m2 = d.symbols().mass(2);
  const std::size_t i1 = space.index("m1"), i2 = space.index("m2");
  const Polynomial cubic(GiNaC::expand(GiNaC::pow(m1 - m2, 3) * (m1 + m2)), d.symbols());
  const Polynomial shifted(GiNaC::expand(GiNaC::pow(m1 - m2, 2) - GiNaC::numeric(1, 1000000) * m2 * m2), d.symbols());
  Point x(d.symbols().all().size(), cl_RA(1));
  for (const cl_RA& at : {cl_RA(3) / 7, cl_RA(10000001) / 10000000, cl_RA(1) / 1000, cl_RA(2) / 3 + cln::expt(cl_RA(2), -60),
                          cln::expt(cl_RA(10), 200), cln::expt(cl_RA(10), -200), cl_RA(1001) / 1000, cl_RA(999) / 1000}) {
    for (const cl_RA& ratio : {cl_RA(1), 1 + cln::expt(cl_RA(2), -52), 1 - cln::expt(cl_RA(2), -53), 1 + cln::expt(cl_RA(10), -3),
                               cl_RA(1001) / 1000, cl_RA(999) / 1000, cl_RA(-1)}) {
      x[i1] = at * ratio, x[i2] = at;
      EXPECT_EQ(cubic.sign(x), exact_sign(cubic, x));
      EXPECT_EQ(shifted.sign(x), exact_sign(shifted, x));
      EXPECT_EQ(cubic.clone().sign(x), exact_sign(cubic, x));
    }
  }
  x[i1] = x[i2] = cl_RA(5) / 3;
  EXPECT_EQ(cubic.sign(x), 0);
  EXPECT_EQ(Polynomial(m1 - m1, d.symbols()).sign(x), 0);
}

TEST(Space, exam_PolynomialRejectsNonPolynomials) {
  const Deriver d(Pattern::paper({2}), Obstacle::Infinite);
  const GiNaC::ex m1 = d.symbols().mass(1);
  EXPECT_THROW(Polynomial(1 / m1, d.symbols()), std::invalid_argument);
  EXPECT_THROW(Polynomial(GiNaC::sqrt(m1), d.symbols()), std::invalid_argument);
  EXPECT_TRUE(Polynomial(m1 - m1, d.symbols()).is_zero());
}

TEST(Space, exam_SamplerIsReproducibleAndAdmissible) {
  const Deriver d(Pattern::paper({1, 2, 3}), Obstacle::Infinite);
  const ParameterSpace space(d);
  RegimeSampler a(space, cl_RA(1) / 1000, 42), b(space, cl_RA(1) / 1000, 42);
  for (int k = 0; k < 50; ++k) {
    const auto x = a.draw(), y = b.draw();
    ASSERT_TRUE(x && y);
    EXPECT_TRUE(space.admissible(*x));
    for (std::size_t i = 0; i < x->size(); ++i) EXPECT_EQ((*x)[i], (*y)[i]);
    // the regime: m1 ~ eps, K14 ~ 1/eps
    EXPECT_LE((*x)[static_cast<std::size_t>(space.index("m1"))], cl_RA(30) / 1000);
    EXPECT_GE((*x)[static_cast<std::size_t>(space.index("K14"))], cl_RA(100));
  }
  Point bad = *a.draw();
  bad[static_cast<std::size_t>(space.index("alpha2"))] = 1000000;  // alpha2^2 > K12 K14
  EXPECT_FALSE(space.admissible(bad));
  EXPECT_THROW(space.index("alpha4"), std::invalid_argument);
}

TEST(Space, check_SceneOfAPointSolvesToItsProblem) {
  for (Obstacle obstacle : {Obstacle::Infinite, Obstacle::Finite}) {
    const Deriver d(Pattern::paper({2, 4}), obstacle);
    const ParameterSpace space(d);
    RegimeSampler sampler(space, cl_RA(1) / 100, 3);
    numeric::CollisionSolver<cl_RA> solver;
    for (int k = 0; k < 10; ++k) {
      const Point x = *sampler.draw();
      const Scene scene = parse_scene(write_scene(space.scene(x, "point")), "point.toml");
      const auto from_file = numeric::Problem<cl_RA>::from(numeric::ExactScene::from(scene));
      const auto a = solver.compute(space.problem(x)), b = solver.compute(from_file);
      ASSERT_EQ(a.status, numeric::Status::Success);
      EXPECT_EQ(a.closed, b.closed);
      for (std::size_t i = 0; i < a.velocities_after.size(); ++i)
        EXPECT_EQ(a.velocities_after[i], b.velocities_after[i] * from_file.unit);
    }
  }
}

/// With the obstacle fixed, the derived exact conditions of a case are exact:
/// each agrees with the exact solution of the imposed case at every point.
TEST(Space, check_ExactConditionsAgreeWithTheExactSolution) {
  const Deriver d(Pattern::paper({2, 5}), Obstacle::Infinite);
  const ParameterSpace space(d);
  numeric::CollisionSolver<cl_RA> solver;
  for (const symbolic::Derivation& c : d.derive_all()) {
    RegimeSampler sampler(space, cl_RA(1) / 100, 11);
    for (int k = 0; k < 40; ++k) {
      const Point x = *sampler.draw();
      const auto problem = space.problem(x);
      numeric::Solution<cl_RA> forced;
      solver.compute_case(problem, c.closed, forced);
      for (const symbolic::Condition& cond : c.conditions) {
        if (cond.kind == symbolic::ConditionKind::Psd) continue;
        const CompiledCondition compiled(cond, cond.exact, d.symbols());
        std::string quantity;
        EXPECT_EQ(compiled.holds(x), condition_truth(cond.kind, cond.about, problem, forced, &quantity))
            << "case " << c.case_name << " " << to_string(cond.kind) << " " << cond.about << ": " << quantity;
      }
    }
  }
}

TEST(Space, check_ClonesEvaluateTheSameInThreads) {
  const Deriver d(Pattern::paper({2}), Obstacle::Infinite);
  const ParameterSpace space(d);
  const symbolic::Derivation c = d.derive(ContactSet::parse("2-3,3-4", 4));
  const CompiledCondition superball(c.conditions.front(), c.conditions.front().exact, d.symbols());
  auto run = [](const ParameterSpace& s, const CompiledCondition& cond, std::vector<int>& out) {
    RegimeSampler sampler(s, cl_RA(1) / 1000, 5);
    numeric::CollisionSolver<cl_RA> solver;
    for (int k = 0; k < 200; ++k) {
      const Point x = *sampler.draw();
      out.push_back(cond.holds(x) ? 1 : 0);
      out.push_back(solver.compute(s.problem(x)).closed.closed(0) ? 1 : 0);
    }
  };
  std::vector<int> serial, first, second;
  run(space, superball, serial);
  const ParameterSpace s1 = space.clone(), s2 = space.clone();
  const CompiledCondition c1 = superball.clone(), c2 = superball.clone();
  std::thread t1([&] { run(s1, c1, first); }), t2([&] { run(s2, c2, second); });
  t1.join();
  t2.join();
  EXPECT_EQ(serial, first);
  EXPECT_EQ(serial, second);
}

}  // namespace
}  // namespace superball::verify
