#include "collision/exact_kernel.hpp"

#include <cln/integer.h>
#include <cln/rational.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <optional>
#include <type_traits>
#include <vector>

// CLN's constructor of the fraction a/b from coprime a and b > 0 (no gcd).
// It is exported by libcln but declared only in CLN's internal headers, so
// it is referenced weakly: where a build of CLN lacks it, fraction() divides
// with CLN's public operator/ instead (the same value, a gcd more).
namespace cln {
const cl_RA I_I_to_RA(const cl_I& a, const cl_I& b) __attribute__((weak));
}
namespace superball::numeric::detail {
namespace {

__extension__ typedef unsigned __int128 u128;
__extension__ typedef __int128 i128;

/// Integers of the 128-bit path are proved below 2^wide_bits in magnitude
/// (signed 128-bit arithmetic modulo 2^128 is then exact), and bounds are
/// computed in double with this relative margin for their own rounding.
constexpr int wide_bits = 126;
constexpr double bound_margin = 1.0 + 1e-6;

// ---------------------------------------------------------------------------
// The two integer rings.

/// A signed integer held modulo 2^128 (two's complement).
struct Wide {
  u128 v = 0;
  Wide() = default;
  Wide(long long x) : v(static_cast<u128>(static_cast<i128>(x))) {}  // NOLINT: integers convert implicitly, as cl_I
  static Wide raw(u128 x) {
    Wide w;
    w.v = x;
    return w;
  }
  friend Wide operator+(Wide a, Wide b) { return raw(a.v + b.v); }
  friend Wide operator-(Wide a, Wide b) { return raw(a.v - b.v); }
  friend Wide operator-(Wide a) { return raw(-a.v); }
  friend Wide operator*(Wide a, Wide b) { return raw(a.v * b.v); }
  Wide& operator+=(Wide b) { return v += b.v, *this; }
  Wide& operator-=(Wide b) { return v -= b.v, *this; }
};

int sign_of(Wide x) {
  const auto s = static_cast<i128>(x.v);
  return s > 0 ? 1 : s < 0 ? -1 : 0;
}
int sign_of(const cln::cl_I& x) { return cln::minusp(x) ? -1 : cln::zerop(x) ? 0 : 1; }
double magnitude(Wide x) {
  const auto s = static_cast<i128>(x.v);
  return static_cast<double>(s < 0 ? -s : s);
}

cln::cl_I to_integer(Wide x) {
  const auto s = static_cast<i128>(x.v);
  if (s >= std::numeric_limits<long long>::min() && s <= std::numeric_limits<long long>::max())
    return cln::cl_I(static_cast<long long>(s));
  const u128 m = s < 0 ? -x.v : x.v;
  const cln::cl_I r = cln::logior(cln::ash(cln::cl_I(static_cast<unsigned long long>(m >> 64)), 64),
                                  cln::cl_I(static_cast<unsigned long long>(m)));
  return s < 0 ? cln::cl_I(-r) : r;
}
const cln::cl_I& to_integer(const cln::cl_I& x) { return x; }

/// A signed integer modulo 2^256 (two's complement, four 64-bit limbs, least
/// significant first): sums of products of three integers of the 128-bit path
/// (energies, dissipation), exact while their bound is below 2^254.
struct Wide256 {
  std::uint64_t limb[4] = {0, 0, 0, 0};
  Wide256& operator+=(const Wide256& b) {
    u128 carry = 0;
    for (int i = 0; i < 4; ++i) {
      const u128 t = static_cast<u128>(limb[i]) + b.limb[i] + carry;
      limb[i] = static_cast<std::uint64_t>(t), carry = t >> 64;
    }
    return *this;
  }
  void negate() {
    u128 carry = 1;
    for (auto& l : limb) {
      const u128 t = static_cast<u128>(~l) + carry;
      l = static_cast<std::uint64_t>(t), carry = t >> 64;
    }
  }
  /// This times the unsigned \p m, modulo 2^256.
  void times(std::uint64_t m) {
    u128 carry = 0;
    for (auto& l : limb) {
      const u128 t = static_cast<u128>(l) * m + carry;
      l = static_cast<std::uint64_t>(t), carry = t >> 64;
    }
  }
};

/// a · b · s exactly (|a|, |b| < 2^127, |s| < 2^63), modulo 2^256.
Wide256 product(Wide a, Wide b, long long s) {
  bool negative = s < 0;
  u128 x = a.v, y = b.v;
  if (static_cast<i128>(x) < 0) x = -x, negative = !negative;
  if (static_cast<i128>(y) < 0) y = -y, negative = !negative;
  const auto x0 = static_cast<std::uint64_t>(x), x1 = static_cast<std::uint64_t>(x >> 64);
  const auto y0 = static_cast<std::uint64_t>(y), y1 = static_cast<std::uint64_t>(y >> 64);
  const u128 p00 = static_cast<u128>(x0) * y0, p01 = static_cast<u128>(x0) * y1, p10 = static_cast<u128>(x1) * y0,
             p11 = static_cast<u128>(x1) * y1;
  const u128 mid = (p00 >> 64) + static_cast<std::uint64_t>(p01) + static_cast<std::uint64_t>(p10);
  const u128 high = (mid >> 64) + (p01 >> 64) + (p10 >> 64) + static_cast<std::uint64_t>(p11);
  Wide256 r;
  r.limb[0] = static_cast<std::uint64_t>(p00), r.limb[1] = static_cast<std::uint64_t>(mid);
  r.limb[2] = static_cast<std::uint64_t>(high), r.limb[3] = static_cast<std::uint64_t>((high >> 64) + (p11 >> 64));
  r.times(static_cast<std::uint64_t>(s < 0 ? -static_cast<i128>(s) : s));
  if (negative) r.negate();
  return r;
}

cln::cl_I to_integer(Wide256 x) {
  const bool negative = x.limb[3] >> 63;
  if (negative) x.negate();
  cln::cl_I r = cln::cl_I(static_cast<unsigned long long>(x.limb[3]));
  for (int i = 2; i >= 0; --i) r = cln::logior(cln::ash(r, 64), cln::cl_I(static_cast<unsigned long long>(x.limb[i])));
  return negative ? cln::cl_I(-r) : r;
}

int trailing_zeros(u128 x) {
  const auto lo = static_cast<std::uint64_t>(x);
  return lo ? __builtin_ctzll(lo) : 64 + __builtin_ctzll(static_cast<std::uint64_t>(x >> 64));
}

// ---------------------------------------------------------------------------
// Fractions written from native integers.

/// gcd(a, b) of 64-bit integers (binary, Stein).
std::uint64_t gcd64(std::uint64_t a, std::uint64_t b) {
  if (a == 0) return b;
  if (b == 0) return a;
  if (((a | b) >> 63) != 0) {  // the loop below needs their difference in a signed word
    const int shift = __builtin_ctzll(a | b);
    a >>= __builtin_ctzll(a);
    do {
      b >>= __builtin_ctzll(b);
      if (a > b) std::swap(a, b);
      b -= a;
    } while (b != 0);
    return a << shift;
  }
  // The next shift is computed from the difference, alongside the min and
  // the absolute value (no branch on which is larger).
  int za = __builtin_ctzll(a);
  const int zb = __builtin_ctzll(b), shift = std::min(za, zb);
  b >>= zb;
  while (a != 0) {
    a >>= za;
    const std::int64_t diff = static_cast<std::int64_t>(b - a);
    za = __builtin_ctzll(static_cast<std::uint64_t>(diff) | (std::uint64_t(1) << 63));
    b = std::min(a, b);
    a = static_cast<std::uint64_t>(diff < 0 ? -diff : diff);
  }
  return b << shift;
}

/// gcd(a, b) of 128-bit integers: one Euclidean step when the sizes differ
/// by a word, then binary steps, in 64 bits once both fit.
u128 gcd128(u128 a, u128 b) {
  if (a < b) std::swap(a, b);
  if (b == 0) return a;
  if ((a >> 64) != 0 && (b >> 64) == 0) {
    a %= b;
    if (a == 0) return b;
  }
  if (((a | b) >> 64) == 0) return gcd64(static_cast<std::uint64_t>(a), static_cast<std::uint64_t>(b));
  const int shift = trailing_zeros(a | b);
  a >>= trailing_zeros(a);
  b >>= trailing_zeros(b);
  for (;;) {  // a, b odd
    if (((a | b) >> 64) == 0) return static_cast<u128>(gcd64(static_cast<std::uint64_t>(a), static_cast<std::uint64_t>(b))) << shift;
    if (a > b) std::swap(a, b);
    b -= a;
    if (b == 0) return a << shift;
    b >>= trailing_zeros(b);
  }
}

/// The integer ±m.
cln::cl_I to_integer(u128 m, bool negative) {
  if ((m >> 63) == 0) return cln::cl_I(negative ? -static_cast<long long>(m) : static_cast<long long>(m));
  cln::cl_I r = (m >> 64) == 0 ? cln::cl_I(static_cast<unsigned long long>(m))
                               : cln::logior(cln::ash(cln::cl_I(static_cast<unsigned long long>(m >> 64)), 64),
                                             cln::cl_I(static_cast<unsigned long long>(m)));
  return negative ? cln::cl_I(-r) : r;
}

/// Whether x (modulo 2^256) is a signed 128-bit integer; then its value.
bool narrow(const Wide256& x, i128& out) {
  const std::uint64_t ext = (x.limb[1] >> 63) ? ~std::uint64_t(0) : 0;
  if (x.limb[2] != ext || x.limb[3] != ext) return false;
  out = static_cast<i128>((static_cast<u128>(x.limb[1]) << 64) | x.limb[0]);
  return true;
}

cln::cl_RA coprime_fraction(const cln::cl_I& a, const cln::cl_I& b);

/// num / den (den > 0, |num| < 2^127) reduced natively, the fraction then
/// made from its coprime parts.
cln::cl_RA fraction(i128 num, u128 den) {
  if (num == 0) return cln::cl_RA(0);
  const bool negative = num < 0;
  u128 a = negative ? -static_cast<u128>(num) : static_cast<u128>(num);
  const u128 g = gcd128(a, den);
  if (g != 1) a /= g, den /= g;
  if (den == 1) return to_integer(a, negative);
  return coprime_fraction(to_integer(a, negative), to_integer(den, false));
}

/// The product of \p factors (positive), false where it reaches 2^127.
bool product_fits(std::initializer_list<u128> factors, u128& out) {
  out = 1;
  for (u128 f : factors)
    if (__builtin_mul_overflow(out, f, &out) || (out >> 127) != 0) return false;
  return true;
}

/// The fraction a/b of coprime a and b > 0.
cln::cl_RA coprime_fraction(const cln::cl_I& a, const cln::cl_I& b) {
  if (&cln::I_I_to_RA != nullptr) return cln::I_I_to_RA(a, b);
  return a / b;
}

/// (hi·2^64 + lo) / d for hi < d: the quotient, and the remainder in \p rem.
inline std::uint64_t divide(std::uint64_t hi, std::uint64_t lo, std::uint64_t d, std::uint64_t& rem) {
#if defined(__x86_64__)
  std::uint64_t q;
  __asm__("divq %4" : "=a"(q), "=d"(rem) : "a"(lo), "d"(hi), "rm"(d) : "cc");
  return q;
#else
  const u128 x = (static_cast<u128>(hi) << 64) | lo;
  rem = static_cast<std::uint64_t>(x % d);
  return static_cast<std::uint64_t>(x / d);
#endif
}

/// num / (Π factors), the factors positive.  Where they are below 2^64 (then
/// packed into as few words as hold their product), the numerator's 256-bit
/// magnitude is reduced by gcd(num, f) for each word f in turn: the p-adic
/// valuation of gcd(num, f₁f₂) is min(v(num), v(f₁) + v(f₂)), which is what
/// reducing by f₁ and then by f₂ takes out, so the parts left are coprime.
/// Otherwise natively where both fit in 128 bits, else CLN's division.
cln::cl_RA fraction(const Wide256& num, std::initializer_list<u128> factors) {
  constexpr int max_words = 8;
  std::uint64_t f[max_words];
  int words = 0;
  bool small = factors.size() <= static_cast<std::size_t>(max_words);
  for (u128 x : factors) {
    if (!small || (x >> 64) != 0) {
      small = false;
      break;
    }
    const auto y = static_cast<std::uint64_t>(x);
    std::uint64_t packed = 0;
    if (words > 0 && !__builtin_mul_overflow(f[words - 1], y, &packed))
      f[words - 1] = packed;
    else
      f[words++] = y;
  }
  if (!small) {
    i128 n = 0;
    u128 den = 1;
    if (narrow(num, n) && product_fits(factors, den) && n != std::numeric_limits<i128>::min()) return fraction(n, den);
    cln::cl_I d = 1;
    for (u128 x : factors) d = d * to_integer(x, false);
    return to_integer(num) / d;
  }
  Wide256 m = num;
  const bool negative = (m.limb[3] >> 63) != 0;
  if (negative) m.negate();
  int top = 4;
  while (top > 0 && m.limb[top - 1] == 0) --top;
  if (top == 0) return cln::cl_RA(0);
  for (int k = 0; k < words; ++k) {
    if (f[k] == 1) continue;
    std::uint64_t r = 0;
    for (int i = top - 1; i >= 0; --i) divide(r, m.limb[i], f[k], r);
    const std::uint64_t h = gcd64(r, f[k]);
    if (h == 1) continue;
    r = 0;
    for (int i = top - 1; i >= 0; --i) m.limb[i] = divide(r, m.limb[i], h, r);
    while (top > 0 && m.limb[top - 1] == 0) --top;
    f[k] /= h;
  }
  cln::cl_I a;
  if (top <= 2) {
    a = to_integer((static_cast<u128>(m.limb[1]) << 64) | m.limb[0], negative);
  } else {
    if (negative) m.negate();
    a = to_integer(m);
  }
  u128 den = 1;
  bool fits = true;
  for (int k = 0; k < words && fits; ++k) fits = !__builtin_mul_overflow(den, static_cast<u128>(f[k]), &den);
  if (fits && den == 1) return a;
  cln::cl_I b = 1;
  if (fits) {
    b = to_integer(den, false);
  } else {
    for (int k = 0; k < words; ++k) b = b * cln::cl_I(static_cast<unsigned long long>(f[k]));
  }
  return coprime_fraction(a, b);
}

/// Exact division in the 128-bit ring: x = q·e with |q| < 2^(127 − t), t the
/// trailing zeros of e, gives q from x and e modulo 2^128 (the odd part of e
/// is invertible there; Newton's iteration doubles the correct bits).
class WideRing {
 public:
  using Z = Wide;
  static constexpr bool bounded = true;
  /// Quotients are known to be below 2^bits in magnitude.
  void set_quotient_bits(int bits) { room_ = 127 - bits; }
  bool ok() const { return ok_; }
  Wide div(Wide x, Wide e) {
    if (e.v != divisor_) {  // a divisor is used for a whole elimination step: its inverse is kept
      if (e.v == 0) return ok_ = false, Wide();
      const int t = trailing_zeros(e.v);
      const u128 odd = e.v >> t;
      u128 inv = (3 * odd) ^ 2;  // correct to 5 bits (Montgomery's seed)
      for (int i = 0; i < 5; ++i) inv *= 2 - odd * inv;
      divisor_ = e.v, inverse_ = inv, shift_ = t;
    }
    if (shift_ > room_) return ok_ = false, Wide();
    const u128 q = (x.v >> shift_) * inverse_;
    return Wide::raw(static_cast<u128>(static_cast<i128>(q << shift_) >> shift_));
  }

