// The numeric entry point: ExactScene::from (exact checks, positive
// semi-definiteness of M decided exactly), Problem<S>::from, the precisions
// and the scalar conversions.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "scalar_internal.hpp"
#include "superball/numeric/precision.hpp"
#include "support.hpp"

namespace superball::testing {
namespace {

/// Positive semi-definite by definition: every principal minor >= 0.
bool psd_by_minors(const Matrix& M) {
  const int m = static_cast<int>(M.size());
  for (std::uint32_t mask = 1; mask < (1u << m); ++mask) {
    std::vector<int> idx;
    for (int i = 0; i < m; ++i)
      if (mask >> i & 1u) idx.push_back(i);
    if (determinant(principal(M, idx)) < 0) return false;
  }
  return true;
}

/// find_negative_minor on a dense matrix (its nonzero entries).
std::optional<numeric::NegativeMinor> negative_minor(const Matrix& M) {
  numeric::SymmetricRows rows(M.size());
  for (std::size_t i = 0; i < M.size(); ++i)
    for (std::size_t j = 0; j < M.size(); ++j)
      if (!cln::zerop(M[i][j])) rows[i][static_cast<int>(j)] = M[i][j];
  return numeric::find_negative_minor(std::move(rows));
}

TEST(FindNegativeMinor, SmallMatrices) {
  EXPECT_FALSE(negative_minor({}).has_value());
  EXPECT_FALSE(negative_minor({{0}}).has_value());
  EXPECT_FALSE(negative_minor({{1, 1}, {1, 1}}).has_value());  // singular, on the boundary
  const auto a = negative_minor({{1, 2}, {2, 1}});
  ASSERT_TRUE(a.has_value());
  EXPECT_EQ(a->indices, (std::vector<int>{0, 1}));
  EXPECT_EQ(a->determinant, -3);
  const auto b = negative_minor({{0, 1}, {1, 0}});
  ASSERT_TRUE(b.has_value());
  EXPECT_EQ(b->determinant, -1);
  const auto c = negative_minor({{1, 0}, {0, -1}});
  ASSERT_TRUE(c.has_value());
  EXPECT_EQ(c->indices, (std::vector<int>{1}));
  EXPECT_EQ(c->determinant, -1);
  // Every 2x2 minor >= 0 but the 3x3 one negative.
  const Matrix m3 = {{1, cl_RA(-9) / 10, cl_RA(-9) / 10}, {cl_RA(-9) / 10, 1, cl_RA(-9) / 10}, {cl_RA(-9) / 10, cl_RA(-9) / 10, 1}};
  const auto d = negative_minor(m3);
  ASSERT_TRUE(d.has_value());
  EXPECT_EQ(d->indices.size(), 3u);
  EXPECT_EQ(d->determinant, determinant(m3));
  EXPECT_TRUE(d->determinant < 0);
}

TEST(FindNegativeMinor, AgreesWithTheDefinitionOnRandomMatrices) {
  // B^T B is PSD; B^T B - t e e^T with small t is often not; the answer must
  // be the definition's (all principal minors >= 0), and a reported minor
  // must be a principal minor of M with exactly the reported negative value.
  int psd = 0, not_psd = 0;
  for (std::uint64_t seed = 1; seed <= 300; ++seed) {
    Rng rng(seed);
    const int m = rng.between(1, 6), r = rng.between(1, m + 1);
    Matrix B(static_cast<std::size_t>(r), std::vector<cl_RA>(static_cast<std::size_t>(m)));
    for (auto& row : B)
      for (auto& x : row) x = rng.chance(40) ? 0 : rng.between(-3, 3);
    Matrix M(static_cast<std::size_t>(m), std::vector<cl_RA>(static_cast<std::size_t>(m), cl_RA(0)));
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < m; ++j)
        for (const auto& row : B) M[i][j] = M[i][j] + row[i] * row[j];
    if (rng.chance(50)) {
      const int i = rng.below(m), j = rng.below(m);
      const cl_RA t = cl_RA(rng.between(1, 4)) / rng.between(1, 8);
      M[i][j] = M[i][j] - t;
      if (i != j) M[j][i] = M[j][i] - t;
    }
    SCOPED_TRACE("seed " + std::to_string(seed));
    const auto found = negative_minor(M);
    const bool definition = psd_by_minors(M);
    EXPECT_EQ(!found.has_value(), definition);
    (definition ? psd : not_psd) += 1;
    if (found) {
      for (std::size_t k = 1; k < found->indices.size(); ++k) EXPECT_LT(found->indices[k - 1], found->indices[k]);
      EXPECT_EQ(found->determinant, determinant(principal(M, found->indices)));
      EXPECT_TRUE(found->determinant < 0);
    }
  }
  EXPECT_GT(psd, 50);
  EXPECT_GT(not_psd, 50);
}

const char* const kBoundary = R"(
fall_speed = 1
[[body]]
mass = 1
[[body]]
mass = 1
[[body]]
mass = 1
[[body]]
mass = "inf"
[dissipation]
K = { "1-2" = 4, "1-4" = 9 }
)";

