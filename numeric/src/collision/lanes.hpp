#pragma once
// Internal: the fixed-size path of CollisionSolver in lanes (lanes.cpp):
// lane_width problems of one structure, differing only in the values of
// M's entries, solved at once in double where they need no pivot.

#include "superball/numeric/collision.hpp"

namespace superball::numeric::detail {

/// The number of problems one lanes solve takes.
inline constexpr int lane_width = 4;

/// A lanes solve for one number of bodies: \p p gives the structure (n,
/// masses, velocities, fixed_bottom, the bodies of each entry of M; its
/// values are not read), \p bandwidth DᵀMD's bandwidth (Problem::check()),
/// \p values the value of entry e in lane q at values[e·lane_width + q],
/// \p todo the lanes to solve (bit q for lane q).  Returns the lanes solved,
/// each into out[q]: those among \p todo whose entries are zero where the
/// first lane of \p todo has them zero, and whose solve by small_solver_for()
/// would factor the case with every contact open, find no pivot and pass
/// the residual check with status Success; out[q] is then that solve's
/// Solution bit for bit.  The other lanes are left to the caller (out[q]
/// unspecified).  Problems must have every contact constrained and be
/// in range (Problem::in_range) and inside the safe window (no scaling).
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
