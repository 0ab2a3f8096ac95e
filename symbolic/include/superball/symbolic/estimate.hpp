#pragma once
/// \file estimate.hpp
/// What a derivation is expected to take before it starts: time and memory
/// from the growth measured per pattern width (docs/SYMBOLIC.md, "Limits"),
/// so that `derive` can say it up front and refuse only what cannot fit in
/// memory.

#include <cstddef>
#include <string>

#include "superball/symbolic/pattern.hpp"
#include "superball/symbolic/symbols.hpp"

#include "superball/symbolic/export.hpp"
SUPERBALL_SYMBOLIC_API_BEGIN

namespace superball::symbolic {

/// The width of \p p: how many bodies apart the widest declared entry joins
/// (a diagonal K or a coupled pair), one more when there are couplings
/// (they were measured to cost as much as one more step of width): 1 for
/// near, 2 for near2, 3 for near2 with its couplings, n − 1 for all pairs.
int pattern_width(const Pattern& p);

/// A derivation's expected cost.
struct Estimate {
  int width = 1;             ///< pattern_width()
  double seconds = 0;        ///< computation on one core, every case together
  double process_bytes = 0;  ///< peak resident memory of one process deriving the largest case
};

/// The cost of deriving \p cases cases of \p pattern with \p obstacle:
/// \p every_case means every case of the pattern (--all), else each case is
/// taken as `--closed none`, the slowest.  Fitted per width class (1, 2, 3,
/// 4 and more) on measured points: t(n) = t_ref·g^(n − n_ref), the memory
/// above a 13 MB process likewise (docs/SYMBOLIC.md, "Limits", has the
/// points and a comparison with real runs); a finite obstacle is taken as
/// three times the fixed one's time (bench_symbolic measured 2.3 to 3.8).
/// An estimate within a factor of about 3 of the real run, not a promise.
Estimate estimate_derivation(const Pattern& pattern, Obstacle obstacle, std::size_t cases, bool every_case);

/// A duration for people: "0.4 s", "26 s", "4 min 16 s", "3 h 5 min", "12 days".
std::string duration_text(double seconds);

}  // namespace superball::symbolic

SUPERBALL_SYMBOLIC_API_END