TEST(ExactScene, MOnTheBoundaryIsAccepted) {
  // alpha_2² = K12 K14 exactly: M is singular, still positive semi-definite.
  Scene s = parse_scene(kBoundary, "boundary.toml");
  s.entries.push_back({Pair::parse("1-2"), Pair::parse("1-4"), Number::parse("-6")});
  EXPECT_NO_THROW(ExactScene::from(s));
  s.entries.back().value = Number::parse("6");
  EXPECT_NO_THROW(ExactScene::from(s));
  // A hair beyond: alpha_2² = 36 + 1/1000000 > K12 K14.
  s.entries.back().value = Number::parse("6.0000001");
  try {
    ExactScene::from(s);
    ADD_FAILURE() << "M with a negative minor accepted";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("boundary.toml: dissipation: M is not positive semi-definite", 0), 0u) << what;
    EXPECT_NE(what.find("1-2, 1-4"), std::string::npos) << "names the pairs of the minor: " << what;
    // det [[4, 6.0000001], [6.0000001, 9]] = 36 - 36.00000120000001 = -0.00000120000001
    EXPECT_NE(what.find("-120000001/100000000000000"), std::string::npos) << "gives the exact minor: " << what;
    EXPECT_EQ(what.find('\n'), std::string::npos);
  }
}

TEST(ExactScene, ThePaperScene) {
  const ExactScene s = ExactScene::from(load_scene(std::string(SUPERBALL_CASES_DIR) + "/scenes/paper-4.4-alpha2.toml"));
  EXPECT_EQ(s.n, 4);
  EXPECT_FALSE(s.fixed_bottom);
  EXPECT_EQ(s.mass, (std::vector<cl_RA>{cl_RA(1) / 1000, 10, 15, 5000000}));
  EXPECT_EQ(s.fall, (std::vector<cl_RA>{-1, -1, -1, 0}));
  EXPECT_EQ(s.velocity, (std::vector<cl_RA>{0, 0, 0, 0}));
  ASSERT_TRUE(s.a_squared.has_value());
  EXPECT_EQ(*s.a_squared, cln::expt(cl_RA(313209) / 100000, 2));
  EXPECT_TRUE(s.homogeneous());
  EXPECT_EQ(s.unit_squared(), *s.a_squared);
  EXPECT_EQ(s.exact_u(), s.fall);
  EXPECT_EQ(s.entries.size(), 7u);
}

