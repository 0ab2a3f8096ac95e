// check_: the derivation's polynomial arithmetic (symbolic/src/poly.hpp)
// against GiNaC on random polynomials: sums, products, determinants of
// random banded matrices, leading coefficients, monomial division,
// specialisation.  Each result is compared as an expanded polynomial
// (GiNaC's normal form), so a wrong term order, a lost cancellation or an
// exponent packed into the wrong byte shows.
#include <gtest/gtest.h>

#include <random>

#include "poly.hpp"
#include "polynomial.hpp"
#include "superball/symbolic/symbols.hpp"

namespace superball::symbolic {
namespace {

using detail::Poly;

/// Same polynomial: GiNaC's expanded difference is 0.
::testing::AssertionResult same(const Poly& p, const GiNaC::ex& e, const Symbols& s) {
  const GiNaC::ex d = GiNaC::expand(p.to_ex(s) - e);
  if (d.is_zero()) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "differs by " << d;
}

struct Random {
  std::mt19937_64 engine;
  explicit Random(std::uint64_t seed) : engine(seed) {}
  int below(int n) { return static_cast<int>(engine() % static_cast<std::uint64_t>(n)); }
  /// A random polynomial with up to \p terms terms, coefficients in [−20, 20], exponents up to 3.
  GiNaC::ex polynomial(const Symbols& s, int terms) {
    GiNaC::ex p = 0;
    const int vars = static_cast<int>(s.all().size());
    for (int t = below(terms + 1); t > 0; --t) {
      GiNaC::ex term = below(41) - 20;
      for (int f = below(4); f > 0; --f) term *= GiNaC::pow(s.all()[static_cast<std::size_t>(below(vars))].symbol, 1 + below(3));
      p += term;
    }
    return GiNaC::expand(p);
  }
};

/// The 7-body near-neighbour pattern has 41 symbols: six 64-bit words of exponents, one of them partial.
const Symbols& symbols() {
  static const Symbols s(Pattern::nearest_and_next_nearest(7), Obstacle::Finite);
  return s;
}

TEST(CheckPoly, ArithmeticAgreesWithGinac) {
  const Symbols& s = symbols();
  ASSERT_GT(s.all().size(), 16u);
  Random random(20261125);
  for (int round = 0; round < 300; ++round) {
    const GiNaC::ex x = random.polynomial(s, 12), y = random.polynomial(s, 12);
    const Poly px = Poly::from_ex(x, s), py = Poly::from_ex(y, s);
    ASSERT_TRUE(same(px, x, s)) << "round " << round;
    EXPECT_TRUE(same(px + py, x + y, s)) << "round " << round;
    EXPECT_TRUE(same(px - py, x - y, s)) << "round " << round;
    EXPECT_TRUE(same(px * py, x * y, s)) << "round " << round;
    EXPECT_TRUE((px - px).is_zero());
    EXPECT_EQ(px * py, py * px);
    EXPECT_EQ((px + py) * py, px * py + py * py);  // term lists equal: one canonical order
    const int k = random.below(static_cast<int>(s.all().size()));
    const GiNaC::ex& xk = s.all()[static_cast<std::size_t>(k)].symbol;
    EXPECT_EQ(px.degree(k), x.degree(xk));
    if (!x.is_zero()) {
      EXPECT_TRUE(same(px.leading_coefficient(k), x.lcoeff(xk), s)) << "round " << round;
    }
  }
}

TEST(CheckPoly, ProductsByFewTermsAndUnexpandedInputAgreeWithGinac) {
  const Symbols& s = symbols();
  Random random(20261127);
  for (int round = 0; round < 200; ++round) {
    // A factor of at most 8 terms is merged (shifted copies of the other), a larger one hashed.
    const GiNaC::ex small = random.polynomial(s, 8), large = random.polynomial(s, 60);
    const Poly ps = Poly::from_ex(small, s), pl = Poly::from_ex(large, s);
    const Poly product = pl * ps;
    EXPECT_TRUE(same(product, small * large, s)) << "round " << round;
    EXPECT_EQ(product, ps * pl);
    EXPECT_EQ(product, Poly::from_ex(GiNaC::expand(small * large), s));
    EXPECT_TRUE((pl * (ps - ps)).is_zero());
    EXPECT_TRUE((pl * ps - ps * pl).is_zero());
    // An expression that is not an expanded sum of monomials (a product of sums among
    // its terms) is expanded first, whatever was read before that term.
    const GiNaC::ex unexpanded = small * large + GiNaC::pow(small, 2);
    EXPECT_TRUE(same(Poly::from_ex(unexpanded, s), unexpanded, s)) << "round " << round;
  }
  const GiNaC::ex& x = s.all()[3].symbol;
  const Poly high = Poly::from_ex(GiNaC::pow(x, 100) + 1, s);
  EXPECT_THROW((void)(high * high), std::overflow_error);
  EXPECT_THROW((void)Poly::from_ex(x / 2 + 1, s), std::invalid_argument);
}

TEST(CheckPoly, MonomialDivisionContentAndSpecialisation) {
  const Symbols& s = symbols();
  Random random(7);
  const int vars = static_cast<int>(s.all().size());
  for (int round = 0; round < 100; ++round) {
    const GiNaC::ex x = random.polynomial(s, 8);
    if (x.is_zero()) continue;
    // Multiply by a known monomial and a known integer; both must come back out.
    GiNaC::ex monomial = 1;
    for (int f = 0; f < 3; ++f) monomial *= s.all()[static_cast<std::size_t>(random.below(vars))].symbol;
    const Poly p = Poly::from_ex(GiNaC::expand(6 * monomial * x), s);
    const std::vector<int> common = p.common_exponents();
    GiNaC::ex g = 1;
    for (int k = 0; k < vars; ++k) g *= GiNaC::pow(s.all()[static_cast<std::size_t>(k)].symbol, common[static_cast<std::size_t>(k)]);
    GiNaC::ex q;
    EXPECT_TRUE(GiNaC::divide(g, monomial, q)) << "the common monomial " << g << " must contain " << monomial;
    EXPECT_TRUE(same(p.divided_by_monomial(common), GiNaC::expand(6 * monomial * x / g), s));
    EXPECT_TRUE(cln::zerop(cln::mod(p.content(), 6)));
    // Specialise every symbol but one at integers.
    std::vector<cln::cl_I> point;
    GiNaC::exmap at;
    for (int k = 0; k < vars; ++k) {
      point.push_back(random.below(9) - 4);
      at[s.all()[static_cast<std::size_t>(k)].symbol] = GiNaC::numeric(cln::cl_N(point.back()));
    }
    const GiNaC::ex value = GiNaC::expand(6 * monomial * x).subs(at);
    EXPECT_TRUE(GiNaC::numeric(cln::cl_N(p.evaluate(point))).is_equal(GiNaC::ex_to<GiNaC::numeric>(value)));
  }
}

TEST(CheckPoly, ModularSpecialisationAndGcdAgreeWithGinac) {
  const Symbols& s = symbols();
  Random random(61);
  const int vars = static_cast<int>(s.all().size());
  const GiNaC::ex& x = s.all().front().symbol;
  for (int round = 0; round < 100; ++round) {
    // Two polynomials with a known common factor (or none), specialised at integers but x.
    const GiNaC::ex common = round % 2 ? random.polynomial(s, 3) + x : GiNaC::ex(1);
    const GiNaC::ex f = GiNaC::expand(common * (random.polynomial(s, 5) + x)), g = GiNaC::expand(common * (random.polynomial(s, 5) + 1));
    std::vector<cln::cl_I> point;
    std::vector<std::uint64_t> point_mod;
    GiNaC::exmap at;
    for (int k = 0; k < vars; ++k) {
      point.push_back(random.below(2001) - 1000);
      point_mod.push_back(detail::mod61::reduce(point.back()));
      if (k) at[s.all()[static_cast<std::size_t>(k)].symbol] = GiNaC::numeric(cln::cl_N(point.back()));
    }
    const Poly pf = Poly::from_ex(f, s), pg = Poly::from_ex(g, s);
    const std::vector<cln::cl_I> exact = pf.univariate(0, point);
    const std::vector<std::uint64_t> reduced = pf.univariate_mod(0, point_mod);
    for (std::size_t d = 0; d < reduced.size(); ++d) EXPECT_EQ(reduced[d], detail::mod61::reduce(exact[d]));
    const GiNaC::ex fa = GiNaC::expand(f.subs(at)), ga = GiNaC::expand(g.subs(at));
    const std::vector<std::uint64_t> gm = pg.univariate_mod(0, point_mod);
    if (reduced.empty() || gm.empty()) continue;
    const int expected = GiNaC::gcd(fa, ga).degree(x);
    // Modulo the prime the gcd can only be as large or larger; with these small integers it is the same.
    EXPECT_EQ(detail::mod61::gcd_degree(reduced, gm), expected) << "round " << round;
  }
}

TEST(CheckPoly, BandedDeterminantsAgreeWithGinac) {
  const Symbols& s = symbols();
  Random random(42);
  for (int n = 1; n <= 6; ++n)
    for (int band = 0; band <= 2; ++band) {
      GiNaC::matrix m(static_cast<unsigned>(n), static_cast<unsigned>(n));
      std::vector<Poly> pm;
      for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c) {
          const GiNaC::ex e = std::abs(r - c) <= band ? random.polynomial(s, 3) : GiNaC::ex(0);
          m(static_cast<unsigned>(r), static_cast<unsigned>(c)) = e;
          pm.push_back(Poly::from_ex(e, s));
        }
      const GiNaC::ex expected = GiNaC::expand(m.determinant(GiNaC::determinant_algo::laplace));
      EXPECT_TRUE(same(detail::determinant(pm, n, static_cast<int>(s.all().size())), expected, s)) << "n = " << n << ", band " << band;
    }
}

TEST(CheckPoly, ToExGivesGinacsOwnCanonicalForm) {
  // to_ex() marks the sums and products it builds as evaluated: they must be
  // the objects GiNaC's own evaluation gives (the same structure and hash),
  // down to one term, one symbol, a constant and zero.
  const Symbols& s = symbols();
  const GiNaC::ex& x = s.all()[0].symbol;
  const GiNaC::ex& y = s.all()[9].symbol;
  std::vector<GiNaC::ex> cases = {0, 7, x, -x, 3 * x, GiNaC::pow(x, 2), 5 * x * y, x * GiNaC::pow(y, 3) + 2, x + 1, x + y, -x - y - 4};
  Random random(12);
  for (int round = 0; round < 200; ++round) cases.push_back(random.polynomial(s, 1 + random.below(12)));
  for (const GiNaC::ex& e : cases) {
    const GiNaC::ex back = Poly::from_ex(e, s).to_ex(s);
    EXPECT_TRUE(back.is_equal(e)) << e << " came back as " << back;
    EXPECT_EQ(back.gethash(), e.gethash()) << e;
    EXPECT_EQ(back.compare(e), 0) << e;
    EXPECT_TRUE(GiNaC::expand(back - e).is_zero()) << e;
  }
}

TEST(CheckPoly, LineAndPointModuloThePrimeAgreeWithGinac) {
  const Symbols& s = symbols();
  Random random(2611);
  const auto vars = s.all().size();
  const GiNaC::symbol t("t");
  for (int round = 0; round < 60; ++round) {
    const GiNaC::ex f = random.polynomial(s, 10);
    std::vector<cln::cl_I> point;
    std::vector<std::uint64_t> a, b, point_mod;
    GiNaC::exmap line, at;
    for (std::size_t k = 0; k < vars; ++k) {
      const int ak = random.below(2001) - 1000, bk = random.below(2001) - 1000;
      a.push_back(detail::mod61::reduce(ak));
      b.push_back(detail::mod61::reduce(bk));
      line[s.all()[k].symbol] = ak + bk * t;
      point.push_back(ak);
      point_mod.push_back(a.back());
      at[s.all()[k].symbol] = ak;
    }
    const Poly p = Poly::from_ex(f, s);
    const GiNaC::ex on_line = GiNaC::expand(f.subs(line));
    std::vector<std::uint64_t> expected;
    for (int d = 0; d <= on_line.degree(t); ++d)
      expected.push_back(detail::mod61::reduce(cln::the<cln::cl_I>(GiNaC::ex_to<GiNaC::numeric>(on_line.coeff(t, d)).to_cl_N())));
    while (!expected.empty() && expected.back() == 0) expected.pop_back();
    EXPECT_EQ(p.on_line_mod(a, b), expected) << "round " << round;
    EXPECT_EQ(p.evaluate_mod(point_mod), detail::mod61::reduce(p.evaluate(point))) << "round " << round;
    EXPECT_EQ(p.evaluate(point), cln::the<cln::cl_I>(GiNaC::ex_to<GiNaC::numeric>(f.subs(at)).to_cl_N())) << "round " << round;
    int total = 0;
    for (const GiNaC::ex& term : GiNaC::is_a<GiNaC::add>(f) ? std::vector<GiNaC::ex>(f.begin(), f.end()) : std::vector<GiNaC::ex>{f}) {
      int d = 0;
      for (std::size_t k = 0; k < vars; ++k) d += term.degree(s.all()[k].symbol);
      total = std::max(total, d);
    }
    EXPECT_EQ(p.total_degree(), f.is_zero() ? 0 : total) << "round " << round;
  }
}

TEST(CheckPoly, CoprimalityIsProvedExactlyWhenTheGcdIsConstant) {
  // coprime_with() answers true only with a proof; with these polynomials
  // (a common factor or none) its proofs succeed, so it agrees with GiNaC's gcd.
  const Symbols& s = symbols();
  Random random(77);
  const GiNaC::ex& x = s.all()[3].symbol;
  int coprime = 0, not_coprime = 0;
  for (int round = 0; round < 80; ++round) {
    const GiNaC::ex common = round % 2 ? random.polynomial(s, 3) + x : GiNaC::ex(1);
    const GiNaC::ex q = GiNaC::expand(common * (random.polynomial(s, 6) + x + 1));
    const GiNaC::ex p = GiNaC::expand(common * (random.polynomial(s, 6) + 2));
    if (p.is_zero() || GiNaC::is_a<GiNaC::numeric>(q)) continue;
    const bool expected = GiNaC::is_a<GiNaC::numeric>(GiNaC::gcd(p, q));
    const detail::Denominator denominator(Poly::from_ex(q, s), s);
    EXPECT_EQ(denominator.coprime_with(Poly::from_ex(p, s)), expected) << "round " << round << ": p = " << p << ", q = " << q;
    (expected ? coprime : not_coprime) += 1;
  }
  EXPECT_GT(coprime, 20);
  EXPECT_GT(not_coprime, 20);
}

TEST(CheckPoly, MisuseIsAnError) {
  const Symbols& s = symbols();
  const int vars = static_cast<int>(s.all().size());
  EXPECT_THROW(Poly::variable(vars, vars), std::invalid_argument);
  EXPECT_THROW(Poly::from_ex(s.all().front().symbol / 2, s), std::invalid_argument);
  EXPECT_THROW(Poly::from_ex(GiNaC::pow(s.all().front().symbol, 200), s), std::invalid_argument);
  const Poly x = Poly::from_ex(GiNaC::pow(s.all().front().symbol, 100), s);
  EXPECT_THROW(x * x, std::overflow_error);
  EXPECT_THROW(detail::determinant({Poly(vars)}, 2, vars), std::invalid_argument);
}

}  // namespace
}  // namespace superball::symbolic
