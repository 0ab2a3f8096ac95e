#include "superball/numeric/certify.hpp"

#include "collision/complete.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

namespace superball::numeric {

namespace {

/// |x| in S (CLN floats have no fabs).
template <class S>
S fabs(const S& x) {
  if constexpr (std::is_floating_point<S>::value) {
    return std::fabs(x);
  } else {
    return detail::abs_value<S>(x);
  }
}

/// √x in S: CLN's sqrt of a cl_R holding an exact rational would give a
/// float of CLN's default (single) format, so the CLN floats take it at the
/// problem's digits; an MpFloat of 64 bits (an integer) too.
template <class S>
S square_root(const S& x, int digits) {
  if constexpr (std::is_floating_point<S>::value) {
    (void)digits;
    return std::sqrt(x);
  } else if constexpr (std::is_same<S, MpFloat>::value) {
    return x.precision() >= digits_precision(digits) ? sqrt(x) : sqrt(S(x + MpFloat::zero(digits_precision(digits))));
  } else {
    return cln::sqrt(cln::cl_float(x, digits_format(digits)));
  }
}

/// The smallest double >= x >= 0, or near it (a bound must stay a bound:
/// an E of 1e-400 in long double or CLN floats is not 0).
template <class S>
double double_above(const S& x) {
  const double d = ScalarTraits<S>::to_double(x);
  if constexpr (std::is_same<S, double>::value) {
    return d;
  } else if constexpr (std::is_floating_point<S>::value) {
    return static_cast<S>(d) < x ? std::nextafter(d, std::numeric_limits<double>::infinity()) : d;
  } else {  // rounded to nearest: one step up is above
    return x > S(0) ? std::nextafter(d, std::numeric_limits<double>::infinity()) : d;
  }
}

/// certify() of a problem whose data lie in the safe window of S.
template <class S>
Certificate certify_in_range(const Problem<S>& p, const Solution<S>& s) {
  const int n = p.n, nc = n - 1, nf = p.fixed_bottom ? n - 1 : n;
  const auto& W = s.velocities_after;
  Certificate cert;
  const int b = p.bandwidth();
  const S unit_roundoff = ScalarTraits<S>::unit_roundoff(p.digits);
  const S gamma = S(4 * (b + 4)) * unit_roundoff;
  // Row residuals rr_i = m_i (W_i − u_i) + (DᵀMD (W + u))_i, their sizes
  // (Σ|terms|) and the row sums Σ_j |A_ij|.
  // On the stack up to kStackBodies bodies (a certificate of a small stack
  // costs no allocation), else on the heap.
  constexpr int kStackBodies = 8;
  S stack[3 * kStackBodies];
  std::vector<S> heap;
  S* base = stack;
  if (n > kStackBodies) heap.resize(3 * static_cast<std::size_t>(n)), base = heap.data();
  std::fill(base, base + 3 * n, S(0));
  S* rr = base;
  S* size = base + n;
  S* row = base + 2 * n;
  auto y = [&](int i) { return W[i] + p.u[i]; };
  auto ay = [&](int i) { return fabs(W[i]) + fabs(p.u[i]); };
  auto add = [&](int i, int j, const S& v, int k, int l) {
    const S f = v * (y(k) - y(l)), sz = fabs(v) * (ay(k) + ay(l));
    rr[i] += f, rr[j] -= f, size[i] += sz, size[j] += sz, row[i] += 2 * fabs(v), row[j] += 2 * fabs(v);
  };
  for (const Entry<S>& e : p.entries) {
    add(e.i, e.j, e.value, e.k, e.l);
    if (!e.diagonal()) add(e.k, e.l, e.value, e.i, e.j);
  }
  for (int i = 0; i < nf; ++i) {
    rr[i] += p.mass[i] * (W[i] - p.u[i]);
    size[i] += p.mass[i] * (fabs(W[i]) + fabs(p.u[i]));
    row[i] += p.mass[i];
  }
  // Cluster residuals (free clusters only) and the smallest free cluster mass.
  S rho2 = S(0), cluster_residual = S(0), cluster_size = S(0), cluster_mass = S(0);
  S min_mass = S(0);
  bool free_cluster = false;
  const bool bottom_cluster_fixed = p.fixed_bottom;
  int top = 0;
  for (int i = 0; i < n; ++i) {
    const bool ends = i == n - 1 || !s.closed.closed(i);
    if (i < nf) {
      cluster_residual += rr[i];
      cluster_size += size[i];
      cluster_mass += p.mass[i];
    }
    if (!ends) continue;
    const bool fixed_cluster = bottom_cluster_fixed && i == n - 1;
    if (!fixed_cluster) {
      const S bound = fabs(cluster_residual) + gamma * cluster_size;
      rho2 += bound * bound;
      const S mass = cluster_mass * (1 - gamma);
      if (!free_cluster || mass < min_mass) min_mass = mass;
      free_cluster = true;
    }
    cluster_residual = cluster_size = cluster_mass = S(0);
    top = i + 1;
  }
  (void)top;
  S E = free_cluster ? S(square_root(rho2, p.digits) / min_mass) : S(0);
  // The bodies of the fixed cluster move with the obstacle's velocity as
  // rounded to S: off the exact one by up to u·|u_n| (0 when it is a dyadic
  // number such as 39/4, not when it is 9.75e-126).
  if (p.fixed_bottom) E = std::max(E, S(fabs(p.u[n - 1]) * unit_roundoff));
  // The case: open gaps beyond 2E, closed reactions beyond their bounds.
  // (E must also be a finite double: Certificate holds it as one.)
  bool certain = finite(E) && std::isfinite(ScalarTraits<S>::to_double(E));
  S lambda = S(0), lambda_bound = S(0);
  for (int c = 0; c < nc && certain; ++c) {
    if (!s.closed.closed(c)) {
      lambda = lambda_bound = S(0);
      if (!(W[c] - W[c + 1] > 2 * E)) certain = false;
      continue;
    }
    lambda += rr[c];
    lambda_bound += gamma * size[c] + row[c] * E;
    if (!(lambda > lambda_bound)) certain = false;
  }
  S vmax = S(0);
  for (int i = 0; i < n; ++i) vmax = std::max(vmax, S(fabs(W[i])));
  cert.case_certain = certain;
  cert.velocity_error = double_above(E);
  cert.relative_error = double_above(vmax > S(0) ? S(E / vmax) : E);
  return cert;
}

}  // namespace

template <class S>
Certificate certify(const Problem<S>& p, const Solution<S>& s) {
  // Nothing is certain of an answer that is not a success, not finite, or of
  // data S does not hold; data outside the safe window are certified in the
  // units of the scaled problem solve() solved (the bound scales back by
  // 2^velocity, the relative bound is the same).
  const Scaling k = scaling_of(p);
  if (s.status != Status::Success || !p.in_range || !k.fits || !detail::all_finite(s)) return Certificate{};
  if (k.identity()) return certify_in_range(p, s);
  Solution<S> scaled = s;
  if (!detail::scale_solution(scaled, k, -1)) return Certificate{};
  Certificate cert = certify_in_range(p.scaled(k), scaled);
  cert.velocity_error = double_above(times_power_of_two(S(cert.velocity_error), k.velocity));
  return cert;
}

template SUPERBALL_NUMERIC_EXPORT Certificate certify(const Problem<double>&, const Solution<double>&);
template SUPERBALL_NUMERIC_EXPORT Certificate certify(const Problem<long double>&, const Solution<long double>&);
template SUPERBALL_NUMERIC_EXPORT Certificate certify(const Problem<cln::cl_R>&, const Solution<cln::cl_R>&);
template SUPERBALL_NUMERIC_EXPORT Certificate certify(const Problem<MpFloat>&, const Solution<MpFloat>&);

template <class S>
std::vector<std::string> trust_warnings(const Problem<S>& problem, const Solution<S>& solution) {
  if constexpr (ScalarTraits<S>::exact) {
    (void)problem, (void)solution;
    return {};
  } else {
    if (solution.status != Status::Success) return {};
    const Certificate c = certify(problem, solution);
    // A relative bound of 1 allows every velocity to be off by its own size.
    constexpr double vacuous = 1;
    if (c.case_certain && c.relative_error < vacuous) return {};
    const std::string name = problem.digits > 0 && !std::is_floating_point<S>::value ? "digits:" + std::to_string(problem.digits)
                                                                                      : ScalarTraits<S>::name();
    const std::string bound = "the velocity error bound is " + to_string(c.relative_error, 3) + " of the largest velocity";
    const bool stated = c.relative_error > 0 && std::isfinite(c.relative_error);  // certify() gives 0 where it bounds nothing
    const std::string what = c.case_certain ? bound + ", which says nothing"
                                            : "the case " + solution.closed.to_string() + " is not certified" +
                                                  (stated ? " (" + bound + ")" : "");
    return {name + ": " + what + ": the answer may be wrong; use --precision auto or exact"};
  }
}

template SUPERBALL_NUMERIC_EXPORT std::vector<std::string> trust_warnings(const Problem<double>&, const Solution<double>&);
template SUPERBALL_NUMERIC_EXPORT std::vector<std::string> trust_warnings(const Problem<long double>&, const Solution<long double>&);
template SUPERBALL_NUMERIC_EXPORT std::vector<std::string> trust_warnings(const Problem<cln::cl_R>&, const Solution<cln::cl_R>&);
template SUPERBALL_NUMERIC_EXPORT std::vector<std::string> trust_warnings(const Problem<MpFloat>&, const Solution<MpFloat>&);
template SUPERBALL_NUMERIC_EXPORT std::vector<std::string> trust_warnings(const Problem<cln::cl_RA>&, const Solution<cln::cl_RA>&);

namespace {

template <class S>
bool try_precision(const ExactScene& scene, double rtol, AutoChoice& choice) {
  const auto problem = Problem<S>::from(scene);
  const auto solution = solve(problem);
  const Certificate c = certify(problem, solution);
  const std::string name = ScalarTraits<S>::name();
  if (solution.status != Status::Success) {
    choice.tried.push_back(name + ": " + to_string(solution.status) + " (residual check failed)");
    return false;
  }
  if (!c.case_certain) {
    choice.tried.push_back(name + ": case not certain (bound " + to_string(c.relative_error, 3) + ")");
    return false;
  }
  if (!(c.relative_error <= rtol)) {
    choice.tried.push_back(name + ": bound " + to_string(c.relative_error, 3) + " > rtol");
    return false;
  }
  std::string line;  // one allocation: this runs on every `--precision auto` solve
  line.reserve(64);
  line.append(name).append(": certified, bound ").append(to_string(c.relative_error, 3));
  choice.tried.push_back(std::move(line));
  choice.relative_error = c.relative_error;
  return true;
}

}  // namespace

AutoChoice choose_precision(const ExactScene& scene, double rtol) {
  SolvePrecision{true, {}, rtol}.check();
  AutoChoice choice;
  if (try_precision<double>(scene, rtol, choice)) {
    choice.precision = {Precision::Kind::Double, 0};
  } else if (try_precision<long double>(scene, rtol, choice)) {
    choice.precision = {Precision::Kind::LongDouble, 0};
  } else {
    choice.precision = {Precision::Kind::Exact, 0};
    choice.relative_error = 0;
    choice.tried.push_back("exact");
  }
  return choice;
}

}  // namespace superball::numeric