TEST(ExactScene, DropHeightGivesAnIrrationalUnit) {
  const Scene scene = load_scene(std::string(SUPERBALL_TEST_DATA_DIR) + "/good/paper-4.4-alpha4-float-inf.toml");
  const ExactScene s = ExactScene::from(scene);
  EXPECT_TRUE(s.fixed_bottom);
  EXPECT_EQ(*s.a_squared, cl_RA(981) / 100);  // 2 g h = 2 · 9.81 · 0.5
  // Homogeneous: the exact solve runs in units of a and says so.
  const auto pe = Problem<cl_RA>::from(s);
  EXPECT_FALSE(pe.unit_exact);
  EXPECT_EQ(pe.unit, 1);
  EXPECT_EQ(pe.u, s.fall);
  const auto pd = Problem<double>::from(s);
  EXPECT_TRUE(pd.unit_exact);
  EXPECT_DOUBLE_EQ(pd.unit, std::sqrt(9.81));
  // Same velocities in units of a in both.
  const auto we = numeric::solve(pe).velocities_after;
  const auto wd = numeric::solve(pd).velocities_after;
  for (std::size_t i = 0; i < we.size(); ++i) EXPECT_NEAR(wd[i], approx(we[i]), 1e-12) << i;
}

TEST(ExactScene, NonHomogeneousIrrationalFallIsRefusedInExactArithmeticOnly) {
  Scene scene = load_scene(std::string(SUPERBALL_TEST_DATA_DIR) + "/good/fractions-and-couplings.toml");
  // h = 1/2, g = 9.81: a = sqrt(9.81) irrational, and bodies 3 and 4 have their own
  // velocities -29/10 and -1/4.
  const ExactScene s = ExactScene::from(scene);
  EXPECT_FALSE(s.homogeneous());
  EXPECT_FALSE(s.exact_u().has_value());
  try {
    Problem<cl_RA>::from(s);
    ADD_FAILURE() << "an irrational velocity accepted in exact arithmetic";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind(scene.origin + ": ", 0), 0u) << what;
    EXPECT_NE(what.find("irrational"), std::string::npos) << what;
  }
  const auto p = Problem<double>::from(s);
  EXPECT_EQ(p.unit, 1);
  EXPECT_DOUBLE_EQ(p.u[0], -std::sqrt(9.81));
  EXPECT_DOUBLE_EQ(p.u[2], -2.9);
  EXPECT_DOUBLE_EQ(p.u[3], -0.25);
  EXPECT_EQ(p.u[4], 0);
  const auto pl = Problem<long double>::from(s);
  EXPECT_NEAR(static_cast<double>(pl.u[0]), -std::sqrt(9.81), 1e-15);
  const auto pc = Problem<cl_R>::from(s, 40);
  EXPECT_TRUE(abs_q(exact_value(pc.u[0] * pc.u[0]) - cl_RA(981) / 100) < cln::expt(cl_RA(10), -38));
  // With a rational fall speed the exact solve works.
  scene.drop_height.reset();
  scene.fall_speed = Number::parse("3");
  const auto q = Problem<cl_RA>::from(ExactScene::from(scene));
  EXPECT_EQ(q.u[0], -3);
  EXPECT_EQ(q.u[2], cl_RA(-29) / 10);
}

