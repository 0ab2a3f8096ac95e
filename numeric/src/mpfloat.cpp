// MpFloat (mpfloat.hpp) on MPFR, and what the solver needs of it
// (ScalarTraits<MpFloat>, to_string): the only file that includes mpfr.h.
#include "superball/numeric/mpfloat.hpp"

#include <gmp.h>
#include <mpfr.h>

#include <cln/float.h>
#include <cln/integer.h>
#include <cln/integer_io.h>
#include <cln/rational.h>

#include <algorithm>
#include <cstddef>
#include <cstdlib>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>

#include "superball/numeric/scalar.hpp"
#include "collision/mpfloat_steps.hpp"
#include "word_division.hpp"

namespace superball::numeric {

static_assert(sizeof(MpFloat::Raw) == sizeof(__mpfr_struct), "MpFloat::Raw mirrors __mpfr_struct");
static_assert(offsetof(MpFloat::Raw, prec) == offsetof(__mpfr_struct, _mpfr_prec), "MpFloat::Raw mirrors __mpfr_struct");
static_assert(offsetof(MpFloat::Raw, sign) == offsetof(__mpfr_struct, _mpfr_sign), "MpFloat::Raw mirrors __mpfr_struct");
static_assert(offsetof(MpFloat::Raw, exp) == offsetof(__mpfr_struct, _mpfr_exp), "MpFloat::Raw mirrors __mpfr_struct");
static_assert(offsetof(MpFloat::Raw, d) == offsetof(__mpfr_struct, _mpfr_d), "MpFloat::Raw mirrors __mpfr_struct");
static_assert(sizeof(mp_limb_t) == sizeof(std::uint64_t) && GMP_NUMB_BITS == 64, "64-bit limbs");

namespace {

mpfr_ptr mp(MpFloat& x) { return reinterpret_cast<mpfr_ptr>(x.raw()); }
mpfr_srcptr mp(const MpFloat& x) { return reinterpret_cast<mpfr_srcptr>(x.raw()); }

long words(long bits) { return (bits + GMP_NUMB_BITS - 1) / GMP_NUMB_BITS; }

using Op = int (*)(mpfr_ptr, mpfr_srcptr, mpfr_srcptr, mpfr_rnd_t);

/// \p x at the larger precision \p bits, exactly, in place: its
/// significand moves to the top words, zeros below; the exponent stays.
void widen(MpFloat& x, long bits) {
  auto& r = *x.raw();
  const long from = (r.prec + 63) / 64, to = (bits + 63) / 64;
  const bool regular = r.exp > __MPFR_EXP_INF;
  if (to > MpFloat::inline_limbs && to > from) {  // may need the heap: by a copy
    const MpFloat keep = x;
    x = MpFloat::zero(bits);
    r.sign = keep.raw()->sign;
    r.exp = keep.raw()->exp;
    if (regular) {
      for (long k = 0; k < to - from; ++k) r.d[k] = 0;
      for (long k = 0; k < from; ++k) r.d[to - from + k] = keep.raw()->d[k];
    }
    return;
  }
  if (regular && to > from) {
    for (long k = from - 1; k >= 0; --k) r.d[to - from + k] = r.d[k];
    for (long k = 0; k < to - from; ++k) r.d[k] = 0;
  }
  r.prec = bits;  // the low bits below the old precision are zero already
}

// Sums, differences, products and quotients of two regular numbers of one
// precision p of 2 to MpFloat::inline_limbs words, computed here on the
// words: mpfr_mul takes about twice the instructions at these sizes
// (callgrind: 105 against 226 at 127 bits; its dispatch on precision, flags
// in thread-local storage), and sums in MPFR made a digits:N solve of the
// paper scene a quarter slower.  The words stay in registers: a sum's
// common case (exponents less than 64 apart) and a product's schoolbook
// are inlined at fixed places, the rare cases are functions of their own,
// and the choices as random as the data (a carry, a normalising shift, a
// rounding up) are selects, not branches.  Each result is the exact one
// rounded once to nearest, ties to even: what MPFR gives, bit for bit
// (tests/numeric/mpfloat_arithmetic_test.cpp compares them on random operands).
namespace fast {

using detail::words::Limb;
using detail::words::Wide;
using detail::words::compare_words;
/// Exponents this far from 0 leave the work to MPFR (its range is ±(2^30 − 1)).
constexpr long kSafeExp = 1L << 29;

/// Rounds 0.W × 2^E (W: N + 1 words, the top bit of W[N] set; \p sticky:
/// nonzero bits below W) to p bits into \p out's significand, exponent and
/// precision (the sign is the caller's), to nearest, ties to even.  False,
/// out untouched, when E leaves the safe range.  U: 64N − p when known at
/// compile time (digits:N's precisions leave 1 bit), else −1.
template <int N, int U>
__attribute__((always_inline)) inline bool round_into(const Limb* W, bool sticky, long E, long p, MpFloat::Raw& out) {
  if (E < -kSafeExp || E > kSafeExp) return false;  // before out is touched: out may be an operand
  const int unused = U >= 0 ? U : static_cast<int>(64L * N - p);  // low bits of the lowest word, 0 … 63
  bool half;                                         // the bit just below the last one kept
  if (unused > 0) {
    half = ((W[1] >> (unused - 1)) & 1) != 0;
    sticky = sticky || W[0] != 0 || (W[1] & ((Limb(1) << (unused - 1)) - 1)) != 0;
  } else {
    half = (W[0] >> 63) != 0;
    sticky = sticky || (W[0] << 1) != 0;
  }
  Limb* d = out.d;
  const Limb ulp = Limb(1) << unused;
  const Limb kept = W[1] & ~(ulp - 1);
  // Up past the half, or at a tie with an odd last bit: the unit added
  // without a branch (whether it is added is as random as the data).
  const Limb up = (half & (sticky | ((kept & ulp) != 0))) ? ulp : 0;
  unsigned char carry = detail::words::add_carry(kept, up, 0, &d[0]);
  for (int k = 1; k < N; ++k) carry = detail::words::add_carry(W[k + 1], 0, carry, &d[k]);
  if (carry != 0) {  // all ones rounded up: 0.1 × 2^(E + 1)
    d[N - 1] = Limb(1) << 63;
    ++E;
  }
  out.exp = E;
  out.prec = p;
  return true;
}

/// The exact product of the N-word significands \p x and \p y into \p P
/// (2N words), inlined into mul() so that the words stay in registers: at
/// 3 to 6 words this beats GMP's mpn_mul_n (assembly, but a call and its
/// dispatch), by 2–3 % of a digits:70, 90 or 100 solve of the paper scene.
template <int N>
__attribute__((always_inline)) inline void schoolbook(const Limb* x, const Limb* y, Limb* P) {
  for (int j = 0; j < N; ++j) {  // the first row
    const Wide t = Wide(x[0]) * y[j] + (j > 0 ? P[j] : 0);
    P[j] = static_cast<Limb>(t), P[j + 1] = static_cast<Limb>(t >> 64);
  }
  for (int i = 1; i < N; ++i) {
    Limb carry = 0;
    for (int j = 0; j < N; ++j) {
      const Wide t = Wide(x[i]) * y[j] + P[i + j] + carry;
      P[i + j] = static_cast<Limb>(t), carry = static_cast<Limb>(t >> 64);
    }
    P[i + N] = carry;
  }
}

/// a × b, both regular, of p bits in N words, into out.
template <int N, int U>
bool mul(const MpFloat::Raw& a, const MpFloat::Raw& b, long p, MpFloat::Raw& out) {
  Limb P[2 * N];
  schoolbook<N>(a.d, b.d, P);
  // 0.01…: one place left (without a branch: the case is as random as the
  // data); only the words round_into() reads move, the rest is sticky.
  const int shift = static_cast<int>(1 - (P[2 * N - 1] >> 63));
  const long E = a.exp + b.exp - shift;
  for (int k = 2 * N - 1; k >= N - 1; --k) P[k] = (P[k] << shift) | ((P[k - 1] >> 1) >> (63 - shift));
  bool sticky = (P[N - 2] << shift) != 0;
  for (int k = 0; k < N - 2; ++k) sticky = sticky || P[k] != 0;
  const int sign = a.sign * b.sign;
  if (!round_into<N, U>(P + N - 1, sticky, E, p, out)) return false;
  out.sign = sign;
  return true;
}

/// a / b, both regular, of p bits in N words, into out.
template <int N, int U>
bool div(const MpFloat::Raw& a, const MpFloat::Raw& b, long p, MpFloat::Raw& out) {
  const int sign = a.sign * b.sign;
  if (U >= 1 || (U < 0 && p < 64L * N)) {  // a bit of the N words unused (digits:N's precisions)
    // q = ⌊A·2^(64N) / B⌋ on N + 1 words: A/B in (1/2, 2), so q has 64N bits
    // or one more, of which round_into() keeps p < 64N and reads the next
    // (the half bit): the rest and the remainder are sticky bits only, so
    // one quotient word fewer than below suffices.
    Limb num[2 * N] = {}, q[N + 1], W[N + 1];
    for (int k = 0; k < N; ++k) num[N + k] = a.d[k];
    detail::divide_words<N, 2 * N>(q, num, b.d);  // the remainder into num[0 … N)
    bool sticky = false;
    for (int k = 0; k < N; ++k) sticky = sticky || num[k] != 0;
    long E = a.exp - b.exp;  // A/B = 0.W × 2^E, W = q·2^64 when q[N] = 0
    if (q[N] != 0) {         // 64N + 1 bits: W = q·2^63, one place right
      W[0] = q[0] << 63;
      for (int k = 1; k <= N; ++k) W[k] = (q[k - 1] >> 1) | (q[k] << 63);
      ++E;
    } else {
      W[0] = 0;
      for (int k = 1; k <= N; ++k) W[k] = q[k - 1];
    }
    if (!round_into<N, U>(W, sticky, E, p, out)) return false;
    out.sign = sign;
    return true;
  }
  // q = ⌊A·2^(64(N+1)) / B⌋ on N + 2 words: A/B in (1/2, 2), so q has
  // 64(N + 1) bits or one more; the remainder is the sticky bit.
  Limb num[2 * N + 1] = {}, q[N + 2];
  for (int k = 0; k < N; ++k) num[N + 1 + k] = a.d[k];
  detail::divide_words<N>(q, num, b.d);  // the remainder into num[0 … N)
  bool sticky = false;
  for (int k = 0; k < N; ++k) sticky = sticky || num[k] != 0;
  long E = a.exp - b.exp;  // A/B = 0.q[0 … N] × 2^E when q[N + 1] = 0
  if (q[N + 1] != 0) {
    sticky = sticky || (q[0] & 1) != 0;
    for (int k = 0; k <= N; ++k) q[k] = (q[k] >> 1) | (q[k + 1] << 63);
    ++E;
  }
  if (!round_into<N, U>(q, sticky, E, p, out)) return false;
  out.sign = sign;
  return true;
}

/// round_into() for N = 2 on 128-bit numbers: S (top bit set) + F/2^128,
/// \p sticky for nonzero bits below F.
template <int U>
bool round_into2(Wide S, Wide F, bool sticky, long E, long p, MpFloat::Raw& out) {
  if (E < -kSafeExp || E > kSafeExp) return false;
  const int unused = U >= 0 ? U : static_cast<int>(128 - p);  // 0 … 63
  bool half;
  Wide ulp = 1;
  if (unused > 0) {
    const Wide h = Wide(1) << (unused - 1);
    half = (S & h) != 0;
    sticky = sticky || (S & (h - 1)) != 0 || F != 0;
    ulp = h << 1;
    S &= ~(ulp - 1);
  } else {
    half = (F >> 127) != 0;
    sticky = sticky || (F << 1) != 0;
  }
  if (half && (sticky || (S & ulp) != 0)) {  // up (a branch: a select measured slower here than in round_into())
    S += ulp;
    if (S == 0) S = Wide(1) << 127, ++E;  // all ones rounded up
  }
  out.d[0] = static_cast<Limb>(S), out.d[1] = static_cast<Limb>(S >> 64);
  out.exp = E;
  out.prec = p;
  return true;
}

template <int U>
bool mul2(const MpFloat::Raw& a, const MpFloat::Raw& b, long p, MpFloat::Raw& out) {
  const Wide ll = Wide(a.d[0]) * b.d[0], lh = Wide(a.d[0]) * b.d[1], hl = Wide(a.d[1]) * b.d[0], hh = Wide(a.d[1]) * b.d[1];
  const Wide mid = (ll >> 64) + static_cast<Limb>(lh) + static_cast<Limb>(hl);  // < 3 · 2^64
  Wide H = hh + (lh >> 64) + (hl >> 64) + (mid >> 64);
  Wide L = (mid << 64) | static_cast<Limb>(ll);
  long E = a.exp + b.exp;
  if ((H >> 127) == 0) {  // 0.01…: one place left
    H = (H << 1) | (L >> 127), L <<= 1;
    --E;
  }
  const int sign = a.sign * b.sign;
  if (!round_into2<U>(H, L, false, E, p, out)) return false;
  out.sign = sign;
  return true;
}

/// The sum or difference (\p subtract) of x and y, |x| ≥ |y|, both regular,
/// of p bits in N words, their exponents \p apart ≥ 64: add()'s rare case,
/// out of its frame.  X sits in the top N of N + 1 words, Y shifted right by
/// \p apart below it, the bits of Y that fall off kept as a sticky bit; the
/// sum or difference of the two windows, normalised, is the exact result
/// truncated (a difference with a sticky Y is one less, and inexact), which
/// round_into() rounds once.
template <int N, int U>
__attribute__((noinline)) bool add_far(const MpFloat::Raw& x, const MpFloat::Raw& y, bool subtract, unsigned long apart, long p,
                                       MpFloat::Raw& out) {
  Limb W[N + 1], Y[N + 1];
  W[0] = 0;
  for (int k = 0; k < N; ++k) W[k + 1] = x.d[k];
  bool sticky = false;
  if (apart >= 64UL * (N + 1)) {  // all of Y below the window: nonzero
    for (int k = 0; k <= N; ++k) Y[k] = 0;
    sticky = true;
  } else {  // Y = (0.y × 2^64N) >> apart in the window, y read as words 1 … N of zeros around it
    const int words = static_cast<int>(apart / 64), bits = static_cast<int>(apart % 64);
    const auto z = [&y](int k) -> Limb { return k >= 1 && k <= N ? y.d[k - 1] : 0; };
    if (bits == 0) {
      for (int k = 0; k <= N; ++k) Y[k] = z(k + words);
    } else {
      for (int k = 0; k <= N; ++k) Y[k] = (z(k + words) >> bits) | (z(k + words + 1) << (64 - bits));
      sticky = (z(words) << (64 - bits)) != 0;  // the bits of the word shifted out
    }
    for (int k = 1; k < words; ++k) sticky = sticky || y.d[k - 1] != 0;  // the words wholly below the window
  }
  long E = x.exp;
  if (!subtract) {
    unsigned char carry = 0;  // the carry chain as add, adc, …
    for (int k = 0; k <= N; ++k) carry = detail::words::add_carry(W[k], Y[k], carry, &W[k]);
    if (carry != 0) {  // 1.… : one place right, the bit out joins the sticky one
      sticky = sticky || (W[0] & 1) != 0;
      for (int k = 0; k < N; ++k) W[k] = (W[k] >> 1) | (W[k + 1] << 63);
      W[N] = (W[N] >> 1) | (Limb(1) << 63);
      ++E;
    }
  } else {
    unsigned char borrow = sticky ? 1 : 0;  // a sticky Y: the truncated difference is one less
    for (int k = 0; k <= N; ++k) borrow = detail::words::subtract_borrow(W[k], Y[k], borrow, &W[k]);  // sub, sbb, …
    // X ≥ 2^(64N + 63) and Y < 2^(64N) here: the difference keeps its top bit or loses one
    if ((W[N] >> 63) == 0) {
      for (int k = N; k > 0; --k) W[k] = (W[k] << 1) | (W[k - 1] >> 63);
      W[0] <<= 1;
      --E;
    }
  }
  return round_into<N, U>(W, sticky, E, p, out);
}

/// A difference that cancelled its top word (\p W: N + 1 words, W[N] = 0,
/// exact): +0 when every word cancelled, else normalised, with E lowered by
/// the places it moved.  add()'s rare case, out of its frame.
template <int N>
__attribute__((noinline)) bool cancelled(Limb* W, long& E) {
  int top = N;
  while (top >= 0 && W[top] == 0) --top;
  if (top < 0) return false;
  const int words = N - top, bits = __builtin_clzl(W[top]);
  for (int k = N; k >= 0; --k) W[k] = k - words >= 0 ? W[k - words] : 0;
  if (bits > 0) {
    for (int k = N; k > 0; --k) W[k] = (W[k] << bits) | (W[k - 1] >> (64 - bits));
    W[0] <<= bits;
  }
  E -= 64L * words + bits;
  return true;
}

/// a + (±b) (\p sign_b: b's sign, flipped for a difference), both regular,
/// of p bits in N words, into out.  The larger magnitude X sits in the top N
/// of N + 1 words, the smaller Y shifted right by the exponents' difference
/// below it.  When they are less than 64 places apart (the common case, here
/// on words at fixed places, so that they stay in registers) no bit of Y
/// falls off: the sum or difference of the windows is exact, and
/// round_into() rounds it once; farther apart, add_far().  A difference that
/// cancels exactly is +0, as MPFR gives it rounding to nearest.
template <int N, int U>
bool add(const MpFloat::Raw& a, const MpFloat::Raw& b, int sign_b, long p, MpFloat::Raw& out) {
  const bool swap = a.exp < b.exp || (a.exp == b.exp && compare_words<N>(a.d, b.d) < 0);
  const MpFloat::Raw& x = swap ? b : a;
  const MpFloat::Raw& y = swap ? a : b;
  const int sign = swap ? sign_b : a.sign;
  const bool subtract = a.sign != sign_b;
  const unsigned long apart = static_cast<unsigned long>(x.exp) - static_cast<unsigned long>(y.exp);
  if (apart >= 64) {
    if (!add_far<N, U>(x, y, subtract, apart, p, out)) return false;
    out.sign = sign;
    return true;
  }
  // Y[k] = the words k − 1 and k of y (y's words at 1 … N, zeros around) shifted right by apart
  const int bits = static_cast<int>(apart);
  const auto high = [bits](Limb w) { return (w << 1) << (63 - bits); };  // w << (64 − bits): 0 when bits = 0
  Limb W[N + 1], Y[N + 1];
  Y[0] = high(y.d[0]);
  for (int k = 1; k < N; ++k) Y[k] = (y.d[k - 1] >> bits) | high(y.d[k]);
  Y[N] = y.d[N - 1] >> bits;
  long E = x.exp;
  bool sticky = false;
  if (!subtract) {
    W[0] = Y[0];
    unsigned char carry = 0;  // the carry chain as add, adc, …
    for (int k = 1; k <= N; ++k) carry = detail::words::add_carry(x.d[k - 1], Y[k], carry, &W[k]);
    // 1.… : one place right, the bit out joins the sticky one (without a
    // branch: whether the sum carries is as random as the data)
    const int shift = carry;
    sticky = (W[0] & static_cast<Limb>(shift)) != 0;
    for (int k = 0; k < N; ++k) W[k] = (W[k] >> shift) | ((W[k + 1] << 1) << (63 - shift));
    W[N] = (W[N] >> shift) | (static_cast<Limb>(shift) << 63);
    E += shift;
  } else {
    unsigned char borrow = detail::words::subtract_borrow(0, Y[0], 0, &W[0]);  // the borrow chain as sub, sbb, …
    for (int k = 1; k <= N; ++k) borrow = detail::words::subtract_borrow(x.d[k - 1], Y[k], borrow, &W[k]);
    if (W[N] == 0) {  // the top word cancelled (only 0 or 1 places apart)
      if (!cancelled<N>(W, E)) {  // exact cancellation: +0
        out.sign = 1, out.exp = __MPFR_EXP_ZERO, out.prec = p;
        return true;
      }
    } else {
      const int shift = __builtin_clzl(W[N]);  // 0 … 63
      for (int k = N; k > 0; --k) W[k] = (W[k] << shift) | ((W[k - 1] >> 1) >> (63 - shift));
      W[0] <<= shift;
      E -= shift;
    }
  }
  if (!round_into<N, U>(W, sticky, E, p, out)) return false;
  out.sign = sign;
  return true;
}

/// add() for N = 2 on 128-bit numbers: the window is X·2^64 (X: 128 bits,
/// the low word 0), Y shifted right into H (128 bits) and L (64 bits).
template <int U>
bool add2(const MpFloat::Raw& a, const MpFloat::Raw& b, int sign_b, long p, MpFloat::Raw& out) {
  const Wide A = (Wide(a.d[1]) << 64) | a.d[0], B = (Wide(b.d[1]) << 64) | b.d[0];
  const bool b_larger = a.exp < b.exp || (a.exp == b.exp && A < B);
  const Wide X = b_larger ? B : A, Y = b_larger ? A : B;
  const long ex = b_larger ? b.exp : a.exp, ey = b_larger ? a.exp : b.exp;
  const int sign = b_larger ? sign_b : a.sign;
  const unsigned long apart = static_cast<unsigned long>(ex) - static_cast<unsigned long>(ey);
  Wide H;
  Limb L;
  bool sticky;
  if (apart < 64) {
    H = apart == 0 ? Y : Y >> apart;
    L = apart == 0 ? 0 : static_cast<Limb>(Y << (64 - apart));
    sticky = false;
  } else if (apart < 128) {
    const int r = static_cast<int>(apart - 64);
    H = Y >> apart;
    L = static_cast<Limb>(Y >> r);
    sticky = r != 0 && (static_cast<Limb>(Y) << (64 - r)) != 0;
  } else if (apart < 192) {
    const int r = static_cast<int>(apart - 64);  // 64 … 127
    H = 0;
    L = static_cast<Limb>(Y >> r);
    sticky = (Y << (128 - r)) != 0;
  } else {
    H = 0, L = 0, sticky = true;
  }
  long E = ex;
  Wide S;
  if (a.sign == sign_b) {
    S = X + H;
    if (S < X) {  // a carry: one place right, the bit out joins the sticky one
      sticky = sticky || (L & 1) != 0;
      L = (L >> 1) | (static_cast<Limb>(S) << 63);
      S = (S >> 1) | (Wide(1) << 127);
      ++E;
    }
  } else {
    const bool borrow = L != 0 || sticky;  // a sticky Y: the truncated difference is one less
    L = Limb(0) - L - (sticky ? 1 : 0);
    S = X - H - (borrow ? 1 : 0);
    if (S == 0 && L == 0) {  // exact cancellation: +0
      out.sign = 1, out.exp = __MPFR_EXP_ZERO, out.prec = p;
      return true;
    }
    if ((S >> 127) == 0) {
      const Limb top = static_cast<Limb>(S >> 64), low = static_cast<Limb>(S);
      const int shift = top != 0 ? __builtin_clzl(top) : low != 0 ? 64 + __builtin_clzl(low) : 128 + __builtin_clzl(L);
      if (shift < 64) {
        S = (S << shift) | (L >> (64 - shift)), L <<= shift;
      } else if (shift < 128) {
        S = ((S << 64) | L) << (shift - 64), L = 0;
      } else {
        S = Wide(L) << (shift - 64), L = 0;
      }
      E -= shift;
    }
  }
  if (!round_into2<U>(S, Wide(L) << 64, sticky, E, p, out)) return false;
  out.sign = sign;
  return true;
}

enum class Kind { add, sub, mul, div };

/// a op b (\p K) of p bits in N words, U as round_into(), into out: one
/// function per operation and size, so that each keeps only its own frame.
template <Kind K, int N, int U>
__attribute__((noinline)) bool apply(const MpFloat::Raw& a, const MpFloat::Raw& b, long p, MpFloat::Raw& out) {
  if constexpr (K == Kind::add) return N == 2 ? add2<U>(a, b, b.sign, p, out) : add<N, U>(a, b, b.sign, p, out);
  if constexpr (K == Kind::sub) return N == 2 ? add2<U>(a, b, -b.sign, p, out) : add<N, U>(a, b, -b.sign, p, out);
  if constexpr (K == Kind::mul) return N == 2 ? mul2<U>(a, b, p, out) : mul<N, U>(a, b, p, out);
  return div<N, U>(a, b, p, out);
}

/// out = a op b here when both are regular of one precision of 2 … 6 words
/// (false, out untouched, when MPFR must do it); digits:N's precisions,
/// 64N − 1 bits, with the unused bit known at compile time.  Quotients of 2
/// words are left to MPFR (mpfr_div's 2-word path beats mpn_tdiv_qr).
template <Kind K>
bool operate(const MpFloat::Raw& a, const MpFloat::Raw& b, MpFloat::Raw& out) {
  if (a.prec != b.prec || a.exp <= __MPFR_EXP_INF || b.exp <= __MPFR_EXP_INF) return false;
  constexpr bool two = K != Kind::div;  // 2 words here
  switch (a.prec) {
    case 127: return two && apply<K, two ? 2 : 3, 1>(a, b, 127, out);
    case 191: return apply<K, 3, 1>(a, b, 191, out);
    case 255: return apply<K, 4, 1>(a, b, 255, out);
    case 319: return apply<K, 5, 1>(a, b, 319, out);
    case 383: return apply<K, 6, 1>(a, b, 383, out);
    default: break;
  }
  switch ((a.prec + 63) / 64) {
    case 2: return two && apply<K, two ? 2 : 3, -1>(a, b, a.prec, out);
    case 3: return apply<K, 3, -1>(a, b, a.prec, out);
    case 4: return apply<K, 4, -1>(a, b, a.prec, out);
    case 5: return apply<K, 5, -1>(a, b, a.prec, out);
    case 6: return apply<K, 6, -1>(a, b, a.prec, out);
    default: return false;
  }
}
static_assert(MpFloat::inline_limbs == 6, "operate() takes 2 … inline_limbs words");

}  // namespace fast

/// x × y or x / y (\p kind) exactly when y, of lower precision than x (a
/// constant of the solver, as the 2 of x / 2), is ±2^k and x is regular: x's
/// significand, its exponent moved, into \p out (x's precision, as MPFR
/// rounds it: exact).  False otherwise.
bool power_of_two(fast::Kind kind, const MpFloat& x, const MpFloat& y, MpFloat& out) {
  const MpFloat::Raw& rx = *x.raw();
  const MpFloat::Raw& ry = *y.raw();
  if (rx.exp <= __MPFR_EXP_INF || ry.exp <= __MPFR_EXP_INF) return false;
  const long n = words(ry.prec);
  if (ry.d[n - 1] != std::uint64_t(1) << 63) return false;
  for (long k = 0; k + 1 < n; ++k)
    if (ry.d[k] != 0) return false;
  const long e = kind == fast::Kind::mul ? rx.exp + ry.exp - 1 : rx.exp - ry.exp + 1;  // y = 2^(ey − 1)
  if (e < -fast::kSafeExp || e > fast::kSafeExp) return false;
  const int sign = rx.sign * ry.sign;
  if (&out != &x) out = x;
  out.raw()->exp = e, out.raw()->sign = sign;
  return true;
}

/// out = a ± b (\p K: add or sub) when one of them is ±0 and the other ±0 or
/// regular: exact, at the larger precision, the other operand's value, or
/// for two zeros the sign rounding to nearest gives (−0 only for −0 − +0 and
/// −0 + −0), as MPFR gives it.  \p out may be \p a.  False otherwise.
template <fast::Kind K>
bool zero_sum(const MpFloat& a, const MpFloat& b, MpFloat& out) {
  const MpFloat::Raw& ra = *a.raw();
  const MpFloat::Raw& rb = *b.raw();
  const bool a_zero = ra.exp == __MPFR_EXP_ZERO, b_zero = rb.exp == __MPFR_EXP_ZERO;
  if (!(a_zero || b_zero) || !MpFloat::zero_or_regular(a) || !MpFloat::zero_or_regular(b)) return false;
  const long p = std::max(ra.prec, rb.prec);
  const int sign_b = K == fast::Kind::sub ? -rb.sign : rb.sign;
  const int sign = !b_zero ? sign_b : !a_zero ? ra.sign : (ra.sign < 0 && sign_b < 0 ? -1 : 1);
  if (!b_zero)
    out = b;
  else if (&out != &a)
    out = a;
  if (out.precision() < p) widen(out, p);
  out.raw()->sign = sign;
  return true;
}

constexpr bool additive(fast::Kind k) { return k == fast::Kind::add || k == fast::Kind::sub; }

/// binary() of operands of different precisions: the one of lower precision
/// (a constant) is first widened exactly to the larger one, so that MPFR
/// takes its paths for operands of one precision (2–3× faster below 192 bits).
template <fast::Kind K>
__attribute__((noinline)) MpFloat binary_mixed(const MpFloat& a, const MpFloat& b, Op op) {
  const long p = std::max(a.precision(), b.precision());
  MpFloat r = MpFloat::zero(p);
  if (additive(K) && zero_sum<K>(a, b, r)) return r;
  if (a.precision() == b.precision()) {  // of more words than the object holds
    if (!fast::operate<K>(*a.raw(), *b.raw(), *r.raw())) op(mp(r), mp(a), mp(b), MPFR_RNDN);
    return r;
  }
  const bool a_low = a.precision() < p;
  const bool scales = K == fast::Kind::mul || (K == fast::Kind::div && !a_low);
  if (scales && power_of_two(K, a_low ? b : a, a_low ? a : b, r)) return r;
  MpFloat wide = a_low ? a : b;
  widen(wide, p);
  const MpFloat& x = a.precision() < p ? wide : a;
  const MpFloat& y = a.precision() < p ? b : wide;
  if (!fast::operate<K>(*x.raw(), *y.raw(), *r.raw())) op(mp(r), mp(x), mp(y), MPFR_RNDN);
  return r;
}

/// a op b rounded to the larger precision: operands of one precision held in
/// the object here, others by binary_mixed().
template <fast::Kind K>
MpFloat binary(const MpFloat& a, const MpFloat& b, Op op) {
  MpFloat r;
  const long p = a.precision();
  if (p == b.precision() && words(p) <= MpFloat::inline_limbs) {
    r.raw()->prec = p;  // room in the object
    if (!fast::operate<K>(*a.raw(), *b.raw(), *r.raw()) && !(additive(K) && zero_sum<K>(a, b, r))) op(mp(r), mp(a), mp(b), MPFR_RNDN);
  } else {
    r = binary_mixed<K>(a, b, op);
  }
  return r;
}

/// in_place() of operands of different precisions: x is widened first when
/// y is the more precise.
template <fast::Kind K>
__attribute__((noinline)) MpFloat& in_place_mixed(MpFloat& x, const MpFloat& y, Op op) {
  if (additive(K) && zero_sum<K>(x, y, x)) return x;  // 0 ± y, as a sum started at S(0), or x ± 0
  if (x.precision() > y.precision()) {
    if ((K == fast::Kind::mul || K == fast::Kind::div) && power_of_two(K, x, y, x)) return x;
    MpFloat wide = y;
    widen(wide, x.precision());
    if (!fast::operate<K>(*x.raw(), *wide.raw(), *x.raw())) op(mp(x), mp(x), mp(wide), MPFR_RNDN);
  } else {
    widen(x, y.precision());
    if (!fast::operate<K>(*x.raw(), *y.raw(), *x.raw())) op(mp(x), mp(x), mp(y), MPFR_RNDN);
  }
  return x;
}

/// x op= y, in place.  A sum started at a zero (S(0), 64 bits) takes its
/// first term ±y exactly, at y's precision (x has room for inline_limbs words).
template <fast::Kind K>
MpFloat& in_place(MpFloat& x, const MpFloat& y, Op op) {
  MpFloat::Raw& r = *x.raw();
  const MpFloat::Raw& t = *y.raw();
  if (additive(K) && r.exp == __MPFR_EXP_ZERO && t.exp > __MPFR_EXP_INF && r.prec <= t.prec && words(t.prec) <= MpFloat::inline_limbs) {
    r.prec = t.prec, r.exp = t.exp, r.sign = K == fast::Kind::sub ? -t.sign : t.sign;
    for (long k = 0, n = words(t.prec); k < n; ++k) r.d[k] = t.d[k];
    return x;
  }
  if (x.precision() != y.precision()) return in_place_mixed<K>(x, y, op);
  if (!fast::operate<K>(*x.raw(), *y.raw(), *x.raw()) && !(additive(K) && zero_sum<K>(x, y, x))) op(mp(x), mp(x), mp(y), MPFR_RNDN);
  return x;
}

/// x ± a·b (\p K: add or sub), rounded as x op= a * b, or with \p Half
/// x += a·b/2 as x += a * b / 2 (the halving exact): the product of
/// operands of one precision p held in the object computed into words on
/// the stack, then added to x in place when x has precision p, or copied
/// when x is 0 of a lower precision (0 ± t is exact); otherwise, and when
/// the product or its half leaves the fast path, by the operators.
template <fast::Kind K, bool Half = false>
void accumulate_product(MpFloat& x, const MpFloat& a, const MpFloat& b, Op op) {
  const long p = a.precision();
  MpFloat::Raw& r = *x.raw();
  if (p == b.precision() && p >= r.prec && words(p) <= MpFloat::inline_limbs) {
    std::uint64_t limbs[MpFloat::inline_limbs];
    MpFloat::Raw t{p, 1, __MPFR_EXP_ZERO, limbs};
    if (fast::operate<fast::Kind::mul>(*a.raw(), *b.raw(), t) && (!Half || t.exp - 1 >= -fast::kSafeExp)) {
      if (Half) --t.exp;  // t / 2, exact, as power_of_two() gives it
      if (r.prec == p) {
        if (!fast::operate<K>(r, t, r)) op(mp(x), mp(x), reinterpret_cast<mpfr_srcptr>(&t), MPFR_RNDN);
        return;
      }
      if (r.exp == __MPFR_EXP_ZERO) {  // x's room holds inline_limbs words
        r.prec = p, r.exp = t.exp, r.sign = K == fast::Kind::sub ? -t.sign : t.sign;
        for (long k = 0, n = words(p); k < n; ++k) r.d[k] = limbs[k];
        return;
      }
    }
  }
  if (Half)
    x += a * b / MpFloat(2);
  else if (K == fast::Kind::sub)
    x -= a * b;
  else
    x += a * b;
}

/// Whether a and b are both ±0 or regular (compare_finite() takes them).
bool both_finite(const MpFloat& a, const MpFloat& b) { return MpFloat::zero_or_regular(a) && MpFloat::zero_or_regular(b); }

/// −1, 0 or 1 as a < b, a = b (+0 = −0) or a > b, for ±0 or regular
/// numbers of any precisions, on the words: MPFR's comparison.
int compare_finite(const MpFloat::Raw& a, const MpFloat::Raw& b) {
  const bool a_zero = a.exp == __MPFR_EXP_ZERO, b_zero = b.exp == __MPFR_EXP_ZERO;
  if (a_zero || b_zero) return a_zero && b_zero ? 0 : a_zero ? -b.sign : a.sign;
  if (a.sign != b.sign) return a.sign;
  if (a.exp != b.exp) return a.exp > b.exp ? a.sign : -a.sign;
  const long na = words(a.prec), nb = words(b.prec);
  for (long k = 1; k <= std::max(na, nb); ++k) {  // from the top word down; missing words are 0
    const std::uint64_t x = k <= na ? a.d[na - k] : 0, y = k <= nb ? b.d[nb - k] : 0;
    if (x != y) return x > y ? a.sign : -a.sign;
  }
  return 0;
}

/// The exact integer \p z as a CLN integer, word by word.
cln::cl_I to_cln(const mpz_t z) {
  cln::cl_I r = 0;
  for (long k = static_cast<long>(mpz_size(z)) - 1; k >= 0; --k)
    r = cln::ash(r, GMP_NUMB_BITS) + cln::cl_I(static_cast<unsigned long long>(mpz_getlimbn(z, k)));
  return mpz_sgn(z) < 0 ? cln::cl_I(-r) : r;
}

/// The exact CLN integer \p x into \p z.
void from_cln(const cln::cl_I& x, mpz_t z) {
  std::ostringstream os;
  cln::print_integer(os, 16, x);
  mpz_set_str(z, os.str().c_str(), 16);
}

}  // namespace

static_assert(MpFloat::Raw{0, 0, -0x7fffffffffffffffL, nullptr}.exp == __MPFR_EXP_ZERO, "MpFloat's zero is MPFR's");
static_assert(-0x7fffffffffffffffL + 2 == __MPFR_EXP_INF && __MPFR_EXP_NAN == -0x7fffffffffffffffL + 1, "MpFloat's inf and NaN are MPFR's");

MpFloat::MpFloat(Uninitialised, long bits) : raw_{bits, 1, kZeroExp, limbs_} {
  if (words(bits) > inline_limbs) grow(bits);
  raw_.prec = bits;
}

void MpFloat::grow(long bits) {
  const long need = words(bits);
  if (need <= capacity_) return;
  auto* d = new std::uint64_t[static_cast<std::size_t>(need)];
  if (raw_.d != limbs_) delete[] raw_.d;
  raw_.d = d;
  capacity_ = static_cast<int>(need);
}

void MpFloat::release() { delete[] raw_.d; }

MpFloat::MpFloat(double x) noexcept : MpFloat(Uninitialised{}, kIntegerBits) { mpfr_set_d(mp(*this), x, MPFR_RNDN); }

MpFloat MpFloat::zero(long bits) {
  if (bits < MPFR_PREC_MIN || bits > MPFR_PREC_MAX) throw std::invalid_argument("MpFloat::zero(): precision out of range: " + std::to_string(bits));
  return MpFloat(Uninitialised{}, bits);
}

MpFloat::MpFloat(MpFloat&& other) noexcept : raw_(other.raw_), capacity_(other.capacity_) {
  if (other.raw_.d == other.limbs_) {
    raw_.d = limbs_;
    copy_significand(other);
  } else {  // steal the heap significand
    other.raw_ = {kIntegerBits, 1, kZeroExp, other.limbs_};
    other.capacity_ = inline_limbs;
  }
}

MpFloat& MpFloat::steal(MpFloat& other) noexcept {
  if (raw_.d != limbs_) delete[] raw_.d;
  raw_ = other.raw_;
  capacity_ = other.capacity_;
  other.raw_ = {kIntegerBits, 1, kZeroExp, other.limbs_};
  other.capacity_ = inline_limbs;
  return *this;
}

MpFloat& MpFloat::operator+=(const MpFloat& x) { return in_place<fast::Kind::add>(*this, x, mpfr_add); }
MpFloat& MpFloat::operator-=(const MpFloat& x) { return in_place<fast::Kind::sub>(*this, x, mpfr_sub); }
MpFloat& MpFloat::operator*=(const MpFloat& x) { return in_place<fast::Kind::mul>(*this, x, mpfr_mul); }
MpFloat& MpFloat::operator/=(const MpFloat& x) { return in_place<fast::Kind::div>(*this, x, mpfr_div); }

MpFloat operator+(const MpFloat& a, const MpFloat& b) { return binary<fast::Kind::add>(a, b, mpfr_add); }
MpFloat operator-(const MpFloat& a, const MpFloat& b) { return binary<fast::Kind::sub>(a, b, mpfr_sub); }
MpFloat operator*(const MpFloat& a, const MpFloat& b) { return binary<fast::Kind::mul>(a, b, mpfr_mul); }
MpFloat operator/(const MpFloat& a, const MpFloat& b) { return binary<fast::Kind::div>(a, b, mpfr_div); }
void add_product(MpFloat& x, const MpFloat& a, const MpFloat& b) { accumulate_product<fast::Kind::add>(x, a, b, mpfr_add); }
void subtract_product(MpFloat& x, const MpFloat& a, const MpFloat& b) { accumulate_product<fast::Kind::sub>(x, a, b, mpfr_sub); }
void add_half_product(MpFloat& x, const MpFloat& a, const MpFloat& b) { accumulate_product<fast::Kind::add, true>(x, a, b, mpfr_add); }
MpFloat sqrt(const MpFloat& x) {
  MpFloat r = MpFloat::zero(x.precision());
  mpfr_sqrt(mp(r), mp(x), MPFR_RNDN);
  return r;
}

bool operator==(const MpFloat& a, const MpFloat& b) {
  return both_finite(a, b) ? compare_finite(*a.raw(), *b.raw()) == 0 : mpfr_equal_p(mp(a), mp(b)) != 0;
}
bool operator!=(const MpFloat& a, const MpFloat& b) { return !(a == b); }
bool less(const MpFloat& a, const MpFloat& b) {
  return both_finite(a, b) ? compare_finite(*a.raw(), *b.raw()) < 0 : mpfr_less_p(mp(a), mp(b)) != 0;
}
bool operator<=(const MpFloat& a, const MpFloat& b) {
  return both_finite(a, b) ? compare_finite(*a.raw(), *b.raw()) <= 0 : mpfr_lessequal_p(mp(a), mp(b)) != 0;
}
bool operator>=(const MpFloat& a, const MpFloat& b) {
  return both_finite(a, b) ? compare_finite(*a.raw(), *b.raw()) >= 0 : mpfr_greaterequal_p(mp(a), mp(b)) != 0;
}

long digits_precision(int digits) {
  if (digits <= 0) throw std::invalid_argument("digits_precision(): digits must be > 0, got " + std::to_string(digits));
  // The bits CLN asks for N digits (cln::float_format(N)), rounded up to
  // whole words less one bit, at least 127: MPFR's fast paths take
  // precisions below 2 and 3 words; CLN took whole words, at least 2.
  const long bits = static_cast<long>(cln::float_format(static_cast<uintE>(digits)));
  return std::max<long>(2 * GMP_NUMB_BITS - 1, words(bits + 1) * GMP_NUMB_BITS - 1);
}

MpFloat ScalarTraits<MpFloat>::from(const cln::cl_RA& r, int digits) {
  if (digits <= 0) throw std::invalid_argument("ScalarTraits<MpFloat>::from(): digits must be > 0");
  MpFloat x = MpFloat::zero(digits_precision(digits));
  mpq_t q;
  mpq_init(q);
  from_cln(cln::numerator(r), mpq_numref(q));
  from_cln(cln::denominator(r), mpq_denref(q));
  mpfr_set_q(mp(x), q, MPFR_RNDN);  // correctly rounded
  mpq_clear(q);
  return x;
}

double ScalarTraits<MpFloat>::to_double(const MpFloat& x) { return mpfr_get_d(mp(x), MPFR_RNDN); }

MpFloat ScalarTraits<MpFloat>::unit_roundoff(int digits) {
  // Rounding to nearest in p bits: |fl(x) − x| <= 2^−p |x|.
  MpFloat u = MpFloat::zero(digits_precision(digits > 0 ? digits : 20));
  mpfr_set_si_2exp(mp(u), 1, -u.precision(), MPFR_RNDN);
  return u;
}

bool ScalarTraits<MpFloat>::sqrt(const cln::cl_RA& square, int digits, MpFloat& out) {
  out = numeric::sqrt(from(square, digits));
  return true;
}

cln::cl_RA rational(const MpFloat& x) {
  if (!mpfr_number_p(mp(x))) throw std::domain_error("rational(): not a finite number");
  if (mpfr_zero_p(mp(x))) return 0;
  mpz_t z;
  mpz_init(z);
  const mpfr_exp_t e = mpfr_get_z_2exp(z, mp(x));
  const cln::cl_I m = to_cln(z);
  mpz_clear(z);
  return e >= 0 ? cln::cl_RA(cln::ash(m, e)) : cln::cl_RA(m) / cln::ash(1, -e);
}

MpFloat times_power_of_two(const MpFloat& x, int k) {
  MpFloat r = MpFloat::zero(x.precision());
  mpfr_mul_2si(mp(r), mp(x), k, MPFR_RNDN);
  return r;
}

bool finite(const MpFloat& x) { return mpfr_number_p(mp(x)) != 0; }

std::string to_string(const MpFloat& x, int significant) {
  if (!mpfr_number_p(mp(x))) return mpfr_nan_p(mp(x)) ? "nan" : mpfr_sgn(mp(x)) > 0 ? "inf" : "-inf";
  if (significant > 0 || mpfr_zero_p(mp(x))) return to_decimal(rational(x), significant > 0 ? significant : 1);
  // All its digits: the fewest that read back to x (as CLN printed its floats).
  const std::size_t most = mpfr_get_str_ndigits(10, x.precision());
  MpFloat back = MpFloat::zero(x.precision());
  for (std::size_t n = most > 4 ? most - 4 : 1;; ++n) {
    mpfr_exp_t e = 0;
    std::unique_ptr<char, void (*)(char*)> digits(mpfr_get_str(nullptr, &e, 10, n, mp(x), MPFR_RNDN), mpfr_free_str);
    std::string d = digits.get();
    const bool negative = d[0] == '-';
    if (negative) d.erase(0, 1);
    const std::string text = (negative ? "-0." : "0.") + d + "e" + std::to_string(e);
    mpfr_strtofr(mp(back), text.c_str(), nullptr, 10, MPFR_RNDN);
    if (n < most && !(back == x)) continue;
    // d·10^(e − |d|): the decimal of to_decimal()'s shape, all of d kept.
    while (d.size() > 1 && d.back() == '0') d.pop_back();
    const long point = static_cast<long>(e);  // digits before the point
    std::string out;
    if (point - 1 < -4 || point - 1 >= static_cast<long>(n)) {
      out = d.substr(0, 1) + (d.size() > 1 ? "." + d.substr(1) : "") + "e" + (point - 1 < 0 ? "-" : "+") +
            (std::labs(point - 1) < 10 ? "0" : "") + std::to_string(std::labs(point - 1));
    } else if (point <= 0) {
      out = "0." + std::string(static_cast<std::size_t>(-point), '0') + d;
    } else {
      if (static_cast<long>(d.size()) < point) d += std::string(static_cast<std::size_t>(point) - d.size(), '0');
      out = d.substr(0, static_cast<std::size_t>(point));
      if (static_cast<long>(d.size()) > point) out += "." + d.substr(static_cast<std::size_t>(point));
    }
    return (negative ? "-" : "") + out;
  }
}

}  // namespace superball::numeric
