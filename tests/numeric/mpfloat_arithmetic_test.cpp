// MpFloat's own arithmetic on 2 … 6 words (numeric/src/mpfloat.cpp, namespace
// fast) against MPFR's correctly rounded results, bit for bit: random
// operands at each precision and the edge cases (zero, signs, ties, carries,
// cancellation, exponents far apart, huge and tiny exponents).
#include <gtest/gtest.h>

#include <gmp.h>
#include <mpfr.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "superball/numeric/mpfloat.hpp"
#include "superball/numeric/scalar.hpp"

namespace superball::testing {
namespace {

using numeric::MpFloat;

/// Random operand pairs per precision and operation.
constexpr int kPairs = 4000;
/// Precisions compared: digits:N's (64k − 1 bits), whole words, one bit over, odd sizes; 2 … 6 words and beyond.
const std::vector<long> kPrecisions = {65, 100, 127, 128, 129, 191, 192, 200, 255, 256, 319, 320, 383, 384, 385, 500};

mpfr_ptr mp(MpFloat& x) { return reinterpret_cast<mpfr_ptr>(x.raw()); }
mpfr_srcptr mp(const MpFloat& x) { return reinterpret_cast<mpfr_srcptr>(x.raw()); }

/// An MPFR number of p bits, cleared on scope exit.
struct Ref {
  mpfr_t v;
  explicit Ref(long p) { mpfr_init2(v, p); }
  ~Ref() { mpfr_clear(v); }
  Ref(const Ref&) = delete;
  Ref& operator=(const Ref&) = delete;
};

/// Bit for bit the same number: sign, exponent and significand (or both NaN).
bool same(const MpFloat& got, mpfr_srcptr want) {
  if (mpfr_nan_p(want)) return mpfr_nan_p(mp(got)) != 0;
  return mpfr_get_prec(mp(got)) == mpfr_get_prec(want) && mpfr_equal_p(mp(got), want) && mpfr_signbit(mp(got)) == mpfr_signbit(want);
}

std::string text(mpfr_srcptr x) {
  char* s = nullptr;
  mpfr_asprintf(&s, "%Ra (prec %ld)", x, static_cast<long>(mpfr_get_prec(x)));
  std::string out = s;
  mpfr_free_str(s);
  return out;
}

/// Operands drawn to reach every branch: random bits, runs of ones (carries),
/// powers of two, a few bits (exact results and ties), values near each other
/// (cancellation), exponents apart by 0 … p + 3 and more.
class Draw {
 public:
  explicit Draw(std::uint64_t seed) : gen_(seed) { gmp_randinit_mt(state_), gmp_randseed_ui(state_, static_cast<unsigned long>(seed)); }
  ~Draw() { gmp_randclear(state_); }
  Draw(const Draw&) = delete;
  Draw& operator=(const Draw&) = delete;

  /// A regular number of p bits with exponent near \p exp into x.
  MpFloat number(long p, long exp) {
    MpFloat x = MpFloat::zero(p);
    switch (pick(6)) {
      case 0: mpfr_set_ui(mp(x), 1, MPFR_RNDN); break;  // 0.1 × 2^1
      case 1:                                           // all ones
        mpfr_set_ui_2exp(mp(x), 1, p, MPFR_RNDN), mpfr_sub_ui(mp(x), mp(x), 1, MPFR_RNDN);
        break;
      case 2:  // a few bits set
        mpfr_set_ui(mp(x), static_cast<unsigned long>(pick(1000) + 1), MPFR_RNDN);
        break;
      default: mpfr_urandomb(mp(x), state_); break;
    }
    if (mpfr_zero_p(mp(x))) mpfr_set_ui(mp(x), 3, MPFR_RNDN);
    mpfr_set_exp(mp(x), exp);
    if (pick(2) == 0) mpfr_neg(mp(x), mp(x), MPFR_RNDN);
    return x;
  }
  /// A second operand for \p a: independent, or a few ulps from ±a (cancellation).
  MpFloat partner(const MpFloat& a, long p) {
    const long e = mpfr_get_exp(mp(a));
    if (pick(4) != 0) return number(p, e - (pick(3) == 0 ? pick(p + 4) : pick(5) - 2));
    MpFloat b = a;
    for (long k = pick(4); k > 0; --k) mpfr_nextabove(mp(b));
    for (long k = pick(4); k > 0; --k) mpfr_nextbelow(mp(b));
    if (pick(2) == 0) mpfr_neg(mp(b), mp(b), MPFR_RNDN);
    return b;
  }
  long pick(long n) { return static_cast<long>(std::uniform_int_distribution<long>(0, n - 1)(gen_)); }