 private:
  int room_ = 0;
  bool ok_ = true;
  u128 divisor_ = 0, inverse_ = 0;  ///< the last divisor and the inverse of its odd part
  int shift_ = 0;                   ///< its trailing zeros
};

/// CLN integers: every value is exact.
class BigRing {
 public:
  using Z = cln::cl_I;
  static constexpr bool bounded = false;
  void set_quotient_bits(int) {}
  bool ok() const { return true; }
  cln::cl_I div(const cln::cl_I& x, const cln::cl_I& e) { return cln::exquo(x, e); }
};

// ---------------------------------------------------------------------------
// The data over common denominators.

/// The problem's rationals as integers over two common denominators, in
/// 64 bits when they fit (small), else as CLN integers.
struct IntegerData {
  bool small = false;
  std::vector<long long> m, v, u;  ///< m̂ (0 for a fixed body), v̂ per entry, û
  long long Lm = 1, Lu = 1;
  std::vector<cln::cl_I> M, V, U;
  cln::cl_I LM = 1, LU = 1;
  std::vector<long long> den;  ///< scratch of integers_small()
};

bool fits(const cln::cl_I& x, long long& out) {
  if (cln::integer_length(x) > 62) return false;
  out = cln::cl_I_to_Q(x);
  return true;
}

/// The 64-bit images; false when some value does not fit.
bool integers_small(const Problem<cln::cl_RA>& p, int nf, IntegerData& d) {
  const std::size_t n = static_cast<std::size_t>(p.n), ne = p.entries.size();
  std::vector<long long>& num = d.m;  // numerators first, scaled in place below
  std::vector<long long>& den = d.den;
  den.clear();
  num.assign(n, 0), d.v.assign(ne, 0), d.u.assign(n, 0);
  auto split = [&den](const cln::cl_RA& x, long long& to) {
    long long q = 1;
    if (!fits(cln::numerator(x), to) || !fits(cln::denominator(x), q)) return false;
    den.push_back(q);
    return true;
  };
  auto lcm = [](long long& L, long long q) {  // L, q > 0; most denominators divide L already
    if (L % q == 0) return true;
    const auto g = static_cast<long long>(gcd64(static_cast<std::uint64_t>(L), static_cast<std::uint64_t>(q)));
    return !__builtin_mul_overflow(L / g, q, &L) && L < (1LL << 62);
  };
  for (int i = 0; i < nf; ++i)
    if (!split(p.mass[static_cast<std::size_t>(i)], num[static_cast<std::size_t>(i)])) return false;
  for (std::size_t e = 0; e < ne; ++e)
    if (!split(p.entries[e].value, d.v[e])) return false;
  d.Lm = 1;
  for (long long q : den)
    if (!lcm(d.Lm, q)) return false;
  const std::size_t masses = den.size();
  for (std::size_t i = 0; i < n; ++i)
    if (!split(p.u[i], d.u[i])) return false;
  d.Lu = 1;
  for (std::size_t k = masses; k < den.size(); ++k)
    if (!lcm(d.Lu, den[k])) return false;
  auto scale = [](long long& x, long long L, long long q) { return !__builtin_mul_overflow(x, L / q, &x) && x < (1LL << 62) && x > -(1LL << 62); };
  std::size_t k = 0;
  for (int i = 0; i < nf; ++i, ++k)
    if (!scale(num[static_cast<std::size_t>(i)], d.Lm, den[k])) return false;
  for (std::size_t e = 0; e < ne; ++e, ++k)
    if (!scale(d.v[e], d.Lm, den[k])) return false;
  for (std::size_t i = 0; i < n; ++i, ++k)
    if (!scale(d.u[i], d.Lu, den[k])) return false;
  d.small = true;
  return true;
}

void integers_big(const Problem<cln::cl_RA>& p, int nf, IntegerData& d) {
  const std::size_t n = static_cast<std::size_t>(p.n), ne = p.entries.size();
  d.small = false;
  d.LM = 1, d.LU = 1;
  for (int i = 0; i < nf; ++i) d.LM = cln::lcm(d.LM, cln::denominator(p.mass[static_cast<std::size_t>(i)]));
  for (const auto& e : p.entries) d.LM = cln::lcm(d.LM, cln::denominator(e.value));
  for (const auto& x : p.u) d.LU = cln::lcm(d.LU, cln::denominator(x));
  auto scaled = [](const cln::cl_RA& x, const cln::cl_I& L) { return cln::numerator(x) * cln::exquo(L, cln::denominator(x)); };
  d.M.assign(n, 0), d.V.assign(ne, 0), d.U.assign(n, 0);
  for (int i = 0; i < nf; ++i) d.M[static_cast<std::size_t>(i)] = scaled(p.mass[static_cast<std::size_t>(i)], d.LM);
  for (std::size_t e = 0; e < ne; ++e) d.V[e] = scaled(p.entries[e].value, d.LM);
  for (std::size_t i = 0; i < n; ++i) d.U[i] = scaled(p.u[i], d.LU);
}

// ---------------------------------------------------------------------------
// The kernel over one ring.

template <class Ring>
class Kernel {
 public:
  using Z = typename Ring::Z;