TEST(ExactScene, RejectsScenesBuiltInMemory) {
  // The loader already refuses these in files; ExactScene::from is the entry
  // point for scenes made by programs and must refuse them too.
  const Scene good = parse_scene(kBoundary, "mem");
  auto message = [](const Scene& s) -> std::string {
    try {
      ExactScene::from(s);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  };
  Scene s = good;
  s.bodies[0].mass = Number::parse("0");
  EXPECT_EQ(message(s).rfind("mem: body[1].mass: must be > 0", 0), 0u) << message(s);
  s = good;
  s.bodies[1].mass = Number::parse("-1/2");
  EXPECT_EQ(message(s).rfind("mem: body[2].mass: must be > 0", 0), 0u) << message(s);
  s = good;
  s.bodies[0].infinite = true;
  EXPECT_EQ(message(s).rfind("mem: body[1].mass: only the bottom body", 0), 0u) << message(s);
  s = good;
  s.entries.push_back({Pair::parse("4-5"), Pair::parse("4-5"), Number::parse("1")});
  EXPECT_NE(message(s).find("pair 4-5 is outside bodies 1..4"), std::string::npos) << message(s);
  s = good;
  s.bodies.resize(1);
  EXPECT_NE(message(s).find("at least 2 bodies"), std::string::npos) << message(s);
  s = good;
  s.fall_speed.reset();
  EXPECT_NE(message(s).find("body[1]: no velocity before the collision"), std::string::npos) << message(s);
  s = good;
  s.entries.push_back({Pair::parse("1-3"), Pair::parse("1-2"), Number::parse("1")});  // K13 = 0 undeclared
  EXPECT_NE(message(s).find("not positive semi-definite"), std::string::npos) << message(s);
  s = good;
  s.bodies[1].velocity = Number::parse("-1/2");  // slower than body 3 (falls at 1): contact 2-3 opens
  EXPECT_EQ(message(s).rfind("mem: body[3].velocity: contact 2-3 opens before the collision", 0), 0u) << message(s);
  s = good;
  s.bodies[0].velocity = Number::parse("-1/2");  // the top falls slower than body 2: contact 1-2 opens
  EXPECT_NE(message(s).find("contact 1-2 opens"), std::string::npos) << message(s);
}

TEST(ExactScene, OpeningContactIsDecidedExactlyWithAnIrrationalFallSpeed) {
  // a = sqrt(2 g h) = sqrt(2) = 1.41421…: body 3 given -1.414 falls slower
  // than body 2 (contact 2-3 closes), -1.415 faster (it opens).  Only an
  // exact comparison of a² = 2 with 1.414² and 1.415² tells them apart.
  Scene s = parse_scene(kBoundary, "mem");
  s.fall_speed.reset();
  s.drop_height = Number::parse("1");
  s.g = Number::parse("1");
  s.bodies[2].velocity = Number::parse("-1.414");
  EXPECT_NO_THROW(ExactScene::from(s));
  s.bodies[2].velocity = Number::parse("-1.415");
  try {
    ExactScene::from(s);
    ADD_FAILURE() << "contact 2-3 opens and was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("body[3].velocity: contact 2-3 opens"), std::string::npos) << e.what();
  }
}

TEST(Precision, ParsesTheCliSpellings) {
  using K = numeric::Precision::Kind;
  EXPECT_EQ(numeric::Precision::parse("double").kind, K::Double);
  EXPECT_EQ(numeric::Precision::parse("long-double").kind, K::LongDouble);
  EXPECT_EQ(numeric::Precision::parse("exact").kind, K::Exact);
  const auto d = numeric::Precision::parse("digits:50");
  EXPECT_EQ(d.kind, K::Digits);
  EXPECT_EQ(d.digits, 50);
  for (const char* text : {"double", "long-double", "exact", "digits:10", "digits:10000", "digits:30"})
    EXPECT_EQ(numeric::Precision::parse(text).name(), text);
  EXPECT_EQ(numeric::Precision::parse(std::string("digits:") + std::to_string(numeric::min_digits)).digits, numeric::min_digits);
}

TEST(Precision, RejectsNonsense) {
  for (const char* text : {"", "nonsense", "Double", "float", "digits", "digits:", "digits:9", "digits:10001", "digits:abc",
                           "digits:+20", "digits:-20", "digits:1e3", "digits:99999999999", "digits: 20", "exact "}) {
    try {
      numeric::Precision::parse(text);
      ADD_FAILURE() << "'" << text << "' accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()).rfind("Precision::parse(): ", 0), 0u) << e.what();
    }
  }
}

/// The bits of \p d.
std::uint64_t bits_of(double d) {
  std::uint64_t b;
  std::memcpy(&b, &d, sizeof b);
  return b;
}

/// The double nearest \p r, ties to even, decided exactly: \p d is it when
/// r is no nearer to either neighbour of d (and at a tie d is even).
bool nearest_double(const cl_RA& r, double d) {
  const cl_RA x = cln::rational(cln::cl_DF(d));
  for (double n : {std::nextafter(d, -1e308), std::nextafter(d, 1e308)}) {
    const cl_RA y = cln::rational(cln::cl_DF(n));
    const cl_RA dx = abs_q(r - x), dy = abs_q(r - y);
    if (dy < dx) return false;
    if (dy == dx && (bits_of(d) & 1) != 0) return false;
  }
  return true;
}

/// Rationals p/q from 1 to 64 bits each (those of at most 53 take one IEEE
/// division), converted to double: the nearest double, as CLN's
/// double_approx() gives it.
TEST(Scalars, check_RationalsConvertToTheNearestDouble) {
  std::mt19937_64 draw(11);
  int fast = 0;
  for (int t = 0; t < 20000; ++t) {
    const int pb = 1 + static_cast<int>(draw() % 64), qb = 1 + static_cast<int>(draw() % 64);
    const auto bits = [&](int b) { return cln::cl_I(static_cast<std::uint64_t>(draw() >> (64 - b))); };
    cl_RA p = bits(pb), q = bits(qb);
    if (t % 7 == 0) p = cln::expt(cl_RA(2), pb % 54) - (t % 2);  // powers of two and all ones
    if (q == 0) q = 1;
    if (p == 0) p = 1;  // a nonzero quotient: its neighbours are normal doubles, which CLN holds
    if (t % 2 == 1) p = -p;
    const cl_RA r = p / q;
    const double d = numeric::ScalarTraits<double>::from(r, 0);
    fast += cln::integer_length(cln::numerator(r)) <= 53 && cln::integer_length(cln::denominator(r)) <= 53 ? 1 : 0;
    ASSERT_TRUE(nearest_double(r, d)) << r << " -> " << d;
    ASSERT_EQ(bits_of(d), bits_of(cln::double_approx(r))) << r;
  }
  EXPECT_GT(fast, 5000);
}

/// The exact value of a long double of 64 bits of significand.
cl_RA exact_long_double(long double x) {
  int e = 0;
  const long double m = std::frexp(x, &e);  // |m| in [1/2, 1): |m|·2⁶⁴ an integer below 2⁶⁴
  const cl_RA v = cln::cl_I(static_cast<std::uint64_t>(std::ldexp(std::fabs(m), 64))) * cln::expt(cl_RA(2), e - 64);
  return m < 0 ? cl_RA(-v) : v;
}

/// Rationals p/q of at most 63 bits each, converted to long double: the
/// nearest long double, decided exactly (no such p/q is a tie: it has at
/// most 63 significant bits where it is a binary fraction).
TEST(Scalars, check_SmallRationalsConvertToTheNearestLongDouble) {
  if (std::numeric_limits<long double>::digits != 64) GTEST_SKIP() << "long double is not x87's 64-bit significand here";
  std::mt19937_64 draw(13);
  for (int t = 0; t < 20000; ++t) {
    const auto bits = [&](int b) { return cln::cl_I(static_cast<std::uint64_t>(draw() >> (64 - b))); };
    cl_RA p = bits(1 + static_cast<int>(draw() % 63)), q = bits(1 + static_cast<int>(draw() % 63));
    if (q == 0) q = 1;
    if (p == 0) p = 1;
    const cl_RA r = t % 2 == 0 ? p / q : cl_RA(-p / q);
    const long double d = numeric::ScalarTraits<long double>::from(r, 0);
    const cl_RA x = exact_long_double(d), dx = abs_q(r - x);
    for (long double n : {std::nextafter(d, -1e4000L), std::nextafter(d, 1e4000L)}) {
      ASSERT_TRUE(dx < abs_q(r - exact_long_double(n))) << r << " -> " << static_cast<double>(d);
    }
  }
}

/// to_decimal()'s shortcut in 128-bit integers gives CLN's text: rationals
/// of 1 to 70 bits over 1 to 70 bits (those of at most 63 take the
/// shortcut), ties of the rounding (k/2, k/8 …), every number of digits
/// from 1 to 40, both signs.
TEST(Scalars, check_DecimalsAreThoseOfTheExactRoute) {
  std::mt19937_64 draw(17);
  const auto bits = [&](int b) { return cln::ash(cln::cl_I(static_cast<std::uint64_t>(draw() >> 1)), b - 63); };
  int shortcut = 0;
  for (int t = 0; t < 30000; ++t) {
    cl_RA q = t % 4 == 0 ? cln::expt(cl_RA(2), static_cast<int>(draw() % 6)) * cln::expt(cl_RA(10), static_cast<int>(draw() % 25)) : cl_RA(bits(1 + static_cast<int>(draw() % 70)));
    if (q == 0) q = 1;
    const cl_RA x = (t % 2 == 0 ? 1 : -1) * bits(1 + static_cast<int>(draw() % 70)) / q;
    const int digits = 1 + static_cast<int>(draw() % 40);
    shortcut += cln::integer_length(cln::numerator(x)) <= 63 && cln::integer_length(cln::denominator(x)) <= 63 ? 1 : 0;
    ASSERT_EQ(numeric::to_decimal(x, digits), numeric::detail::to_decimal_by_cln(x, digits)) << x << " to " << digits << " digits";
  }
  EXPECT_GT(shortcut, 10000);
  for (const char* text : {"1/2", "5/2", "-5/2", "1/8", "125/1000", "999999999995/1000", "20", "0", "1/3", "-2/3", "100000000000000000000"})
    for (int digits : {1, 2, 3, 10, 17})
      EXPECT_EQ(numeric::to_decimal(cl_RA(text), digits), numeric::detail::to_decimal_by_cln(cl_RA(text), digits)) << text << " " << digits;
  EXPECT_EQ(numeric::to_decimal(cl_RA(5) / 2, 1), "3");  // half away from zero
  EXPECT_EQ(numeric::to_decimal(cl_RA(-5) / 2, 1), "-3");
  EXPECT_EQ(numeric::to_decimal(cl_RA(999999999995) / 1000, 10), "1000000000");  // the rounding carries into a new digit
}

TEST(Scalars, ConversionsAreCorrectlyRounded) {
  using numeric::ScalarTraits;
  EXPECT_EQ(ScalarTraits<double>::from(cl_RA(1) / 3, 0), 1.0 / 3.0);
  EXPECT_EQ(ScalarTraits<double>::from(cl_RA(1) / 10, 0), 0.1);
  EXPECT_EQ(ScalarTraits<long double>::from(cl_RA(1) / 10, 0), 0.1L);
  EXPECT_EQ(ScalarTraits<long double>::from(cl_RA(2) / 3, 0), 2.0L / 3.0L);
  EXPECT_EQ(ScalarTraits<long double>::from(cl_RA(-313209) / 100000, 0), -3.13209L);
  const cl_R third = ScalarTraits<cl_R>::from(cl_RA(1) / 3, 30);
  EXPECT_TRUE(abs_q(exact_value(third) - cl_RA(1) / 3) < cln::expt(cl_RA(10), -30));
  EXPECT_THROW(ScalarTraits<cl_R>::from(cl_RA(1) / 3, 0), std::invalid_argument);
  cl_RA r;
  EXPECT_TRUE(ScalarTraits<cl_RA>::sqrt(cl_RA(9) / 4, 0, r));
  EXPECT_EQ(r, cl_RA(3) / 2);
  EXPECT_FALSE(ScalarTraits<cl_RA>::sqrt(2, 0, r));
  EXPECT_EQ(numeric::parse_rational("-10/4"), cl_RA(-5) / 2);
  EXPECT_EQ(numeric::parse_rational(numeric::to_string(cl_RA(-7) / 3)), cl_RA(-7) / 3);
  EXPECT_THROW(numeric::parse_rational("1/x"), std::invalid_argument);
}

}  // namespace
}  // namespace superball::testing
