#pragma once
/// \file support.hpp
/// Shared helpers of the numeric tests: the scalar types under test and
/// their tolerances, exact conversions, a seeded generator of random scenes
/// (written as TOML so that a failure prints a scene anyone can run), and an
/// independent check of the physics of a solution.

#include <gtest/gtest.h>

#include <cln/dfloat.h>
#include <cln/float.h>
#include <cln/integer.h>
#include <cln/rational.h>
#include <cln/rational_io.h>
#include <cln/real.h>
#include <cln/real_io.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Eigenvalues>

#include "superball/cases/scene_file.hpp"
#include "superball/numeric/certify.hpp"
#include "superball/numeric/chain.hpp"
#include "superball/numeric/collision.hpp"
#include "superball/numeric/problem.hpp"

namespace superball::numeric {
/// gtest prints a Status by name.
inline void PrintTo(Status s, std::ostream* os) { *os << to_string(s); }
}  // namespace superball::numeric

namespace superball::testing {

using cln::cl_R;
using cln::cl_RA;
using numeric::ExactScene;
using numeric::Problem;
using numeric::ScalarTraits;
using numeric::Solution;

// ---------------------------------------------------------------------------
// Settings of long runs.

/// The environment variable \p name when set (a positive integer), else
/// \p fallback: how long runs of the property tests are asked for
/// (SUPERBALL_PROPERTY_SCENES, SUPERBALL_EXTREME_SCENES, their first seeds).
inline std::uint64_t positive_setting(const char* name, std::uint64_t fallback) {
  const char* text = std::getenv(name);
  if (!text || !*text) return fallback;
  const std::string s(text);
  if (s.find_first_not_of("0123456789") != std::string::npos || s.size() > 12 || std::stoull(s) == 0)
    throw std::invalid_argument(std::string("positive_setting(): ") + name + " must be a positive integer, got '" + s + "'");
  return std::stoull(s);
}

// ---------------------------------------------------------------------------
// Scalar types under test.

/// Decimal digits of the MPFR (and CLN) float type under test (digits:30).
inline constexpr int kClnDigits = 30;

/// The digits argument of Problem<S>::from for \p S.
template <class S>
int digits_of() {
  return std::is_same<S, cl_R>::value || std::is_same<S, numeric::MpFloat>::value ? kClnDigits : 0;
}

/// The unit roundoff u of \p S (0 for exact rationals), as an exact rational.
template <class S>
cl_RA unit_roundoff() {
  if (std::is_same<S, cl_RA>::value) return 0;
  if (std::is_same<S, double>::value) return cln::expt(cl_RA(2), -53);
  if (std::is_same<S, long double>::value) return cln::expt(cl_RA(2), -64);
  // CLN floats of N digits carry at least N decimal digits: u <= 10^-N.
  return cln::expt(cl_RA(10), -kClnDigits);
}

/// Error bounds of a solve in a floating type, in units of u.
///
/// The solve is a backward-stable LDLᵀ of A = diag(m) + DᵀMD (free bodies)
/// followed by principal pivots on N = C A⁻¹ Cᵀ.  Two kinds of quantities:
///  - residuals (equations of motion, momentum, energy balance) relative to
///    the size of their terms: at most kResidualAllowance · u, the bound of
///    the solver's own check.  They are not at the level of u because
///    U⁺ = A⁻¹b + (A⁻¹Cᵀ)λ carries the residual of each solve times the
///    reactions λ (measured: up to 1e4 u when the solver reports Success,
///    1.2e5 u when it reports NumericalIssue);
///  - forward errors (velocities against the exact ones, gaps of closed
///    contacts, signs of gaps and reactions) grow with the condition number
///    κ(A): at most kForwardErrorFactor · n · κ(A) · u.  Measured on the
///    random scenes below, the largest ratio error / (n κ(A) u) is about 1;
///    the factor leaves room for other seeds without hiding a lost digit.
inline constexpr double kResidualAllowance = 1e6;
inline constexpr double kForwardErrorFactor = 8;

/// Scenes with n · κ(A) at most this must solve with status Success: their
/// forward errors (at most kForwardErrorFactor · n · κ(A) · u = 8e5 u) stay
/// below the solver's own residual check (1e6 · u, Settings::defaults).  The
/// solver's check is not scaled by κ, so worse-conditioned scenes may report
/// NumericalIssue; their results must still satisfy every bound here.
inline constexpr double kMustSucceedNKappa = 1e5;

inline cl_RA exact_value(long double x);
/// The exact rational value of a double (used for tolerances; subnormals too).
inline cl_RA rational_of(double x) { return exact_value(static_cast<long double>(x)); }

template <class S>
cl_RA residual_tolerance() {
  return unit_roundoff<S>() * rational_of(kResidualAllowance);
}

/// The exact rational value of a scalar (floats are dyadic or decimal rationals).
inline cl_RA exact_value(const cl_RA& x) { return x; }
inline cl_RA exact_value(const cl_R& x) { return cln::rational(x); }
inline cl_RA exact_value(const numeric::MpFloat& x) { return numeric::rational(x); }
inline cl_RA exact_value(double x) { return exact_value(static_cast<long double>(x)); }
inline cl_RA exact_value(long double x) {
  if (x == 0) return 0;
  int e = 0;
  const long double frac = std::frexp(x, &e);  // x = frac · 2^e, 0.5 <= |frac| < 1
  const long double scaled = std::ldexp(std::fabs(frac), 64);
  const unsigned long long mantissa = static_cast<unsigned long long>(scaled);  // exact: 64 bits
  std::ostringstream os;
  os << mantissa;
  const cl_RA m = cl_RA(os.str().c_str()) * cln::expt(cl_RA(2), e - 64);
  return x < 0 ? cl_RA(-m) : m;
}

inline double approx(const cl_RA& x) { return cln::double_approx(x); }
inline cl_RA abs_q(const cl_RA& x) { return cln::minusp(x) ? cl_RA(-x) : x; }
inline cl_RA max_q(const cl_RA& a, const cl_RA& b) { return a < b ? b : a; }
inline std::string text(const cl_RA& x) {
  std::ostringstream os;
  cln::fprint(os, x);
  return os.str();
}

/// A velocity vector in exact rationals.
template <class S>
std::vector<cl_RA> exact_vector(const std::vector<S>& v) {
  std::vector<cl_RA> out;
  for (const S& x : v) out.push_back(exact_value(x));
  return out;
}

/// κ₂(A), A = diag(m) + DᵀMD on the free bodies, from the problem data
/// (assembled here independently of the solver), in long double.
template <class S>
long double condition_number(const Problem<S>& p) {
  const int n = p.n, nf = p.fixed_bottom ? n - 1 : n;
  Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic> K = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>::Zero(n, n);
  auto d = [&](int i, int j) {  // the row of D for pair (i, j): e_i - e_j
    Eigen::Matrix<long double, Eigen::Dynamic, 1> v = Eigen::Matrix<long double, Eigen::Dynamic, 1>::Zero(n);
    v(i) = 1;
    v(j) = -1;
    return v;
  };
  for (const auto& e : p.entries) {
    const long double v = static_cast<long double>(approx(exact_value(e.value)));
    const auto a = d(e.i, e.j), b = d(e.k, e.l);
    K += e.diagonal() ? (v * a * a.transpose()).eval() : (v * (a * b.transpose() + b * a.transpose())).eval();
  }
  Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic> A = K.topLeftCorner(nf, nf);
  for (int i = 0; i < nf; ++i) A(i, i) += static_cast<long double>(approx(exact_value(p.mass[static_cast<std::size_t>(i)])));
  Eigen::SelfAdjointEigenSolver<decltype(A)> eig(A, Eigen::EigenvaluesOnly);
  // λ_min(A) >= the smallest free mass (M is positive semi-definite): where
  // long double cannot resolve λ_min (κ beyond 1/u, e.g. masses 1e-40 and 1
  // under K = 1e40), that bound keeps κ an upper bound instead of ∞ or < 0.
  long double lightest = std::numeric_limits<long double>::infinity();
  for (int i = 0; i < nf; ++i)
    lightest = std::min(lightest, static_cast<long double>(approx(exact_value(p.mass[static_cast<std::size_t>(i)]))));
  return eig.eigenvalues().maxCoeff() / std::max(eig.eigenvalues().minCoeff(), lightest);
}

/// The forward error bound kForwardErrorFactor · n · κ(A) · u of a problem (0 when S is exact).
template <class S>
cl_RA forward_tolerance(const Problem<S>& p) {
  return unit_roundoff<S>() * rational_of(kForwardErrorFactor * p.n * static_cast<double>(condition_number(p)));
}

// ---------------------------------------------------------------------------
// Random scenes.

/// SplitMix64: a portable generator, so a seed names the same scene on every
/// platform and standard library (std::uniform_int_distribution does not).
class Rng {
 public:
  explicit Rng(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  /// Uniform in 0 .. bound-1 (the tiny modulo bias does not matter here).
  int below(int bound) { return static_cast<int>(next() % static_cast<std::uint64_t>(bound)); }
  /// Uniform in lo .. hi.
  int between(int lo, int hi) { return lo + below(hi - lo + 1); }
  bool chance(int percent) { return below(100) < percent; }

 private:
  std::uint64_t state_;
};

/// How the velocities before the collision are given.
enum class Fall {
  FallSpeed,   ///< falling stack, rational fall_speed a (bottom body at rest)
  DropHeight,  ///< falling stack, a = sqrt(2 g h) irrational in general
  Explicit,    ///< every body its own velocity, non-decreasing downwards
  Mixed,       ///< the top bodies fall at -a (rational), the others given
};

struct RandomScene {
  std::uint64_t seed = 0;
  int n = 0;
  bool fixed_bottom = false;
  bool moving_obstacle = false;  ///< a fixed obstacle with a velocity of its own (a paddle)
  Fall fall = Fall::FallSpeed;
  std::string toml;

