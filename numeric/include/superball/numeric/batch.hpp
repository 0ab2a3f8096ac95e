#pragma once
/// \file batch.hpp
/// Many scenes of one structure solved one after another: the same bodies,
/// masses, velocities and pattern of M, only some entries of M varying (the
/// grid points of a map, the values of a sweep).  What does not change from
/// scene to scene is done once: the scene's checks and its conversion into
/// S, the solver's workspace and the solution's storage.  Each scene is then
/// numeric::solve() of the problem Problem<S>::from() makes of it, bit for
/// bit (tests/numeric/batch_test.cpp).

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

  /// Scenes 0 .. \p count − 1, each numeric::solve() of its problem bit for
  /// bit, as solve() after its set() calls:
  ///
  ///     batch.solve_each(count, [&](std::size_t k) { batch.set(0, x[k], x_is_zero[k]); },
  ///                      [&](std::size_t k, const Solution<double>& s) { ... });
  ///
  /// \p set_scene(k) sets scene k's varying entries with set() (it may be
  /// called again for a scene the lanes hand back); \p take(k,
  /// solution) receives its solution (valid during the call; problem() is
  /// then some scene of the same group of lanes, not necessarily k's).  In
  /// double, 4 scenes are set one after another and solved together by the
  /// fixed-size path in SIMD lanes (AVX2 where the processor has it), pivots
  /// included, as long as they take the branches of the first of them; the
  /// others, and every scene in other types, are solved by solve().  Scenes
  /// are taken in increasing k.
  template <class SetScene, class Take>
  void solve_each(std::size_t count, SetScene&& set_scene, Take&& take) {
    using Set = std::remove_reference_t<SetScene>;
    using Get = std::remove_reference_t<Take>;
    solve_each_calling(
        count, [](void* f, std::size_t k) { (*static_cast<Set*>(f))(k); }, const_cast<void*>(static_cast<const void*>(&set_scene)),
        [](void* f, std::size_t k, const Solution<S>& s) { (*static_cast<Get*>(f))(k, s); }, const_cast<void*>(static_cast<const void*>(&take)));
  }

 private:
  /// Every datum of the scene set is 0 or inside the safe window of S
  /// (scaling_of() leaves it as it is): the others' verdict made once, the
  /// varying entries checked (floating types; false for the others).
  bool inside() const;
  /// solve_each() on its callbacks as functions and their objects.
  void solve_each_calling(std::size_t count, void (*set_scene)(void*, std::size_t), void* set_object,
                  void (*take)(void*, std::size_t, const Solution<S>&), void* take_object);

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
  /// The fixed-size path in lanes for problem_ (double, where solve() takes the dense solver's fixed-size path; nullptr otherwise).
  unsigned (*lanes_)(const Problem<double>&, int, const double*, unsigned, const Settings<double>&, Solution<double>*) = nullptr;
  std::vector<double> lane_values_;  ///< entry e of M in lane q at [e·4 + q]
  std::vector<Solution<S>> lane_out_;
};

extern template class SUPERBALL_NUMERIC_EXPORT Batch<double>;
extern template class SUPERBALL_NUMERIC_EXPORT Batch<long double>;
extern template class SUPERBALL_NUMERIC_EXPORT Batch<MpFloat>;
extern template class SUPERBALL_NUMERIC_EXPORT Batch<cln::cl_RA>;

}  // namespace superball::numeric

SUPERBALL_NUMERIC_API_END
