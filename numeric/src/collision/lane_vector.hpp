#pragma once
// Internal: lane_width doubles in one SIMD vector (GCC and Clang vector
// extensions), for the fixed-size path in lanes (small_solver.cpp).  Every
// operation is the IEEE one of double on each lane (no fused multiply-add:
// small_solver.cpp is compiled with -ffp-contract=off and its AVX2 copy
// enables no FMA), so each lane computes what the scalar code computes.
// Header-only and inline: each function that uses it (the baseline and the
// AVX2 copy) gets its own code for its target.

#include "collision/lanes.hpp"

namespace superball::numeric::detail {

// Vectors pass by value only between functions of one target: every
// function here is always inlined, small_solver.cpp's AVX2 entries inline
// every call (flatten), and its baseline entries call baseline code only.
// So the compilers' note on the ABI of a 32-byte vector without AVX does not
// apply.
#if defined(__clang__)
#pragma clang diagnostic ignored "-Wpsabi"
#elif defined(__GNUC__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif
#define SUPERBALL_LANE inline __attribute__((always_inline))

static_assert(lane_width == 4, "the initializers below list 4 lanes");

/// A condition per lane: all bits set where it holds.
struct LaneMask {
  using Bits = long long __attribute__((vector_size(8 * lane_width)));
  Bits bits;
};
SUPERBALL_LANE LaneMask operator&(LaneMask a, LaneMask b) { return {a.bits & b.bits}; }
SUPERBALL_LANE LaneMask operator!(LaneMask a) { return {~a.bits}; }
/// The lanes where \p m holds, lane q as bit q.
SUPERBALL_LANE unsigned lanes_of(LaneMask m) {
  unsigned out = 0;
  for (int q = 0; q < lane_width; ++q) out |= m.bits[q] ? 1u << q : 0u;
  return out;
}

/// lane_width doubles, one problem's number per lane.
struct Lanes {
  using Vector = double __attribute__((vector_size(8 * lane_width)));
  Vector v;

  Lanes() = default;
  /// \p x in every lane (also −0, NaN, ±inf as they are).
  SUPERBALL_LANE Lanes(double x) : v{x, x, x, x} {}  // NOLINT: implicit, as double's constants are in the scalar code
  SUPERBALL_LANE explicit Lanes(Vector x) : v(x) {}
  /// lane_width doubles from \p x.
  SUPERBALL_LANE static Lanes load(const double* x) {
    Lanes out;
    __builtin_memcpy(&out.v, x, sizeof out.v);
    return out;
  }
  SUPERBALL_LANE double operator[](int q) const { return v[q]; }

  SUPERBALL_LANE Lanes& operator+=(Lanes b) { return v += b.v, *this; }
  SUPERBALL_LANE Lanes& operator-=(Lanes b) { return v -= b.v, *this; }
  SUPERBALL_LANE Lanes& operator*=(Lanes b) { return v *= b.v, *this; }
  SUPERBALL_LANE Lanes& operator/=(Lanes b) { return v /= b.v, *this; }
  friend SUPERBALL_LANE Lanes operator+(Lanes a, Lanes b) { return Lanes(a.v + b.v); }
  friend SUPERBALL_LANE Lanes operator-(Lanes a, Lanes b) { return Lanes(a.v - b.v); }
  friend SUPERBALL_LANE Lanes operator*(Lanes a, Lanes b) { return Lanes(a.v * b.v); }
  friend SUPERBALL_LANE Lanes operator/(Lanes a, Lanes b) { return Lanes(a.v / b.v); }
  friend SUPERBALL_LANE Lanes operator-(Lanes a) { return Lanes(-a.v); }
  friend SUPERBALL_LANE LaneMask operator<(Lanes a, Lanes b) { return {(LaneMask::Bits)(a.v < b.v)}; }
  friend SUPERBALL_LANE LaneMask operator>(Lanes a, Lanes b) { return {(LaneMask::Bits)(a.v > b.v)}; }
  friend SUPERBALL_LANE LaneMask operator<=(Lanes a, Lanes b) { return {(LaneMask::Bits)(a.v <= b.v)}; }
  friend SUPERBALL_LANE LaneMask operator==(Lanes a, Lanes b) { return {(LaneMask::Bits)(a.v == b.v)}; }
};

/// |x| per lane (the sign bits cleared, as std::fabs).
SUPERBALL_LANE Lanes magnitude(Lanes x) {
  constexpr long long bits = 0x7fffffffffffffffll;
  return Lanes((Lanes::Vector)((LaneMask::Bits)x.v & LaneMask::Bits{bits, bits, bits, bits}));
}
/// Per lane, \p a where \p m holds, else \p b.
SUPERBALL_LANE Lanes select(LaneMask m, Lanes a, Lanes b) {
  return Lanes((Lanes::Vector)(((LaneMask::Bits)a.v & m.bits) | ((LaneMask::Bits)b.v & ~m.bits)));
}

/// The decisions of the fixed-size path on lanes (OneProblem's for one
/// problem, dense_steps.hpp): the lanes still being solved are `live`; a
/// branch that gives up drops the lanes where its condition holds, and a
/// branch that chooses the next step is decided by the first live lane, the
/// lanes that would choose otherwise dropped.  So each lane left has taken
/// every branch its own solve takes, and its numbers are that solve's.
struct LaneFlow {
  unsigned live;
  /// Drops the lanes where \p condition holds; true when none is left.
  SUPERBALL_LANE bool fails(LaneMask condition) {
    live &= ~lanes_of(condition);
    return live == 0;
  }
  /// The first live lane's \p condition; the lanes where it differs dropped.
  SUPERBALL_LANE bool leader(LaneMask condition) {
    const unsigned holds = lanes_of(condition);
    const bool taken = ((holds >> __builtin_ctz(live)) & 1u) != 0;
    live &= taken ? holds : ~holds;
    return taken;
  }
};

}  // namespace superball::numeric::detail

#undef SUPERBALL_LANE