  Kernel() = default;
  Kernel(const Problem<cln::cl_RA>& p, const IntegerData& data, int bandwidth) { reset(p, data, bandwidth); }

  /// The kernel of \p p (a kernel reused keeps its storage: no allocation
  /// once it has seen a problem as large).
  void reset(const Problem<cln::cl_RA>& p, const IntegerData& data, int bandwidth) {
    p_ = &p, ring_ = Ring(), assembled_ = true;
    n_ = p.n, nf_ = p.fixed_bottom ? n_ - 1 : n_, nc_ = n_ - 1, b_ = bandwidth;
    const auto n = static_cast<std::size_t>(n_);
    auto z = [&](std::size_t i, const std::vector<long long>& s, const std::vector<cln::cl_I>& big) -> Z {
      if constexpr (Ring::bounded) return Z(s[i]);
      else return data.small ? cln::cl_I(s[i]) : big[i];
    };
    m_.resize(n), u_.resize(n), v_.resize(p.entries.size());
    absm_.assign(n, 0), absu_.assign(n, 0), absv_.assign(p.entries.size(), 0);
    for (std::size_t i = 0; i < n; ++i) {
      m_[i] = z(i, data.m, data.M), u_[i] = z(i, data.u, data.U);
      if (data.small) absm_[i] = std::fabs(static_cast<double>(data.m[i])), absu_[i] = std::fabs(static_cast<double>(data.u[i]));
    }
    for (std::size_t e = 0; e < v_.size(); ++e) {
      v_[e] = z(e, data.v, data.V);
      if (data.small) absv_[e] = std::fabs(static_cast<double>(data.v[e]));
    }
    if constexpr (Ring::bounded) {
      Lm_ = Z(data.Lm), Lu_ = Z(data.Lu);
    } else {
      Lm_ = data.small ? cln::cl_I(data.Lm) : data.LM, Lu_ = data.small ? cln::cl_I(data.Lu) : data.LU;
    }
    assemble();
  }

