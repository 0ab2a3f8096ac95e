// Problem::constrained: impenetrability on some adjacent contacts only (a
// collision at a distance, numeric/drop.hpp with distant = true).  Every
// contact flagged is the solve of today, bit for bit; with some contacts
// left out, the answer satisfies the equations of motion with no reaction
// on them and the complementarity conditions on the others, and it is the
// one evolution case, over the constrained contacts, whose signs hold.
#include <gtest/gtest.h>

#include <cstdint>

#include "support.hpp"

namespace superball::testing {
namespace {

constexpr std::uint64_t kFirstSeed = 7000, kSeeds = 80;

/// \p p with contact c constrained when bit c of \p mask is set.
template <class S>
Problem<S> with_mask(Problem<S> p, unsigned mask) {
  p.constrained.assign(static_cast<std::size_t>(p.n - 1), 0);
  for (int c = 0; c + 1 < p.n; ++c) p.constrained[static_cast<std::size_t>(c)] = (mask >> c) & 1u;
  return p;
}

template <class S>
void expect_same_bits(const Solution<S>& a, const Solution<S>& b) {
  ASSERT_EQ(a.status, b.status);
  ASSERT_EQ(a.velocities_after.size(), b.velocities_after.size());
  for (std::size_t i = 0; i < a.velocities_after.size(); ++i) EXPECT_TRUE(a.velocities_after[i] == b.velocities_after[i]) << "body " << i + 1;
  for (std::size_t c = 0; c < a.reactions.size(); ++c) EXPECT_TRUE(a.reactions[c] == b.reactions[c]) << "contact " << c + 1;
  EXPECT_EQ(a.closed, b.closed);
}

TEST(Constrained, EveryContactFlaggedIsTodaysSolveBitForBit) {
  for (std::uint64_t seed = kFirstSeed; seed < kFirstSeed + kSeeds; ++seed) {
    const RandomScene r = random_scene(seed, {2, 10});
    SCOPED_TRACE(r.describe());
    const ExactScene scene = ExactScene::from(r.scene());
    const unsigned all = (1u << (r.n - 1)) - 1;
    const auto d = Problem<double>::from(scene);
    expect_same_bits(numeric::solve(d), numeric::solve(with_mask(d, all)));
    const auto l = Problem<long double>::from(scene);
    expect_same_bits(numeric::solve(l), numeric::solve(with_mask(l, all)));
    const auto e = Problem<cl_RA>::from(scene);
    expect_same_bits(numeric::solve(e), numeric::solve(with_mask(e, all)));
  }
}

TEST(Constrained, OpenContactsCarryNoReactionAndTheCaseIsTheOneWhoseSignsHold) {
  // Exact: the answer against every case over the constrained contacts,
  // each imposed by compute_case(): those with λ >= 0 on their closed
  // contacts and gaps >= 0 on their open constrained ones give the answer
  // (more than one only where λ = 0 and the gap is 0 on a contact: the same
  // velocities; the LCP of a P-matrix has one solution).
  int with_open_negative_gap = 0;
  for (std::uint64_t seed = kFirstSeed; seed < kFirstSeed + kSeeds; ++seed) {
    const RandomScene r = random_scene(seed, {3, 7});
    SCOPED_TRACE(r.describe());
    const auto full = Problem<cl_RA>::from(ExactScene::from(r.scene()));
    const int nc = r.n - 1;
    const unsigned mask = static_cast<unsigned>(seed * 2654435761u) % (1u << nc);
    const Problem<cl_RA> p = with_mask(full, mask);
    const Solution<cl_RA> s = numeric::solve(p);
    ASSERT_EQ(s.status, numeric::Status::Success);
    for (int c = 0; c < nc; ++c) {
      if (!p.constrained_contact(c)) {
        EXPECT_EQ(s.reactions[c], 0) << "contact " << c + 1 << " is open: no reaction";
        EXPECT_FALSE(s.closed.closed(c));
        if (s.gaps[c] < 0) ++with_open_negative_gap;
      } else {
        EXPECT_GE(s.gaps[c], 0) << "contact " << c + 1;
        EXPECT_LE(s.reactions[c], 0) << "contact " << c + 1;
        EXPECT_EQ(s.reactions[c] * s.gaps[c], 0) << "contact " << c + 1;
      }
    }
    if (!p.fixed_bottom || p.u[r.n - 1] == 0) {
      EXPECT_LE(s.kinetic_energy_after, s.kinetic_energy_before);  // a moving obstacle does work
    }
    if (!p.fixed_bottom) {
      EXPECT_EQ(s.momentum_after, s.momentum_before);
    }
    numeric::CollisionSolver<cl_RA> solver;
    int admissible = 0;
    for (unsigned closed = 0; closed < (1u << nc); ++closed) {
      if ((closed & ~mask) != 0) continue;  // only constrained contacts may be closed
      ContactSet imposed(r.n);
      for (int c = 0; c < nc; ++c) imposed.set_closed(c, (closed >> c) & 1u);
      Solution<cl_RA> t;
      solver.compute_case(full, imposed, t);
      if (t.status != numeric::Status::Success) continue;
      bool signs = true;
      for (int c = 0; c < nc; ++c)
        if ((mask >> c) & 1u) signs = signs && ((closed >> c) & 1u ? t.reactions[c] <= 0 : t.gaps[c] >= 0);
      if (!signs) continue;
      ++admissible;
      EXPECT_EQ(t.velocities_after, s.velocities_after);
    }
    EXPECT_GE(admissible, 1);
  }
  // The scenes close every contact before the collision: left open, some gap stays negative (the bodies are apart).
  EXPECT_GT(with_open_negative_gap, 0);
}

TEST(Constrained, DoubleAgreesWithExactWithContactsLeftOut) {
  for (std::uint64_t seed = kFirstSeed; seed < kFirstSeed + kSeeds; ++seed) {
    const RandomScene r = random_scene(seed, {3, 9});
    SCOPED_TRACE(r.describe());
    const ExactScene scene = ExactScene::from(r.scene());
    const unsigned mask = static_cast<unsigned>(seed * 40503u) % (1u << (r.n - 1));
    const Solution<cl_RA> e = numeric::solve(with_mask(Problem<cl_RA>::from(scene), mask));
    const Solution<double> d = numeric::solve(with_mask(Problem<double>::from(scene), mask));
    if (d.status != numeric::Status::Success) continue;  // a scene double cannot hold says so
    double scale = 0;
    for (const cl_RA& w : e.velocities_after) scale = std::max(scale, std::abs(cln::double_approx(w)));
    for (std::size_t i = 0; i < e.velocities_after.size(); ++i)
      EXPECT_NEAR(d.velocities_after[i], cln::double_approx(e.velocities_after[i]), 1e-6 * scale) << "body " << i + 1;
  }
}

TEST(Constrained, AFlagPerContactOrNone) {
  auto p = Problem<double>::from(ExactScene::from(random_scene(kFirstSeed, {4, 4}).scene()));
  p.constrained = {1, 0};
  EXPECT_THROW(numeric::solve(p), std::invalid_argument);
}

}  // namespace
}  // namespace superball::testing
