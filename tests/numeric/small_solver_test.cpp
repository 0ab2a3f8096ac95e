// The fixed-size path of CollisionSolver (numeric/src/collision/small_solver.cpp, n <= 8
// in double and long double) against the general path and against exact
// rationals, on seeded random scenes of 2 to 8 bodies: the same statuses,
// cases, pivots, velocities, reactions, energies and residuals bit for bit,
// and velocities within the a-priori bound 8·n·κ(A)·u of the exact solution
// (docs/ACCURACY.md) with the exact case wherever it is decidable or
// certified.
#include <gtest/gtest.h>

#include <cstdint>
#include <cmath>
#include <iostream>
#include <tuple>
#include <string>

#include "collision/small_solver.hpp"
#include "superball/numeric/chain.hpp"
#include "support.hpp"

namespace superball::testing {
namespace {

/// Seeds of the comparison (each a scene of 2 to 8 bodies).
constexpr std::uint64_t kScenes = 400;
/// At most this share of the scenes may be handed back to the general path
/// (a pivot of A or of the tableau that is not positive in S, the pivot cap):
/// the generator's scenes are well posed, so the fixed-size path must solve
/// nearly all of them itself, or the bit-for-bit comparison proves little.
constexpr int kMaxHandedBackPercent = 2;

/// The same value with the same sign (NaN matching NaN): bit for bit for
/// every value the solver produces.
template <class S>
bool same_bits(const S& a, const S& b) {
  if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b);
  return a == b && std::signbit(a) == std::signbit(b);
}

template <class S>
void expect_same_bits(const std::vector<S>& a, const std::vector<S>& b, const char* what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_TRUE(same_bits(a[i], b[i])) << what << "[" << i << "]: " << a[i] << " against " << b[i];
}

/// Every field of two solutions, bit for bit.
template <class S>
void expect_identical(const Solution<S>& a, const Solution<S>& b) {
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.closed, b.closed) << a.closed.to_string() << " against " << b.closed.to_string();
  EXPECT_EQ(a.pivots, b.pivots);
  expect_same_bits(a.velocities_after, b.velocities_after, "velocities_after");
  expect_same_bits(a.reactions, b.reactions, "reactions");
  expect_same_bits(a.gaps, b.gaps, "gaps");
  for (const auto& [x, y, what] : {std::make_tuple(a.kinetic_energy_before, b.kinetic_energy_before, "kinetic_energy_before"),
                                   std::make_tuple(a.kinetic_energy_after, b.kinetic_energy_after, "kinetic_energy_after"),
                                   std::make_tuple(a.dissipation, b.dissipation, "dissipation"),
                                   std::make_tuple(a.momentum_before, b.momentum_before, "momentum_before"),
                                   std::make_tuple(a.momentum_after, b.momentum_after, "momentum_after")})
    EXPECT_TRUE(same_bits(x, y)) << what << ": " << x << " against " << y;
  EXPECT_TRUE(same_bits(a.residual_motion, b.residual_motion)) << a.residual_motion << " against " << b.residual_motion;
  EXPECT_TRUE(same_bits(a.residual_complementarity, b.residual_complementarity))
      << a.residual_complementarity << " against " << b.residual_complementarity;
}

template <class S>
class SmallSolver : public ::testing::Test {};
using Floats = ::testing::Types<double, long double>;
struct FloatNames {
  template <class S>
  static std::string GetName(int) {
    return std::is_same<S, double>::value ? "double" : "long_double";
  }
};
TYPED_TEST_SUITE(SmallSolver, Floats, FloatNames);