  /// The kernel of \p wide in CLN integers, its assembly converted (not redone).
  template <class Other, class = std::enable_if_t<!std::is_same_v<Other, Ring>>>
  explicit Kernel(const Kernel<Other>& wide)
      : p_(wide.p_), n_(wide.n_), nf_(wide.nf_), nc_(wide.nc_), b_(wide.b_), absm_(wide.absm_), absu_(wide.absu_),
        absv_(wide.absv_), umax_(wide.umax_), row_(wide.row_) {
    auto convert = [](const std::vector<Wide>& from, std::vector<Z>& to) {
      to.resize(from.size());
      for (std::size_t i = 0; i < from.size(); ++i) to[i] = to_integer(from[i]);
    };
    convert(wide.m_, m_), convert(wide.u_, u_), convert(wide.v_, v_), convert(wide.A_, A_), convert(wide.rhs_, rhs_);
    Lm_ = to_integer(wide.Lm_), Lu_ = to_integer(wide.Lu_);
  }

  /// Whether the assembly is within the ring's reach (always, for CLN integers).
  bool assembled() const { return assembled_; }

  /// Solve the case \p closed: Ŵ, Λ, d.  False where the ring cannot prove
  /// its values or a pivot is not positive.
  bool solve_case(const std::vector<char>& closed);
  /// The sign of the gap of contact c (open contacts) and of λ_c (closed).
  int gap_sign(int c) const { return sign_of(Z(W_[c] - W_[c + 1])); }
  int lambda_sign(int c) const { return sign_of(Lam_[c]); }
  /// The exact residual check of the last case; then the answer into \p out.
  bool check(const std::vector<char>& closed);
  void write(const std::vector<char>& closed, Solution<cln::cl_RA>& out) const;
  /// write() in native integers (bounded ring): false, with \p out untouched,
  /// where a value's bound does not prove it exact.
  bool write_native(const std::vector<char>& closed, Solution<cln::cl_RA>& out) const;
  /// The numerators of the energies and of the dissipation (see write()) in
  /// 256 bits; false where their bound does not prove that exact (or the
  /// ring is CLN's).
  bool sums_in_256_bits(cln::cl_I& before, cln::cl_I& after, cln::cl_I& dissipation) const;

 private:
  Z& A(int i, int d) { return A_[static_cast<std::size_t>(i * (b_ + 1) + d)]; }
  const Z& A(int i, int d) const { return A_[static_cast<std::size_t>(i * (b_ + 1) + d)]; }
  void assemble();