 private:
  std::mt19937_64 gen_;
  gmp_randstate_t state_;
};

using Op = int (*)(mpfr_ptr, mpfr_srcptr, mpfr_srcptr, mpfr_rnd_t);
struct Operation {
  const char* name;
  Op mpfr;
  std::function<MpFloat(const MpFloat&, const MpFloat&)> binary;
  std::function<void(MpFloat&, const MpFloat&)> in_place;
};
const std::vector<Operation>& operations() {
  static const std::vector<Operation> ops = {
      {"+", mpfr_add, [](const MpFloat& a, const MpFloat& b) { return a + b; }, [](MpFloat& a, const MpFloat& b) { a += b; }},
      {"-", mpfr_sub, [](const MpFloat& a, const MpFloat& b) { return a - b; }, [](MpFloat& a, const MpFloat& b) { a -= b; }},
      {"*", mpfr_mul, [](const MpFloat& a, const MpFloat& b) { return a * b; }, [](MpFloat& a, const MpFloat& b) { a *= b; }},
      {"/", mpfr_div, [](const MpFloat& a, const MpFloat& b) { return a / b; }, [](MpFloat& a, const MpFloat& b) { a /= b; }},
  };
  return ops;
}

/// a op b, a op= b, and (when a is b) a op= a, against MPFR at p bits.
void expect_as_mpfr(const Operation& op, const MpFloat& a, const MpFloat& b, long p) {
  Ref want(p);
  op.mpfr(want.v, mp(a), mp(b), MPFR_RNDN);
  const MpFloat got = op.binary(a, b);
  ASSERT_TRUE(same(got, want.v)) << text(mp(a)) << " " << op.name << " " << text(mp(b)) << ": got " << text(mp(got)) << ", MPFR "
                                 << text(want.v);
  MpFloat acc = a;
  op.in_place(acc, b);
  ASSERT_TRUE(same(acc, want.v)) << text(mp(a)) << " " << op.name << "= " << text(mp(b)) << ": got " << text(mp(acc));
  MpFloat self = a;
  op.in_place(self, self);
  op.mpfr(want.v, mp(a), mp(a), MPFR_RNDN);
  ASSERT_TRUE(same(self, want.v)) << text(mp(a)) << " " << op.name << "= itself: got " << text(mp(self));
}

TEST(MpFloatArithmetic, RandomOperandsAreRoundedAsMpfrRoundsThem) {
  Draw draw(20261127);
  for (long p : kPrecisions) {
    for (const Operation& op : operations()) {
      for (int k = 0; k < kPairs; ++k) {
        const MpFloat a = draw.number(p, draw.pick(200) - 100);
        const MpFloat b = draw.partner(a, p);
        expect_as_mpfr(op, a, b, p);
        if (::testing::Test::HasFatalFailure()) return;
      }
    }
  }
}

TEST(MpFloatArithmetic, ZerosSignsAndCancellationAreMpfrs) {
  Draw draw(7);
  for (long p : kPrecisions) {
    const MpFloat zero = MpFloat::zero(p), minus_zero = -MpFloat::zero(p), x = draw.number(p, 3);
    for (const Operation& op : operations()) {
      for (const MpFloat* a : {&zero, &minus_zero, &x})
        for (const MpFloat* b : {&zero, &minus_zero, &x}) expect_as_mpfr(op, *a, *b, p);
      expect_as_mpfr(op, x, -x, p);  // exact cancellation: +0
    }
    // x − y for y one ulp either side: the result is exact, 2^(e − p).
    MpFloat up = x, down = x;
    mpfr_nextabove(mp(up)), mpfr_nextbelow(mp(down));
    expect_as_mpfr(operations()[1], x, up, p);
    expect_as_mpfr(operations()[1], x, down, p);
  }
}

/// Sums and differences with a zero of either precision, as the solver's
/// accumulators start at S(0) (64 bits) and add terms of p bits, some of them
/// 0: the other operand exactly, at the larger precision, or the sign of a
/// sum of zeros rounding to nearest; every operation checked, in both orders.
TEST(MpFloatArithmetic, ZerosOfEitherPrecisionAreMpfrs) {
  Draw draw(11);
  for (long p : {127L, 191L, 383L, 500L}) {
    const MpFloat zero64 = MpFloat(0), minus_zero64 = -MpFloat(0), zero = MpFloat::zero(p), minus_zero = -MpFloat::zero(p);
    const MpFloat x = draw.number(p, 5), minus_x = -x, c(-7);  // c: 64 bits, regular
    const std::vector<const MpFloat*> operands = {&zero64, &minus_zero64, &zero, &minus_zero, &x, &minus_x, &c};
    for (const Operation& op : operations())
      for (const MpFloat* a : operands)
        for (const MpFloat* b : operands) {
          Ref want(std::max(a->precision(), b->precision()));
          op.mpfr(want.v, mp(*a), mp(*b), MPFR_RNDN);
          EXPECT_TRUE(same(op.binary(*a, *b), want.v)) << text(mp(*a)) << " " << op.name << " " << text(mp(*b));
          MpFloat acc = *a;
          op.in_place(acc, *b);
          EXPECT_TRUE(same(acc, want.v)) << text(mp(*a)) << " " << op.name << "= " << text(mp(*b)) << ": got " << text(mp(acc));
        }
  }
}

TEST(MpFloatArithmetic, TiesRoundToEvenAndCarriesRaiseTheExponent) {
  for (long p : kPrecisions) {
    // 1 + 2^−p is a tie: to even, 1; (1 + 2^(1−p)) + 2^−p is a tie: up, to 1 + 2^(2−p).
    MpFloat one = MpFloat::zero(p), half_ulp = MpFloat::zero(p), odd = MpFloat::zero(p), ones = MpFloat::zero(p);
    mpfr_set_ui(mp(one), 1, MPFR_RNDN);
    mpfr_set_ui_2exp(mp(half_ulp), 1, -p, MPFR_RNDN);
    mpfr_set_ui(mp(odd), 1, MPFR_RNDN), mpfr_nextabove(mp(odd));
    mpfr_set_ui(mp(ones), 2, MPFR_RNDN), mpfr_nextbelow(mp(ones));  // 2 − 2^(1−p): all ones
    for (const Operation& op : operations()) {
      expect_as_mpfr(op, one, half_ulp, p);
      expect_as_mpfr(op, odd, half_ulp, p);
      expect_as_mpfr(op, ones, half_ulp, p);  // + rounds up through every word: 2
      expect_as_mpfr(op, ones, ones, p);
      expect_as_mpfr(op, ones, odd, p);
    }
  }
}

TEST(MpFloatArithmetic, ExponentsFarApartHugeAndTinyAreMpfrs) {
  Draw draw(11);
  const long emax = mpfr_get_emax(), emin = mpfr_get_emin();
  for (long p : kPrecisions) {
    for (const Operation& op : operations()) {
      for (long apart : {p - 1, p, p + 1, p + 2, p + 3, 2 * p, 10 * p}) {
        const MpFloat a = draw.number(p, 5), b = draw.number(p, 5 - apart);
        expect_as_mpfr(op, a, b, p);
        expect_as_mpfr(op, b, a, p);
      }
      // Near MPFR's exponent range: overflow to ±inf, underflow to ±0, and
      // the exponents just inside and outside the range computed here.
      for (long e : {emax, emax - 1, emax / 2 + 1, (1L << 29) - 1, 1L << 29, (1L << 29) + 1, emin, emin + 1, emin / 2, -(1L << 29)}) {
        const MpFloat a = draw.number(p, e), b = draw.number(p, e), one = draw.number(p, 1), small = draw.number(p, -e / 2);
        expect_as_mpfr(op, a, b, p);
        expect_as_mpfr(op, a, one, p);
        expect_as_mpfr(op, one, a, p);
        expect_as_mpfr(op, a, small, p);
      }
    }
  }
}

/// Sums and differences at every distance of the exponents from 0 to p + 140
/// (past the word below the significand, where the smaller operand's low bits
/// leave the window and only their sticky bit remains): the larger operand 1,
/// 1 + ulp, all ones or random; the smaller one a power of two, its top and
/// bottom bits set (so that a tie of the top bit is broken by bits far below),
/// all ones, or random; every sign.
TEST(MpFloatArithmetic, SumsAndDifferencesAtEveryDistanceOfTheExponents) {
  Draw draw(19);
  for (long p : kPrecisions) {
    MpFloat one = MpFloat::zero(p), odd = MpFloat::zero(p), ones = MpFloat::zero(p);
    mpfr_set_ui(mp(one), 1, MPFR_RNDN);
    mpfr_set_ui(mp(odd), 1, MPFR_RNDN), mpfr_nextabove(mp(odd));
    mpfr_set_ui(mp(ones), 2, MPFR_RNDN), mpfr_nextbelow(mp(ones));
    for (long apart = 0; apart <= p + 140; ++apart) {
      const MpFloat random = draw.number(p, 1);
      MpFloat power = MpFloat::zero(p), ends = MpFloat::zero(p), low_ones = MpFloat::zero(p);
      mpfr_set_ui_2exp(mp(power), 1, -apart, MPFR_RNDN);                                    // 0.1 × 2^(1 − apart)
      mpfr_set_ui_2exp(mp(ends), 1, -apart, MPFR_RNDN), mpfr_nextabove(mp(ends));          // 0.10…01
      mpfr_set_ui_2exp(mp(low_ones), 1, 1 - apart, MPFR_RNDN), mpfr_nextbelow(mp(low_ones));  // 0.11…1
      const MpFloat low_random = draw.number(p, 1 - apart);
      const MpFloat* const larger[] = {&one, &odd, &ones, &random};
      const MpFloat* const smaller[] = {&power, &ends, &low_ones, &low_random};
      for (const MpFloat* a : larger)
        for (const MpFloat* b : smaller)
          for (int sign : {1, -1}) {
            const MpFloat c = sign > 0 ? *b : -*b;
            expect_as_mpfr(operations()[0], *a, c, p);
            expect_as_mpfr(operations()[1], *a, c, p);
            expect_as_mpfr(operations()[1], c, *a, p);
            if (::testing::Test::HasFatalFailure()) return;
          }
    }
  }
}

TEST(MpFloatArithmetic, MixedPrecisionsWidenTheLessPreciseExactly) {
  Draw draw(5);
  for (long p : {127L, 191L, 383L}) {
    for (const Operation& op : operations()) {
      for (int k = 0; k < 500; ++k) {
        const MpFloat a = draw.number(p, draw.pick(40) - 20);
        const MpFloat c(draw.pick(2000) - 1000);  // 64 bits, as the solver's constants
        const MpFloat d(1.0 / static_cast<double>(draw.pick(97) + 3));
        const MpFloat two_k = (k % 2 == 0 ? 1 : -1) * std::ldexp(1.0, static_cast<int>(draw.pick(200)) - 100);  // ±2^k: an exact scaling
        for (const MpFloat* b : {&c, &d, &two_k}) {
          Ref want(p);
          op.mpfr(want.v, mp(a), mp(*b), MPFR_RNDN);
          EXPECT_TRUE(same(op.binary(a, *b), want.v)) << text(mp(a)) << " " << op.name << " " << text(mp(*b));
          MpFloat high = a;
          op.in_place(high, *b);
          EXPECT_TRUE(same(high, want.v)) << text(mp(a)) << " " << op.name << "= " << text(mp(*b));
          op.mpfr(want.v, mp(*b), mp(a), MPFR_RNDN);
          EXPECT_TRUE(same(op.binary(*b, a), want.v)) << text(mp(*b)) << " " << op.name << " " << text(mp(a));
          MpFloat acc = *b;
          op.in_place(acc, a);
          EXPECT_TRUE(same(acc, want.v)) << text(mp(*b)) << " " << op.name << "= " << text(mp(a));
        }
      }
    }
  }
}

/// Comparisons on the words against MPFR's: ±0, ±inf, NaN, and numbers of
/// different precisions that agree in their leading words.
TEST(MpFloatArithmetic, ComparisonsOfZerosInfinitiesAndMixedPrecisionsAreMpfrs) {
  Draw draw(23);
  std::vector<MpFloat> values;
  for (long p : {64L, 127L, 128L, 191L, 383L, 500L}) {
    MpFloat zero = MpFloat::zero(p), inf = MpFloat::zero(p), nan = MpFloat::zero(p);
    mpfr_set_inf(mp(inf), 1), mpfr_set_nan(mp(nan));
    values.insert(values.end(), {zero, -zero, inf, -inf, nan, MpFloat(1), MpFloat(-1)});
    MpFloat third = MpFloat::zero(p);
    mpfr_set_ui(mp(third), 1, MPFR_RNDN), mpfr_div_ui(mp(third), mp(third), 3, MPFR_RNDN);
    values.insert(values.end(), {third, -third, draw.number(p, 0), draw.number(p, 1), draw.number(p, -1)});
    MpFloat one_up = MpFloat::zero(p);
    mpfr_set_ui(mp(one_up), 1, MPFR_RNDN), mpfr_nextabove(mp(one_up));  // 1 and 1 + ulp agree but in their last word
    values.push_back(one_up);
  }
  for (const MpFloat& a : values)
    for (const MpFloat& b : values) {
      EXPECT_EQ(a < b, mpfr_less_p(mp(a), mp(b)) != 0) << text(mp(a)) << " < " << text(mp(b));
      EXPECT_EQ(a <= b, mpfr_lessequal_p(mp(a), mp(b)) != 0) << text(mp(a)) << " <= " << text(mp(b));
      EXPECT_EQ(a > b, mpfr_greater_p(mp(a), mp(b)) != 0) << text(mp(a)) << " > " << text(mp(b));
      EXPECT_EQ(a >= b, mpfr_greaterequal_p(mp(a), mp(b)) != 0) << text(mp(a)) << " >= " << text(mp(b));
      EXPECT_EQ(a == b, mpfr_equal_p(mp(a), mp(b)) != 0) << text(mp(a)) << " == " << text(mp(b));
      EXPECT_EQ(a != b, mpfr_equal_p(mp(a), mp(b)) == 0) << text(mp(a)) << " != " << text(mp(b));
    }
}

TEST(MpFloatArithmetic, ComparisonsAndConversionsAgreeWithMpfr) {
  Draw draw(3);
  for (long p : kPrecisions) {
    for (int k = 0; k < 2000; ++k) {
      const MpFloat a = draw.number(p, draw.pick(8) - 4);
      const MpFloat b = k % 7 == 0 ? a : draw.partner(a, p);
      EXPECT_EQ(a < b, mpfr_less_p(mp(a), mp(b)) != 0);
      EXPECT_EQ(a <= b, mpfr_lessequal_p(mp(a), mp(b)) != 0);
      EXPECT_EQ(a > b, mpfr_greater_p(mp(a), mp(b)) != 0);
      EXPECT_EQ(a >= b, mpfr_greaterequal_p(mp(a), mp(b)) != 0);
      EXPECT_EQ(a == b, mpfr_equal_p(mp(a), mp(b)) != 0);
      EXPECT_EQ(a != b, mpfr_equal_p(mp(a), mp(b)) == 0);
      // to double and exact rationals, and back from them correctly rounded.
      EXPECT_EQ(numeric::ScalarTraits<MpFloat>::to_double(a), mpfr_get_d(mp(a), MPFR_RNDN));
      const cln::cl_RA q = numeric::rational(a);
      const int digits = static_cast<int>(p / 3.33);
      const MpFloat back = numeric::ScalarTraits<MpFloat>::from(q, digits);
      Ref rounded(numeric::digits_precision(digits));
      mpfr_set(rounded.v, mp(a), MPFR_RNDN);
      EXPECT_TRUE(same(back, rounded.v)) << text(mp(a));
      const double x = mpfr_get_d(mp(a), MPFR_RNDN);
      Ref exact(64);
      mpfr_set_d(exact.v, x, MPFR_RNDN);
      EXPECT_TRUE(same(MpFloat(x), exact.v));
    }
  }
}

}  // namespace
}  // namespace superball::testing
