#include "superball/numeric/batch.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

#include "collision/lanes.hpp"
#include "collision/small_solver.hpp"
#include "map_internal.hpp"

namespace superball::numeric {

namespace {

/// Whether \p x is 0 or finite with a binary exponent inside the safe
/// window of S (−w < e <= w, |x| = f·2^e, 1/2 <= f < 1): where scaling_of()
/// leaves a datum as it is.
template <class S>
bool inside_window(const S& x) {
  static const S low = std::ldexp(S(1), -safe_exponent<S>()), high = std::ldexp(S(1), safe_exponent<S>());
  const S a = std::fabs(x);
  return a == S(0) || (a >= low && a < high);
}

}  // namespace

template <class S>
Batch<S>::Batch(const ExactScene& base, std::vector<std::size_t> varying, int digits)
    : varying_(std::move(varying)), held_(varying_.size(), 1), problem_(Problem<S>::from(base, digits)),
      chain_(solves_as_chain(problem_)), dense_(Settings<S>::defaults(digits)), banded_(Settings<S>::defaults(digits)) {
  for (std::size_t k = 0; k < varying_.size(); ++k) {
    if (varying_[k] >= base.entries.size())
      throw std::invalid_argument("Batch::Batch(): entry " + std::to_string(varying_[k]) + " of M does not exist (the scene declares " +
                                  std::to_string(base.entries.size()) + ")");
    if (std::find(varying_.begin(), varying_.begin() + static_cast<std::ptrdiff_t>(k), varying_[k]) != varying_.begin() + static_cast<std::ptrdiff_t>(k))
      throw std::invalid_argument("Batch::Batch(): entry " + std::to_string(varying_[k]) + " of M is listed twice");
  }
  // Problem::from()'s verdict on the other data: the varying entries set to
  // 1, which every type holds.
  ExactScene ones = base;
  for (const std::size_t e : varying_) ones.entries[e].value = 1;
  others_in_range_ = Problem<S>::from(ones, digits).in_range;
  bandwidth_ = problem_.check("Batch::Batch()");
  if constexpr (std::is_floating_point<S>::value) {
    // CollisionSolver::compute()'s choice of its fixed-size path, made once: the same settings, every contact constrained.
    if (dense_.settings().small_sizes && problem_.constrained.empty()) small_ = detail::small_solver_for<S>(problem_.n);
    for (std::size_t k = 0; k < varying_.size(); ++k)
      held_[k] = detail::held(problem_.entries[varying_[k]].value, cln::zerop(base.entries[varying_[k]].value));
    others_inside_ = std::all_of(problem_.mass.begin(), problem_.mass.end(), inside_window<S>) &&
                     std::all_of(problem_.u.begin(), problem_.u.end(), inside_window<S>);
    for (std::size_t e = 0; e < problem_.entries.size(); ++e)
      if (std::find(varying_.begin(), varying_.end(), e) == varying_.end()) others_inside_ = others_inside_ && inside_window(problem_.entries[e].value);
  }
  if constexpr (std::is_same<S, double>::value) {
    if (small_ && !chain_) lanes_ = detail::lanes_solver_for(problem_.n);
    constexpr std::size_t lanes = detail::lane_width;
    for (const Entry<S>& e : problem_.entries) lane_values_.insert(lane_values_.end(), lanes, e.value);
    lane_out_.resize(lanes);
  }
}

template <class S>
void Batch<S>::solve_each_calling(std::size_t count, void (*set_scene)(void*, std::size_t), void* set_object,
                                  void (*take)(void*, std::size_t, const Solution<S>&), void* take_object) {
  constexpr std::size_t lanes = std::is_same<S, double>::value ? detail::lane_width : 1;
  for (std::size_t first = 0; first < count; first += lanes) {
    const std::size_t group = std::min(lanes, count - first);
    if (group == 1 || !lanes_) {
      for (std::size_t q = 0; q < group; ++q) set_scene(set_object, first + q), take(take_object, first + q, solve());
      continue;
    }
    if constexpr (std::is_same<S, double>::value) {
      // Each scene set kept as a lane; the lanes take those that solve()
      // would solve by the fixed-size path unscaled, in range.
      unsigned todo = 0;
      for (std::size_t q = 0; q < group; ++q) {
        set_scene(set_object, first + q);
        for (const std::size_t e : varying_) lane_values_[e * lanes + q] = problem_.entries[e].value;
        if (inside() && problem_.in_range) todo |= 1u << q;
      }
      const unsigned solved = todo ? lanes_(problem_, bandwidth_, lane_values_.data(), todo, dense_.settings(), lane_out_.data()) : 0u;
      for (std::size_t q = 0; q < group; ++q) {
        if ((solved >> q) & 1u) {
          take(take_object, first + q, lane_out_[q]);
          continue;
        }
        set_scene(set_object, first + q);  // the lane's scene set again, and solved alone
        take(take_object, first + q, solve());
      }
    }
  }
}

template <class S>
void Batch<S>::set(std::size_t k, const S& value, bool is_zero) {
  if (k >= varying_.size())
    throw std::out_of_range("Batch::set(): entry " + std::to_string(k) + " of " + std::to_string(varying_.size()) + " that vary");
  problem_.entries[varying_[k]].value = value;
  if constexpr (std::is_floating_point<S>::value) {
    held_[k] = detail::held(value, is_zero);
    problem_.in_range = others_in_range_ && std::all_of(held_.begin(), held_.end(), [](char h) { return h != 0; });
  } else {
    (void)is_zero;
  }
}

template <class S>
bool Batch<S>::inside() const {
  if constexpr (std::is_floating_point<S>::value) {
    bool in = others_inside_;
    for (const std::size_t e : varying_) in = in && inside_window(problem_.entries[e].value);
    return in;
  } else {
    return false;
  }
}

template <class S>
const Solution<S>& Batch<S>::solve() {
  // solve()'s choice (chain.cpp): as given inside the safe window, else its
  // scaled solve, which this batch leaves to it.
  // Every datum inside the window: scaling_of() is the identity, and fits;
  // the check on the varying entries alone, the others' made once.
  if (!inside()) {
    const Scaling scaling = scaling_of(problem_);
    if (!(scaling.identity() && scaling.fits)) return out_ = numeric::solve(problem_);
  }
  if (chain_)
    banded_.compute(problem_, out_);
  else if (!(small_ && small_(problem_, bandwidth_, dense_.settings(), out_)))
    dense_.compute(problem_, out_);  // the general path (the fixed-size one handed over, or none)
  // A failed solve leaves in its storage what the steps it took wrote there
  // (Solution: only a success's fields are meaningful), part of it the
  // scene's before: solved again afresh, it has solve()'s fields too.
  if (out_.status != Status::Success) out_ = numeric::solve(problem_);
  return out_;
}

template class Batch<double>;
template class Batch<long double>;
template class Batch<MpFloat>;
template class Batch<cln::cl_RA>;

}  // namespace superball::numeric
