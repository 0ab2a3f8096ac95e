#pragma once
// Internal: the fixed-size path of CollisionSolver in lanes
// (small_solver.cpp): lane_width problems of one structure, differing only
// in the values of M's entries, solved at once in double.

#include "superball/numeric/collision.hpp"

namespace superball::numeric::detail {

/// The number of problems one lanes solve takes.
inline constexpr int lane_width = 4;

/// A lanes solve for one number of bodies: \p p gives the structure (n,
/// masses, velocities, fixed_bottom, the bodies of each entry of M; its
/// values are not read), \p bandwidth DᵀMD's bandwidth (Problem::check()),
/// \p values the value of entry e in lane q at values[e·lane_width + q],
/// \p todo the lanes to solve (bit q for lane q).  Returns the lanes solved,
/// each into out[q], out[q] then the Solution of small_solver_for()'s solve
/// of lane q's problem alone, bit for bit, with status Success.  Each branch
/// of that solve on a number (a zero of M, the pivots chosen, the pivot row
/// of a cluster's reactions) is decided by the first lane still solved; a
/// lane that would decide otherwise, or whose solve hands over to the
/// general path or fails the residual check, is left to the caller (out[q]
/// unspecified).  So the first lane of \p todo is solved exactly when its
/// solve alone succeeds, and lanes whose solves take the same branches are
/// solved together.  Problems must have every contact constrained and be in
/// range (Problem::in_range) and inside the safe window (no scaling).
using LanesSolve = unsigned (*)(const Problem<double>& p, int bandwidth, const double* values, unsigned todo,
                                const Settings<double>& settings, Solution<double>* out);

/// Which compiled copy of the lanes a LanesSolve runs.
enum class LaneCode {
  Best,      ///< AVX2 where the processor has it (4 lanes a register), else Baseline
  Baseline,  ///< the build's baseline target (x86-64: SSE2, 2 lanes a register)
};

/// The lanes solve for \p n bodies (2 <= n <= small_max_bodies), or nullptr.
LanesSolve lanes_solver_for(int n, LaneCode code = LaneCode::Best);

/// Whether LaneCode::Best runs the AVX2 copy on this processor.
bool lanes_use_avx2();

}  // namespace superball::numeric::detail
