#include "detail/complete.hpp"

#include <algorithm>
#include <cmath>

namespace superball::numeric::detail {

namespace {
/// Whether every row of A (free bodies, from \p system's band) has a
/// positive diagonal exceeding the sum of its |off-diagonal| entries by more
/// than the rounding of that sum (|error| <= 2b·u·sum): then A is positive
/// definite (Gershgorin), with no factorization.  O(n b), no division.
template <class S>
bool diagonally_dominant(const ClusterSystem<S>& system, int nf, const S& u) {
  const int b = system.bandwidth();
  const S margin = S(4 * (b + 1)) * u;
  for (int i = 0; i < nf; ++i) {
    S off = S(0);
    for (int d = 1; d <= b && d <= i; ++d) off += abs_value<S>(system.band(i, d));
    for (int d = 1; d <= b && i + d < nf; ++d) off += abs_value<S>(system.band(i + d, d));
    if (!(S(system.band(i, 0) - off) > margin * off)) return false;
  }
  return true;
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
    out.closed.set_closed(c, active[k] || (!imposed && ScalarTraits<S>::exact && out.gaps[k] == S(0)));
  }
  // Energies and momentum of the finite bodies; dissipation P·X = 2XᵀMX + R·X.
  out.kinetic_energy_before = out.kinetic_energy_after = out.momentum_before = out.momentum_after = S(0);
  for (int i = 0; i < nf; ++i) {
    out.kinetic_energy_before += p.mass[i] * p.u[i] * p.u[i] / S(2);
    out.kinetic_energy_after += p.mass[i] * W[i] * W[i] / S(2);
    out.momentum_before += p.mass[i] * p.u[i];
    out.momentum_after += p.mass[i] * W[i];
  }
  auto X = [&](int i, int j) { return (W[i] + p.u[i] - W[j] - p.u[j]) / S(2); };
  S dissipation = S(0);
  for (const Entry<S>& e : p.entries) dissipation += (e.diagonal() ? S(2) : S(4)) * e.value * X(e.i, e.j) * X(e.k, e.l);
  for (int c = 0; c < nc; ++c) dissipation += out.reactions[static_cast<std::size_t>(c)] * X(c, c + 1);
  out.dissipation = dissipation;

  // Residual of the equations of motion, entry by entry: the force DᵀMD y,
  // y = W + u, gets v (y_k − y_l)(e_i − e_j) from entry (i-j, k-l, v), and the
  // transposed term off the diagonal of M.  Relative to the sum of |terms|.
  std::vector<S>& r = work.residual;
  std::vector<S>& size = work.size;
  r.assign(static_cast<std::size_t>(n), S(0));
  size.assign(static_cast<std::size_t>(n), S(0));
  auto y = [&](int i) { return W[i] + p.u[i]; };
  auto ay = [&](int i) { return abs_value<S>(W[i]) + abs_value<S>(p.u[i]); };
  auto add = [&](int i, int j, const S& v, int k, int l) {
    const S f = v * (y(k) - y(l)), s = abs_value<S>(v) * (ay(k) + ay(l));
    r[i] += f, r[j] -= f, size[i] += s, size[j] += s;
  };
  for (const Entry<S>& e : p.entries) {
    add(e.i, e.j, e.value, e.k, e.l);
    if (!e.diagonal()) add(e.k, e.l, e.value, e.i, e.j);
  }
  double motion = 0;
  for (int i = 0; i < nf; ++i) {
    const auto k = static_cast<std::size_t>(i);
    r[k] += p.mass[k] * (W[k] - p.u[k]);
    size[k] += abs_value<S>(p.mass[k] * W[k]) + abs_value<S>(p.mass[k] * p.u[k]);
    if (i < nc) r[k] -= lambda[k], size[k] += abs_value<S>(lambda[k]);
    if (i > 0) r[k] += lambda[k - 1], size[k] += abs_value<S>(lambda[k - 1]);
    if (!(r[k] == S(0))) motion = std::max(motion, to_double(abs_value<S>(r[k])) / std::max(to_double(size[k]), 1e-300));
  }
  // Gaps relative to the largest velocity; reactions relative to the largest
  // row of the equations of motion (momenta, percussions and reactions), so
  // that a reaction at rounding level whose sign came out wrong, where all
  // reactions are about 0, is not taken for a violation.
  double comp = 0, vscale = 0, lscale = 0;
  for (int i = 0; i < n; ++i) vscale = std::max({vscale, std::fabs(to_double(W[i])), std::fabs(to_double(p.u[i]))});
  for (int i = 0; i < nf; ++i) lscale = std::max(lscale, to_double(size[static_cast<std::size_t>(i)]));
  for (int c = 0; c < nc; ++c) {
    const auto k = static_cast<std::size_t>(c);
    const double w = to_double(out.gaps[k]), l = to_double(lambda[k]);
    if (active[k]) {
      if (!(out.gaps[k] == S(0))) comp = std::max(comp, std::fabs(w) / std::max(vscale, 1e-300));
      if (l < 0 && !imposed) comp = std::max(comp, -l / std::max(lscale, 1e-300));
    } else if (w < 0 && !imposed) {
      comp = std::max(comp, -w / std::max(vscale, 1e-300));
    }
  }
  out.residual_motion = motion;
  out.residual_complementarity = comp;
  const double tol = to_double(settings.residual);
  if (out.status == Status::Success && (motion > tol || comp > tol)) out.status = Status::NumericalIssue;
  if (out.status == Status::Success && !diagonally_dominant(system, nf, ScalarTraits<S>::unit_roundoff(p.digits)) &&
      !system.definite())
    out.status = Status::NumericalIssue;
}

template void complete_solution(const Problem<double>&, ClusterSystem<double>&, const std::vector<double>&, const std::vector<char>&, bool,
                                const Settings<double>&, CheckWorkspace<double>&, Solution<double>&);
template void complete_solution(const Problem<long double>&, ClusterSystem<long double>&, const std::vector<long double>&, const std::vector<char>&, bool,
                                const Settings<long double>&, CheckWorkspace<long double>&, Solution<long double>&);
template void complete_solution(const Problem<cln::cl_R>&, ClusterSystem<cln::cl_R>&, const std::vector<cln::cl_R>&, const std::vector<char>&, bool,
                                const Settings<cln::cl_R>&, CheckWorkspace<cln::cl_R>&, Solution<cln::cl_R>&);
template void complete_solution(const Problem<cln::cl_RA>&, ClusterSystem<cln::cl_RA>&, const std::vector<cln::cl_RA>&, const std::vector<char>&, bool,
                                const Settings<cln::cl_RA>&, CheckWorkspace<cln::cl_RA>&, Solution<cln::cl_RA>&);

}  // namespace superball::numeric::detail
