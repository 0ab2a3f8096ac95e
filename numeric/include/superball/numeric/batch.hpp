#pragma once
/// \file batch.hpp
/// Many scenes of one structure solved one after another: the same bodies,
/// masses, velocities and pattern of M, only some entries of M varying (the
/// grid points of a map, the values of a sweep).  What does not change from
/// scene to scene is done once: the scene's checks and its conversion into
/// S, the solver's workspace and the solution's storage.  Each scene is then
/// numeric::solve() of the problem Problem<S>::from() makes of it, bit for
/// bit (tests/numeric/batch_test.cpp).

#include <algorithm>
#include <cstddef>
#include <type_traits>
#include <vector>

#include "superball/numeric/chain.hpp"
#include "superball/numeric/collision.hpp"
#include "superball/numeric/problem.hpp"
#include "superball/numeric/export.hpp"
SUPERBALL_NUMERIC_API_BEGIN

namespace superball::numeric {

/// The scenes of \p base (an ExactScene) whose entries of M listed in
/// `varying` take other values, solved in S one at a time:
///
///     Batch<double> batch(exact, {kx, ky});
///     batch.set(0, x, x_is_zero);
///     batch.set(1, y, y_is_zero);
///     const Solution<double>& s = batch.solve();  // numeric::solve(Problem<double>::from(scene at (x, y)))
///
/// The problem is converted once; set() writes one entry and keeps
/// Problem::in_range as Problem::from() would give it; solve() runs the
/// solver solve() would choose (the dense solver and its fixed-size path, or
/// the banded one) on a workspace kept from scene to scene, and the scaled
/// solve of solve() where the data leave the safe window of S.  In double
/// and long double, solve() allocates nothing once the first scene is
/// solved (unless a scene needs scaling).  solve_each() solves many scenes,
/// in double several at once (lanes of SIMD registers), each bit for bit.  One Batch per thread: it holds
/// the problem and the workspace (for CLN types, CLN objects).
template <class S>
class Batch {
 public:
  /// The scenes of \p base with the entries \p varying (indices into
  /// ExactScene::entries, distinct) set by set(); \p digits for the digits:N
  /// types (ScalarTraits).  Until set, an entry holds base's value.  Throws
  /// std::invalid_argument("Batch::Batch(): …") when an index is out of
  /// range or repeated.
  Batch(const ExactScene& base, std::vector<std::size_t> varying, int digits = 0);

  /// The number of entries that vary.
  std::size_t size() const { return varying_.size(); }
  /// Varying entry \p k (0 <= k < size()) set to \p value, the value in S
  /// of an exact value that is zero exactly when \p is_zero (which
  /// Problem::in_range needs: a nonzero value rounded to zero is out of
  /// range).  Throws std::out_of_range("Batch::set(): …") for a bad \p k.
  void set(std::size_t k, const S& value, bool is_zero);
  /// The problem of the scene set: Problem<S>::from() of that scene, field
  /// for field.
  const Problem<S>& problem() const { return problem_; }
  /// numeric::solve(problem()), bit for bit, into storage kept for the next
  /// scene (valid until the next solve()).
  const Solution<S>& solve();

  /// How many scenes solve_each() solves at once: 4 in double, else 1.
  static constexpr std::size_t lanes = std::is_same<S, double>::value ? 4 : 1;
  /// Scenes 0 .. \p count − 1, each numeric::solve() of its problem bit for
  /// bit, as solve() after its set() calls:
  ///
  ///     batch.solve_each(count, [&](std::size_t k) { batch.set(0, x[k], x_is_zero[k]); },
  ///                      [&](std::size_t k, const Solution<double>& s) { ... });
  ///
  /// \p set_scene(k) sets scene k's varying entries with set(); \p take(k,
  /// solution) receives its solution (valid during the call; problem() is
  /// then some scene of the same group of lanes, not necessarily k's).  In
  /// double, up to `lanes` scenes are set one after another and solved
  /// together where every contact stays open (the fixed-size path in lanes,
  /// AVX2 where the processor has it); the others, and every scene in other
  /// types, are solved by solve().  Scenes are taken in increasing k.
  template <class SetScene, class Take>
  void solve_each(std::size_t count, SetScene&& set_scene, Take&& take);

