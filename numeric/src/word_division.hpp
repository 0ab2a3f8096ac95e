#pragma once
// Internal: the quotient of two significands of N 64-bit words, for
// MpFloat's quotients (numeric/src/mpfloat.cpp), by schoolbook division with
// a reciprocal of the divisor's two top words: no division instruction per
// word, only products (N. Möller and T. Granlund, "Improved division by
// invariant integers", IEEE Trans. Computers 60(2), 2011, algorithms 4 and
// 6 and their use in GMP's mpn_sbpi1_div_qr).  The same quotient and
// remainder as GMP's mpn_tdiv_qr, which takes 3–4 times the instructions at
// these sizes (its dispatch on the sizes and a general reciprocal);
// tests/numeric/word_division_test.cpp compares the two.

#include <cstdint>
#if defined(__x86_64__)
#include <immintrin.h>  // _addcarry_u64, _subborrow_u64 (GCC and Clang)
#endif

namespace superball::numeric::detail {

namespace words {

using Limb = std::uint64_t;
__extension__ typedef unsigned __int128 Wide;  // GCC and Clang's 128-bit integer

/// ⌊(hi·2⁶⁴ + lo) / d⌋ for hi < d (the quotient fits a word).
inline Limb divide_2by1(Limb hi, Limb lo, Limb d) {
#if defined(__x86_64__)
  Limb q, r;
  __asm__("divq %4" : "=a"(q), "=d"(r) : "a"(lo), "d"(hi), "rm"(d) : "cc");
  (void)r;
  return q;
#else
  return static_cast<Limb>(((Wide(hi) << 64) | lo) / d);
#endif
}

/// v = ⌊(2¹⁹² − 1) / (d1·2⁶⁴ + d0)⌋ − 2⁶⁴ for d1 ≥ 2⁶³: the reciprocal of
/// the divisor's top two words (invert_pi1 in GMP).  The reciprocal of d1
/// alone, ⌊(2¹²⁸ − 1)/d1⌋ − 2⁶⁴, is ⌊((2⁶⁴ − 1 − d1)·2⁶⁴ + 2⁶⁴ − 1)/d1⌋,
/// whose quotient fits a word; then corrected for d0.
inline Limb reciprocal_3by2(Limb d1, Limb d0) {
  Limb v = divide_2by1(~d1, ~Limb(0), d1);
  Limb p = d1 * v + d0;
  if (p < d0) {  // the sum wrapped
    --v;
    if (p >= d1) --v, p -= d1;
    p -= d1;
  }
  const Wide t = Wide(d0) * v;
  const Limb t1 = static_cast<Limb>(t >> 64), t0 = static_cast<Limb>(t);
  p += t1;
  if (p < t1) {
    --v;
    if (p > d1 || (p == d1 && t0 >= d0)) --v;
  }
  return v;
}

/// q = ⌊(n2·2¹²⁸ + n1·2⁶⁴ + n0) / (d1·2⁶⁴ + d0)⌋ and its remainder r1·2⁶⁴ + r0,
/// for n2·2⁶⁴ + n1 < d1·2⁶⁴ + d0 (the quotient fits a word) and v =
/// reciprocal_3by2(d1, d0) (udiv_qr_3by2 in GMP).
inline Limb divide_3by2(Limb& r1, Limb& r0, Limb n2, Limb n1, Limb n0, Limb d1, Limb d0, Limb v) {
  const Wide D = (Wide(d1) << 64) | d0;
  Wide Q = Wide(n2) * v + ((Wide(n2) << 64) | n1);
  Limb q = static_cast<Limb>(Q >> 64);
  const Limb q0 = static_cast<Limb>(Q);
  r1 = n1 - d1 * q;  // the two top words of n − q·d, modulo 2¹²⁸
  Wide R = (Wide(r1) << 64) | n0;
  R -= D;
  R -= Wide(d0) * q;
  ++q;
  if (static_cast<Limb>(R >> 64) >= q0) {  // one too many
    --q;
    R += D;
  }
  if (R >= D) {  // one too few (rare)
    ++q;
    R -= D;
  }
  r1 = static_cast<Limb>(R >> 64), r0 = static_cast<Limb>(R);
  return q;
}

/// a + b + carry (0 or 1) into \p sum, returning the carry out (add with carry).
inline unsigned char add_carry(Limb a, Limb b, unsigned char carry, Limb* sum) {
#if defined(__x86_64__)
  unsigned long long r;
  const unsigned char out = _addcarry_u64(carry, a, b, &r);
  *sum = r;
  return out;
#else
  const Wide t = Wide(a) + b + carry;
  *sum = static_cast<Limb>(t);
  return static_cast<unsigned char>(t >> 64);
#endif
}

/// a − b − borrow (0 or 1) into \p difference, returning the borrow out (subtract with borrow).
inline unsigned char subtract_borrow(Limb a, Limb b, unsigned char borrow, Limb* difference) {
#if defined(__x86_64__)
  unsigned long long r;
  const unsigned char out = _subborrow_u64(borrow, a, b, &r);
  *difference = r;
  return out;
#else
  const Wide t = Wide(a) - b - borrow;
  *difference = static_cast<Limb>(t);
  return static_cast<unsigned char>((t >> 64) & 1);
#endif
}

/// Compares the numbers of N words x and y (least significant first): −1, 0 or 1.
template <int N>
int compare_words(const Limb* x, const Limb* y) {
  for (int k = N - 1; k >= 0; --k)
    if (x[k] != y[k]) return x[k] < y[k] ? -1 : 1;
  return 0;
}

/// x[0 … K) −= q·d[0 … K), returning the word borrowed out of x[K − 1].
/// In words, not in 128-bit sums (those GCC spills to the stack on the
/// chain of borrows).
template <int K>
Limb subtract_multiple(Limb* x, const Limb* d, Limb q) {
  Limb borrow = 0;
  for (int k = 0; k < K; ++k) {
    const Wide t = Wide(q) * d[k];
    Limb low = static_cast<Limb>(t), high = static_cast<Limb>(t >> 64);
    low += borrow;
    high += low < borrow ? 1 : 0;  // q·d[k] + borrow < 2¹²⁸
    high += x[k] < low ? 1 : 0;
    x[k] -= low;
    borrow = high;
  }
  return borrow;
}

/// x[0 … K) += d[0 … K), returning the carry out.
template <int K>
Limb add_words(Limb* x, const Limb* d) {
  Limb carry = 0;
  for (int k = 0; k < K; ++k) {
    const Wide t = Wide(x[k]) + d[k] + carry;
    x[k] = static_cast<Limb>(t), carry = static_cast<Limb>(t >> 64);
  }
  return carry;
}

}  // namespace words

/// The quotient and remainder of n (M words, least significant first; 2N + 1
/// unless given) by d (N ≥ 2 words, the top bit of d[N − 1] set): q (M − N
/// + 1 words) = ⌊n / d⌋ and the remainder into n[0 … N) (n's other words are
/// left undefined), as GMP's mpn_tdiv_qr(q, r, 0, n, M, d, N) gives them.
template <int N, int M = 2 * N + 1>
void divide_words(std::uint64_t* q, std::uint64_t* n, const std::uint64_t* d) {
  static_assert(N >= 2 && M > N, "a divisor of two words or more, a longer numerator");
  using words::Limb;
  constexpr int kTop = M - N;  // n[kTop … M − 1]: the top N words
  // The top quotient word, 0 or 1: whether n's top N words reach d (then less d).
  const bool reach = words::compare_words<N>(n + kTop, d) >= 0;
  if (reach) words::subtract_multiple<N>(n + kTop, d, 1);
  q[M - N] = reach ? 1 : 0;
  const Limb d1 = d[N - 1], d0 = d[N - 2], v = words::reciprocal_3by2(d1, d0);
  // One quotient word per step, from the top (M − N steps): the partial
  // remainder is n1 over r[0 … N), r = n + j − N + 1, its second word r[N − 1] = n[j].
  Limb n1 = n[M - 1];
  for (int j = M - 2; j >= N - 1; --j) {
    Limb* r = n + (j - N + 1);
    Limb qw;
    if (n1 == d1 && r[N - 1] == d0) {  // the estimate overflows a word: q = 2⁶⁴ − 1, exact here
      qw = ~Limb(0);
      words::subtract_multiple<N>(r, d, qw);
      n1 = r[N - 1];
    } else {
      Limb n0;
      qw = words::divide_3by2(n1, n0, n1, r[N - 1], r[N - 2], d1, d0, v);
      const Limb borrow = words::subtract_multiple<N - 2>(r, d, qw);
      const Limb borrow1 = n0 < borrow ? 1 : 0;
      n0 -= borrow;
      const Limb out = n1 < borrow1 ? 1 : 0;
      n1 -= borrow1;
      r[N - 2] = n0;
      if (out != 0) {  // q one too large: add d back
        n1 += d1 + words::add_words<N - 1>(r, d);
        --qw;
      }
    }
    q[j - N + 1] = qw;
  }
  n[N - 1] = n1;
}

}  // namespace superball::numeric::detail