  Scene scene() const { return parse_scene(toml, origin()); }
  std::string origin() const { return "random-scene-" + std::to_string(seed) + ".toml"; }
  /// For failure messages: the seed and the scene itself.
  std::string describe() const { return "seed " + std::to_string(seed) + ", scene:\n" + toml; }
};

struct RandomSceneOptions {
  int min_bodies = 2;
  int max_bodies = 12;
};

/// A random physically admissible scene: masses from 1e-3 to 1e6, some
/// scenes with a fixed obstacle at the bottom (at rest, or moving up or down
/// at its own velocity), M = s·BᵀB on a random set of
/// declared pairs (positive semi-definite by construction, often singular),
/// and velocities before the collision that close every contact (each body
/// falls at least as fast as the one below: D_c(U⁻) <= 0, the condition for
/// the impenetrability term of the pseudo-potential to vanish at X = 0).
inline RandomScene random_scene(std::uint64_t seed, const RandomSceneOptions& options = {}) {
  Rng rng(seed * 0x2545F4914F6CDD1Dull + 17);
  RandomScene r;
  r.seed = seed;
  r.n = rng.between(options.min_bodies, options.max_bodies);
  r.fixed_bottom = rng.chance(35);
  r.fall = static_cast<Fall>(rng.below(4));
  r.moving_obstacle = r.fixed_bottom && (r.fall == Fall::Explicit || r.fall == Fall::Mixed) && rng.chance(40);
  const int n = r.n;
  std::ostringstream os;
  os << "title = \"random scene, seed " << seed << "\"\n";
  // Fall speed a, rational (p/q) or from a height.
  const int ap = rng.between(1, 40), aq = rng.between(1, 8);
  if (r.fall == Fall::DropHeight)
    os << "drop_height = " << rng.between(1, 300) << "e-2\n";
  else if (r.fall != Fall::Explicit)
    os << "fall_speed = \"" << ap << "/" << aq << "\"\n";
  // Velocities: non-decreasing from top to bottom.
  std::vector<int> v(static_cast<std::size_t>(n), 0);  // quarters of m/s
  const int mixed_top = rng.between(1, n - 1);         // Mixed: bodies 1..mixed_top fall
  if (r.fall == Fall::Explicit || r.fall == Fall::Mixed) {
    // Mixed: the given velocities are >= -a, so that the fall stays a collision.
    const int lo = r.fall == Fall::Mixed ? -(4 * ap) / aq : -40;
    const int hi = r.fixed_bottom && !r.moving_obstacle ? 0 : 40;
    for (int& x : v) x = rng.between(lo, hi);
    std::sort(v.begin(), v.end());
  }
  for (int i = 0; i < n; ++i) {
    os << "[[body]]\n";
    const bool bottom = i == n - 1;
    if (bottom && r.fixed_bottom) {
      os << "mass = \"inf\"\n";
      if (r.moving_obstacle) os << "velocity = \"" << v[static_cast<std::size_t>(i)] << "/4\"\n";
      continue;
    }
    const int mantissa = rng.between(1, 999), exponent = rng.between(-3, 3);
    if (rng.chance(20))
      os << "mass = \"" << mantissa << "/" << rng.between(1, 97) << "\"\n";
    else
      os << "mass = " << mantissa << "e" << exponent << "\n";
    switch (r.fall) {
      case Fall::FallSpeed:
      case Fall::DropHeight:
        if (bottom) os << "velocity = 0\n";
        break;
      case Fall::Explicit: os << "velocity = \"" << v[static_cast<std::size_t>(i)] << "/4\"\n"; break;
      case Fall::Mixed:
        if (i >= mixed_top) os << "velocity = \"" << v[static_cast<std::size_t>(i)] << "/4\"\n";
        break;
    }
  }
  // Declared pairs and M = s · BᵀB on them.
  std::vector<Pair> pairs;
  const int density = rng.between(10, 90);
  for (int i = 1; i <= n; ++i)
    for (int j = i + 1; j <= n; ++j)
      if (rng.chance(j == i + 1 ? std::min(95, density + 20) : density)) pairs.push_back({i, j});
  while (static_cast<int>(pairs.size()) > 3 * n) pairs.erase(pairs.begin() + rng.below(static_cast<int>(pairs.size())));
  const int p = static_cast<int>(pairs.size());
  if (p > 0) {
    const int rank = rng.chance(30) ? rng.between(1, p) : p + rng.between(0, 2);
    const int sparsity = rng.between(30, 85);  // percent of zeros in B
    std::vector<std::vector<int>> B(static_cast<std::size_t>(rank), std::vector<int>(static_cast<std::size_t>(p), 0));
    for (auto& row : B)
      for (int& b : row) b = rng.chance(sparsity) ? 0 : rng.between(-4, 4);
    const cl_RA scale = cl_RA(rng.between(1, 9)) * cln::expt(cl_RA(10), rng.between(-3, 2));
    auto m = [&](int a, int b) {
      cl_RA s = 0;
      for (const auto& row : B) s = s + row[static_cast<std::size_t>(a)] * row[static_cast<std::size_t>(b)];
      return s * scale;
    };
    os << "[dissipation]\nK = {";
    for (int a = 0; a < p; ++a)
      os << (a ? ", " : " ") << '"' << pairs[static_cast<std::size_t>(a)].name() << "\" = \"" << text(m(a, a)) << '"';
    os << " }\n";
    std::ostringstream couplings;
    for (int a = 0; a < p; ++a)
      for (int b = a + 1; b < p; ++b) {
        const cl_RA x = m(a, b);
        if (cln::zerop(x)) continue;
        couplings << "  { pairs = [\"" << pairs[static_cast<std::size_t>(a)].name() << "\", \""
                  << pairs[static_cast<std::size_t>(b)].name() << "\"], value = \"" << text(x) << "\" },\n";
      }
    if (!couplings.str().empty()) os << "coupling = [\n" << couplings.str() << "]\n";
  }
  r.toml = os.str();
  return r;
}

/// A scene of the extreme-exponent family: a random_scene() of 2 to 7 bodies
/// with its masses and M multiplied by 10^mass_exponent and its velocities
/// (explicit ones, and the fall speed) by 10^velocity_exponent, exponents
/// from ±20 to ±300 (or 0).  Its own seed stream: seed k scales the property
/// family's scene kExtremeSeedBase + k, a seed range no property run reaches,
/// so the property family is untouched.
struct ExtremeScene {
  std::uint64_t seed = 0;
  RandomScene base;
  int mass_exponent = 0, velocity_exponent = 0;

