#include "collision/cluster.hpp"
#include "collision/dense_steps.hpp"

#include <algorithm>

namespace superball::numeric::detail {

template <class S>
void ClusterSystem<S>::assemble(const Problem<S>& p, int bandwidth) {
  n_ = p.n;
  nf_ = p.fixed_bottom ? n_ - 1 : n_;
  nc_ = n_ - 1;
  digits_ = p.digits;
  definite_ = -1;
  b_ = bandwidth;
  entries_ = static_cast<int>(p.entries.size());
  A_.assign(static_cast<std::size_t>(n_) * static_cast<std::size_t>(b_ + 1), S(0));
  scale_.assign(static_cast<std::size_t>(n_), SizeOf<S>{});
  // Symmetric lower-band storage: add(r, c, v) adds v to A_rc and A_cr.
  auto add = [&](int r, int c, const S& v) {
    if (r < c) std::swap(r, c);
    A(r, r - c) += v;
  };
  // Every entry puts terms of size |v| (2|v| on a diagonal it meets twice)
  // into the rows it names, 2|v| in each: scale_ sums them.
  const SizeOf<S> two = size_of(S(2));
  for (const Entry<S>& e : p.entries) {
    const SizeOf<S> size = two * size_of(e.value);
    scale_[e.i] += size;
    scale_[e.j] += size;
    if (e.diagonal()) {  // v (e_i − e_j)(e_i − e_j)ᵀ
      A(e.i, 0) += e.value;
      A(e.j, 0) += e.value;
      add(e.j, e.i, -e.value);
      continue;
    }
    scale_[e.k] += size;
    scale_[e.l] += size;
    // v [(e_i − e_j)(e_k − e_l)ᵀ + transpose]
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
  // b̃ = m u − K u − [fixed] K_{·,n} u_n on free bodies (K u before the masses enter A).
  // Row by row in a register: the terms of row j of A left of the
  // diagonal, then those right of it (held by the rows below), then the
  // fixed body's column once more.
  rhs_.resize(static_cast<std::size_t>(nf_));
  for (int j = 0; j < nf_; ++j) {
    S acc = S(0);
    for (int d = 0; d <= b_ && d <= j; ++d) subtract_product(acc, A(j, d), p.u[j - d]);
    for (int d = 1; d <= b_ && j + d < n_; ++d) subtract_product(acc, A(j + d, d), p.u[j + d]);
    if (p.fixed_bottom && n_ - 1 - j <= b_) subtract_product(acc, A(n_ - 1, n_ - 1 - j), p.u[n_ - 1]);
    rhs_[j] = acc;
  }
  for (int i = 0; i < nf_; ++i) {
    rhs_[i] += p.mass[i] * p.u[i];
    A(i, 0) += p.mass[i];
    scale_[i] += size_of(p.mass[i]);
    if (i == 0 || p.mass[i] < min_mass_) min_mass_ = p.mass[i];
  }
}

template <class S>
bool ClusterSystem<S>::definite_by_bound() const {
  // A = diag(m) + DᵀMD with M positive semi-definite has λ_min(A) >= min m.
  // Each computed A_rc sums at most k − 1 = 2·entries + 1 terms (at most two
  // per entry of M, and a mass), each a rounded datum (relative error <= u)
  // times ±1 or ±2, so (Higham, Thm 3.1, γ_k = k u/(1 − k u))
  // |fl(A_rc) − A_rc| <= γ_k · Σ|terms of A_rc|, and row r of the error E
  // sums to at most γ_k · scale_r.  E is symmetric, so ‖E‖₂ <= ‖E‖_∞, and by
  // Weyl's inequality fl(A) is positive definite when γ_k · max_r scale_r <
  // min m.  The factor 4 covers γ_k <= 2 k u (k u <= 1/2) and the rounding
  // of this test's own sums; the principal submatrix on the free bodies
  // inherits every bound.  Where the scales are Magnitudes (MpFloat, exact),
  // their sums and this product are within (k + 3)·2⁻⁵² of their values
  // and min m within 2⁻⁵³: inside the same factor 2.
  const S u = ScalarTraits<S>::unit_roundoff(digits_);
  const S k = S(2 * static_cast<long long>(entries_) + 2);
  if (!(S(8) * k * u < S(1))) return false;
  SizeOf<S> worst{};
  for (int r = 0; r < nf_; ++r)
    if (scale_[r] > worst) worst = scale_[r];
  return size_of<S>(S(4) * k * u) * worst < size_of(min_mass_);
}

template <class S>
bool ClusterSystem<S>::factor(int k) {
  for (int j = 0; j < k; ++j) {
    const S dj = R(j, 0);
    if (!(dj > S(0))) return false;
    const int last = std::min(k - 1, j + b_);
    // Column j of L is R(r, r−j)/dj; the update reads column j unscaled, so
    // the quotients wait in l_ until it is done (one division each).
    for (int r = j + 1; r <= last; ++r) l_[r - j] = R(r, r - j) / dj;
    for (int r = j + 1; r <= last; ++r)
      for (int i = r; i <= last; ++i) subtract_product(R(i, i - r), R(i, i - j), l_[r - j]);
    for (int r = j + 1; r <= last; ++r) R(r, r - j) = l_[r - j];
  }
  return true;
}

template <class S>
S ClusterSystem<S>::determinant() const {
  S d = S(1);
  for (int i = 0; i < k_; ++i) d *= R_[static_cast<std::size_t>(i) * static_cast<std::size_t>(b_ + 1)];
  return d;
}

template <class S>
bool ClusterSystem<S>::definite() {
  if (definite_ < 0) definite_ = definite_by_bound() || definite_by_factor() ? 1 : 0;
  return definite_ == 1;
}

template <class S>
bool ClusterSystem<S>::definite_by_factor() {
  // The pivots of the LDLᵀ of A on the free bodies, streamed through a
  // window of the Schur complement on rows j … j+b (L is not kept, A is not
  // copied), so that the check costs a fraction of one solve.  The
  // operations are factor()'s, in its order, so both give the same verdict.
  // win_(r, c) = W[r·(b+1) + c], c <= r.
  const int w = b_ + 1;
  win_.assign(static_cast<std::size_t>(w * w + 2 * w), S(0));  // and the eliminated column, and it over the pivot
  auto W = [&](int r, int c) -> S& { return win_[static_cast<std::size_t>(r * w + c)]; };
  auto load = [&](int r, int row) {  // window row r <- A_{row, row−r … row} (0 below the free bodies)
    for (int c = 0; c <= r; ++c) W(r, c) = row < nf_ ? A(row, r - c) : S(0);
  };
  for (int r = 0; r < w; ++r) load(r, r);
  for (int j = 0; j < nf_; ++j) {
    const S d = W(0, 0);
    if (!(d > S(0))) return false;
    S* col = win_.data() + w * w;
    S* l = col + w;
    for (int r = 1; r < w; ++r) col[r] = W(r, 0), l[r] = col[r] / d;
    for (int r = 1; r < w; ++r)
      for (int c = 1; c <= r; ++c) W(r - 1, c - 1) = W(r, c) - col[r] * l[c];
    load(b_, j + w);
  }
  return true;
}

template <class S>
bool ClusterSystem<S>::solve(const Problem<S>& p, const std::vector<char>& closed_, std::vector<S>& W, std::vector<S>& lambda_) {
  cluster_.resize(static_cast<std::size_t>(n_));
  R_.resize(static_cast<std::size_t>(n_) * static_cast<std::size_t>(b_ + 1));
  l_.resize(static_cast<std::size_t>(b_ + 1));
  y_.resize(static_cast<std::size_t>(n_));
  lambda_.resize(static_cast<std::size_t>(nc_));
  W.resize(static_cast<std::size_t>(n_));
  // Clusters: consecutive bodies joined by closed contacts; the one holding
  // a fixed bottom body (if any) is last and has the known velocity u_n.
  cluster_[0] = 0;
  for (int c = 0; c < nc_; ++c) cluster_[c + 1] = cluster_[c] + (closed_[c] ? 0 : 1);
  const int fixed = p.fixed_bottom ? cluster_[n_ - 1] : -1;
  const int k = p.fixed_bottom ? fixed : cluster_[n_ - 1] + 1;
  const S u_fixed = p.fixed_bottom ? p.u[n_ - 1] : S(0);
  std::fill(R_.begin(), R_.begin() + static_cast<std::ptrdiff_t>(k) * (b_ + 1), S(0));
  std::fill(y_.begin(), y_.begin() + k, S(0));
  // A cluster's right side and diagonal are summed in registers over its
  // rows and stored once (the clusters are runs of rows), so that no row
  // waits for the previous row's update through memory.
  int current = -1;
  S y_sum = S(0), diagonal_sum = S(0);
  const auto flush = [&] {
    if (current < 0) return;
    y_[current] += y_sum;
    R(current, 0) += diagonal_sum;
  };
  for (int i = 0; i < nf_; ++i) {
    const int ci = cluster_[i];
    if (ci == fixed) {  // columns of the fixed cluster move to the right side
      flush();
      current = -1;
      for (int d = 1; d <= b_ && d <= i; ++d)
        if (cluster_[i - d] != fixed) subtract_product(y_[cluster_[i - d]], A(i, d), u_fixed);
      continue;
    }
    if (ci != current) {
      flush();
      current = ci, y_sum = S(0), diagonal_sum = S(0);
    }
    y_sum += rhs_[i];
    // Row i of A adds A_ii and twice its couplings inside the cluster to the
    // cluster's diagonal, and its other couplings off it.
    S inner = A(i, 0);
    for (int d = 1; d <= b_ && d <= i; ++d) {
      const int cj = cluster_[i - d];
      if (cj == ci)
        inner += S(2) * A(i, d);
      else
        R(ci, ci - cj) += A(i, d);
    }
    diagonal_sum += inner;
  }
  flush();
  // Banded LDLᵀ in place, then the three triangular/diagonal solves.  With
  // every contact open the reduced system is A itself: its factorization
  // decides definite() too.
  k_ = k;
  const bool factored = factor(k);
  if (k == nf_) definite_ = factored ? 1 : 0;
  if (!factored) return false;
  for (int i = 0; i < k; ++i)
    for (int j = std::max(0, i - b_); j < i; ++j) subtract_product(y_[i], R(i, i - j), y_[j]);
  for (int i = 0; i < k; ++i) y_[i] /= R(i, 0);
  for (int i = k - 1; i >= 0; --i)
    for (int j = i + 1; j <= std::min(k - 1, i + b_); ++j) subtract_product(y_[i], R(j, j - i), y_[j]);
  for (int i = 0; i < n_; ++i) W[i] = cluster_[i] == fixed ? u_fixed : y_[cluster_[i]];
  // Reactions.  Inside a cluster λ_c − λ_{c−1} = (A W − b̃)_c, so λ_c is the
  // running sum of the row residuals from the top of the cluster, or minus
  // the running sum from its bottom (the rows of a free cluster add up to
  // its equation, 0).  Summing from both ends towards the row with the
  // largest terms puts the cluster's own rounding residual on that
  // row, where it is smallest relative to the row's terms.  A cluster on a
  // fixed obstacle has no equation of its own: its sums run from the top.
  auto row_residual = [&](int c) {
    S r = -rhs_[c];
    for (int d = 0; d <= b_ && d <= c; ++d) add_product(r, A(c, d), W[c - d]);
    for (int d = 1; d <= b_ && c + d < nf_; ++d) add_product(r, A(c + d, d), W[c + d]);
    return r;
  };
  for (int top = 0; top < n_;) {
    int bottom = top;
    while (bottom < nc_ && closed_[bottom]) ++bottom;  // bodies top..bottom form a cluster
    if (bottom < nc_) lambda_[bottom] = S(0);          // the open contact below it
    if (bottom > top) {
      int pivot = bottom;  // the fixed cluster: sums from the top only
      if (cluster_[top] != fixed) {
        SizeOf<S> largest{};  // below every row's scale, which holds a mass > 0
        for (int k = top; k <= bottom; ++k)
          if (scale_[k] > largest) largest = scale_[k], pivot = k;
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

template class ClusterSystem<double>;
template class ClusterSystem<long double>;
template class ClusterSystem<cln::cl_R>;
template class ClusterSystem<MpFloat>;
template class ClusterSystem<cln::cl_RA>;

}  // namespace superball::numeric::detail
