// The fixed-size path of CollisionSolver (small_solver.hpp): the
// operations of collision.cpp, cluster.cpp and complete.cpp, in their order,
// on arrays whose sizes are known at compile time; the dense LDLᵀ, its
// solves and the pivoting step are the general path's own templates
// (dense_steps.hpp).  Any change to the arithmetic of those files must be
// made here too; the tests compare the two paths bit for bit
// (tests/numeric/small_solver_test.cpp).
//
// The same template solves lane_width problems of one structure at once
// (lanes.hpp), one a lane of SIMD vectors (Lanes, lane_vector.hpp): each
// operation is the IEEE one of each lane, each branch on a number a
// per-lane select or decided by the first lane still solved, the lanes
// that would branch otherwise left to the caller (LaneFlow).  So each lane
// solved is its problem's solve here, bit for bit
// (tests/numeric/batch_test.cpp).  That code is compiled twice: for the
// build's baseline target (x86-64: GCC and Clang split each vector into
// SSE2 pairs) and, on x86, for AVX2 in a function of target("avx2"), chosen
// at run time.  This file is compiled with -ffp-contract=off.
#include "collision/small_solver.hpp"

#include "collision/complete.hpp"
#include "collision/dense_steps.hpp"
#include "collision/lane_vector.hpp"
#include "collision/lanes.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <type_traits>
#include <utility>

namespace superball::numeric::detail {

namespace {

/// |x|: abs_value() of complete.hpp for the floating-point types, without
/// its branch (the two differ only in the sign of a zero, and every |x| here
/// enters only sums of magnitudes and comparisons, where −0 = +0).
template <class S>
S magnitude(const S& x) {
  return std::fabs(x);
}

/// Union-find over at most 8 bodies as one label byte per body in a 64-bit
/// word: join(a, b) relabels the group of a with the label of b's group, as
/// complete.cpp's parent[root(a)] = root(b) does, so the groups and their
/// representatives (hence the order of the final loop) are the same.
class Labels {
 public:
  Labels() {
    for (int i = 0; i < 8; ++i) word_ |= static_cast<std::uint64_t>(i) << (8 * i);
  }
  int of(int i) const { return static_cast<int>((word_ >> (8 * i)) & 0xffu); }
  void join(int a, int b) {
    constexpr std::uint64_t ones = 0x0101010101010101ull, low7 = 0x7f7f7f7f7f7f7f7full;
    const std::uint64_t ra = static_cast<std::uint64_t>(of(a)), rb = static_cast<std::uint64_t>(of(b));
    if (ra == rb) return;  // most joins of a scene are (predictably) inside a group: off the dependency chain
    const std::uint64_t x = word_ ^ (ra * ones);           // zero bytes where the label is ra
    const std::uint64_t zero = ~(((x & low7) + low7) | x | low7);  // 0x80 in exactly those bytes
    const std::uint64_t mask = (zero >> 7) * 0xffu;
    word_ = (word_ & ~mask) | ((rb * ones) & mask);
  }