  template <class>
  friend class Kernel;
  const Problem<cln::cl_RA>* p_ = nullptr;
  Ring ring_;
  int n_ = 0, nf_ = 0, nc_ = 0, b_ = 0;
  bool assembled_ = true;
  std::vector<Z> m_, u_, v_;
  Z Lm_, Lu_;
  std::vector<double> absm_, absu_, absv_;  ///< magnitudes (bounded ring)
  double umax_ = 0;  ///< max |û| (bounded ring)
  std::vector<Z> A_, rhs_;   ///< Â (lower band over all bodies) and b̂ (free bodies)
  std::vector<double> row_;  ///< per body: Σ |terms| of its row of Â (masses and M), a bound on Σ_j |Â_ij|
  // The last case.
  std::vector<int> cluster_;
  std::vector<Z> F_, y_, X_;  ///< band rows of the reduced system (2b+1 per row), its right side, Cramer numerators
  std::vector<Z> W_, Lam_;    ///< Ŵ = d L_u W (n), Λ = L_m d L_u λ (nc)
  std::vector<Z> pivots_;
  Z d_;
  std::vector<Z> rows_, yc_;  ///< check()'s rows and ŷ
  mutable std::vector<i128> w_, y_wide_;  ///< write_native()'s w and ŷ
};

template <class Ring>
void Kernel<Ring>::assemble() {
  // ClusterSystem::assemble in integers: Â = L_m (diag(m) + DᵀMD) on all
  // bodies, b̂ = L_m L_u (m u − K u − K_{·,fixed} u_fixed) on free bodies.
  const auto w = static_cast<std::size_t>(b_ + 1);
  A_.assign(static_cast<std::size_t>(n_) * w, Z(0));
  row_.assign(static_cast<std::size_t>(n_), 0.0);
  auto add = [&](int r, int c, const Z& x) {
    if (r < c) std::swap(r, c);
    A(r, r - c) += x;
  };
  for (std::size_t k = 0; k < p_->entries.size(); ++k) {
    const auto& e = p_->entries[k];
    const Z& x = v_[k];
    const double size = 2 * absv_[k];
    row_[e.i] += size, row_[e.j] += size;
    if (e.diagonal()) {
      A(e.i, 0) += x, A(e.j, 0) += x;
      add(e.j, e.i, Z(-x));
      continue;
    }
    row_[e.k] += size, row_[e.l] += size;
    const int rows[2] = {e.i, e.j}, cols[2] = {e.k, e.l};
    for (int a = 0; a < 2; ++a)
      for (int c = 0; c < 2; ++c) {
        const Z y = a == c ? x : Z(-x);
        if (rows[a] == cols[c])
          A(rows[a], 0) += Z(Z(2) * y);
        else
          add(rows[a], cols[c], y);
      }
  }
  rhs_.resize(static_cast<std::size_t>(nf_));
  umax_ = 0;
  for (int i = 0; i < n_; ++i) umax_ = std::max(umax_, absu_[i]);
  for (int j = 0; j < nf_; ++j) {
    Z acc = Z(0);
    for (int d = 0; d <= b_ && d <= j; ++d) acc -= A(j, d) * u_[j - d];
    for (int d = 1; d <= b_ && j + d < n_; ++d) acc -= A(j + d, d) * u_[j + d];
    if (p_->fixed_bottom && n_ - 1 - j <= b_) acc -= A(n_ - 1, n_ - 1 - j) * u_[n_ - 1];
    rhs_[j] = acc + m_[j] * u_[j];
  }
  for (int i = 0; i < nf_; ++i) A(i, 0) += m_[i], row_[i] += absm_[i];
  if constexpr (Ring::bounded) {
    // Σ_j |Â_ij| <= row_i; |b̂_j| <= 3 row_j max|û| (the fixed column counted
    // twice).
    // A case's reduced system sums rows of Â and b̂: at most Σ_i row_i (1 + 3 max|û|).
    double total = 0;
    for (int i = 0; i < n_; ++i) total += row_[i];
    assembled_ = total * (1 + 3 * umax_) * bound_margin < std::ldexp(1.0, wide_bits - 6);
  }
}

template <class Ring>
bool Kernel<Ring>::solve_case(const std::vector<char>& closed) {
  const auto n = static_cast<std::size_t>(n_);
  cluster_.resize(n);
  cluster_[0] = 0;
  for (int c = 0; c < nc_; ++c) cluster_[c + 1] = cluster_[c] + (closed[c] ? 0 : 1);
  const int fixed = p_->fixed_bottom ? cluster_[n_ - 1] : -1;
  const int K = p_->fixed_bottom ? fixed : cluster_[n_ - 1] + 1;
  const int w = 2 * b_ + 1;
  const auto Ks = static_cast<std::size_t>(K);
  F_.assign(Ks * static_cast<std::size_t>(w), Z(0));
  y_.assign(Ks, Z(0));
  auto F = [&](int r, int c) -> Z& { return F_[static_cast<std::size_t>(r * w + (c - r + b_))]; };
  const Z& u_fixed = u_[n - 1];
  for (int i = 0; i < nf_; ++i) {
    const int ci = cluster_[i];
    if (ci == fixed) {
      for (int d = 1; d <= b_ && d <= i; ++d)
        if (cluster_[i - d] != fixed) y_[cluster_[i - d]] -= A(i, d) * u_fixed;
      continue;
    }
    y_[ci] += rhs_[i];
    Z inner = A(i, 0);
    for (int d = 1; d <= b_ && d <= i; ++d) {
      const int cj = cluster_[i - d];
      if (cj == ci) {
        inner += Z(Z(2) * A(i, d));
      } else {
        F(ci, cj) += A(i, d);
        F(cj, ci) += A(i, d);
      }
    }
    F(ci, ci) += inner;
  }
  if constexpr (Ring::bounded) {
    // Hadamard: every minor of [R | y] is at most the product of its rows'
    // 2-norms (R and y are exact here: their entries sum at most
    // Σ_i row_i (1 + 3 max|û|) < 2^120 in magnitude, assemble()).
    double h = 1;
    for (int r = 0; r < K; ++r) {
      double norm2 = magnitude(y_[r]) * magnitude(y_[r]);
      for (int c = std::max(0, r - b_); c <= std::min(K - 1, r + b_); ++c) norm2 += magnitude(F(r, c)) * magnitude(F(r, c));
      h *= std::max(1.0, std::sqrt(norm2));
    }
    h *= bound_margin;
    if (!(h < std::ldexp(1.0, wide_bits - 1))) return false;
    int bits = 0;
    std::frexp(h, &bits);
    ring_.set_quotient_bits(bits);
  }
  // Bareiss on the band, rows entering the window scaled by the previous
  // pivot (a row untouched by steps 0 … k−1 has a^(k) = a · p_{k−1}).
  pivots_.assign(Ks, Z(0));
  Z prev = Z(1);
  for (int k = 0; k < K; ++k) {
    if (k > 0 && k + b_ < K) {
      const int r = k + b_;
      for (int c = std::max(0, r - b_); c <= std::min(K - 1, r + b_); ++c) F(r, c) = F(r, c) * prev;
      y_[r] = y_[r] * prev;
    }
    const Z piv = F(k, k);
    if (sign_of(piv) <= 0) return false;
    pivots_[k] = piv;
    const int last = std::min(K - 1, k + b_);
    for (int i = k + 1; i <= last; ++i) {
      const Z f = F(i, k);
      for (int j = k + 1; j <= std::min(K - 1, i + b_); ++j) {
        const Z t = j <= k + b_ ? Z(piv * F(i, j) - f * F(k, j)) : Z(piv * F(i, j));
        F(i, j) = k > 0 ? ring_.div(t, prev) : t;
      }
      const Z t = piv * y_[i] - f * y_[k];
      y_[i] = k > 0 ? ring_.div(t, prev) : t;
      F(i, k) = Z(0);
    }
    prev = piv;
  }
  d_ = K > 0 ? prev : Z(1);
  X_.assign(Ks, Z(0));
  for (int i = K - 1; i >= 0; --i) {
    Z t = d_ * y_[i];
    for (int j = i + 1; j <= std::min(K - 1, i + b_); ++j) t -= F(i, j) * X_[j];
    X_[i] = i == K - 1 ? y_[i] : ring_.div(t, pivots_[i]);
  }
  if (!ring_.ok()) return false;
  W_.resize(n);
  for (int i = 0; i < n_; ++i) W_[i] = cluster_[i] == fixed ? Z(d_ * u_fixed) : X_[cluster_[i]];
  if constexpr (Ring::bounded) {
    // Bounds of every later integer from the values found: |ŷ| <= 2 wmax
    // (wmax = max(|Ŵ|, d max|û|)); Λ's partial sums add row residuals of at
    // most 3 row_r wmax (|b̂_r| <= 3 row_r max|û|, Σ_j |Â_rj| <= row_r) over
    // closed contacts; a row of the check is at most 4 row_i wmax + 2 max|Λ|;
    // the momentum after at most Σ_i row_i wmax.
    double wmax = magnitude(d_) * umax_, rows = 0, closed_rows = 0, widest = 0;
    for (int i = 0; i < n_; ++i) wmax = std::max(wmax, magnitude(W_[i]));
    for (int i = 0; i < n_; ++i) {
      rows += row_[i], widest = std::max(widest, row_[i]);
      if (i < nc_ && closed[i]) closed_rows += row_[i];
    }
    const double lambda = 3 * closed_rows * wmax;
    const double largest = std::max({4 * widest * wmax + 2 * lambda, 2 * rows * wmax, 2 * wmax});
    if (!(largest * bound_margin < std::ldexp(1.0, wide_bits - 1))) return false;
  }
  // Λ: running sums of the row residuals ÂŴ − d b̂ down each closed run.
  Lam_.assign(static_cast<std::size_t>(nc_), Z(0));
  auto row_residual = [&](int c) {
    Z r = Z(-(d_ * rhs_[c]));
    for (int d = 0; d <= b_ && d <= c; ++d) r += A(c, d) * W_[c - d];
    for (int d = 1; d <= b_ && c + d < nf_; ++d) r += A(c + d, d) * W_[c + d];
    return r;
  };
  Z sum = Z(0);
  for (int c = 0; c < nc_; ++c) {
    if (!closed[c]) {
      sum = Z(0);
      continue;
    }
    sum += row_residual(c);
    Lam_[c] = sum;
  }
  return true;
}

template <class Ring>
bool Kernel<Ring>::check(const std::vector<char>& closed) {
  // complete_solution's check, in integers scaled by L_m d L_u: with
  // ŷ = Ŵ + d û, every free body's row
  //   Σ_entries v̂ (ŷ_k − ŷ_l)(e_i − e_j) [+ transpose] + m̂ (Ŵ − d û) − Λ_i + Λ_{i−1}
  // is 0, closed gaps are 0 with Λ >= 0, open gaps are >= 0.
  std::vector<Z>&rows = rows_, &y = yc_;
  rows.assign(static_cast<std::size_t>(n_), Z(0)), y.resize(static_cast<std::size_t>(n_));
  for (int i = 0; i < n_; ++i) y[i] = W_[i] + d_ * u_[i];
  for (std::size_t k = 0; k < p_->entries.size(); ++k) {
    const auto& e = p_->entries[k];
    const Z f = v_[k] * Z(y[e.k] - y[e.l]);
    rows[e.i] += f, rows[e.j] -= f;
    if (e.diagonal()) continue;
    const Z g = v_[k] * Z(y[e.i] - y[e.j]);
    rows[e.k] += g, rows[e.l] -= g;
  }
  for (int i = 0; i < nf_; ++i) {
    Z r = rows[i] + m_[i] * Z(W_[i] - d_ * u_[i]);
    if (i < nc_) r -= Lam_[i];
    if (i > 0) r += Lam_[i - 1];
    if (sign_of(r) != 0) return false;
  }
  for (int c = 0; c < nc_; ++c) {
    const int g = gap_sign(c);
    if (closed[c] ? g != 0 || lambda_sign(c) < 0 : g < 0 || sign_of(Lam_[c]) != 0) return false;
  }
  return sign_of(d_) > 0;
}

template <class Ring>
void Kernel<Ring>::write(const std::vector<char>& closed, Solution<cln::cl_RA>& out) const {
  if constexpr (Ring::bounded)
    if (write_native(closed, out)) return;
  // One gcd per value: numerators over the common denominators.
  const cln::cl_I d = to_integer(d_), Lm = to_integer(Lm_), Lu = to_integer(Lu_);
  const cln::cl_I den = d * Lu, lden = Lm * den;
  const auto n = static_cast<std::size_t>(n_), nc = static_cast<std::size_t>(nc_);
  out.velocities_after.resize(n);
  out.gaps.resize(nc);
  out.reactions.resize(nc);
  for (std::size_t i = 0; i < n; ++i) out.velocities_after[i] = to_integer(W_[i]) / den;
  if (out.closed.bodies() != n_) out.closed = ContactSet(n_);
  for (std::size_t c = 0; c < nc; ++c) {
    const Z g = W_[c] - W_[c + 1];
    out.gaps[c] = sign_of(g) == 0 ? cln::cl_RA(0) : cln::cl_RA(to_integer(g) / den);
    out.reactions[c] = sign_of(Lam_[c]) == 0 ? cln::cl_RA(0) : cln::cl_RA(to_integer(Z(-Lam_[c])) / lden);
    out.closed.set_closed(static_cast<int>(c), closed[c] || sign_of(g) == 0);
  }
  // Momenta and energies of the free bodies; dissipation P·X = 2XᵀMX + R·X
  // with X = y/2, as complete_solution (scaled: y = ŷ / den, R = −Λ / lden).
  Z pb = Z(0), pa = Z(0);
  for (int i = 0; i < nf_; ++i) pb += m_[i] * u_[i], pa += m_[i] * W_[i];
  out.momentum_before = to_integer(pb) / (Lm * Lu);
  out.momentum_after = to_integer(pa) / lden;
  // 2 Lm Lu² · energy before = Σ m̂ û², 2 Lm den² · energy after = Σ m̂ Ŵ²,
  // 2 Lm den² · dissipation = Σ_diag v̂ ŷij ŷkl + 2 Σ_off v̂ ŷij ŷkl − Σ_c Λ_c (ŷ_c − ŷ_{c+1}).
  cln::cl_I eb, ea, diss;
  if (!sums_in_256_bits(eb, ea, diss)) {
    eb = 0, ea = 0, diss = 0;
    std::vector<cln::cl_I> y(n);
    for (std::size_t i = 0; i < n; ++i) y[i] = to_integer(Z(W_[i] + d_ * u_[i]));
    for (int i = 0; i < nf_; ++i) {
      const cln::cl_I mi = to_integer(m_[i]), ui = to_integer(u_[i]), wi = to_integer(W_[i]);
      eb = eb + mi * ui * ui, ea = ea + mi * wi * wi;
    }
    for (std::size_t k = 0; k < p_->entries.size(); ++k) {
      const auto& e = p_->entries[k];
      const cln::cl_I t = to_integer(v_[k]) * (y[e.i] - y[e.j]) * (y[e.k] - y[e.l]);
      diss = diss + (e.diagonal() ? t : cln::cl_I(2 * t));
    }
    for (std::size_t c = 0; c < nc; ++c)
      if (sign_of(Lam_[c]) != 0) diss = diss - to_integer(Lam_[c]) * (y[c] - y[c + 1]);
  }
  out.kinetic_energy_before = eb / (2 * Lm * Lu * Lu);
  out.kinetic_energy_after = ea / (2 * Lm * den * den);
  out.dissipation = diss / (2 * Lm * den * den);
  out.residual_motion = 0;
  out.residual_complementarity = 0;
  out.status = Status::Success;
}

template <class Ring>
bool Kernel<Ring>::write_native(const std::vector<char>& closed, Solution<cln::cl_RA>& out) const {
  if constexpr (!Ring::bounded) {
    (void)closed, (void)out;
    return false;
  } else {
    // The velocities share the denominator den = d L_u: divided first by
    // g = gcd(den, Ŵ_0 … Ŵ_{n−1}), W = w / e with e = den / g, so that each
    // fraction's own gcd (and those of the gaps, momenta and energy after,
    // in that scale) works on smaller integers, natively where 128 bits hold
    // them (fraction()).  The sums are those of write(), in 256 bits under
    // the same kind of bound.
    const auto n = static_cast<std::size_t>(n_), nc = static_cast<std::size_t>(nc_);
    auto value = [](Wide x) { return static_cast<i128>(x.v); };
    auto size = [](i128 x) { return x < 0 ? -static_cast<u128>(x) : static_cast<u128>(x); };
    auto wide = [](i128 x) { return Wide::raw(static_cast<u128>(x)); };
    auto small = [&](Wide x) { return static_cast<long long>(value(x)); };  // data: below 2^62
    if (sign_of(d_) <= 0) return false;
    const auto d = static_cast<u128>(value(d_)), L_m = static_cast<u128>(value(Lm_)), L_u = static_cast<u128>(value(Lu_));
    u128 den = 0;
    if (!product_fits({d, L_u}, den)) return false;
    u128 g = den;
    for (std::size_t i = 0; i < n && g != 1; ++i) g = gcd128(g, size(value(W_[i])));
    const u128 e = den / g;
    std::vector<i128>&w = w_, &y = y_wide_;
    w.resize(n), y.resize(n);
    for (std::size_t i = 0; i < n; ++i) w[i] = value(W_[i]) / static_cast<i128>(g), y[i] = value(W_[i] + d_ * u_[i]);
    // Bounds (Σ |terms|) of the 256-bit sums.
    double eb = 0, ea = 0, ed = 0;
    Wide256 pb, pa, b, a, dis;
    for (int i = 0; i < nf_; ++i) {
      const double wi = static_cast<double>(size(w[i]));
      eb += absm_[i] * absu_[i] * absu_[i], ea += absm_[i] * std::max(wi * wi, wi);
      const long long mi = small(m_[i]);
      pb += product(u_[i], Wide(1), mi), b += product(u_[i], u_[i], mi);
      pa += product(wide(w[i]), Wide(1), mi), a += product(wide(w[i]), wide(w[i]), mi);
    }
    for (std::size_t k = 0; k < p_->entries.size(); ++k) {
      const auto& en = p_->entries[k];
      const Wide yij = wide(y[en.i] - y[en.j]), ykl = wide(y[en.k] - y[en.l]);
      const long long v = small(v_[k]) * (en.diagonal() ? 1 : 2);
      ed += std::fabs(static_cast<double>(v)) * magnitude(yij) * magnitude(ykl);
      dis += product(yij, ykl, v);
    }
    for (int c = 0; c < nc_; ++c)
      if (sign_of(Lam_[c]) != 0) {
        const Wide dy = wide(y[c] - y[c + 1]);
        ed += magnitude(Lam_[c]) * magnitude(dy);
        dis += product(Lam_[c], dy, -1);
      }
    if (!(std::max({eb, ea, ed}) * bound_margin < std::ldexp(1.0, 254))) return false;
    out.velocities_after.resize(n);
    out.gaps.resize(nc);
    out.reactions.resize(nc);
    for (std::size_t i = 0; i < n; ++i) out.velocities_after[i] = fraction(w[i], e);
    if (out.closed.bodies() != n_) out.closed = ContactSet(n_);
    for (std::size_t c = 0; c < nc; ++c) {
      const i128 gap = w[c] - w[c + 1];
      out.gaps[c] = fraction(gap, e);
      out.reactions[c] = sign_of(Lam_[c]) == 0 ? cln::cl_RA(0) : fraction(product(Z(-Lam_[c]), Wide(1), 1), {L_m, g, e});
      out.closed.set_closed(static_cast<int>(c), closed[c] || gap == 0);
    }
    out.momentum_before = fraction(pb, {L_m, L_u});
    out.momentum_after = fraction(pa, {L_m, e});
    out.kinetic_energy_before = fraction(b, {2, L_m, L_u, L_u});
    out.kinetic_energy_after = fraction(a, {2, L_m, e, e});
    out.dissipation = fraction(dis, {2, L_m, g, e, g, e});  // den = g e
    out.residual_motion = 0;
    out.residual_complementarity = 0;
    out.status = Status::Success;
    return true;
  }
}

template <class Ring>
bool Kernel<Ring>::sums_in_256_bits(cln::cl_I& before, cln::cl_I& after, cln::cl_I& dissipation) const {
  if constexpr (!Ring::bounded) {
    (void)before, (void)after, (void)dissipation;
    return false;
  } else {
    const auto n = static_cast<std::size_t>(n_);
    auto small = [](Wide x) { return static_cast<long long>(static_cast<i128>(x.v)); };  // data: below 2^62
    std::vector<Wide> y(n);
    for (std::size_t i = 0; i < n; ++i) y[i] = W_[i] + d_ * u_[i];
    double eb = 0, ea = 0, ed = 0;  // the bounds: Σ |terms|
    Wide256 b, a, dis;
    for (int i = 0; i < nf_; ++i) {
      eb += absm_[i] * absu_[i] * absu_[i], ea += absm_[i] * magnitude(W_[i]) * magnitude(W_[i]);
      b += product(u_[i], u_[i], small(m_[i]));
      a += product(W_[i], W_[i], small(m_[i]));
    }
    for (std::size_t k = 0; k < p_->entries.size(); ++k) {
      const auto& e = p_->entries[k];
      const Wide yij = y[e.i] - y[e.j], ykl = y[e.k] - y[e.l];
      const long long v = small(v_[k]) * (e.diagonal() ? 1 : 2);
      ed += std::fabs(static_cast<double>(v)) * magnitude(yij) * magnitude(ykl);
      dis += product(yij, ykl, v);
    }
    for (int c = 0; c < nc_; ++c)
      if (sign_of(Lam_[c]) != 0) {
        const Wide dy = y[c] - y[c + 1];
        ed += magnitude(Lam_[c]) * magnitude(dy);
        dis += product(Lam_[c], dy, -1);
      }
    if (!(std::max({eb, ea, ed}) * bound_margin < std::ldexp(1.0, 254))) return false;
    before = to_integer(b), after = to_integer(a), dissipation = to_integer(dis);
    return true;
  }
}

/// The solver's pivoting rule on the cases solved by \p solve(closed) (false:
/// the kernel declines), whose signs \p gap_sign(c) and \p lambda_sign(c)
/// give; the number of pivots (Murty) or iterations (Block), −1 where the
/// kernel declines.
template <class Solve, class Gap, class Lambda>
int pivot(int nc, ExactPivoting rule, int cap, std::vector<char>& closed, std::vector<char>& flip, Solve&& solve, Gap&& gap_sign,
          Lambda&& lambda_sign) {
  constexpr int block_pivot_patience = 10;  // ChainSolver's
  closed.assign(static_cast<std::size_t>(nc), rule == ExactPivoting::Block ? 1 : 0);
  int count = 0, best = std::numeric_limits<int>::max(), stall = 0;
  for (;;) {
    if (!solve(closed)) return -1;
    auto bad = [&](int c) { return closed[c] ? lambda_sign(c) < 0 : gap_sign(c) < 0; };
    int wrong = 0, first = -1;
    for (int c = 0; c < nc; ++c)
      if (bad(c)) {
        ++wrong;
        if (first < 0) first = c;
        if (rule == ExactPivoting::Murty) break;
      }
    if (wrong == 0) return count;
    if (++count > cap) return -1;  // the rational path reports NoConvergence
    if (rule == ExactPivoting::Murty) {
      closed[first] ^= 1;
      continue;
    }
    if (wrong < best) {
      best = wrong, stall = 0;
    } else {
      ++stall;
    }
    if (stall < block_pivot_patience) {
      flip.assign(static_cast<std::size_t>(nc), 0);
      for (int c = 0; c < nc; ++c) flip[c] = bad(c);
      for (int c = 0; c < nc; ++c) closed[c] ^= flip[c];
    } else {
      closed[first] ^= 1;
    }
  }
}

/// Each case in 128 bits where its bounds allow (\p data small), else in
/// CLN integers; the answer from the kernel that solved the last case.
/// What a solve needs besides CLN's integers, kept per thread from one solve
/// to the next (no allocation once a thread has solved a problem as large).
struct Workspace {
  IntegerData data;
  Kernel<WideRing> wide;
  std::vector<char> closed, flip;
};

bool run(const Problem<cln::cl_RA>& p, Workspace& ws, int bandwidth, ExactPivoting rule, int cap, Solution<cln::cl_RA>& out) {
  const IntegerData& data = ws.data;
  Kernel<WideRing>& wide_storage = ws.wide;
  Kernel<WideRing>* wide = nullptr;
  std::optional<Kernel<BigRing>> big;
  if (data.small) {
    wide_storage.reset(p, data, bandwidth);
    if (wide_storage.assembled()) wide = &wide_storage;
  }
  bool last_wide = false;
  auto solve = [&](const std::vector<char>& closed) {
    last_wide = wide && wide->solve_case(closed);
    if (last_wide) return true;
    if (!big) {
      if (wide)
        big.emplace(*wide);
      else
        big.emplace(p, data, bandwidth);
    }
    return big->solve_case(closed);
  };
  auto gap = [&](int c) { return last_wide ? wide->gap_sign(c) : big->gap_sign(c); };
  auto lambda = [&](int c) { return last_wide ? wide->lambda_sign(c) : big->lambda_sign(c); };
  std::vector<char>& closed = ws.closed;
  const int count = pivot(p.n - 1, rule, cap, closed, ws.flip, solve, gap, lambda);
  if (count < 0) return false;
  if (last_wide ? !wide->check(closed) : !big->check(closed)) return false;
  if (last_wide)
    wide->write(closed, out);
  else
    big->write(closed, out);
  out.pivots = count;
  return true;
}

}  // namespace

bool exact_integer_solve(const Problem<cln::cl_RA>& p, ExactPivoting rule, int max_iterations,
                         const Settings<cln::cl_RA>& settings, Solution<cln::cl_RA>& out) {
  if (!cln::zerop(settings.feasibility)) return false;
  const int nf = p.fixed_bottom ? p.n - 1 : p.n;
  for (int i = 0; i < nf; ++i)
    if (!cln::plusp(p.mass[static_cast<std::size_t>(i)])) return false;
  const int bandwidth = p.bandwidth();
  thread_local Workspace ws;
  if (!integers_small(p, nf, ws.data)) integers_big(p, nf, ws.data);
  return run(p, ws, bandwidth, rule, max_iterations, out);
}

}  // namespace superball::numeric::detail
