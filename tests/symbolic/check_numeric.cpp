// Randomized cross-check of the two backends: for every case of several
// patterns, the symbolic velocities after the collision and the reactions
// on the closed contacts, evaluated at random rational parameter points
// (positive masses, M diagonally dominant hence positive semi-definite),
// equal the exact solution of the numeric backend with the same contacts
// forced closed (CollisionSolver<cl_RA>::compute_case), bit for bit in rationals.
#include <gtest/gtest.h>

#include <cln/rational.h>

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "superball/numeric/collision.hpp"
#include "superball/numeric/problem.hpp"
#include "superball/symbolic/derivation.hpp"

namespace superball::symbolic {
namespace {

using cln::cl_RA;

/// A random rational in [lo, hi] with denominator up to 12.
cl_RA random_rational(std::mt19937_64& rng, int lo, int hi) {
  std::uniform_int_distribution<int> den(1, 12);
  const int q = den(rng);
  std::uniform_int_distribution<int> num(lo * q, hi * q);
  return cl_RA(num(rng)) / q;
}

GiNaC::numeric to_ginac(const cl_RA& x) { return GiNaC::numeric(cln::cl_N(x)); }

struct Point {
  GiNaC::exmap symbolic;
  numeric::Problem<cl_RA> problem;
};

/// Masses in [1/12, 10], K in [1, 10], couplings with |c| <= min K / (couplings + 1), a in [1, 5].
Point random_point(const Symbols& s, std::mt19937_64& rng) {
  Point pt;
  const int n = s.bodies();
  auto& p = pt.problem;
  p.n = n;
  p.fixed_bottom = s.obstacle() == Obstacle::Infinite;
  p.mass.assign(static_cast<std::size_t>(n), cl_RA(0));
  const cl_RA a = random_rational(rng, 1, 5);
  pt.symbolic[s.fall_speed()] = to_ginac(a);
  for (int i = 0; i < n; ++i) p.u.push_back(i + 1 < n ? cl_RA(-a) : cl_RA(0));
  p.unit = 1;
  const auto couplings = static_cast<int>(s.pattern().couplings.size());
  for (const SymbolInfo& info : s.all()) {
    switch (info.kind) {
      case SymbolKind::Mass: {
        cl_RA m = random_rational(rng, 0, 10);
        if (m <= 0) m = cl_RA(1) / 12;
        p.mass[static_cast<std::size_t>(info.body - 1)] = m;
        pt.symbolic[info.symbol] = to_ginac(m);
        break;
      }
      case SymbolKind::Diagonal: {
        const cl_RA k = random_rational(rng, 1, 10);
        p.entries.push_back({info.first.i - 1, info.first.j - 1, info.first.i - 1, info.first.j - 1, k});
        pt.symbolic[info.symbol] = to_ginac(k);
        break;
      }
      case SymbolKind::Coupling: {
        // Each diagonal is >= 1 and each row of M has at most `couplings` off-diagonal entries of size <= 1/(couplings+1).
        const cl_RA c = random_rational(rng, -1, 1) / (couplings + 1);
        p.entries.push_back({info.first.i - 1, info.first.j - 1, info.second.i - 1, info.second.j - 1, c});
        pt.symbolic[info.symbol] = to_ginac(c);
        break;
      }
      case SymbolKind::FallSpeed: break;
    }
  }
  return pt;
}

GiNaC::numeric value_at(const Fraction& f, const GiNaC::exmap& point) {
  const GiNaC::ex num = f.numerator.subs(point, GiNaC::subs_options::no_pattern);
  const GiNaC::ex den = f.denominator.subs(point, GiNaC::subs_options::no_pattern);
  if (!GiNaC::is_a<GiNaC::numeric>(num) || !GiNaC::is_a<GiNaC::numeric>(den)) throw std::logic_error("value_at(): not a number");
  return GiNaC::ex_to<GiNaC::numeric>(num) / GiNaC::ex_to<GiNaC::numeric>(den);
}

void cross_check(const Pattern& pattern, Obstacle obstacle, std::uint64_t seed, int points) {
  const Deriver deriver(pattern, obstacle);
  const Symbols& s = deriver.symbols();
  std::mt19937_64 rng(seed);
  numeric::CollisionSolver<cl_RA> solver;
  int compared = 0;
  for (const Derivation& d : deriver.derive_all()) {
    for (int k = 0; k < points; ++k) {
      const Point pt = random_point(s, rng);
      numeric::Solution<cl_RA> out;
      solver.compute_case(pt.problem, d.closed, out);
      ASSERT_EQ(out.status, numeric::Status::Success) << d.case_name;
      for (int i = 0; i < s.bodies(); ++i) {
        const GiNaC::numeric sym = value_at(d.velocities[static_cast<std::size_t>(i)], pt.symbolic);
        EXPECT_EQ(sym, to_ginac(out.velocities_after[static_cast<std::size_t>(i)])) << "case " << d.case_name << ", U" << i + 1;
        ++compared;
      }
      for (int c = 0; c + 1 < s.bodies(); ++c) {
        const GiNaC::numeric sym = value_at(d.reactions[static_cast<std::size_t>(c)], pt.symbolic);
        EXPECT_EQ(sym, to_ginac(out.reactions[static_cast<std::size_t>(c)])) << "case " << d.case_name << ", R on contact " << c + 1;
        ++compared;
      }
      // The sign of each condition agrees with the numeric solution: superball U1 > a,
      // evolution U_c > U_{c+1}, contact R <= 0 (exact forms, proved denominators).
      for (const Condition& cond : d.conditions) {
        if (cond.kind == ConditionKind::Psd) continue;
        const ConditionForm& form = cond.finite ? *cond.finite : cond.exact;  // the finite obstacle's own form
        ASSERT_TRUE(form.sign_proved());
        const GiNaC::ex v = form.numerator.subs(pt.symbolic, GiNaC::subs_options::no_pattern);
        ASSERT_TRUE(GiNaC::is_a<GiNaC::numeric>(v));
        const GiNaC::numeric x = GiNaC::ex_to<GiNaC::numeric>(v);
        const bool symbolic_holds = cond.relation == Relation::Greater ? x.is_positive() : !x.is_negative();
        bool numeric_holds = false;
        const cl_RA a = pt.problem.u.front() < 0 ? cl_RA(-pt.problem.u.front()) : pt.problem.u.front();
        if (cond.kind == ConditionKind::Superball) numeric_holds = out.velocities_after[0] > a;
        if (cond.kind == ConditionKind::Evolution || cond.kind == ConditionKind::Contact) {
          const Pair p = Pair::parse(cond.about);
          numeric_holds = cond.kind == ConditionKind::Evolution
                              ? out.velocities_after[static_cast<std::size_t>(p.i - 1)] > out.velocities_after[static_cast<std::size_t>(p.j - 1)]
                              : out.reactions[static_cast<std::size_t>(p.i - 1)] <= 0;
        }
        EXPECT_EQ(symbolic_holds, numeric_holds) << "case " << d.case_name << ", " << to_string(cond.kind) << " " << cond.about;
      }
    }
  }
  EXPECT_GT(compared, 0);
}

TEST(CheckNumeric, PaperAlphaPatternsFixedObstacle) {
  cross_check(Pattern::paper({2}), Obstacle::Infinite, 11, 3);
  cross_check(Pattern::paper({1, 6}), Obstacle::Infinite, 12, 3);
  cross_check(Pattern::paper({5}), Obstacle::Infinite, 13, 3);
  cross_check(Pattern::paper({4}), Obstacle::Infinite, 14, 3);
  cross_check(Pattern::paper({7}), Obstacle::Infinite, 15, 3);
}

TEST(CheckNumeric, AllSevenAlphas) {
  cross_check(Pattern::paper({1, 2, 3, 4, 5, 6, 7}), Obstacle::Infinite, 21, 2);
  cross_check(Pattern::paper({1, 2, 3, 4, 5, 6, 7}), Obstacle::Finite, 22, 1);
}

TEST(CheckNumeric, FiniteObstacle) {
  cross_check(Pattern::paper({2}), Obstacle::Finite, 31, 3);
  cross_check(Pattern::all_pairs(3), Obstacle::Finite, 32, 3);
  cross_check(Pattern::all_pairs(2), Obstacle::Finite, 33, 3);
}

TEST(CheckNumeric, OtherBodyCounts) {
  cross_check(Pattern::all_pairs(2), Obstacle::Infinite, 41, 3);
  cross_check(Pattern::all_pairs(3, {{Pair{1, 2}, Pair{1, 3}}}), Obstacle::Infinite, 42, 3);
  cross_check(Pattern::near(5, 1), Obstacle::Infinite, 43, 2);
  cross_check(Pattern::nearest_and_next_nearest(5), Obstacle::Infinite, 44, 2);
  cross_check(Pattern::near(6, 2), Obstacle::Infinite, 45, 1);
}

}  // namespace
}  // namespace superball::symbolic