 private:
  std::uint64_t word_ = 0;
};

/// What the fixed-size path computes in, and how it decides: one problem in
/// S (double, long double), or lane_width problems in Lanes, one a lane
/// (lane_vector.hpp).  Base: the type of one problem's numbers; Real: a
/// residual (double, or double per lane); Flow: the branches (OneProblem,
/// LaneFlow); Mask: a condition.
template <class S>
struct Number {
  static constexpr bool lanes = false;
  using Base = S;
  using Real = double;
  using Flow = OneProblem;
  using Mask = bool;
};
template <>
struct Number<Lanes> {
  static constexpr bool lanes = true;
  using Base = double;
  using Real = Lanes;
  using Flow = LaneFlow;
  using Mask = LaneMask;
};

/// Per problem, \p a where \p m holds, else \p b (for one problem, m ? a : b).
template <class S>
S select(bool m, const S& a, const S& b) {
  return m ? a : b;
}
/// Both conditions (for one problem, a && b).
inline bool both(bool a, bool b) { return a && b; }
inline LaneMask both(LaneMask a, LaneMask b) { return a & b; }
/// std::max(a, b), per problem: b where a < b, else a.
template <class S>
S larger(const S& a, const S& b) {
  return select(a < b, b, a);
}
/// to = x() where \p m holds, x() computed only there for one problem (so a
/// quotient is never formed where the scalar code does not form it).
template <class S, class X>
void set_where(bool m, S& to, X&& x) {
  if (m) to = x();
}
template <class X>
void set_where(LaneMask m, Lanes& to, X&& x) {
  to = select(m, x(), to);
}
/// if (\p m) raise \p to to x() (if to < x(): to = x()), per problem.
template <class S, class X>
void raise_where(bool m, S& to, X&& x) {
  if (!m) return;
  const S v = x();
  if (to < v) to = v;
}
template <class X>
void raise_where(LaneMask m, Lanes& to, X&& x) {
  const Lanes v = x();
  to = select(m & (to < v), v, to);
}
/// \p x as a residual (Number::Real).
template <class S>
double real(const S& x) {
  return to_double(x);
}
inline Lanes real(Lanes x) { return x; }
/// Problem \p q's number of \p x (for one problem, x).
template <class S>
const S& lane(const S& x, int) {
  return x;
}
inline double lane(Lanes x, int q) { return x[q]; }

/// One solve of a problem of exactly N bodies, or of lane_width problems of
/// one structure at once (S = Lanes).  Members are arrays of N (or N × N); a
/// Small lives on the stack of small_solve().  Full: the bandwidth of DᵀMD
/// is N − 1 (every loop over the band has a length known at compile time),
/// else the runtime bandwidth bounds them.  Every branch on a number is a
/// select (both sides computed for lanes, only the one taken for one
/// problem), a flow_.fails() or a flow_.leader() (Number::Flow).
template <class S, int N, bool Full>
class Small {
 public:
  using Base = typename Number<S>::Base;
  using Real = typename Number<S>::Real;
  using Mask = typename Number<S>::Mask;

  /// One problem: its entries' values are read from \p p.
  Small(const Problem<Base>& p, int bandwidth) : Small(p, bandwidth, nullptr, 1u) {}
  /// Lanes: entry k's value in lane q at values[k·lane_width + q], the lanes \p todo (bit q for lane q).
  Small(const Problem<Base>& p, int bandwidth, const double* values, unsigned todo)
      : p_(p), bandwidth_(bandwidth), nf_(p.fixed_bottom ? N - 1 : N), values_(values) {
    if constexpr (Number<S>::lanes) flow_.live = todo;
    (void)todo;
    for (int i = 0; i < N; ++i) m_[i] = S(p.mass[static_cast<std::size_t>(i)]), u_[i] = S(p.u[static_cast<std::size_t>(i)]);
  }

  /// CollisionSolver::compute(): false to hand over to the general path.
  bool compute(const Settings<Base>& settings, Solution<Base>& out);
  /// The lanes' compute(): the lanes solved, each into out[q] as compute()
  /// of its problem alone (lanes.hpp).
  unsigned compute_lanes(const Settings<Base>& settings, Solution<Base>* out);

 private:
  static constexpr int n_ = N, nc_ = N - 1;

  /// The bandwidth of DᵀMD, a constant when Full.
  int band() const { return Full ? N - 1 : bandwidth_; }
  S& A(int i, int d) { return A_[i][d]; }
  S& R(int i, int d) { return R_[i][d]; }
  /// The value of entry \p k of M.
  S value(int k) const {
    if constexpr (Number<S>::lanes)
      return S::load(values_ + lane_width * k);
    else
      return p_.entries[static_cast<std::size_t>(k)].value;
  }
  int entries() const { return static_cast<int>(p_.entries.size()); }
  bool solve(const Settings<Base>& settings);  // the case: false to hand over (for lanes: none left)
  void assemble();
  void assemble_scale();  // scale_, at the first case with a closed contact
  bool factor(int k);
  bool factor_and_solve(int k);  // factor(k), then y_ := R⁻¹ y_ on the first k rows
  bool solve_case(const char* closed);  // ClusterSystem::solve() into W_, lambda_
  bool solve_open_case();               // solve_case() with every contact open, its bookkeeping done at compile time
  S row_residual(int c);
  bool factorize();
  void solve_in_place(S* x, int stride) const;
  void form_tableau();
  bool pivot_on(int p);
  int pivot(const Settings<Base>& settings);
  Real group_momentum_residual(const char* active) const;
  void complete(const Settings<Base>& settings);
  void write(Solution<Base>& out, int q) const;  // problem q's answer (complete()'s) into out