TYPED_TEST(SmallSolver, AgreesBitForBitWithTheGeneralPathAndWithExactRationals) {
  using S = TypeParam;
  numeric::Settings<S> general_settings = numeric::Settings<S>::defaults();
  general_settings.small_sizes = false;
  numeric::CollisionSolver<S> small, general(general_settings);
  Solution<S> direct, via_solver, reference;
  int handed_back = 0, pivoted = 0, fixed = 0, banded = 0, undecidable = 0;
  int sizes[numeric::detail::small_max_bodies + 1] = {};
  for (std::uint64_t seed = 1; seed <= kScenes; ++seed) {
    const RandomScene r = random_scene(seed, {2, numeric::detail::small_max_bodies});
    SCOPED_TRACE(r.describe());
    const ExactScene scene = ExactScene::from(r.scene());
    const auto p = Problem<S>::from(scene);
    ASSERT_TRUE(numeric::scaling_of(p).identity()) << "the generator's data lie in the safe window";
    ++sizes[p.n];
    fixed += p.fixed_bottom;
    banded += p.bandwidth() < p.n - 1;
    // The fixed-size solve itself, then through CollisionSolver::compute().
    const auto solve = numeric::detail::small_solver_for<S>(p.n);
    ASSERT_NE(solve, nullptr);
    const bool solved = solve(p, p.check("test"), numeric::Settings<S>::defaults(), direct);
    handed_back += !solved;
    general.compute(p, reference);
    small.compute(p, via_solver);
    expect_identical(via_solver, reference);
    if (solved) expect_identical(direct, reference);
    pivoted += solved && direct.pivots > 0;
    // Against the exact solution: velocities within 8·n·κ(A)·u, the exact
    // case wherever the exact solution is not within that of a switch point
    // or the certificate proves the case.
    const auto pe = Problem<cl_RA>::from(scene);
    const auto se = numeric::CollisionSolver<cl_RA>().compute(pe);
    ASSERT_EQ(se.status, numeric::Status::Success);
    const Tolerances tol = tolerances(p);
    if (static_cast<double>(p.n) * static_cast<double>(condition_number(p)) <= kMustSucceedNKappa) {
      EXPECT_EQ(via_solver.status, numeric::Status::Success);
    }
    if (via_solver.status != numeric::Status::Success) continue;
    const cl_RA err = relative_velocity_error(exact_vector(via_solver.velocities_after), se.velocities_after, pe.u);
    EXPECT_TRUE(err <= tol.forward) << "relative velocity error " << approx(err) << " > bound " << approx(tol.forward);
    undecidable += !expect_case_and_certificate(p, via_solver, pe, se, tol.forward).decidable;
  }
  for (int n = 2; n <= numeric::detail::small_max_bodies; ++n) EXPECT_GT(sizes[n], 10) << "scenes of " << n << " bodies";
  EXPECT_LE(handed_back * 100, kMaxHandedBackPercent * static_cast<int>(kScenes));
  EXPECT_GT(pivoted, static_cast<int>(kScenes) / 10) << "the pivoting of the fixed-size path must be exercised";
  EXPECT_GT(fixed, static_cast<int>(kScenes) / 5);
  EXPECT_GT(banded, static_cast<int>(kScenes) / 20) << "scenes whose DᵀMD is banded (the runtime-bandwidth variant)";
  EXPECT_LE(undecidable * 10, static_cast<int>(kScenes));
  std::cout << "[ info ] " << FloatNames::GetName<S>(0) << ": " << kScenes << " scenes, " << handed_back
            << " handed back to the general path, " << pivoted << " pivoted, " << undecidable << " within rounding of a switch point\n";
}

TYPED_TEST(SmallSolver, TheSolverChoosesThePathOncePerSizeAndReusesItsOutput) {
  // One solver and one Solution over scenes of changing sizes (the cached
  // choice must follow n), above 8 bodies too (the general path).
  using S = TypeParam;
  numeric::Settings<S> general_settings = numeric::Settings<S>::defaults();
  general_settings.small_sizes = false;
  numeric::CollisionSolver<S> small, general(general_settings);
  Solution<S> a, b;
  for (std::uint64_t seed = 5000; seed < 5060; ++seed) {
    const RandomScene r = random_scene(seed, {2, 11});
    SCOPED_TRACE(r.describe());
    const auto p = problem_of<S>(r.scene());
    small.compute(p, a);
    general.compute(p, b);
    expect_identical(a, b);
  }
}

TYPED_TEST(SmallSolver, AReusedSolverKeepsMsGroupsOnlyWhileTheEntriesAreTheSame) {
  // The residual check keeps the union-find of M's joins between solves
  // while n and the bodies and zero-ness of M's entries stay the same
  // (CheckWorkspace::entry_key).  One solver reused over problems that keep,
  // then change, then restore them (every value set to 0, an entry
  // dropped) must give what a new solver gives, bit for bit, every field:
  // the residuals included, which the groups of the momentum balance set.
  using S = TypeParam;
  numeric::Settings<S> general_settings = numeric::Settings<S>::defaults();
  general_settings.small_sizes = false;
  numeric::CollisionSolver<S> reused_dense(general_settings);
  numeric::ChainSolver<S> reused_chain;
  int changed = 0;
  for (std::uint64_t seed = 7000; seed < 7040; ++seed) {
    const RandomScene r = random_scene(seed, {3, 12});
    SCOPED_TRACE(r.describe());
    const auto p = problem_of<S>(r.scene());
    if (p.entries.empty()) continue;
    // M = 0 (every entry kept, each value 0: no group but the contacts'),
    // and M without its last entry.
    Problem<S> zeroed = p, dropped = p;
    for (auto& e : zeroed.entries) e.value = S(0);
    dropped.entries.pop_back();
    changed += 1;
    for (const Problem<S>* q : std::initializer_list<const Problem<S>*>{&zeroed, &p, &dropped, &p, &zeroed, &p}) {
      Solution<S> a, b, c, d;
      reused_dense.compute(*q, a);
      numeric::CollisionSolver<S>(general_settings).compute(*q, b);
      expect_identical(a, b);
      reused_chain.compute(*q, c);
      numeric::ChainSolver<S>().compute(*q, d);
      expect_identical(c, d);
    }
  }
  EXPECT_GT(changed, 30);
}

TYPED_TEST(SmallSolver, OnlySizesTwoToEightHaveAFixedSizePath) {
  using S = TypeParam;
  for (int n : {-1, 0, 1, numeric::detail::small_max_bodies + 1, 64}) EXPECT_EQ(numeric::detail::small_solver_for<S>(n), nullptr) << n;
  for (int n = 2; n <= numeric::detail::small_max_bodies; ++n) EXPECT_NE(numeric::detail::small_solver_for<S>(n), nullptr) << n;
}

}  // namespace
}  // namespace superball::testing
