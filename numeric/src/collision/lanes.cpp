// The fixed-size path in lanes (lanes.hpp): small_solver.cpp's operations
// for the case with every contact open (assemble(), solve_open_case(), the
// start of pivot(), complete() with no contact closed), in their order, on
// vectors of lane_width doubles, one problem per lane.  Every operation is
// the IEEE add, subtract, multiply, divide or comparison of the scalar code
// (no fused multiply-add: the AVX2 copy enables no FMA, and this file is
// compiled with -ffp-contract=off), and every branch of the scalar code on
// a value is a per-lane select or ends the lane, so each lane solved is
// small_solver.cpp's solve bit for bit (tests/numeric/batch_test.cpp, Lanes.*).
// Any change to the arithmetic of small_solver.cpp must be made here too.
//
// The kernel is written once and compiled twice: for the build's baseline
// target (x86-64: GCC and Clang split each vector into SSE2 pairs) and, on
// x86, for AVX2 in a function of target("avx2"), chosen at run time.
#include "collision/lanes.hpp"

#include <algorithm>
#include <cstring>

#include "collision/small_solver.hpp"

namespace superball::numeric::detail {

namespace {

#if defined(__GNUC__) && !defined(__clang__)
// V passed by value between the helpers below, which are always inlined:
// no call passes one, so GCC's note on the ABI of a 32-byte vector without
// AVX does not apply.
#pragma GCC diagnostic ignored "-Wpsabi"
// R's entries outside the band are never written nor read, which GCC cannot
// tell when the bandwidth is not a constant.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

using V = double __attribute__((vector_size(8 * lane_width)));
using Mask = long long __attribute__((vector_size(8 * lane_width)));

#define SUPERBALL_LANE inline __attribute__((always_inline))

SUPERBALL_LANE V broadcast(double x) { return V{x, x, x, x}; }
SUPERBALL_LANE V load(const double* x) {
  V v;
  std::memcpy(&v, x, sizeof v);
  return v;
}
/// |x| (clears the sign bits: std::fabs per lane).
SUPERBALL_LANE V magnitude(V x) {
  constexpr long long bits = 0x7fffffffffffffffll;
  return (V)((Mask)x & Mask{bits, bits, bits, bits});
}
/// Per lane, a where \p m is set, else b.
SUPERBALL_LANE V pick(Mask m, V a, V b) { return (V)(((Mask)a & m) | ((Mask)b & ~m)); }
/// if (to < x) to = x, per lane.
SUPERBALL_LANE void raise(V& to, V x) { to = pick((Mask)(to < x), x, to); }
SUPERBALL_LANE unsigned lanes_of(Mask m) {
  unsigned bits = 0;
  for (int q = 0; q < lane_width; ++q) bits |= m[q] ? 1u << q : 0u;
  return bits;
}

/// small_solver.cpp's Small<double, N, Full>::compute() on lane_width
/// problems, for the lanes that take its path without a pivot (lanes.hpp).
/// Full: DᵀMD's bandwidth is N − 1 (every loop's length a constant, as
/// Small<double, N, true>), else \p bandwidth bounds them.
template <int N, bool Full>
SUPERBALL_LANE unsigned solve_lanes(const Problem<double>& p, int bandwidth, const double* values, unsigned todo,
                                    const Settings<double>& settings, Solution<double>* out) {
  const int band = Full ? N - 1 : bandwidth;
  if (band < 0 || band >= N) __builtin_unreachable();  // tells the compiler the indices stay inside the arrays
  constexpr int n = N, nc = N - 1;
  const int nf = p.fixed_bottom ? N - 1 : N;
  const int ne = static_cast<int>(p.entries.size());
  Mask ok;
  for (int q = 0; q < lane_width; ++q) ok[q] = (todo >> q) & 1u ? -1 : 0;
  const int first = __builtin_ctz(todo);
  V m[N], u[N];
  for (int i = 0; i < N; ++i) m[i] = broadcast(p.mass[static_cast<std::size_t>(i)]), u[i] = broadcast(p.u[static_cast<std::size_t>(i)]);

  // assemble(): A and b̃; the groups M's nonzero entries join (Labels'
  // joins, on the first lane's zeros, which the other lanes must share).
  int group[N];
  for (int i = 0; i < N; ++i) group[i] = i;
  const auto join = [&group](int a, int b) {
    const int ra = group[a], rb = group[b];
    for (int i = 0; i < N; ++i)
      if (group[i] == ra) group[i] = rb;
  };
  V A[N][N];
  for (int i = 0; i < N; ++i)
    for (int d = 0; d <= i; ++d) A[i][d] = V{};
  for (int k = 0; k < ne; ++k) {
    const Entry<double>& e = p.entries[static_cast<std::size_t>(k)];
    const V v = load(values + lane_width * k);
    const bool nonzero = !(values[lane_width * k + first] == 0.0);
    ok &= nonzero ? (Mask)(v != 0.0) : (Mask)(v == 0.0);
    if (nonzero) {
      join(e.i, e.j);
      if (!e.diagonal()) join(e.k, e.l), join(e.i, e.k);
    }
    if (e.diagonal()) {
      A[e.i][0] += v;
      A[e.j][0] += v;
      A[e.j][e.j - e.i] += -v;
      continue;
    }
    const int rows[2] = {e.i, e.j}, cols[2] = {e.k, e.l};
    for (int a = 0; a < 2; ++a)
      for (int c = 0; c < 2; ++c) {
        const V w = a == c ? v : -v;
        if (rows[a] == cols[c])
          A[rows[a]][0] += 2.0 * w;
        else
          A[std::max(rows[a], cols[c])][std::max(rows[a], cols[c]) - std::min(rows[a], cols[c])] += w;
      }
  }
  V rhs[N];
  for (int j = 0; j < nf; ++j) {
    V acc = V{};
    for (int d = 0; d <= band && d <= j; ++d) acc -= A[j][d] * u[j - d];
    for (int d = 1; d <= band && j + d < n; ++d) acc -= A[j + d][d] * u[j + d];
    if (p.fixed_bottom && n - 1 - j <= band) acc -= A[n - 1][n - 1 - j] * u[n - 1];
    rhs[j] = acc;
  }
  for (int i = 0; i < nf; ++i) {
    rhs[i] += m[i] * u[i];
    A[i][0] += m[i];
  }

  // solve_open_case(): factor_and_solve() of the case's banded system.
  V R[N][N], y[N], l[N], W[N];
  for (int i = 0; i < nf; ++i) {
    y[i] = 0.0 + rhs[i];
    R[i][0] = 0.0 + A[i][0];
    for (int d = 1; d <= band; ++d) R[i][d] = d <= i ? V(0.0 + A[i][d]) : V{};
  }
  const int k = nf;
  for (int j = 0; j < k; ++j) {
    const V dj = R[j][0];
    ok &= (Mask)(dj > 0.0);  // else the general path decides
    const int last = std::min(k - 1, j + band);
    for (int r = j + 1; r <= last; ++r) l[r - j] = R[r][r - j] / dj;
    for (int r = j + 1; r <= last; ++r)
      for (int i = r; i <= last; ++i) R[i][i - r] -= R[i][i - j] * l[r - j];
    for (int r = j + 1; r <= last; ++r) R[r][r - j] = l[r - j];
  }
  for (int i = 0; i < k; ++i)
    for (int j = std::max(0, i - band); j < i; ++j) y[i] -= R[i][i - j] * y[j];
  for (int i = 0; i < k; ++i) y[i] /= R[i][0];
  for (int i = k - 1; i >= 0; --i)
    for (int j = i + 1; j <= std::min(k - 1, i + band); ++j) y[i] -= R[j][j - i] * y[j];
  for (int i = 0; i < nf; ++i) W[i] = y[i];
  if (p.fixed_bottom) W[n - 1] = u[n - 1];

  // pivot(): a lane with a contact to pivot on leaves the lanes.
  V t[N], scale = V{};
  for (int c = 0; c < nc; ++c) t[c] = c + 1 < nf ? V(W[c] - W[c + 1]) : V(W[c] - u[n - 1]);
  for (int c = 0; c < nc; ++c) scale = pick((Mask)(scale < magnitude(t[c])), magnitude(t[c]), scale);  // std::max
  const V tol = settings.feasibility * scale;
  for (int c = 0; c < nc; ++c) ok &= ~(Mask)(t[c] < -tol);
  if (!lanes_of(ok)) return 0;

  // complete() with no contact closed (every λ and reaction +0).
  V gaps[N];
  for (int c = 0; c < nc; ++c) gaps[c] = W[c] - W[c + 1];
  double ke_before = 0, p_before = 0;
  V ke_after = V{}, p_after = V{};
  for (int i = 0; i < nf; ++i) {
    const double mi = p.mass[static_cast<std::size_t>(i)], ui = p.u[static_cast<std::size_t>(i)];
    ke_before += mi * ui * ui / 2.0;
    ke_after += m[i] * W[i] * W[i] / 2.0;
    p_before += mi * ui;
    p_after += m[i] * W[i];
  }
  V yv[N], ys[N], rv[N], rs[N];
  for (int i = 0; i < n; ++i) yv[i] = W[i] + u[i], ys[i] = magnitude(W[i]) + magnitude(u[i]), rv[i] = V{}, rs[i] = V{};
  V dissipation = V{};
  for (int k = 0; k < ne; ++k) {
    const Entry<double>& e = p.entries[static_cast<std::size_t>(k)];
    const V v = load(values + lane_width * k);
    const V yij = yv[e.i] - yv[e.j], ykl = yv[e.k] - yv[e.l];
    const V f = v * ykl, s = magnitude(v) * (ys[e.k] + ys[e.l]);
    rv[e.i] += f, rs[e.i] += s;
    rv[e.j] += -f, rs[e.j] += s;
    if (e.diagonal()) {
      dissipation += f * yij / 2.0;
      continue;
    }
    const V g = v * yij, w = magnitude(v) * (ys[e.i] + ys[e.j]);
    rv[e.k] += g, rs[e.k] += w;
    rv[e.l] += -g, rs[e.l] += w;
    dissipation += g * ykl;
  }
  for (int c = 0; c < nc; ++c) dissipation += 0.0 * V(yv[c] - yv[c + 1]) / 2.0;

  V motion = V{};
  for (int i = 0; i < nf; ++i) {
    V r = rv[i], size = rs[i];
    r += m[i] * (W[i] - u[i]);
    size += magnitude(m[i] * W[i]) + magnitude(m[i] * u[i]);
    if (i < nc) r -= 0.0, size += 0.0;
    if (i > 0) r += 0.0, size += 0.0;
    rs[i] = size;
    const V ar = magnitude(r);
    motion = pick((Mask)(size > 0.0) & (Mask)(ar > motion * size), ar / size, motion);
  }
  // group_momentum_residual() with no contact closed: M's groups.
  V sum_value[N], sum_size[N];
  for (int i = 0; i < N; ++i) sum_value[i] = V{}, sum_size[i] = V{};
  for (int i = 0; i < nf; ++i) {
    sum_value[group[i]] += m[i] * (W[i] - u[i]);
    sum_size[group[i]] += m[i] * (magnitude(W[i]) + magnitude(u[i]));
  }
  const int anchored = p.fixed_bottom ? group[n - 1] : -1;
  V worst = V{};
  for (int r = 0; r < n; ++r) {
    if (group[r] != r || r == anchored) continue;
    const V v = magnitude(sum_value[r]), size = sum_size[r];
    worst = pick((Mask)(size > 0.0) & (Mask)(v > worst * size), v / size, worst);
  }
  motion = pick((Mask)(motion < worst), worst, motion);  // std::max
  V comp = V{}, vscale = V{}, lscale = V{};
  for (int i = 0; i < n; ++i) raise(vscale, magnitude(W[i])), raise(vscale, magnitude(u[i]));
  for (int i = 0; i < nf; ++i) raise(lscale, rs[i]);
  for (int c = 0; c < nc; ++c) {
    const V w = gaps[c], x = -w / vscale;
    comp = pick((Mask)(w < 0.0) & (Mask)(vscale > 0.0) & (Mask)(comp < x), x, comp);
  }
  const double tol_residual = settings.residual;
  ok &= (Mask)(motion <= tol_residual) & (Mask)(comp <= tol_residual);
  // finite_answer(): x·0 is ±0 for every finite x, NaN otherwise.
  V zero = 0.0 * ke_before + 0.0 * ke_after + 0.0 * dissipation + 0.0 * p_before + 0.0 * p_after;
  for (int i = 0; i < n; ++i) zero += 0.0 * W[i];
  ok &= (Mask)(zero == 0.0);

  const unsigned solved = lanes_of(ok);
  for (int q = 0; q < lane_width; ++q) {
    if (!((solved >> q) & 1u)) continue;
    Solution<double>& o = out[q];
    o.status = Status::Success;
    o.pivots = 0;
    o.velocities_after.resize(static_cast<std::size_t>(n));
    o.reactions.assign(static_cast<std::size_t>(nc), 0.0);
    o.gaps.resize(static_cast<std::size_t>(nc));
    if (o.closed.bodies() != n) o.closed = ContactSet(n);
    for (int i = 0; i < n; ++i) o.velocities_after[static_cast<std::size_t>(i)] = W[i][q];
    for (int c = 0; c < nc; ++c) o.gaps[static_cast<std::size_t>(c)] = gaps[c][q], o.closed.set_closed(c, false);
    o.kinetic_energy_before = ke_before, o.kinetic_energy_after = ke_after[q];
    o.momentum_before = p_before, o.momentum_after = p_after[q];
    o.dissipation = dissipation[q];
    o.residual_motion = motion[q];
    o.residual_complementarity = comp[q];
  }
  return solved;
}

template <int N>
unsigned baseline(const Problem<double>& p, int band, const double* values, unsigned todo, const Settings<double>& settings,
                  Solution<double>* out) {
  if (band == N - 1) return solve_lanes<N, true>(p, band, values, todo, settings, out);
  return solve_lanes<N, false>(p, band, values, todo, settings, out);
}

#if defined(__x86_64__) || defined(__i386__)
#define SUPERBALL_LANES_AVX2 1
template <int N>
__attribute__((target("avx2"))) unsigned avx2(const Problem<double>& p, int band, const double* values, unsigned todo,
                                              const Settings<double>& settings, Solution<double>* out) {
  if (band == N - 1) return solve_lanes<N, true>(p, band, values, todo, settings, out);
  return solve_lanes<N, false>(p, band, values, todo, settings, out);
}
#endif


}  // namespace

bool lanes_use_avx2() {
#ifdef SUPERBALL_LANES_AVX2
  static const bool avx2 = __builtin_cpu_supports("avx2");
  return avx2;
#else
  return false;
#endif
}

LanesSolve lanes_solver_for(int n, LaneCode code) {
  static_assert(small_max_bodies == 8 && lane_width == 4, "one case per size below, 4 lanes in V's initializers");
#ifdef SUPERBALL_LANES_AVX2
  if (code == LaneCode::Best && lanes_use_avx2()) switch (n) {
      case 2: return &avx2<2>;
      case 3: return &avx2<3>;
      case 4: return &avx2<4>;
      case 5: return &avx2<5>;
      case 6: return &avx2<6>;
      case 7: return &avx2<7>;
      case 8: return &avx2<8>;
      default: return nullptr;
    }
#else
  (void)code;
#endif
  switch (n) {
    case 2: return &baseline<2>;
    case 3: return &baseline<3>;
    case 4: return &baseline<4>;
    case 5: return &baseline<5>;
    case 6: return &baseline<6>;
    case 7: return &baseline<7>;
    case 8: return &baseline<8>;
    default: return nullptr;
  }
}

}  // namespace superball::numeric::detail
