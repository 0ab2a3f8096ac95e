// The fixed-size path of CollisionSolver (small_solver.hpp): the
// operations of collision.cpp, cluster.cpp and complete.cpp, in their order,
// on arrays whose sizes are known at compile time; the dense LDLᵀ, its
// solves and the pivoting step are the general path's own templates
// (dense_steps.hpp).  Any change to the
// arithmetic of those files must be made here too; the tests compare the two
// paths bit for bit (tests/numeric/small_solver_test.cpp).  lanes.cpp does
// this path's case with every contact open on several problems at once: a
// change here must be made there too (tests/numeric/batch_test.cpp).
#include "collision/small_solver.hpp"

#include "collision/complete.hpp"
#include "collision/dense_steps.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

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

/// One solve of a problem of exactly N bodies.  Members are arrays of N
/// (or N × N); a Small lives on the stack of small_solve().  Full: the
/// bandwidth of DᵀMD is N − 1 (every loop over the band has a length known
/// at compile time), else the runtime bandwidth bounds them.
template <class S, int N, bool Full>
class Small {
 public:
  Small(const Problem<S>& p, int bandwidth) : p_(p), bandwidth_(bandwidth), nf_(p.fixed_bottom ? N - 1 : N) {
    for (int i = 0; i < N; ++i) m_[i] = p.mass[static_cast<std::size_t>(i)], u_[i] = p.u[static_cast<std::size_t>(i)];
  }

  /// CollisionSolver::compute(): false to hand over to the general path.
  bool compute(const Settings<S>& settings, Solution<S>& out);

 private:
  static constexpr int n_ = N, nc_ = N - 1;

  /// The bandwidth of DᵀMD, a constant when Full.
  int band() const { return Full ? N - 1 : bandwidth_; }
  S& A(int i, int d) { return A_[i][d]; }
  S& R(int i, int d) { return R_[i][d]; }
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
  int pivot(const Settings<S>& settings);
  double group_momentum_residual(const char* active) const;
  bool finite_answer(const Solution<S>& out) const;
  void complete(const Settings<S>& settings, Solution<S>& out);

