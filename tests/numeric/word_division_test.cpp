// divide_words() (numeric/src/word_division.hpp), the schoolbook division of
// MpFloat's quotients, against GMP's mpn_tdiv_qr: the same quotient and
// remainder, word for word, for divisors of 2 … 6 words, on random words
// and on words drawn from a few values (0, 1, 2⁶³, all ones, …) that reach
// the rare steps: a quotient word of all ones whose estimate overflows, an
// estimate one too large that adds the divisor back, a remainder of zero.

#include <gtest/gtest.h>

#include <gmp.h>

#include <cstdint>
#include <random>
#include <string>

#include "word_division.hpp"

namespace {

using Limb = std::uint64_t;

/// Words drawn at random or from values at the edges of a word.
struct Draw {
  std::mt19937_64 bits;
  Limb word(bool edges) {
    if (!edges) return bits();
    static constexpr Limb kEdges[] = {0, 1, 2, Limb(1) << 63, (Limb(1) << 63) + 1, ~Limb(0), ~Limb(0) - 1, ~Limb(0) >> 1};
    return kEdges[bits() % (sizeof kEdges / sizeof kEdges[0])];
  }
};

/// Numerators of M words (2N + 1: the quotients of MpFloat's general
/// precisions; 2N: of digits:N's, one word shorter).
template <int N, int M = 2 * N + 1>
void compare_with_gmp(std::uint64_t seed, int draws, int& overflowing_words, int& exact) {
  Draw draw{std::mt19937_64(seed)};
  for (int t = 0; t < draws; ++t) {
    const bool edges = t % 2 == 1;
    Limb d[N], n[M];
    for (Limb& w : d) w = draw.word(edges);
    d[N - 1] |= Limb(1) << 63;  // normalised, as a significand
    for (Limb& w : n) w = draw.word(edges);
    switch (draw.bits() % 4) {  // numerators near a multiple of d
      case 0:
        for (int k = 0; k < N; ++k) n[M - N + k] = d[k];  // the top words are d
        break;
      case 1:
        for (int k = 0; k < N; ++k) n[M - N - 1 + k] = d[k];  // d one word down: quotient words of all ones
        n[M - 1] = d[N - 1];
        break;
      default: break;
    }
    Limb want_q[M - N + 1], want_r[N], got_q[M - N + 1], work[M];
    for (int k = 0; k < M; ++k) work[k] = n[k];
    mpn_tdiv_qr(want_q, want_r, 0, n, M, d, N);
    superball::numeric::detail::divide_words<N, M>(got_q, work, d);
    std::string where = "N = " + std::to_string(N) + ", M = " + std::to_string(M) + ", draw " + std::to_string(t) + ", seed " + std::to_string(seed);
    for (int k = 0; k <= M - N; ++k) ASSERT_EQ(got_q[k], want_q[k]) << where << ": quotient word " << k;
    bool zero = true;
    for (int k = 0; k < N; ++k) {
      ASSERT_EQ(work[k], want_r[k]) << where << ": remainder word " << k;
      zero = zero && want_r[k] == 0;
    }
    for (int k = 0; k < M - N; ++k) overflowing_words += want_q[k] == ~Limb(0) ? 1 : 0;
    exact += zero ? 1 : 0;
  }
}

TEST(WordDivision, check_QuotientsAndRemaindersAreGmps) {
  int all_ones = 0, exact = 0;
  compare_with_gmp<2>(2, 40000, all_ones, exact);
  compare_with_gmp<3>(3, 40000, all_ones, exact);
  compare_with_gmp<4>(4, 40000, all_ones, exact);
  compare_with_gmp<5>(5, 40000, all_ones, exact);
  compare_with_gmp<6>(6, 40000, all_ones, exact);
  // The draws reach the rare steps: quotient words of all ones, exact quotients.
  EXPECT_GT(all_ones, 1000);
  EXPECT_GT(exact, 100);
}

TEST(WordDivision, check_ShorterNumeratorsToo) {
  int all_ones = 0, exact = 0;
  compare_with_gmp<2, 4>(12, 40000, all_ones, exact);
  compare_with_gmp<3, 6>(13, 40000, all_ones, exact);
  compare_with_gmp<4, 8>(14, 40000, all_ones, exact);
  compare_with_gmp<5, 10>(15, 40000, all_ones, exact);
  compare_with_gmp<6, 12>(16, 40000, all_ones, exact);
  EXPECT_GT(all_ones, 1000);
  EXPECT_GT(exact, 100);
}

TEST(WordDivision, check_ReciprocalsAreTheQuotientsOfAllOnes) {
  // v = ⌊(2¹⁹² − 1) / d⌋ − 2⁶⁴, d = d1·2⁶⁴ + d0 of two words, d1 ≥ 2⁶³.
  Draw draw{std::mt19937_64(7)};
  for (int t = 0; t < 200000; ++t) {
    const bool edges = t % 2 == 1;
    Limb d[2] = {draw.word(edges), draw.word(edges) | Limb(1) << 63};
    if (t % 3 == 0) d[0] = ~d[1] + (draw.bits() % 3);  // d1 + d0 near 2⁶⁴: the steps where the product wraps
    Limb ones[3] = {~Limb(0), ~Limb(0), ~Limb(0)}, q[2], r[2];
    mpn_tdiv_qr(q, r, 0, ones, 3, d, 2);
    ASSERT_EQ(q[1], 1u);
    ASSERT_EQ(superball::numeric::detail::words::reciprocal_3by2(d[1], d[0]), q[0]) << std::hex << d[1] << " " << d[0];
  }
}

TEST(WordDivision, exam_KnownQuotients) {
  // (2¹²⁸ − 1)·2⁶⁴ / (2¹²⁸ − 1) on 2 words: 2⁶⁴ exactly, remainder 0.
  Limb n[5] = {0, ~Limb(0), ~Limb(0), 0, 0}, d[2] = {~Limb(0), ~Limb(0)}, q[4];
  superball::numeric::detail::divide_words<2>(q, n, d);
  EXPECT_EQ(q[0], 0u);
  EXPECT_EQ(q[1], 1u);
  EXPECT_EQ(q[2], 0u);
  EXPECT_EQ(q[3], 0u);
  EXPECT_EQ(n[0], 0u);
  EXPECT_EQ(n[1], 0u);
  // 2⁴⁴⁷ / 2¹⁹¹ on 3 words, the top words of n equal to d: 2²⁵⁶ exactly,
  // the top quotient word 1.
  Limb m[7] = {0, 0, 0, 0, 0, 0, Limb(1) << 63}, e[3] = {0, 0, Limb(1) << 63}, r[5];
  superball::numeric::detail::divide_words<3>(r, m, e);
  EXPECT_EQ(r[4], 1u);
  for (int k = 0; k < 4; ++k) EXPECT_EQ(r[k], 0u) << k;
  for (int k = 0; k < 3; ++k) EXPECT_EQ(m[k], 0u) << k;
}

}  // namespace