 private:
  /// The scene set() made, kept as lane \p lane of the next solve_staged().
  void stage(std::size_t lane);
  /// Lanes 0 .. count − 1 solved into lane_out_: the bits of those solved.
  unsigned solve_staged(std::size_t count) {
    const unsigned todo = lane_todo_ & ((1u << count) - 1u);
    if constexpr (std::is_same<S, double>::value)
      if (todo) return lanes_(problem_, bandwidth_, lane_values_.data(), todo, dense_.settings(), lane_out_.data());
    return 0;
  }
  /// The scene of lane \p lane set again (for solve()).
  void restore(std::size_t lane) {
    if constexpr (std::is_same<S, double>::value) {
      for (std::size_t k = 0; k < varying_.size(); ++k) {
        problem_.entries[varying_[k]].value = lane_values_[varying_[k] * lanes + lane];
        held_[k] = lane_held_[lane * varying_.size() + k];
      }
      problem_.in_range = others_in_range_ && std::all_of(held_.begin(), held_.end(), [](char h) { return h != 0; });
    } else {
      (void)lane;
    }
  }

  std::vector<std::size_t> varying_;
  std::vector<char> held_;    ///< per varying entry: its value is held as Problem::from() requires
  bool others_in_range_ = true;  ///< Problem::from()'s verdict on every datum but the varying entries
  bool others_inside_ = false;   ///< every datum but the varying entries is 0 or inside the safe window of S (scaling_of())
  Problem<S> problem_;
  bool chain_ = false;           ///< solves_as_chain(problem_): the banded solver (a property of the structure)
  int bandwidth_ = 0;            ///< Problem::check() of problem_: DᵀMD's bandwidth (a property of the structure)
  /// The dense solver's fixed-size path for problem_ (double and long double, nullptr otherwise), called
  /// directly: CollisionSolver::compute() without re-checking the structure at each scene.
  bool (*small_)(const Problem<S>&, int, const Settings<S>&, Solution<S>&) = nullptr;
  CollisionSolver<S> dense_;
  ChainSolver<S> banded_;
  Solution<S> out_;
  /// The fixed-size path in lanes for problem_ (double, the dense solver's fixed-size path only; nullptr otherwise).
  unsigned (*lanes_)(const Problem<double>&, int, const double*, unsigned, const Settings<double>&, Solution<double>*) = nullptr;
  std::vector<double> lane_values_;  ///< entry e of M in lane q at [e·lanes + q]
  std::vector<char> lane_held_;      ///< held_ of lane q at [q·size() + k]
  unsigned lane_todo_ = 0;           ///< the staged lanes the lanes may solve: in range and inside the safe window
  std::vector<Solution<S>> lane_out_;
};

template <class S>
template <class SetScene, class Take>
inline void Batch<S>::solve_each(std::size_t count, SetScene&& set_scene, Take&& take) {
  for (std::size_t first = 0; first < count; first += lanes) {
    const std::size_t group = std::min(lanes, count - first);
    if (group == 1) {
      set_scene(first);
      take(first, solve());
      continue;
    }
    for (std::size_t q = 0; q < group; ++q) set_scene(first + q), stage(q);
    const unsigned solved = solve_staged(group);
    for (std::size_t q = 0; q < group; ++q) {
      if ((solved >> q) & 1u) {
        take(first + q, lane_out_[q]);
        continue;
      }
      restore(q);
      take(first + q, solve());
    }
  }
}

extern template class SUPERBALL_NUMERIC_EXPORT Batch<double>;
extern template class SUPERBALL_NUMERIC_EXPORT Batch<long double>;
extern template class SUPERBALL_NUMERIC_EXPORT Batch<MpFloat>;
extern template class SUPERBALL_NUMERIC_EXPORT Batch<cln::cl_RA>;

}  // namespace superball::numeric

SUPERBALL_NUMERIC_API_END