  const Problem<S>& p_;
  const int bandwidth_, nf_;
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
  for (const Entry<S>& e : p_.entries) {
    // The groups of the momentum balance (complete()): the joins complete.cpp
    // makes before the contacts' ones, in the same order (a diagonal entry
    // joins only i and j).
    if (!(e.value == S(0))) {
      entry_groups_.join(e.i, e.j);
      if (!e.diagonal()) entry_groups_.join(e.k, e.l), entry_groups_.join(e.i, e.k);
    }
    if (e.diagonal()) {
      A(e.i, 0) += e.value;
      A(e.j, 0) += e.value;
      add(e.j, e.i, -e.value);
      continue;
    }
    const int rows[2] = {e.i, e.j}, cols[2] = {e.k, e.l};
    for (int a = 0; a < 2; ++a)
      for (int c = 0; c < 2; ++c) {
        const S v = (a == c) ? e.value : S(-e.value);
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
  for (const Entry<S>& e : p_.entries) {
    const S size = S(2) * (e.value < S(0) ? S(-e.value) : e.value);
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
    if (!(dj > S(0))) return false;
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
          if (scale_[j] > largest) largest = scale_[j], pivot = j;
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
  return ldlt_in_place<S>(dense, nf_);
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
  if (!principal_pivot<S>(T, t, nc_, p)) return false;
  basic_[p] ^= 1;
  return true;
}

template <class S, int N, bool Full>
int Small<S, N, Full>::pivot(const Settings<S>& settings) {
  const int nc = nc_;
  S scale = S(0);
  for (int c = 0; c < nc; ++c) scale = std::max(scale, magnitude<S>(t_[c]));
  const S tol = settings.feasibility * scale;
  const int cap = settings.max_pivots_per_contact * std::max(nc, 1);
  int pivots = 0;
  for (;;) {
    int p = -1;
    for (int c = 0; c < nc && p < 0; ++c)
      if (t_[c] < -tol) p = c;
    if (p < 0) return pivots;
    if (++pivots > cap) return -1;
    if (!pivot_on(p)) return -2;
  }
}

template <class S, int N, bool Full>
double Small<S, N, Full>::group_momentum_residual(const char* active) const {
  static_assert(N <= 8, "Labels holds 8 bodies");
  const int n = n_;
  Labels group = entry_groups_;
  for (int c = 0; c + 1 < n; ++c)
    if (active[c]) group.join(c, c + 1);
  Sized<S> sum[N];
  for (int i = 0; i < nf_; ++i)
    sum[group.of(i)].add(m_[i] * (W_[i] - u_[i]), m_[i] * (magnitude<S>(W_[i]) + magnitude<S>(u_[i])));
  const int anchored = p_.fixed_bottom ? group.of(n - 1) : -1;
  S worst = S(0);
  for (int r = 0; r < n; ++r) {
    if (group.of(r) != r || r == anchored) continue;
    const S v = magnitude<S>(sum[r].value()), size = sum[r].size();
    if (size > S(0) && v > worst * size) worst = v / size;
  }
  return to_double(worst);
}

template <class S, int N, bool Full>
bool Small<S, N, Full>::finite_answer(const Solution<S>& out) const {
  // all_finite(out) on arrays of known length, without a branch per value:
  // x·0 is ±0 for a finite x and NaN for ±inf and NaN, so the sum is 0
  // exactly when every value is finite.
  S zero = S(0) * out.kinetic_energy_before + S(0) * out.kinetic_energy_after + S(0) * out.dissipation +
           S(0) * out.momentum_before + S(0) * out.momentum_after;
  for (int i = 0; i < n_; ++i) zero += S(0) * out.velocities_after[static_cast<std::size_t>(i)];
  for (int c = 0; c < nc_; ++c) zero += S(0) * out.reactions[static_cast<std::size_t>(c)];
  return zero == S(0);
}

template <class S, int N, bool Full>
void Small<S, N, Full>::complete(const Settings<S>& settings, Solution<S>& out) {
  // complete_solution() with imposed = false and A known to be positive
  // definite in S (the case with every contact open was factored).
  const int n = n_, nc = nc_, nf = nf_;
  const S* W = W_;
  const char* active = basic_;
  out.velocities_after.resize(static_cast<std::size_t>(n));
  out.reactions.resize(static_cast<std::size_t>(nc));
  out.gaps.resize(static_cast<std::size_t>(nc));
  if (out.closed.bodies() != n) out.closed = ContactSet(n);
  S gaps[N], reactions[N];
  for (int i = 0; i < n; ++i) out.velocities_after[static_cast<std::size_t>(i)] = W[i];
  for (int c = 0; c < nc; ++c) {
    const auto k = static_cast<std::size_t>(c);
    gaps[c] = W[c] - W[c + 1];
    reactions[c] = active[c] ? S(-lambda_[c]) : S(0);
    out.gaps[k] = gaps[c];
    out.reactions[k] = reactions[c];
    out.closed.set_closed(c, active[c]);
  }
  S ke_before = S(0), ke_after = S(0), p_before = S(0), p_after = S(0);
  for (int i = 0; i < nf; ++i) {
    ke_before += m_[i] * u_[i] * u_[i] / S(2);
    ke_after += m_[i] * W[i] * W[i] / S(2);
    p_before += m_[i] * u_[i];
    p_after += m_[i] * W[i];
  }
  out.kinetic_energy_before = ke_before, out.kinetic_energy_after = ke_after;
  out.momentum_before = p_before, out.momentum_after = p_after;
  Sized<S> y[N], rows[N];
  for (int i = 0; i < n; ++i) y[i].set(W[i] + u_[i], magnitude<S>(W[i]) + magnitude<S>(u_[i]));
  S dissipation = S(0);
  for (const Entry<S>& e : p_.entries) {
    const S yij = y[e.i].value() - y[e.j].value(), ykl = y[e.k].value() - y[e.l].value();
    const S f = e.value * ykl, s = magnitude<S>(e.value) * (y[e.k].size() + y[e.l].size());
    rows[e.i].add(f, s), rows[e.j].add(-f, s);
    if (e.diagonal()) {
      dissipation += f * yij / S(2);
      continue;
    }
    const S g = e.value * yij, t = magnitude<S>(e.value) * (y[e.i].size() + y[e.j].size());
    rows[e.k].add(g, t), rows[e.l].add(-g, t);
    dissipation += g * ykl;
  }
  for (int c = 0; c < nc; ++c) dissipation += reactions[c] * S(y[c].value() - y[c + 1].value()) / S(2);
  out.dissipation = dissipation;

  S motion_s = S(0);
  for (int i = 0; i < nf; ++i) {
    S r = rows[i].value(), size = rows[i].size();
    r += m_[i] * (W[i] - u_[i]);
    size += magnitude<S>(m_[i] * W[i]) + magnitude<S>(m_[i] * u_[i]);
    if (i < nc) r -= lambda_[i], size += magnitude<S>(lambda_[i]);
    if (i > 0) r += lambda_[i - 1], size += magnitude<S>(lambda_[i - 1]);
    rows[i].set(r, size);
    const S ar = magnitude<S>(r);
    if (size > S(0) && ar > motion_s * size) motion_s = ar / size;
  }
  const double motion = std::max(to_double(motion_s), group_momentum_residual(active));
  S comp_s = S(0), vscale = S(0), lscale = S(0);
  const auto raise = [](S& to, const S& x) {
    if (to < x) to = x;
  };
  for (int i = 0; i < n; ++i) raise(vscale, magnitude<S>(W[i])), raise(vscale, magnitude<S>(u_[i]));
  for (int i = 0; i < nf; ++i) raise(lscale, rows[i].size());
  for (int c = 0; c < nc; ++c) {
    const S& w = gaps[c];
    const S& l = lambda_[c];
    if (active[c]) {
      if (!(w == S(0)) && vscale > S(0)) raise(comp_s, magnitude<S>(w) / vscale);
      if (l < S(0) && lscale > S(0)) raise(comp_s, S(-l) / lscale);
    } else if (w < S(0) && vscale > S(0)) {
      raise(comp_s, S(-w) / vscale);
    }
  }
  const double comp = to_double(comp_s);
  out.residual_motion = motion;
  out.residual_complementarity = comp;
  const double tol = to_double(settings.residual);
  if (out.status == Status::Success && !(motion <= tol && comp <= tol)) out.status = Status::NumericalIssue;
  if (out.status == Status::Success && !(p_.in_range && finite_answer(out))) out.status = Status::NumericalIssue;
}

template <class S, int N, bool Full>
bool Small<S, N, Full>::compute(const Settings<S>& settings, Solution<S>& out) {
  assemble();
  // The case with every contact open; a pivot of A that is not positive
  // sends the problem to the general path (its dense factors, its verdict).
  if (!solve_open_case()) return false;
  for (int c = 0; c < nc_; ++c) t_[c] = c + 1 < nf_ ? S(W_[c] - W_[c + 1]) : S(W_[c] - u_[n_ - 1]);
  const int pivots = pivot(settings);
  if (pivots < 0) return false;
  if (pivots > 0 && !solve_case(basic_)) return false;
  out.status = Status::Success;
  out.pivots = pivots;
  complete(settings, out);
  return true;
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

}  // namespace

template <class S>
SmallSolve<S> small_solver_for(int n) {
  static_assert(small_max_bodies == 8, "one case per size below");
  switch (n) {
    case 2: return &small_solve<S, 2>;
    case 3: return &small_solve<S, 3>;
    case 4: return &small_solve<S, 4>;
    case 5: return &small_solve<S, 5>;
    case 6: return &small_solve<S, 6>;
    case 7: return &small_solve<S, 7>;
    case 8: return &small_solve<S, 8>;
    default: return nullptr;
  }
}

template SmallSolve<double> small_solver_for<double>(int);
template SmallSolve<long double> small_solver_for<long double>(int);

}  // namespace superball::numeric::detail