  const Problem<Base>& p_;
  const int bandwidth_, nf_;
  const double* values_;  // lanes: the entries' values (see the constructor)
  typename Number<S>::Flow flow_{};
  S m_[N], u_[N];      // the masses and velocities before, copied out of the problem's vectors (which the output's could alias)
  S A_[N][N];     // lower band: A(i, d) = A_{i, i−d}, d <= min(i, band()) (only those are zeroed and read)
  S rhs_[N];      // b̃ on the free bodies
  S scale_[N];    // per row: Σ |terms| of the assembly (formed by assemble_scale() when first needed)
  bool scaled_ = false;
  int cluster_[N];
  S R_[N][N];     // the reduced banded system of a case
  S y_[N];
  S l_[N];
  S W_[N];        // velocities after of the case solved last
  S lambda_[N];   // λ on contacts, 0 where open
  char basic_[N];  // contact c closed (λ_c basic)
  S Ad_[N][N];    // dense LDLᵀ of A on the free bodies
  S G_[N][N];     // A⁻¹ C_Fᵀ, column c in G_[.][c]
  S T_[N][N];     // the tableau
  S t_[N];        // its constant column
  bool tableau_ = false;
  Labels entry_groups_;  // the groups of bodies that the nonzero entries of M join (found by assemble())
  int pivots_ = 0;
  // complete()'s answer
  S gaps_[N], reactions_[N];
  S ke_before_, ke_after_, p_before_, p_after_, dissipation_;
  Real motion_, comp_;
  Mask bad_;  // the residual check fails, or a number is not finite
};

template <class S, int N, bool Full>
void Small<S, N, Full>::assemble() {
  const int n = n_;
  // Zeroed by loops of known length over what is read (no block clear of
  // the whole arrays: a `rep stos` was 7 % of a 4-body solve).
  for (int i = 0; i < N; ++i) {
    for (int d = 0; d <= i; ++d) A(i, d) = S(0);
    basic_[i] = 0;
  }
  auto add = [&](int r, int c, const S& v) {
    if (r < c) std::swap(r, c);
    A(r, r - c) += v;
  };
  for (int k = 0; k < entries(); ++k) {
    const Entry<Base>& e = p_.entries[static_cast<std::size_t>(k)];
    const S value = this->value(k);
    // The groups of the momentum balance (complete()): the joins complete.cpp
    // makes before the contacts' ones, in the same order (a diagonal entry
    // joins only i and j).
    if (flow_.leader(!(value == S(0)))) {
      entry_groups_.join(e.i, e.j);
      if (!e.diagonal()) entry_groups_.join(e.k, e.l), entry_groups_.join(e.i, e.k);
    }
    if (e.diagonal()) {
      A(e.i, 0) += value;
      A(e.j, 0) += value;
      add(e.j, e.i, -value);
      continue;
    }
    const int rows[2] = {e.i, e.j}, cols[2] = {e.k, e.l};
    for (int a = 0; a < 2; ++a)
      for (int c = 0; c < 2; ++c) {
        const S v = (a == c) ? value : S(-value);
        if (rows[a] == cols[c])
          A(rows[a], 0) += S(2) * v;
        else
          add(rows[a], cols[c], v);
      }
  }
  for (int j = 0; j < nf_; ++j) {
    S acc = S(0);
    for (int d = 0; d <= band() && d <= j; ++d) acc -= A(j, d) * u_[j - d];
    for (int d = 1; d <= band() && j + d < n; ++d) acc -= A(j + d, d) * u_[j + d];
    if (p_.fixed_bottom && n - 1 - j <= band()) acc -= A(n - 1, n - 1 - j) * u_[n - 1];
    rhs_[j] = acc;
  }
  for (int i = 0; i < nf_; ++i) {
    rhs_[i] += m_[i] * u_[i];
    A(i, 0) += m_[i];
  }
}

template <class S, int N, bool Full>
void Small<S, N, Full>::assemble_scale() {
  // The assembly's per-row sums of |terms| (the general path forms them with
  // A, entry by entry, then the mass): only a case with a closed contact
  // reads them, so a solve without a pivot never forms them.
  for (int i = 0; i < N; ++i) scale_[i] = S(0);
  for (int k = 0; k < entries(); ++k) {
    const Entry<Base>& e = p_.entries[static_cast<std::size_t>(k)];
    const S value = this->value(k);
    const S size = S(2) * select(value < S(0), S(-value), value);
    scale_[e.i] += size;
    scale_[e.j] += size;
    if (e.diagonal()) continue;
    scale_[e.k] += size;
    scale_[e.l] += size;
  }
  for (int i = 0; i < nf_; ++i) scale_[i] += m_[i];
  scaled_ = true;
}

template <class S, int N, bool Full>
inline __attribute__((always_inline)) bool Small<S, N, Full>::factor_and_solve(int k) {
  if (k < 0 || k > N || band() < 0) __builtin_unreachable();  // tells the compiler the indices stay inside the arrays
  if (!factor(k)) return false;
  for (int i = 0; i < k; ++i)
    for (int j = std::max(0, i - band()); j < i; ++j) y_[i] -= R(i, i - j) * y_[j];
  for (int i = 0; i < k; ++i) y_[i] /= R(i, 0);
  for (int i = k - 1; i >= 0; --i)
    for (int j = i + 1; j <= std::min(k - 1, i + band()); ++j) y_[i] -= R(j, j - i) * y_[j];
  return true;
}

template <class S, int N, bool Full>
inline __attribute__((always_inline)) bool Small<S, N, Full>::factor(int k) {
  for (int j = 0; j < k; ++j) {
    const S dj = R(j, 0);
    if (flow_.fails(!(dj > S(0)))) return false;
    const int last = std::min(k - 1, j + band());
    for (int r = j + 1; r <= last; ++r) l_[r - j] = R(r, r - j) / dj;
    for (int r = j + 1; r <= last; ++r)
      for (int i = r; i <= last; ++i) R(i, i - r) -= R(i, i - j) * l_[r - j];
    for (int r = j + 1; r <= last; ++r) R(r, r - j) = l_[r - j];
  }
  return true;
}

template <class S, int N, bool Full>
S Small<S, N, Full>::row_residual(int c) {
  if (c < 0 || c >= N || nf_ > N || band() < 0) __builtin_unreachable();  // tells the compiler the indices stay inside the arrays
  S r = -rhs_[c];
  for (int d = 0; d <= band() && d <= c; ++d) r += A(c, d) * W_[c - d];
  for (int d = 1; d <= band() && c + d < nf_; ++d) r += A(c + d, d) * W_[c + d];
  return r;
}

template <class S, int N, bool Full>
bool Small<S, N, Full>::solve_case(const char* closed) {
  const int n = n_, nc = nc_;
  cluster_[0] = 0;
  for (int c = 0; c < nc; ++c) cluster_[c + 1] = cluster_[c] + (closed[c] ? 0 : 1);
  const int fixed = p_.fixed_bottom ? cluster_[n - 1] : -1;
  const int k = p_.fixed_bottom ? fixed : cluster_[n - 1] + 1;
  const S u_fixed = p_.fixed_bottom ? u_[n - 1] : S(0);
  for (int i = 0; i < k; ++i) {
    for (int d = 0; d <= band(); ++d) R(i, d) = S(0);
    y_[i] = S(0);
  }
  int current = -1;
  S y_sum = S(0), diagonal_sum = S(0);
  const auto flush = [&] {
    if (current < 0) return;
    y_[current] += y_sum;
    R(current, 0) += diagonal_sum;
  };
  for (int i = 0; i < nf_; ++i) {
    const int ci = cluster_[i];
    if (ci == fixed) {
      flush();
      current = -1;
      for (int d = 1; d <= band() && d <= i; ++d)
        if (cluster_[i - d] != fixed) y_[cluster_[i - d]] -= A(i, d) * u_fixed;
      continue;
    }
    if (ci != current) {
      flush();
      current = ci, y_sum = S(0), diagonal_sum = S(0);
    }
    y_sum += rhs_[i];
    S inner = A(i, 0);
    for (int d = 1; d <= band() && d <= i; ++d) {
      const int cj = cluster_[i - d];
      if (cj == ci)
        inner += S(2) * A(i, d);
      else
        R(ci, ci - cj) += A(i, d);
    }
    diagonal_sum += inner;
  }
  flush();
  // With k a constant (every contact open: k = N, or N − 1 on a fixed
  // obstacle) the compiler unrolls the factorization and the solves.
  const bool solved = k == N ? factor_and_solve(N) : k == N - 1 ? factor_and_solve(N - 1) : factor_and_solve(k);
  if (!solved) return false;
  for (int i = 0; i < n; ++i) W_[i] = cluster_[i] == fixed ? u_fixed : y_[cluster_[i]];
  for (int top = 0; top < n;) {
    int bottom = top;
    while (bottom < nc && closed[bottom]) ++bottom;
    if (bottom < nc) lambda_[bottom] = S(0);
    if (bottom > top) {
      int pivot = bottom;
      if (cluster_[top] != fixed) {
        if (!scaled_) assemble_scale();
        S largest = S(-1);
        for (int j = top; j <= bottom; ++j)
          if (flow_.leader(scale_[j] > largest)) largest = scale_[j], pivot = j;
      }
      S sum = S(0);
      for (int c = top; c < pivot; ++c) lambda_[c] = sum = sum + row_residual(c);
      sum = S(0);
      for (int c = bottom - 1; c >= pivot; --c) lambda_[c] = sum = sum - row_residual(c + 1);
    }
    top = bottom + 1;
  }
  return true;
}

template <class S, int N, bool Full>
bool Small<S, N, Full>::solve_open_case() {
  // solve_case() with no contact closed: one cluster per body, so its sums
  // are single terms (0 + x, which only turns −0 into +0, as there), no
  // reaction, and the size of the factorization is a constant.
  constexpr int n = N;
  const int fixed = p_.fixed_bottom ? n - 1 : -1;
  for (int i = 0; i < n; ++i) cluster_[i] = i;
  for (int i = 0; i < nf_; ++i) {
    y_[i] = S(0) + rhs_[i];
    R(i, 0) = S(0) + A(i, 0);
    for (int d = 1; d <= band(); ++d) R(i, d) = d <= i ? S(S(0) + A(i, d)) : S(0);
  }
  if (fixed >= 0) {  // b̃ holds the obstacle's share (assemble()); only bodies it is in contact with add more
    if (!factor_and_solve(N - 1)) return false;
    for (int i = 0; i < n - 1; ++i) W_[i] = y_[i];
    W_[n - 1] = u_[n - 1];
  } else {
    if (!factor_and_solve(N)) return false;
    for (int i = 0; i < n; ++i) W_[i] = y_[i];
  }
  for (int c = 0; c < nc_; ++c) lambda_[c] = S(0);
  return true;
}

template <class S, int N, bool Full>
bool Small<S, N, Full>::factorize() {
  for (int i = 0; i < nf_; ++i)
    for (int j = 0; j <= i; ++j) Ad_[i][j] = i - j <= band() ? A(i, i - j) : S(0);
  auto dense = [this](int i, int j) -> S& { return Ad_[i][j]; };
  return ldlt_in_place<S>(dense, nf_, flow_);
}

template <class S, int N, bool Full>
void Small<S, N, Full>::solve_in_place(S* x, int stride) const {
  const auto dense = [this](int i, int j) -> const S& { return Ad_[i][j]; };
  ldlt_solve_in_place(dense, nf_, [x, stride](int i) -> S& { return x[i * stride]; });
}

template <class S, int N, bool Full>
void Small<S, N, Full>::form_tableau() {
  for (int i = 0; i < nf_; ++i)
    for (int c = 0; c < nc_; ++c) G_[i][c] = S(0);
  for (int c = 0; c < nc_; ++c) {
    G_[c][c] = S(1);
    if (c + 1 < nf_) G_[c + 1][c] = S(-1);
    solve_in_place(&G_[0][c], N);
  }
  for (int c = 0; c < nc_; ++c)
    for (int j = 0; j < nc_; ++j) T_[c][j] = c + 1 < nf_ ? S(G_[c][j] - G_[c + 1][j]) : G_[c][j];
  tableau_ = true;
}

template <class S, int N, bool Full>
bool Small<S, N, Full>::pivot_on(int p) {
  if (!tableau_) {
    if (!factorize()) return false;
    form_tableau();
  }
  auto T = [this](int i, int j) -> S& { return T_[i][j]; };
  auto t = [this](int i) -> S& { return t_[i]; };
  if (!principal_pivot<S>(T, t, nc_, p, flow_)) return false;
  basic_[p] ^= 1;
  return true;
}

template <class S, int N, bool Full>
int Small<S, N, Full>::pivot(const Settings<Base>& settings) {
  const int nc = nc_;
  S scale = S(0);
  for (int c = 0; c < nc; ++c) scale = larger(scale, magnitude(t_[c]));
  const S tol = settings.feasibility * scale;
  const int cap = settings.max_pivots_per_contact * std::max(nc, 1);
  int pivots = 0;
  for (;;) {
    int p = -1;
    for (int c = 0; c < nc && p < 0; ++c)
      if (flow_.leader(t_[c] < -tol)) p = c;
    if (p < 0) return pivots;
    if (++pivots > cap) return -1;
    if (!pivot_on(p)) return -2;
  }
}

template <class S, int N, bool Full>
auto Small<S, N, Full>::group_momentum_residual(const char* active) const -> Real {
  static_assert(N <= 8, "Labels holds 8 bodies");
  const int n = n_;
  Labels group = entry_groups_;
  for (int c = 0; c + 1 < n; ++c)
    if (active[c]) group.join(c, c + 1);
  Sized<S> sum[N];
  for (int i = 0; i < nf_; ++i)
    sum[group.of(i)].add(m_[i] * (W_[i] - u_[i]), m_[i] * (magnitude(W_[i]) + magnitude(u_[i])));
  const int anchored = p_.fixed_bottom ? group.of(n - 1) : -1;
  S worst = S(0);
  for (int r = 0; r < n; ++r) {
    if (group.of(r) != r || r == anchored) continue;
    const S v = magnitude(sum[r].value()), size = sum[r].size();
    set_where(both(size > S(0), v > worst * size), worst, [&] { return S(v / size); });
  }
  return real(worst);
}

template <class S, int N, bool Full>
void Small<S, N, Full>::complete(const Settings<Base>& settings) {
  // complete_solution() with imposed = false and A known to be positive
  // definite in S (the case with every contact open was factored).
  const int n = n_, nc = nc_, nf = nf_;
  const S* W = W_;
  const char* active = basic_;
  for (int c = 0; c < nc; ++c) {
    gaps_[c] = W[c] - W[c + 1];
    reactions_[c] = active[c] ? S(-lambda_[c]) : S(0);
  }
  S ke_before = S(0), ke_after = S(0), p_before = S(0), p_after = S(0);
  for (int i = 0; i < nf; ++i) {
    ke_before += m_[i] * u_[i] * u_[i] / S(2);
    ke_after += m_[i] * W[i] * W[i] / S(2);
    p_before += m_[i] * u_[i];
    p_after += m_[i] * W[i];
  }
  ke_before_ = ke_before, ke_after_ = ke_after;
  p_before_ = p_before, p_after_ = p_after;
  Sized<S> y[N], rows[N];
  for (int i = 0; i < n; ++i) y[i].set(W[i] + u_[i], magnitude(W[i]) + magnitude(u_[i]));
  S dissipation = S(0);
  for (int k = 0; k < entries(); ++k) {
    const Entry<Base>& e = p_.entries[static_cast<std::size_t>(k)];
    const S value = this->value(k);
    const S yij = y[e.i].value() - y[e.j].value(), ykl = y[e.k].value() - y[e.l].value();
    const S f = value * ykl, s = magnitude(value) * (y[e.k].size() + y[e.l].size());
    rows[e.i].add(f, s), rows[e.j].add(-f, s);
    if (e.diagonal()) {
      dissipation += f * yij / S(2);
      continue;
    }
    const S g = value * yij, t = magnitude(value) * (y[e.i].size() + y[e.j].size());
    rows[e.k].add(g, t), rows[e.l].add(-g, t);
    dissipation += g * ykl;
  }
  for (int c = 0; c < nc; ++c) dissipation += reactions_[c] * S(y[c].value() - y[c + 1].value()) / S(2);
  dissipation_ = dissipation;

  S motion_s = S(0);
  for (int i = 0; i < nf; ++i) {
    S r = rows[i].value(), size = rows[i].size();
    r += m_[i] * (W[i] - u_[i]);
    size += magnitude(S(m_[i] * W[i])) + magnitude(S(m_[i] * u_[i]));
    if (i < nc) r -= lambda_[i], size += magnitude(lambda_[i]);
    if (i > 0) r += lambda_[i - 1], size += magnitude(lambda_[i - 1]);
    rows[i].set(r, size);
    const S ar = magnitude(r);
    set_where(both(size > S(0), ar > motion_s * size), motion_s, [&] { return S(ar / size); });
  }
  const Real motion = larger(real(motion_s), group_momentum_residual(active));
  S comp_s = S(0), vscale = S(0), lscale = S(0);
  for (int i = 0; i < n; ++i) vscale = larger(larger(vscale, magnitude(W[i])), magnitude(u_[i]));
  for (int i = 0; i < nf; ++i) lscale = larger(lscale, rows[i].size());
  for (int c = 0; c < nc; ++c) {
    const S& w = gaps_[c];
    const S& l = lambda_[c];
    if (active[c]) {
      raise_where(both(!(w == S(0)), vscale > S(0)), comp_s, [&] { return S(magnitude(w) / vscale); });
      raise_where(both(l < S(0), lscale > S(0)), comp_s, [&] { return S(S(-l) / lscale); });
    } else {
      raise_where(both(w < S(0), vscale > S(0)), comp_s, [&] { return S(S(-w) / vscale); });
    }
  }
  const Real comp = real(comp_s);
  motion_ = motion, comp_ = comp;
  const Real tol = to_double(settings.residual);
  // finite_answer(): x·0 is ±0 for a finite x and NaN for ±inf and NaN, so
  // the sum is 0 exactly when every value is finite (all_finite(), without
  // a branch per value).
  S zero = S(0) * ke_before + S(0) * ke_after + S(0) * dissipation + S(0) * p_before + S(0) * p_after;
  for (int i = 0; i < n; ++i) zero += S(0) * W[i];
  for (int c = 0; c < nc; ++c) zero += S(0) * reactions_[c];
  bad_ = !both(both(motion <= tol, comp <= tol), zero == S(0));
}

template <class S, int N, bool Full>
void Small<S, N, Full>::write(Solution<Base>& out, int q) const {
  const int n = n_, nc = nc_;
  out.pivots = pivots_;
  out.velocities_after.resize(static_cast<std::size_t>(n));
  out.reactions.resize(static_cast<std::size_t>(nc));
  out.gaps.resize(static_cast<std::size_t>(nc));
  if (out.closed.bodies() != n) out.closed = ContactSet(n);
  for (int i = 0; i < n; ++i) out.velocities_after[static_cast<std::size_t>(i)] = lane(W_[i], q);
  for (int c = 0; c < nc; ++c) {
    const auto k = static_cast<std::size_t>(c);
    out.gaps[k] = lane(gaps_[c], q);
    out.reactions[k] = lane(reactions_[c], q);
    out.closed.set_closed(c, basic_[c]);
  }
  out.kinetic_energy_before = lane(ke_before_, q), out.kinetic_energy_after = lane(ke_after_, q);
  out.momentum_before = lane(p_before_, q), out.momentum_after = lane(p_after_, q);
  out.dissipation = lane(dissipation_, q);
  out.residual_motion = lane(motion_, q);
  out.residual_complementarity = lane(comp_, q);
}

template <class S, int N, bool Full>
bool Small<S, N, Full>::solve(const Settings<Base>& settings) {
  assemble();
  // The case with every contact open; a pivot of A that is not positive
  // sends the problem to the general path (its dense factors, its verdict).
  if (!solve_open_case()) return false;
  for (int c = 0; c < nc_; ++c) t_[c] = c + 1 < nf_ ? S(W_[c] - W_[c + 1]) : S(W_[c] - u_[n_ - 1]);
  pivots_ = pivot(settings);
  if (pivots_ < 0) return false;
  if (pivots_ > 0 && !solve_case(basic_)) return false;
  complete(settings);
  return true;
}

template <class S, int N, bool Full>
bool Small<S, N, Full>::compute(const Settings<Base>& settings, Solution<Base>& out) {
  if (!solve(settings)) return false;
  write(out, 0);
  out.status = bad_ || !p_.in_range ? Status::NumericalIssue : Status::Success;
  return true;
}

template <class S, int N, bool Full>
unsigned Small<S, N, Full>::compute_lanes(const Settings<Base>& settings, Solution<Base>* out) {
  if (!p_.in_range || !solve(settings) || flow_.fails(bad_)) return 0;
  for (unsigned left = flow_.live; left != 0; left &= left - 1) {
    const int q = __builtin_ctz(left);
    write(out[q], q);
    out[q].status = Status::Success;
  }
  return flow_.live;
}

template <class S, int N>
bool small_solve(const Problem<S>& p, int bandwidth, const Settings<S>& settings, Solution<S>& out) {
  if (bandwidth == N - 1) {
    Small<S, N, true> s(p, bandwidth);
    return s.compute(settings, out);
  }
  Small<S, N, false> s(p, bandwidth);
  return s.compute(settings, out);
}

/// The lanes solve (lanes.hpp) of N bodies, the bandwidth a run-time value
/// (a constant band, as the one-problem path's Full, was measured to gain
/// nothing in lanes and to cost a fifth of the build of this file).  The
/// baseline copy calls Small's functions; the AVX2 copy below inlines every
/// call (flatten), so that it is AVX2 code throughout and no vector passes
/// between code of two targets.
template <int N>
unsigned lanes_baseline(const Problem<double>& p, int band, const double* values, unsigned todo, const Settings<double>& settings,
                        Solution<double>* out) {
  return Small<Lanes, N, false>(p, band, values, todo).compute_lanes(settings, out);
}

#if defined(__x86_64__) || defined(__i386__)
#define SUPERBALL_LANES_AVX2 1
template <int N>
__attribute__((target("avx2"), flatten)) unsigned lanes_avx2(const Problem<double>& p, int band, const double* values, unsigned todo,
                                                           const Settings<double>& settings, Solution<double>* out) {
  return Small<Lanes, N, false>(p, band, values, todo).compute_lanes(settings, out);
}
#endif

/// make(size) for size = std::integral_constant<int, n>, where 2 <= n <=
/// small_max_bodies; nullptr for any other n.
template <class F, class Make, int... k>
F by_size(int n, Make make, std::integer_sequence<int, k...>) {
  const F table[] = {make(std::integral_constant<int, k + 2>{})...};
  return n >= 2 && n <= small_max_bodies ? table[n - 2] : nullptr;
}
template <class F, class Make>
F by_size(int n, Make make) {
  return by_size<F>(n, make, std::make_integer_sequence<int, small_max_bodies - 1>{});
}

}  // namespace

template <class S>
SmallSolve<S> small_solver_for(int n) {
  return by_size<SmallSolve<S>>(n, [](auto size) { return &small_solve<S, decltype(size)::value>; });
}

template SmallSolve<double> small_solver_for<double>(int);
template SmallSolve<long double> small_solver_for<long double>(int);

bool lanes_use_avx2() {
#ifdef SUPERBALL_LANES_AVX2
  static const bool avx2 = __builtin_cpu_supports("avx2");
  return avx2;
#else
  return false;
#endif
}

LanesSolve lanes_solver_for(int n, LaneCode code) {
#ifdef SUPERBALL_LANES_AVX2
  if (code == LaneCode::Best && lanes_use_avx2()) return by_size<LanesSolve>(n, [](auto size) { return &lanes_avx2<decltype(size)::value>; });
#else
  (void)code;
#endif
  return by_size<LanesSolve>(n, [](auto size) { return &lanes_baseline<decltype(size)::value>; });
}

}  // namespace superball::numeric::detail