  /// \p base_scene (ExactScene::from(base.scene())) scaled, exactly.
  ExactScene exact(const ExactScene& base_scene) const {
    ExactScene s = base_scene;
    s.origin = "extreme-scene-" + std::to_string(seed) + ".toml";
    const cl_RA lambda = cln::expt(cl_RA(10), mass_exponent), mu = cln::expt(cl_RA(10), velocity_exponent);
    for (cl_RA& m : s.mass) m = m * lambda;
    for (auto& e : s.entries) e.value = e.value * lambda;
    for (cl_RA& v : s.velocity) v = v * mu;
    if (s.a_squared) s.a_squared = *s.a_squared * mu * mu;
    return s;
  }
  std::string describe() const {
    return "extreme seed " + std::to_string(seed) + ": masses and M times 1e" + std::to_string(mass_exponent) +
           ", velocities times 1e" + std::to_string(velocity_exponent) + ", of the " + base.describe();
  }
};

inline constexpr std::uint64_t kExtremeSeedBase = std::uint64_t(1) << 40;

inline ExtremeScene random_extreme_scene(std::uint64_t seed) {
  Rng rng(seed * 0xD1342543DE82EF95ull + 0x5851F42D4C957F2Dull);
  ExtremeScene x;
  x.seed = seed;
  x.base = random_scene(kExtremeSeedBase + seed, {2, 7});
  auto exponent = [&rng] {
    if (rng.chance(15)) return 0;
    const int e = rng.between(20, 300);
    return rng.chance(50) ? e : -e;
  };
  x.mass_exponent = exponent();
  x.velocity_exponent = exponent();
  return x;
}

// ---------------------------------------------------------------------------
// Independent check of a solution against the physics of the paper, from the
// problem data only (not from the solver's intermediate matrices).

/// The percussions P_p = 2 (M X)_p + R_p on every pair that appears in M or
/// is a contact, X = D((U⁺ + U⁻)/2), exact; with the size of the terms of
/// each (Σ |2 M_pq| · |X_q|-terms + |R_p|), for relative residuals.
struct Percussions {
  std::map<std::pair<int, int>, cl_RA> P, X, Psize, Xsize;
};

template <class S>
Percussions percussions(const Problem<S>& p, const std::vector<cl_RA>& W, const std::vector<cl_RA>& R) {
  Percussions out;
  const std::vector<cl_RA> u = exact_vector(p.u);
  auto add_pair = [&](int i, int j) {
    const auto a = static_cast<std::size_t>(i), b = static_cast<std::size_t>(j);
    out.X[{i, j}] = (W[a] + u[a] - W[b] - u[b]) / 2;
    out.Xsize[{i, j}] = (abs_q(W[a]) + abs_q(u[a]) + abs_q(W[b]) + abs_q(u[b])) / 2;
    out.P[{i, j}] = 0;
    out.Psize[{i, j}] = 0;
  };
  for (const auto& e : p.entries) add_pair(e.i, e.j), add_pair(e.k, e.l);
  for (int c = 0; c + 1 < p.n; ++c) add_pair(c, c + 1);
  for (const auto& e : p.entries) {
    const cl_RA v2 = 2 * exact_value(e.value);
    const std::pair<int, int> a{e.i, e.j}, b{e.k, e.l};
    out.P[a] = out.P[a] + v2 * out.X[b];
    out.Psize[a] = out.Psize[a] + abs_q(v2) * out.Xsize[b];
    if (!e.diagonal()) {
      out.P[b] = out.P[b] + v2 * out.X[a];
      out.Psize[b] = out.Psize[b] + abs_q(v2) * out.Xsize[a];
    }
  }
  for (int c = 0; c + 1 < p.n; ++c) {
    const auto k = static_cast<std::size_t>(c);
    out.P[{c, c + 1}] = out.P[{c, c + 1}] + R[k];
    out.Psize[{c, c + 1}] = out.Psize[{c, c + 1}] + abs_q(R[k]);
  }
  return out;
}

/// What check_physics() found (exact values computed from the solution).
struct PhysicsReport {
  cl_RA ke_before, ke_after, dissipation;
  cl_RA motion_residual = 0;  ///< largest relative residual of the equations of motion
  bool all_finite = true;
};

/// Tolerances of check_physics(), relative (0 and 0: exact).
struct Tolerances {
  cl_RA residual;  ///< equations of motion, momentum, energy balance
  cl_RA forward;   ///< gaps and reactions: signs, complementarity, closed gaps
};

template <class S>
Tolerances tolerances(const Problem<S>& p) {
  return {residual_tolerance<S>(), forward_tolerance(p)};
}

/// Checks, from the problem data and the velocities and reactions only:
///  - the equations of motion (5), m_i [U_i] = −Σ_{j>i} P_ij + Σ_{j<i} P_ji, on every finite body,
///  - a fixed obstacle keeps its velocity,
///  - momentum Σ m U⁺ = Σ m U⁻ when every body is finite,
///  - KE⁻ − KE⁺ = P·X (the energy balance of the paper's virtual work; plus
///    the work of a fixed obstacle that moves), P·X >= 0 (second law; the
///    contacts are closing before the collision), and KE⁺ <= KE⁻ unless a
///    fixed obstacle moves,
///  - complementarity on each contact: gap >= 0, R <= 0, gap·R = 0, R = 0
///    where the solution says open, gap = 0 where it says closed,
///  - the solver's own energies, momentum, gaps and dissipation agree with these.
template <class S>
PhysicsReport check_physics(const Problem<S>& p, const Solution<S>& s, const Tolerances& tol, const std::string& context) {
  SCOPED_TRACE(context);
  PhysicsReport rep;
  const int n = p.n, nc = n - 1;
  const std::vector<cl_RA> W = exact_vector(s.velocities_after), R = exact_vector(s.reactions), u = exact_vector(p.u),
                           m = exact_vector(p.mass);
  EXPECT_EQ(static_cast<int>(W.size()), n);
  EXPECT_EQ(static_cast<int>(R.size()), nc);
  EXPECT_EQ(static_cast<int>(s.gaps.size()), nc);
  EXPECT_EQ(s.closed.bodies(), n);
  if (static_cast<int>(W.size()) != n || static_cast<int>(R.size()) != nc || static_cast<int>(s.gaps.size()) != nc) return rep;
  const Percussions pc = percussions(p, W, R);
  const int nf = p.fixed_bottom ? n - 1 : n;
  rep.all_finite = !p.fixed_bottom;
  cl_RA vscale = 0, rscale = 0;
  for (int i = 0; i < n; ++i) vscale = max_q(vscale, max_q(abs_q(W[static_cast<std::size_t>(i)]), abs_q(u[static_cast<std::size_t>(i)])));
  for (const auto& [pair, x] : pc.P) rscale = max_q(rscale, abs_q(x));
  for (int i = 0; i < nf; ++i) rscale = max_q(rscale, abs_q(m[static_cast<std::size_t>(i)] * u[static_cast<std::size_t>(i)]));
  // Equations of motion.
  cl_RA total_size = 0;
  for (int i = 0; i < nf; ++i) {
    const auto k = static_cast<std::size_t>(i);
    cl_RA residual = m[k] * (W[k] - u[k]), size = abs_q(m[k] * W[k]) + abs_q(m[k] * u[k]);
    for (const auto& [pair, P] : pc.P) {
      if (pair.first == i) residual = residual + P, size = size + pc.Psize.at(pair);
      if (pair.second == i) residual = residual - P, size = size + pc.Psize.at(pair);
    }
    total_size = total_size + size;
    if (!cln::zerop(size)) rep.motion_residual = max_q(rep.motion_residual, abs_q(residual) / size);
    EXPECT_TRUE(abs_q(residual) <= tol.residual * size)
        << "equation of motion of body " << i + 1 << ": residual " << approx(residual) << " for terms of size " << approx(size);
  }
  if (p.fixed_bottom) {
    EXPECT_EQ(W.back(), u.back()) << "the fixed obstacle moved";
  }
  // Momentum: the sum of the equations of motion.
  if (rep.all_finite) {
    cl_RA before = 0, after = 0;
    for (int i = 0; i < n; ++i) {
      const auto k = static_cast<std::size_t>(i);
      before = before + m[k] * u[k];
      after = after + m[k] * W[k];
    }
    EXPECT_TRUE(abs_q(after - before) <= tol.residual * total_size)
        << "momentum before " << approx(before) << ", after " << approx(after);
    EXPECT_TRUE(abs_q(exact_value(s.momentum_after) - after) <= tol.residual * total_size) << "solver's momentum_after";
    EXPECT_TRUE(abs_q(exact_value(s.momentum_before) - before) <= tol.residual * total_size) << "solver's momentum_before";
  }
  // Energy.
  rep.ke_before = rep.ke_after = rep.dissipation = 0;
  for (int i = 0; i < nf; ++i) {
    const auto k = static_cast<std::size_t>(i);
    rep.ke_before = rep.ke_before + m[k] * u[k] * u[k] / 2;
    rep.ke_after = rep.ke_after + m[k] * W[k] * W[k] / 2;
  }
  cl_RA esize = rep.ke_before + rep.ke_after, reaction_work = 0, obstacle_work = 0;
  for (const auto& [pair, P] : pc.P) {
    rep.dissipation = rep.dissipation + P * pc.X.at(pair);
    esize = esize + pc.Psize.at(pair) * pc.Xsize.at(pair);
    // A fixed obstacle moving at u_n receives the impulse Σ_j P_jn and does
    // the work -(Σ_j P_jn) u_n on the bodies: KE- - KE+ = P·X + (Σ_j P_jn) u_n.
    if (p.fixed_bottom && pair.second == n - 1) {
      obstacle_work = obstacle_work + P * u.back();
      esize = esize + pc.Psize.at(pair) * abs_q(u.back());
    }
  }
  for (const cl_RA& r : R) reaction_work = reaction_work + abs_q(r) * vscale;
  // A closed gap off by rounding lets R·X go negative by R·gap/2: a forward error.
  const cl_RA slack = tol.residual * esize + tol.forward * reaction_work;
  EXPECT_TRUE(abs_q(rep.ke_before - rep.ke_after - rep.dissipation - obstacle_work) <= tol.residual * esize)
      << "energy balance: KE- " << approx(rep.ke_before) << " - KE+ " << approx(rep.ke_after) << " != P.X "
      << approx(rep.dissipation) << " + work of the obstacle " << approx(obstacle_work);
  EXPECT_TRUE(rep.dissipation >= -slack) << "negative dissipation " << approx(rep.dissipation);
  if (!p.fixed_bottom || cln::zerop(u.back())) {  // a moving paddle may give energy
    EXPECT_TRUE(rep.ke_after <= rep.ke_before + slack)
        << "kinetic energy increased: " << approx(rep.ke_before) << " -> " << approx(rep.ke_after);
  }
  EXPECT_TRUE(abs_q(exact_value(s.dissipation) - rep.dissipation) <= tol.residual * esize)
      << "solver's dissipation " << approx(exact_value(s.dissipation)) << " vs P.X " << approx(rep.dissipation);
  EXPECT_TRUE(abs_q(exact_value(s.kinetic_energy_before) - rep.ke_before) <= tol.residual * esize);
  EXPECT_TRUE(abs_q(exact_value(s.kinetic_energy_after) - rep.ke_after) <= tol.residual * esize);
  // Complementarity on the contacts.
  for (int c = 0; c < nc; ++c) {
    const auto k = static_cast<std::size_t>(c);
    const std::string name = std::to_string(c + 1) + "-" + std::to_string(c + 2);
    const cl_RA gap = W[k] - W[k + 1];
    EXPECT_TRUE(abs_q(exact_value(s.gaps[k]) - gap) <= tol.residual * vscale) << "solver's gap of contact " << name;
    EXPECT_TRUE(gap >= -tol.forward * vscale) << "contact " << name << " interpenetrates: gap " << approx(gap);
    EXPECT_TRUE(R[k] <= tol.forward * rscale) << "contact " << name << " pulls: R " << approx(R[k]);
    EXPECT_TRUE(abs_q(gap * R[k]) <= tol.forward * vscale * rscale)
        << "contact " << name << ": gap " << approx(gap) << " and R " << approx(R[k]) << " both non-zero";
    if (s.closed.closed(c)) {
      EXPECT_TRUE(abs_q(gap) <= tol.forward * vscale) << "closed contact " << name << " has gap " << approx(gap);
    } else {
      EXPECT_TRUE(cln::zerop(R[k])) << "open contact " << name << " has reaction " << approx(R[k]);
    }
  }
  return rep;
}

/// The smallest strict-complementarity margin of an exact solution: for each
/// contact, its reaction (closed) or its gap (open) relative to the scale of
/// reactions or velocities.  0 when some contact has gap = R = 0 (degenerate:
/// the scene sits exactly on a switch point).
inline cl_RA complementarity_margin(const Problem<cl_RA>& p, const Solution<cl_RA>& s) {
  cl_RA vscale = 0, rscale = 0;
  for (int i = 0; i < p.n; ++i)
    vscale = max_q(vscale, max_q(abs_q(s.velocities_after[static_cast<std::size_t>(i)]), abs_q(p.u[static_cast<std::size_t>(i)])));
  for (const auto& r : s.reactions) rscale = max_q(rscale, abs_q(r));
  for (int i = 0; i < p.n; ++i) rscale = max_q(rscale, abs_q(p.mass[static_cast<std::size_t>(i)] * p.u[static_cast<std::size_t>(i)]));
  if (cln::zerop(vscale)) vscale = 1;
  if (cln::zerop(rscale)) rscale = 1;
  cl_RA margin = 1;
  for (int c = 0; c + 1 < p.n; ++c) {
    const auto k = static_cast<std::size_t>(c);
    const cl_RA m = s.closed.closed(c) ? abs_q(s.reactions[k]) / rscale : abs_q(s.gaps[k]) / vscale;
    if (m < margin) margin = m;
  }
  return margin;
}

/// Whether numeric::certify() is defined for \p S (double and long double).
template <class S>
inline constexpr bool kHasCertificate = std::is_same<S, double>::value || std::is_same<S, long double>::value;

/// What the certificate (numeric/certify.hpp) says of a solution; nullopt for
/// the arithmetics that have none.
template <class S>
std::optional<numeric::Certificate> certificate_of(const Problem<S>& p, const Solution<S>& s) {
  if constexpr (kHasCertificate<S>) {
    return numeric::certify(p, s);
  } else {
    (void)p, (void)s;
    return std::nullopt;
  }
}

/// Whether every velocity after, reaction and energy of \p s is a finite number.
template <class S>
bool finite_answer(const Solution<S>& s) {
  bool ok = numeric::finite(s.kinetic_energy_before) && numeric::finite(s.kinetic_energy_after) && numeric::finite(s.dissipation);
  for (const S& x : s.velocities_after) ok = ok && numeric::finite(x);
  for (const S& x : s.reactions) ok = ok && numeric::finite(x);
  return ok;
}

/// Max absolute difference of two vectors, exact.
inline cl_RA max_difference(const std::vector<cl_RA>& a, const std::vector<cl_RA>& b) {
  cl_RA d = 0;
  for (std::size_t i = 0; i < a.size(); ++i) d = max_q(d, abs_q(a[i] - b[i]));
  return d;
}

/// What expect_case_and_certificate() saw on one scene.
struct CaseVerdict {
  bool decidable = false;  ///< the exact solution is farther than the margin from a switch point
  bool certified = false;  ///< the certificate says the case is certain
  double error_over_certified_bound = 0;  ///< largest |error| / certified bound (0 when not certified)
};

/// The evolution case of \p ss is the exact one (\p se) wherever the exact
/// solution is farther than \p margin from a switch point; and wherever the
/// certificate says the case is certain, it is the exact case and the
/// velocities are within the certified bound (a proof, no slack).
template <class S>
CaseVerdict expect_case_and_certificate(const Problem<S>& ps, const Solution<S>& ss, const Problem<cl_RA>& pe,
                                        const Solution<cl_RA>& se, const cl_RA& margin) {
  CaseVerdict v;
  v.decidable = complementarity_margin(pe, se) > margin;
  if (v.decidable) {
    EXPECT_EQ(ss.closed, se.closed) << "case " << ss.closed.to_string() << ", exact " << se.closed.to_string();
  }
  const auto cert = certificate_of(ps, ss);
  if (!cert || !cert->case_certain) return v;
  v.certified = true;
  EXPECT_EQ(ss.closed, se.closed) << "certified case " << ss.closed.to_string() << ", exact " << se.closed.to_string();
  const cl_RA abs_err = max_difference(exact_vector(ss.velocities_after), se.velocities_after);
  EXPECT_TRUE(abs_err <= rational_of(cert->velocity_error))
      << "error " << approx(abs_err) << " above the certified bound " << cert->velocity_error;
  if (cert->velocity_error > 0) v.error_over_certified_bound = approx(abs_err) / cert->velocity_error;
  return v;
}

// ---------------------------------------------------------------------------
// Exact matrices (M of a scene, its principal minors).

using Matrix = std::vector<std::vector<cl_RA>>;

/// Determinant by exact Gaussian elimination.
inline cl_RA determinant(Matrix a) {
  const std::size_t m = a.size();
  cl_RA det = 1;
  for (std::size_t k = 0; k < m; ++k) {
    std::size_t pivot = k;
    while (pivot < m && cln::zerop(a[pivot][k])) ++pivot;
    if (pivot == m) return 0;
    if (pivot != k) std::swap(a[pivot], a[k]), det = -det;
    det = det * a[k][k];
    for (std::size_t i = k + 1; i < m; ++i) {
      const cl_RA f = a[i][k] / a[k][k];
      for (std::size_t j = k; j < m; ++j) a[i][j] = a[i][j] - f * a[k][j];
    }
  }
  return det;
}

/// The principal submatrix of \p M on the rows and columns \p idx.
inline Matrix principal(const Matrix& M, const std::vector<int>& idx) {
  Matrix out(idx.size(), std::vector<cl_RA>(idx.size()));
  for (std::size_t i = 0; i < idx.size(); ++i)
    for (std::size_t j = 0; j < idx.size(); ++j)
      out[i][j] = M[static_cast<std::size_t>(idx[i])][static_cast<std::size_t>(idx[j])];
  return out;
}

/// Max relative difference of two velocity vectors, relative to the largest
/// velocity before or after.
inline cl_RA relative_velocity_error(const std::vector<cl_RA>& W, const std::vector<cl_RA>& exact, const std::vector<cl_RA>& u) {
  cl_RA scale = 0, err = 0;
  for (std::size_t i = 0; i < exact.size(); ++i) {
    scale = max_q(scale, max_q(abs_q(exact[i]), abs_q(u[i])));
    err = max_q(err, abs_q(W[i] - exact[i]));
  }
  return cln::zerop(scale) ? err : err / scale;
}

}  // namespace superball::testing

namespace superball::testing {

/// The four arithmetics every numeric property is checked in.
using Scalars = ::testing::Types<double, long double, numeric::MpFloat, cl_RA>;

/// Test names: RandomScenes/double, …/digits30, …/exact.
struct ScalarNames {
  template <class S>
  static std::string GetName(int) {
    if (std::is_same<S, double>::value) return "double";
    if (std::is_same<S, long double>::value) return "long_double";
    if (std::is_same<S, numeric::MpFloat>::value) return "digits" + std::to_string(kClnDigits);
    return "exact";
  }
};

/// Load and check a scene file, then convert it for \p S.
template <class S>
Problem<S> problem_of(const Scene& scene) {
  return Problem<S>::from(ExactScene::from(scene), digits_of<S>());
}

/// Velocities after the collision in m/s (the solver's unit times the unit), exact.
template <class S>
std::vector<cl_RA> velocities_si(const Problem<S>& p, const Solution<S>& s) {
  std::vector<cl_RA> out;
  for (const S& w : s.velocities_after) out.push_back(exact_value(S(w * p.unit)));
  return out;
}

}  // namespace superball::testing
