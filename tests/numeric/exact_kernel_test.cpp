// The exact solve by fraction-free integer elimination (numeric/src/
// exact_kernel.cpp, Settings::integer_kernel) against the solve in CLN
// rationals throughout (integer_kernel = false): the same fractions for every
// field of the answer (velocities, reactions, gaps, the case, energies,
// momenta, dissipation), the same pivot count and status, on random scenes
// of 2 to 8 bodies, on chains by both solvers, on scenes whose data have
// large prime denominators (answers whose parts outgrow 64 and 128 bits), and
// on scenes whose data span hundreds of decimal exponents (the kernel's
// CLN-integer path); and the
// physics of the answer checked on its own (momentum, energy balance).
#include <gtest/gtest.h>

#include <cln/integer.h>

#include <sstream>
#include <string>

#include "support.hpp"

namespace superball::testing {
namespace {

using numeric::ChainSolver;
using numeric::CollisionSolver;
using numeric::Settings;

Settings<cl_RA> rational_settings() {
  Settings<cl_RA> s = Settings<cl_RA>::defaults();
  s.integer_kernel = false;
  return s;
}

/// Every field of \p a equals that of \p b, fraction for fraction.
void expect_same(const Solution<cl_RA>& a, const Solution<cl_RA>& b) {
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.pivots, b.pivots);
  EXPECT_EQ(a.velocities_after, b.velocities_after);
  EXPECT_EQ(a.reactions, b.reactions);
  EXPECT_EQ(a.gaps, b.gaps);
  EXPECT_EQ(a.closed, b.closed);
  EXPECT_EQ(a.kinetic_energy_before, b.kinetic_energy_before);
  EXPECT_EQ(a.kinetic_energy_after, b.kinetic_energy_after);
  EXPECT_EQ(a.momentum_before, b.momentum_before);
  EXPECT_EQ(a.momentum_after, b.momentum_after);
  EXPECT_EQ(a.dissipation, b.dissipation);
  EXPECT_EQ(a.residual_motion, b.residual_motion);
  EXPECT_EQ(a.residual_complementarity, b.residual_complementarity);
}

/// Both solvers, with and without the kernel, on \p p; the dense answers of
/// the kernel returned.
Solution<cl_RA> expect_kernel_matches_rationals(const Problem<cl_RA>& p) {
  const Solution<cl_RA> dense = CollisionSolver<cl_RA>().compute(p);
  expect_same(dense, CollisionSolver<cl_RA>(rational_settings()).compute(p));
  const Solution<cl_RA> chain = ChainSolver<cl_RA>().compute(p);
  expect_same(chain, ChainSolver<cl_RA>(rational_settings()).compute(p));
  // The two formulations: same answer, pivot counts of their own rules.
  EXPECT_EQ(dense.velocities_after, chain.velocities_after);
  EXPECT_EQ(dense.reactions, chain.reactions);
  EXPECT_EQ(dense.closed, chain.closed);
  return dense;
}

/// Physics of an exact answer, independently of either path: momentum
/// conserved on a free stack, the energy balance an identity, dissipation >= 0.
void expect_physics(const Problem<cl_RA>& p, const Solution<cl_RA>& s) {
  ASSERT_EQ(s.status, numeric::Status::Success);
  if (!p.fixed_bottom) {
    EXPECT_EQ(s.momentum_before, s.momentum_after);
  }
  if (!p.fixed_bottom || cln::zerop(p.u.back())) {
    EXPECT_EQ(s.kinetic_energy_before - s.kinetic_energy_after, s.dissipation);
  }
  EXPECT_GE(s.dissipation, 0);
  for (int c = 0; c + 1 < p.n; ++c) {
    EXPECT_GE(s.gaps[static_cast<std::size_t>(c)], 0);
    EXPECT_LE(s.reactions[static_cast<std::size_t>(c)], 0);
    EXPECT_TRUE(cln::zerop(s.gaps[static_cast<std::size_t>(c)] * s.reactions[static_cast<std::size_t>(c)]));
  }
}

/// Random scenes compared: SUPERBALL_PROPERTY_SCENES when set (a long run),
/// else this many.
constexpr std::uint64_t kDefaultKernelScenes = 400;

TEST(ExactKernel, RandomScenesOfTwoToEightBodiesGiveTheRationalPathsFractions) {
  int closed = 0, pivoted = 0;
  const std::uint64_t scenes = positive_setting("SUPERBALL_PROPERTY_SCENES", kDefaultKernelScenes);
  for (std::uint64_t seed = 1; seed <= scenes; ++seed) {
    const RandomScene r = random_scene(seed, {2, 8});
    SCOPED_TRACE(r.describe());
    const auto p = problem_of<cl_RA>(r.scene());
    const Solution<cl_RA> s = expect_kernel_matches_rationals(p);
    expect_physics(p, s);
    for (int c = 0; c + 1 < p.n; ++c) closed += s.closed.closed(c);
    pivoted += s.pivots > 0;
  }
  // The scenes exercise closed contacts and Murty's pivoting, not only q >= 0.
  EXPECT_GT(closed, static_cast<int>(scenes / 4));
  EXPECT_GT(pivoted, static_cast<int>(scenes / 10));
}

/// \p p with masses and M multiplied by 10^mass_exponent and velocities by
/// 10^velocity_exponent (the answer scales exactly: velocities by the second,
/// reactions and momenta by both, energies by the first and twice the second).
Problem<cl_RA> rescaled(Problem<cl_RA> p, int mass_exponent, int velocity_exponent) {
  const cl_RA fm = cln::expt(cl_RA(10), mass_exponent), fu = cln::expt(cl_RA(10), velocity_exponent);
  for (auto& m : p.mass) m = m * fm;
  for (auto& e : p.entries) e.value = e.value * fm;
  for (auto& u : p.u) u = u * fu;
  return p;
}

TEST(ExactKernel, HugeAndTinyExponentsTakeTheIntegerPathAndScaleExactly) {
  // Data of 10^±300 do not fit 64 bits: the kernel works in CLN integers.
  for (std::uint64_t seed = 500; seed < 540; ++seed) {
    const RandomScene r = random_scene(seed, {2, 8});
    SCOPED_TRACE(r.describe());
    const auto p = problem_of<cl_RA>(r.scene());
    const Solution<cl_RA> base = CollisionSolver<cl_RA>().compute(p);
    for (const auto& [em, eu] : {std::pair{300, -300}, std::pair{-300, 300}, std::pair{250, 0}, std::pair{0, -250}, std::pair{17, 9}}) {
      SCOPED_TRACE("masses x 1e" + std::to_string(em) + ", velocities x 1e" + std::to_string(eu));
      const auto q = rescaled(p, em, eu);
      const Solution<cl_RA> s = expect_kernel_matches_rationals(q);
      expect_physics(q, s);
      const cl_RA fu = cln::expt(cl_RA(10), eu), fr = cln::expt(cl_RA(10), em + eu);
      ASSERT_EQ(s.velocities_after.size(), base.velocities_after.size());
      for (std::size_t i = 0; i < s.velocities_after.size(); ++i) EXPECT_EQ(s.velocities_after[i], base.velocities_after[i] * fu);
      for (std::size_t c = 0; c < s.reactions.size(); ++c) EXPECT_EQ(s.reactions[c], base.reactions[c] * fr);
      EXPECT_EQ(s.closed, base.closed);
    }
  }
}

TEST(ExactKernel, MixedMagnitudesInOneSceneGiveTheRationalPathsFractions) {
  // One body 10^-200 against others of 10^200, so that the 128-bit bounds
  // fail on some cases only and the kernel switches ring between cases.
  for (std::uint64_t seed = 600; seed < 630; ++seed) {
    const RandomScene r = random_scene(seed, {3, 8});
    SCOPED_TRACE(r.describe());
    auto p = problem_of<cl_RA>(r.scene());
    p.mass[0] = p.mass[0] * cln::expt(cl_RA(10), -200);
    if (!p.fixed_bottom) p.mass.back() = p.mass.back() * cln::expt(cl_RA(10), 200);
    const Solution<cl_RA> s = expect_kernel_matches_rationals(p);
    expect_physics(p, s);
  }
}

TEST(ExactKernel, LargePrimeDenominatorsGiveTheRationalPathsFractions) {
  // Masses, entries of M and velocities multiplied by (q + 1)/q for primes q
  // near 2^10, 2^15, 2^16 and 2^17: common denominators of up to 62 bits
  // (beyond, the data leave 64 bits and the CLN-integer path takes over), so
  // that the answer's denominators outgrow 64 bits and the fractions are
  // reduced by each of their paths (word by word, in 128 bits, by CLN's
  // division), all against the rational path.
  const long long primes[4][3] = {{1021, 1019, 1013}, {32749, 32719, 32717}, {65521, 65519, 65497}, {131071, 131063, 131059}};
  for (std::uint64_t seed = 700; seed < 780; ++seed) {
    const RandomScene r = random_scene(seed, {2, 8});
    SCOPED_TRACE(r.describe());
    auto p = problem_of<cl_RA>(r.scene());
    const auto& q = primes[seed % 4];
    auto perturb = [&](cl_RA& x, std::size_t k) { x = x * cl_RA(q[k % 3] + 1) / q[k % 3]; };
    for (std::size_t i = 0; i < p.mass.size(); ++i) perturb(p.mass[i], i);
    for (std::size_t e = 0; e < p.entries.size(); ++e) perturb(p.entries[e].value, e + 1);
    for (std::size_t i = 0; i < p.u.size(); ++i) perturb(p.u[i], i + 2);
    const Solution<cl_RA> s = expect_kernel_matches_rationals(p);
    expect_physics(p, s);
  }
}

/// A chain of \p n bodies as bench/bench_chain.cpp builds it (masses
/// 0.001 … 0.007, K = 1, 1/2, couplings 1/4, speeds −1.9 … −1.0), exactly.
Problem<cl_RA> chain(int n, bool fixed) {
  Problem<cl_RA> p;
  p.n = n;
  p.fixed_bottom = fixed;
  for (int i = 0; i < n; ++i) {
    const bool obstacle = fixed && i + 1 == n;
    p.mass.push_back(obstacle ? cl_RA(0) : cl_RA(1 + i % 7) / 1000);
    p.u.push_back(obstacle ? cl_RA(0) : cl_RA(-19 + (10 * i / (n - 1))) / 10);
  }
  for (int i = 0; i + 1 < n; ++i) {
    p.entries.push_back({i, i + 1, i, i + 1, cl_RA(1)});
    if (i + 2 < n) {
      p.entries.push_back({i, i + 2, i, i + 2, cl_RA(1) / 2});
      p.entries.push_back({i, i + 1, i + 1, i + 2, cl_RA(1) / 4});
    }
  }
  return p;
}

TEST(ExactKernel, ChainsAndTheSceneFilesGiveTheRationalPathsFractionsAndIterations) {
  for (int n : {3, 8, 16, 32, 48}) {
    for (bool fixed : {true, false}) {
      SCOPED_TRACE("chain of " + std::to_string(n) + (fixed ? " on a fixed obstacle" : ", free"));
      const auto p = chain(n, fixed);
      expect_physics(p, expect_kernel_matches_rationals(p));
    }
  }
  for (const std::string path : {"/scenes/chain-32.toml", "/scenes/paper-4.4-alpha2.toml", "/scenes/hard-eps-1e-8.toml",
                                  "/scenes/hard-mass-ratio-1e12.toml"}) {
    SCOPED_TRACE(path);
    const auto p = Problem<cl_RA>::from(ExactScene::from(load_scene(std::string(SUPERBALL_CASES_DIR) + path)));
    expect_physics(p, expect_kernel_matches_rationals(p));
  }
}

TEST(ExactKernel, NoConvergenceAndTolerancesAreLeftToTheRationalPath) {
  // A pivot cap the kernel cannot meet, and a feasibility tolerance that is
  // not 0: the outcome is the rational path's (here NoConvergence).
  for (std::uint64_t seed = 1; seed <= 60; ++seed) {
    const RandomScene r = random_scene(seed, {3, 8});
    const auto p = problem_of<cl_RA>(r.scene());
    Settings<cl_RA> capped = Settings<cl_RA>::defaults(), reference = rational_settings();
    capped.max_pivots_per_contact = reference.max_pivots_per_contact = 0;
    expect_same(CollisionSolver<cl_RA>(capped).compute(p), CollisionSolver<cl_RA>(reference).compute(p));
    expect_same(ChainSolver<cl_RA>(capped).compute(p), ChainSolver<cl_RA>(reference).compute(p));
    Settings<cl_RA> loose = Settings<cl_RA>::defaults(), loose_reference = rational_settings();
    loose.feasibility = loose_reference.feasibility = cl_RA(1) / 1000;
    expect_same(CollisionSolver<cl_RA>(loose).compute(p), CollisionSolver<cl_RA>(loose_reference).compute(p));
  }
}

}  // namespace
}  // namespace superball::testing
