#include "collision/complete.hpp"
#include "collision/dense_steps.hpp"

#include <algorithm>
#include <cmath>

namespace superball::numeric::detail {

namespace {

/// x == 0, without forming a 0 of S where S says it cheaper.
template <class S>
bool is_zero(const S& x) {
  return x == S(0);
}
template <>
bool is_zero<MpFloat>(const MpFloat& x) {
  return x.is_zero();
}

/// The root of body \p i in the union-find forest \p parent (path halving).
int root_of(std::vector<int>& parent, int i) {
  while (parent[static_cast<std::size_t>(i)] != i) {
    auto& up = parent[static_cast<std::size_t>(i)];
    up = parent[static_cast<std::size_t>(up)];
    i = up;
  }
  return i;
}

/// The momentum balance of every free group of bodies, a check the rows of
/// the equations of motion cannot make.  Bodies joined by an entry of M or by
/// a contact solved as closed form a group; summed over a group that does not
/// hold a fixed bottom, the percussions of M and of the closed contacts cancel
/// in pairs and the open contacts carry none, so Σ m (W − u) = 0 over the
/// group, exactly.  Returns the largest |Σ m (W − u)| / Σ m (|W| + |u|),
/// from work.change (m (W − u)) and work.y (|W| + |u|) of complete_solution().
/// Each row of the equations is measured against its largest terms, which are
/// those of M when the masses are light against M (masses 1e-200 with K of
/// order 1): there the rows hold to rounding while the common velocity of a
/// group, set by the masses alone, is lost; this balance sees it.
template <class S>
double group_momentum_residual(const Problem<S>& p, const std::vector<char>& active, CheckWorkspace<S>& work) {
  const int n = p.n, nf = p.fixed_bottom ? n - 1 : n;
  auto& parent = work.group;
  // parent[root(a)] = root(b); a join of two bodies whose parents show them
  // in one tree already changes no root and is skipped without walking the
  // tree (most joins of a chain's entries are such).
  const auto join = [&parent](int a, int b) {
    const int pa = parent[static_cast<std::size_t>(a)], pb = parent[static_cast<std::size_t>(b)];
    if (pa == pb || pa == b || pb == a) return;
    parent[static_cast<std::size_t>(root_of(parent, a))] = root_of(parent, b);
  };
  // M's joins, or their outcome kept from the last problem with the same n
  // and the same bodies and zero-ness of M's entries (the same joins give
  // the same parents).
  auto& key = work.entry_key;
  bool same = work.entry_bodies == n && key.size() == 5 * p.entries.size();
  for (std::size_t k = 0; same && k < p.entries.size(); ++k) {
    const Entry<S>& e = p.entries[k];
    const int* x = &key[5 * k];
    same = x[0] == e.i && x[1] == e.j && x[2] == e.k && x[3] == e.l && x[4] == (is_zero(e.value) ? 0 : 1);
  }
  if (same) {
    parent = work.entry_group;
  } else {
    parent.resize(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) parent[static_cast<std::size_t>(i)] = i;
    for (const Entry<S>& e : p.entries) {
      if (is_zero(e.value)) continue;
      join(e.i, e.j);
      // A diagonal entry's other two joins are (i, j) again and (i, i): they
      // change no root, so skipping them leaves every group and its
      // representative as they were.
      if (!e.diagonal()) join(e.k, e.l), join(e.i, e.k);
    }
    key.clear();
    for (const Entry<S>& e : p.entries) key.insert(key.end(), {e.i, e.j, e.k, e.l, is_zero(e.value) ? 0 : 1});
    work.entry_group = parent;
    work.entry_bodies = n;
  }
  for (int c = 0; c + 1 < n; ++c)
    if (active[static_cast<std::size_t>(c)]) join(c, c + 1);
  auto& sum = work.momentum;
  sum.assign(static_cast<std::size_t>(n), Sized<S>{});
  for (int i = 0; i < nf; ++i) {
    const auto k = static_cast<std::size_t>(i);
    sum[static_cast<std::size_t>(root_of(parent, i))].add(work.change[k], size_of(p.mass[k]) * work.y[k].size());  // y's size: |W| + |u|
  }
  const int anchored = p.fixed_bottom ? root_of(parent, n - 1) : -1;  // the obstacle takes momentum
  using Size = SizeOf<S>;
  Size worst{};  // not in double, as the rows: momenta of 1e-308 are beyond double's range
  for (int r = 0; r < n; ++r) {
    const auto k = static_cast<std::size_t>(r);
    if (parent[k] != r || r == anchored) continue;
    const Size v = size_of(sum[k].value()), size = sum[k].size();
    if (size > Size{} && v > worst * size) worst = v / size;
  }
  return to_double(worst);
}

}  // namespace

template <class S>
void complete_solution(const Problem<S>& p, ClusterSystem<S>& system, const std::vector<S>& lambda,
                       const std::vector<char>& active, bool imposed, const Settings<S>& settings, CheckWorkspace<S>& work,
                       Solution<S>& out) {
  const int n = p.n, nc = n - 1, nf = p.fixed_bottom ? n - 1 : n;
  const auto& W = out.velocities_after;
  out.reactions.resize(static_cast<std::size_t>(nc));
  out.gaps.resize(static_cast<std::size_t>(nc));
  if (out.closed.bodies() != n) out.closed = ContactSet(n);
  for (int c = 0; c < nc; ++c) {
    const auto k = static_cast<std::size_t>(c);
    out.gaps[k] = W[k] - W[k + 1];
    out.reactions[k] = active[k] ? S(-lambda[k]) : S(0);
    out.closed.set_closed(c, active[k] || (!imposed && ScalarTraits<S>::exact && out.gaps[k] == S(0) && p.constrained_contact(c)));
  }
  // Energies and momentum of the finite bodies; dissipation P·X = 2XᵀMX + R·X.
  // m u and m W once per body (m u u / 2 is (m u) u / 2).
  out.kinetic_energy_before = out.kinetic_energy_after = out.momentum_before = out.momentum_after = S(0);
  work.mu.resize(static_cast<std::size_t>(nf));
  work.mw.resize(static_cast<std::size_t>(nf));
  work.change.resize(static_cast<std::size_t>(nf));
  for (int i = 0; i < nf; ++i) {
    const auto k = static_cast<std::size_t>(i);
    S& mu = work.mu[k];
    S& mw = work.mw[k];
    mu = p.mass[k] * p.u[k];
    mw = p.mass[k] * W[k];
    add_half_product(out.kinetic_energy_before, mu, p.u[k]);
    add_half_product(out.kinetic_energy_after, mw, W[k]);
    out.momentum_before += mu;
    out.momentum_after += mw;
    work.change[k] = p.mass[k] * (W[k] - p.u[k]);
  }
  // One pass over the entries gives the dissipation P·X = 2XᵀMX + R·X and
  // the residual of the equations of motion, entry by entry: with
  // y = W + u = 2X, the force DᵀMD y gets v (y_k − y_l)(e_i − e_j) from entry
  // (i-j, k-l, v), and the transposed term off the diagonal of M; residuals
  // are relative to the sum of |terms|.
  // The sizes are SizeOf<S>: S, or a Magnitude of 53 bits (MpFloat, exact).
  using Size = SizeOf<S>;
  std::vector<Sized<S>>& y = work.y;
  std::vector<Sized<S>>& rows = work.rows;
  y.resize(static_cast<std::size_t>(n));
  Size vscale{};  // the largest |W| and |u|: complementarity's scale of velocities, below
  for (int i = 0; i < n; ++i) {
    const Size w = size_of(W[i]), v = size_of(p.u[i]);
    y[i].set(W[i] + p.u[i], w + v);
    if (vscale < w) vscale = w;
    if (vscale < v) vscale = v;
  }
  rows.assign(static_cast<std::size_t>(n), Sized<S>{});
  S dissipation = S(0);
  for (const Entry<S>& e : p.entries) {
    const S ykl = y[e.k].value() - y[e.l].value();
    const Size v = size_of(e.value);
    const S f = e.value * ykl;
    const Size s = v * (y[e.k].size() + y[e.l].size());
    rows[e.i].add(f, s), rows[e.j].subtract(f, s);
    if (e.diagonal()) {  // 2 v X_ij² = v y_ij² / 2 (y_ij is y_kl)
      add_half_product(dissipation, f, ykl);
      continue;
    }
    const S yij = y[e.i].value() - y[e.j].value();
    const S g = e.value * yij;
    const Size t = v * (y[e.i].size() + y[e.j].size());
    rows[e.k].add(g, t), rows[e.l].subtract(g, t);
    add_product(dissipation, g, ykl);  // 4 v X_ij X_kl
  }
  for (int c = 0; c < nc; ++c) add_half_product(dissipation, out.reactions[static_cast<std::size_t>(c)], S(y[c].value() - y[c + 1].value()));
  out.dissipation = dissipation;

  Size motion_s{};  // not in double: rows of 1e-308 in CLN floats are beyond double's range
  for (int i = 0; i < nf; ++i) {
    const auto k = static_cast<std::size_t>(i);
    S r = rows[k].value();
    Size size = rows[k].size();
    r += work.change[k];
    size += size_of(work.mw[k]) + size_of(work.mu[k]);
    if (i < nc) r -= lambda[k], size += size_of(lambda[k]);
    if (i > 0) r += lambda[k - 1], size += size_of(lambda[k - 1]);
    rows[k].set(r, size);
    // max |r|/size, dividing only where the row beats the largest so far
    const Size ar = size_of(r);
    if (size > Size{} && ar > motion_s * size) motion_s = ar / size;
  }
  const double motion = std::max(to_double(motion_s), group_momentum_residual(p, active, work));
  // Gaps relative to the largest velocity; reactions relative to the largest
  // row of the equations of motion (momenta, percussions and reactions), so
  // that a reaction at rounding level whose sign came out wrong, where all
  // reactions are about 0, is not taken for a violation.
  // Not in double, as the rows: gaps of 1e-444 m/s in long double are beyond double's
  // range, and a violated sign there would convert to a residual of 0.
  Size comp_s{}, lscale{};
  const auto raise = [](Size& to, const Size& x) {
    if (to < x) to = x;
  };
  for (int i = 0; i < nf; ++i) raise(lscale, rows[static_cast<std::size_t>(i)].size());
  for (int c = 0; c < nc; ++c) {
    const auto k = static_cast<std::size_t>(c);
    const S& w = out.gaps[k];
    const S& l = lambda[k];
    if (active[k]) {
      if (!(w == S(0)) && vscale > Size{}) raise(comp_s, size_of(w) / vscale);
      if (l < S(0) && !imposed && lscale > Size{}) raise(comp_s, size_of(l) / lscale);
    } else if (w < S(0) && !imposed && vscale > Size{} && p.constrained_contact(c)) {  // an open contact that is not constrained has no sign
      raise(comp_s, size_of(w) / vscale);
    }
  }
  const double comp = to_double(comp_s);
  out.residual_motion = motion;
  out.residual_complementarity = comp;
  // Written so that a NaN residual fails; and every value of the answer must
  // be a number (an overflow in S gives ±inf or NaN, whose residuals can
  // compare as small), from data S holds.
  const double tol = to_double(settings.residual);
  if (out.status == Status::Success && !(motion <= tol && comp <= tol)) out.status = Status::NumericalIssue;
  if (out.status == Status::Success && !(p.in_range && all_finite(out))) out.status = Status::NumericalIssue;
  if (out.status == Status::Success && !system.definite()) out.status = Status::NumericalIssue;
}

template <class S>
bool all_finite(const Solution<S>& s) {
  bool ok = finite(s.kinetic_energy_before) && finite(s.kinetic_energy_after) && finite(s.dissipation) &&
            finite(s.momentum_before) && finite(s.momentum_after);
  for (const S& x : s.velocities_after) ok = ok && finite(x);
  for (const S& x : s.reactions) ok = ok && finite(x);
  return ok;
}

template <class S>
bool scale_solution(Solution<S>& s, const Scaling& k, int direction) {
  // Velocities scale by μ = 2^velocity, reactions and momenta by λμ,
  // energies by λμ² (λ = 2^mass).  Exact unless a value leaves the range of
  // S, which the round trip detects.
  bool exact = true;
  auto scale = [&](S& x, int e) {
    const S y = times_power_of_two(x, direction * e);
    exact = exact && finite(y) && times_power_of_two(y, -direction * e) == x;
    x = y;
  };
  const int v = k.velocity, r = k.mass + k.velocity, e = k.mass + 2 * k.velocity;
  for (S& x : s.velocities_after) scale(x, v);
  for (S& x : s.gaps) scale(x, v);
  for (S& x : s.reactions) scale(x, r);
  scale(s.momentum_before, r);
  scale(s.momentum_after, r);
  scale(s.kinetic_energy_before, e);
  scale(s.kinetic_energy_after, e);
  scale(s.dissipation, e);
  return exact;
}

template bool all_finite(const Solution<double>&);
template bool all_finite(const Solution<long double>&);
template bool all_finite(const Solution<cln::cl_R>&);
template bool all_finite(const Solution<MpFloat>&);
template bool all_finite(const Solution<cln::cl_RA>&);
template bool scale_solution(Solution<double>&, const Scaling&, int);
template bool scale_solution(Solution<long double>&, const Scaling&, int);
template bool scale_solution(Solution<cln::cl_R>&, const Scaling&, int);
template bool scale_solution(Solution<MpFloat>&, const Scaling&, int);
template bool scale_solution(Solution<cln::cl_RA>&, const Scaling&, int);
template void complete_solution(const Problem<double>&, ClusterSystem<double>&, const std::vector<double>&, const std::vector<char>&, bool,
                                const Settings<double>&, CheckWorkspace<double>&, Solution<double>&);
template void complete_solution(const Problem<long double>&, ClusterSystem<long double>&, const std::vector<long double>&, const std::vector<char>&, bool,
                                const Settings<long double>&, CheckWorkspace<long double>&, Solution<long double>&);
template void complete_solution(const Problem<cln::cl_R>&, ClusterSystem<cln::cl_R>&, const std::vector<cln::cl_R>&, const std::vector<char>&, bool,
                                const Settings<cln::cl_R>&, CheckWorkspace<cln::cl_R>&, Solution<cln::cl_R>&);
template void complete_solution(const Problem<MpFloat>&, ClusterSystem<MpFloat>&, const std::vector<MpFloat>&, const std::vector<char>&, bool,
                                const Settings<MpFloat>&, CheckWorkspace<MpFloat>&, Solution<MpFloat>&);
template void complete_solution(const Problem<cln::cl_RA>&, ClusterSystem<cln::cl_RA>&, const std::vector<cln::cl_RA>&, const std::vector<char>&, bool,
                                const Settings<cln::cl_RA>&, CheckWorkspace<cln::cl_RA>&, Solution<cln::cl_RA>&);

}  // namespace superball::numeric::detail
